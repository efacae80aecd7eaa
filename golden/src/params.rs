//! Parameters of the method: matching mode, reference view, search bound and
//! the interpolation rule at the ends of a line.

use crate::error::GoldenError;

/// Which variant of the method runs: the paper's, or the paper's with
/// changes that each fix a measured failure (README, "Accuracy beyond the
/// paper"). Every change runs in the streaming hardware at one pixel per
/// clock with bounded memory; its cost is given with it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Mode {
    /// The paper's method exactly as `DESIGN.md` §2 settles it: eq. 4–8
    /// read literally (`f = 3·gmax` when both photometric distances are below
    /// `gmax`, `gmax` when exactly one is, rejection otherwise), linear
    /// interpolation along the line.
    Paper,
    /// Paper + offset-compensated photometric distances
    /// ([`Features::relative`]).
    Relative,
    /// Paper + one-sided nodes scored on their similar side
    /// ([`Features::one_sided`]).
    OneSided,
    /// Paper + matches confirmed by a neighbouring row
    /// ([`Features::consistent`]).
    Consistent,
    /// Paper + interpolation that does not bridge disparity jumps
    /// ([`Features::edge_jump`]).
    Edges,
    /// Paper + a vertical median over nine rows of the dense map
    /// ([`Features::median_rows`]).
    Median,
    /// Paper + matches next to a depth edge flagged and not reported
    /// ([`Features::edge_flag`]).
    EdgeFlag,
    /// All of the above: the default, the best measured combination.
    #[default]
    Robust,
    /// Robust + inter-scanline support: the row above's matches enter the
    /// gain of the declivities that continue them ([`Features::contour`]).
    Contour,
}

/// The changes to the paper's method that a [`Mode`] switches on.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Features {
    /// Photometric distances (eq. 4–5) after removing the brightness offset
    /// between the two declivities, `δ = (m_ref - m_other)` with `m` the mean
    /// of a declivity's two end levels, and nodes only between declivities of
    /// one polarity. A brightness offset between the cameras then no longer
    /// pushes true pairs over `gmax`.
    /// Hardware: the matcher's record memory stores the six neighbour
    /// levels relative to the end-level mean as they come in, doubled
    /// (`2·I - (I(x_i) + I(x_{i+1}))` plus an offset: one adder and 6
    /// subtractors, 10-bit; the paper's rule stores `2·I` plus the offset in
    /// the same format); each processing element also compares the two
    /// polarity bits (1 XOR). No added latency.
    pub relative: bool,
    /// A node similar on one side only (the paper's "partially masked"
    /// case) gets `gmax - d_similar` instead of `gmax - lpd - rpd ≤ 0`, so it
    /// can join the path: occluded edges get matched.
    /// Hardware: per PE one multiplexer selecting which distances are
    /// subtracted. No added latency.
    pub one_sided: bool,
    /// A match is kept only if the row above or the row below has a match
    /// within [`CONSISTENT_DX`] px of it whose disparity differs by at most
    /// [`CONSISTENT_DD`] px: isolated wrong matches are dropped.
    /// Hardware (`rtl::post::row_check`): the matches of four rows (above,
    /// checked, below, incoming) in banks of `N_MAX` (position, disparity)
    /// entries; matches are sorted, so each neighbour row is read in order
    /// into a window of eight entries, and each match is compared with the
    /// entries held. Latency: one line period.
    pub consistent: bool,
    /// Between consecutive matches whose disparities differ by more than
    /// this (px), the interpolation holds the smaller disparity (the
    /// background) instead of bridging the depth discontinuity.
    /// Hardware: one comparator and one multiplexer in the interpolator. No
    /// added latency.
    pub edge_jump: Option<f64>,
    /// Rows of a vertical median of the dense disparity map (1 = none):
    /// streaks of a single wrong line disappear.
    /// Hardware (`rtl::post::vertical_median`): `median_rows - 1` line
    /// buffers of `W_MAX` 14-bit disparities (one block RAM each) and a
    /// median network per pixel (for 9 rows the 19 compare-exchanges of
    /// `crate::disparity::MEDIAN9_NETWORK`, pipelined). Latency:
    /// `median_rows / 2` lines.
    pub median_rows: usize,
    /// Matches whose disparity differs by more than this (px) from that of
    /// the previous or the next match of their row sit on a depth edge: the
    /// declivity separates two surfaces, and which one its pixel belongs to
    /// is undecided. They stay anchors of the interpolation (which holds the
    /// background across the jump) but are flagged and not reported as
    /// matches.
    /// Hardware: one match of look-ahead in the traceback's output (2
    /// comparators and a flag bit per match). Latency: one match.
    pub edge_flag: Option<f64>,
    /// Inter-scanline support (Ohta and Kanade's intra- and inter-scanline
    /// search, 1985): a reference declivity that continues a matched
    /// reference declivity of the row above (same polarity, positions within
    /// [`ContourSupport::dx`]) lies on an edge contour, and a node of it
    /// whose disparity is within [`ContourSupport::dd`] of the contour's
    /// disparity in the row above gets [`ContourSupport::weight`]` · gmax`
    /// added to its gain (`crate::gain::contour_term`), so that the per-line
    /// DP (eq. 9) chooses with the contour. Rows are then matched in order,
    /// each after the row above.
    /// Hardware: a line buffer of the row above's matches as the traceback
    /// emits them, two banks (written, read) of `N_MAX` entries of position
    /// (14 bits), disparity (11 bits) and polarity (1 bit): one `DP16KD`;
    /// the record loader merges each reference record with it (sorted
    /// positions: 2 comparators, `|Δx| ≤ dx` and the polarity) and stores
    /// the contour's disparity and a valid bit in the record memory (12 more
    /// bits per reference declivity, read by its processing element); per
    /// processing element a subtractor and a comparator (`|d - d_c| ≤ dd`)
    /// and an adder of `weight · gmax` (computed once per line). Latency:
    /// the row's sweep needs the row above's traceback finished, so the
    /// traceback no longer overlaps the next sweep (the matcher's line
    /// period becomes sweep + traceback instead of their maximum) unless
    /// the row two above is used.
    pub contour: Option<ContourSupport>,
}

/// The settings of [`Features::contour`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContourSupport {
    /// Largest position difference (px) between a reference declivity and
    /// the matched declivity of the row above that it continues.
    pub dx: f64,
    /// Largest difference (px) between a node's disparity and the
    /// contour's for the node to get the bonus.
    pub dd: f64,
    /// The bonus as a fraction of `gmax` (eq. 8); 0 leaves every gain as
    /// it is.
    pub weight: f64,
}

/// [`Features::consistent`]: largest position difference (px) of a
/// confirming match in a neighbouring row (of 1, 2, 3 and 4 px, 3 kept the
/// accuracy of 2 with more matches and a better map; 4 added little).
pub const CONSISTENT_DX: f64 = 3.0;
/// [`Features::consistent`]: largest disparity difference (px) of a
/// confirming match.
pub const CONSISTENT_DD: f64 = 1.0;
/// [`Features::edge_jump`] of the modes that use it (px): of 1, 2, 4, 5, 6
/// and 8 px, 6 gave the lowest mean bad2 on the eight pairs with the other
/// changes on.
pub const EDGE_JUMP: f64 = 6.0;
/// [`Features::edge_flag`] of the modes that use it (px): of 1, 1.5, 2, 2.5,
/// 3 and 4 px, the smallest that keeps `match_frac` at or above the paper
/// mode's on every pair.
const EDGE_FLAG_JUMP: f64 = 2.0;
/// [`Features::contour`] of the modes that use it: contours within 1 px,
/// disparities within 1 px, a bonus of `gmax / 2`. Of the weights 0.25,
/// 0.5, 1 and 2 (with `dx = dd = 1`), and of `dx` 0.5 and 2 and `dd` 0.5
/// (with weight 1), none moved the mean `sparse_acc1` on the eight pairs by
/// more than 0.15 point from the robust mode's (docs/method.md, "Inter-scanline
/// support"); 0.5 adds matches at the least cost in accuracy.
pub const CONTOUR: ContourSupport = ContourSupport { dx: 1.0, dd: 1.0, weight: 0.5 };
/// [`Features::median_rows`] of the modes that use it: of 5, 7, 9 and 11
/// rows (`sim` example `accuracy_limits -- medians`), 9 is the fewest that
/// brings the robust mode's mean bad2 on the eight pairs below SGBM's.
pub const MEDIAN_ROWS: usize = 9;

impl Mode {
    /// Every mode, in the order the CLI lists them.
    pub const ALL: [Mode; 9] = [
        Mode::Paper,
        Mode::Relative,
        Mode::OneSided,
        Mode::Consistent,
        Mode::Edges,
        Mode::Median,
        Mode::EdgeFlag,
        Mode::Robust,
        Mode::Contour,
    ];

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Paper => "paper",
            Mode::Relative => "relative",
            Mode::OneSided => "one-sided",
            Mode::Consistent => "consistent",
            Mode::Edges => "edges",
            Mode::Median => "median",
            Mode::EdgeFlag => "edge-flag",
            Mode::Robust => "robust",
            Mode::Contour => "contour",
        }
    }

    /// One line saying what the mode is (for `--help`).
    pub fn summary(self) -> &'static str {
        match self {
            Mode::Paper => "The paper's method exactly (DESIGN.md section 2)",
            Mode::Relative => "Paper + photometric distances with the brightness offset between the declivities removed",
            Mode::OneSided => "Paper + one-sided nodes (similar on one side only) scored on their similar side",
            Mode::Consistent => "Paper + matches kept only when a neighbouring row confirms them",
            Mode::Edges => "Paper + interpolation holding the background across disparity jumps",
            Mode::Median => "Paper + a vertical median over nine rows of the dense map",
            Mode::EdgeFlag => "Paper + matches next to a disparity jump flagged as depth-edge matches, not reported",
            Mode::Robust => "All of the above (the best measured combination)",
            Mode::Contour => "Robust + inter-scanline support: the row above's matches enter the gain of the declivities continuing them",
        }
    }

    /// The changes this mode makes to the paper's method.
    pub fn features(self) -> Features {
        let none = Features { median_rows: 1, ..Features::default() };
        match self {
            Mode::Paper => none,
            Mode::Relative => Features { relative: true, ..none },
            Mode::OneSided => Features { one_sided: true, ..none },
            Mode::Consistent => Features { consistent: true, ..none },
            Mode::Edges => Features { edge_jump: Some(EDGE_JUMP), ..none },
            Mode::Median => Features { median_rows: MEDIAN_ROWS, ..none },
            Mode::EdgeFlag => Features { edge_flag: Some(EDGE_FLAG_JUMP), ..none },
            Mode::Robust => Features {
                relative: true,
                one_sided: true,
                consistent: true,
                edge_jump: Some(EDGE_JUMP),
                median_rows: MEDIAN_ROWS,
                edge_flag: Some(EDGE_FLAG_JUMP),
                contour: None,
            },
            Mode::Contour => Features { contour: Some(CONTOUR), ..Mode::Robust.features() },
        }
    }
}

/// The view whose declivities get disparities and whose pixels form the map.
///
/// Disparity is always `d = x_left - x_right > 0` (Middlebury's convention).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum RefView {
    /// The left view (default: the ground truth in `data/stereo` is for it).
    #[default]
    Left,
    /// The right view, as in the paper (its axes give `D = X_R - X_L`).
    Right,
}

/// What the interpolation does before the first and after the last matched
/// declivity of a line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum EndRule {
    /// Hold the nearest matched disparity out to the line's ends.
    #[default]
    Hold,
    /// Leave the ends without disparity.
    Empty,
}

/// Everything the method needs besides the two images.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Local-gain rule.
    pub mode: Mode,
    /// Upper search bound of eq. 6: a node exists when
    /// `dispmin < d < dispmax`.
    pub dispmax: f64,
    /// Lower search bound of eq. 6 (0 in the paper: `0 < d < dispmax`); a
    /// verged or offset rig, or a scene with a known nearest range, sets it
    /// higher.
    pub dispmin: f64,
    /// Reference view.
    pub ref_view: RefView,
    /// Interpolation at the line's ends.
    pub ends: EndRule,
    /// Hardware parity: detect declivities as the streaming detector with
    /// these sizes does (`crate::hardware`); `None` is the unlimited method.
    pub hardware: Option<crate::hardware::HardwareLimits>,
}

impl Params {
    /// The default mode, left reference, holding ends, with the given search
    /// bound.
    pub fn new(dispmax: f64) -> Result<Self, GoldenError> {
        Self::with_mode(Mode::default(), dispmax)
    }

    /// The paper's method, left reference, holding ends, with the given
    /// search bound.
    pub fn paper(dispmax: f64) -> Result<Self, GoldenError> {
        Self::with_mode(Mode::Paper, dispmax)
    }

    /// `mode`, left reference, holding ends, with the given search bound.
    pub fn with_mode(mode: Mode, dispmax: f64) -> Result<Self, GoldenError> {
        let p = Params { mode, dispmax, dispmin: 0.0, ref_view: RefView::Left, ends: EndRule::Hold, hardware: None };
        p.validate()?;
        Ok(p)
    }

    /// Checks the search bounds: eq. 6 needs room for a positive disparity
    /// above `dispmin ≥ 0`; in hardware parity `dispmin` is on the
    /// positions' grid, as the line processor takes it.
    pub fn validate(&self) -> Result<(), GoldenError> {
        if self.dispmax.is_nan() || self.dispmax <= 1.0 || self.dispmax.is_infinite() {
            return Err(GoldenError::InvalidDispmax(self.dispmax));
        }
        if !(self.dispmin >= 0.0 && self.dispmin < self.dispmax - 1.0) {
            return Err(GoldenError::InvalidDispmin { dispmin: self.dispmin, dispmax: self.dispmax });
        }
        if let Some(hw) = self.hardware {
            let unit = (1u64 << hw.pos_frac_bits) as f64;
            if (self.dispmin * unit).fract() != 0.0 {
                return Err(GoldenError::DispminOffGrid { dispmin: self.dispmin, unit });
            }
        }
        Ok(())
    }
}
