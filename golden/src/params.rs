//! Parameters of the method: matching mode, reference view, search bound and
//! the interpolation rule at the ends of a line.

use crate::error::GoldenError;

/// Which local-gain rule the matcher uses.
///
/// `Paper` is the paper's method exactly as `DESIGN.md` §2 settles it
/// (eq. 7–8 read literally). Other modes are added, each justified by a
/// measurement, by the issue "Accuracy beyond the paper".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Mode {
    /// Eq. 7–8 literally: `f = 3·gmax` when both photometric distances are
    /// below `gmax`, `f = gmax` when exactly one is, rejection otherwise.
    #[default]
    Paper,
}

impl Mode {
    /// Every mode, in the order the CLI lists them.
    pub const ALL: [Mode; 1] = [Mode::Paper];

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Paper => "paper",
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
    /// Search bound of eq. 6: a node exists when `0 < d < dispmax`.
    pub dispmax: f64,
    /// Reference view.
    pub ref_view: RefView,
    /// Interpolation at the line's ends.
    pub ends: EndRule,
}

impl Params {
    /// Paper mode, left reference, holding ends, with the given search bound.
    pub fn new(dispmax: f64) -> Result<Self, GoldenError> {
        let p = Params {
            mode: Mode::Paper,
            dispmax,
            ref_view: RefView::Left,
            ends: EndRule::Hold,
        };
        p.validate()?;
        Ok(p)
    }

    /// Checks the search bound: eq. 6 needs room for a positive disparity.
    pub fn validate(&self) -> Result<(), GoldenError> {
        if !(self.dispmax > 1.0) || !self.dispmax.is_finite() {
            return Err(GoldenError::InvalidDispmax(self.dispmax));
        }
        Ok(())
    }
}
