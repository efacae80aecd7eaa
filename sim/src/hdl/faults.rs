//! The fault-injection campaign: the line processor's Verilog under
//! Verilator, fed by two cameras that break the stream's rules, frame after
//! frame, in every way a camera in the field does (`docs/hardware/datasheet.md`,
//! "Faulty cameras"):
//!
//! - [`Fault::ShortFrame`]: a frame cut short, fewer rows than `height`;
//! - [`Fault::MixedWidths`]: lines of other widths inside a frame, some
//!   wider than `W_MAX`;
//! - [`Fault::MissingTlast`]: a line's `tlast` missing on one camera or both,
//!   so that it runs on into the next line (or the next frame);
//! - [`Fault::SofMidFrame`]: a start of frame in the middle of a frame, at a
//!   line's start or inside a line;
//! - [`Fault::OutOfStep`]: the right camera some clocks or a line behind,
//!   its `tlast` on another beat, or a line more or less than the left;
//! - [`Fault::IdleClocks`]: idle clocks inside lines, on each camera on its
//!   own.
//!
//! Each faulty frame (one class, or two or three mixed) is followed by a
//! clean frame, one of a few, both cameras in step after a vertical gap of
//! [`CampaignSpec::gap_lines`] line periods (counted from the faulty frame's
//! last beat, or from when its output has left if that is later: every
//! output line has its frame's width, so a frame whose first line is wider
//! than the others' line period takes longer to leave than to come in). The frames are crops of real
//! pairs given by the caller and generated textures. The invariants checked
//! over the whole run:
//!
//! - **no hang**: every beat of both scripts is taken, and the output goes
//!   quiet before the clock limit;
//! - **well-formed output lines**: `m_tuser` only on a line's first beat,
//!   and no line left without its `m_tlast`;
//! - **aligned lines**: inside an output frame (from one `m_tuser` to the
//!   next) every line has one width, and it is the width of an input
//!   frame's first reference line as the detector stores it (at most
//!   `W_MAX`, run on into the next line when its `tlast` is missing);
//! - **clean frames exact**: each clean frame gives, beat for beat and clock
//!   for clock from its first pixel, what a fresh run of that frame alone
//!   gives (the core idle since configuration), with nothing else on the
//!   output in between; the whole frame may come out [`LATE_START_MAX`]
//!   clock later when the line before ended only on its first pixel's
//!   `tuser` (counted in [`CampaignReport::clean_late`]).

use std::collections::BTreeMap;

use golden::GreyImage;
use rtl::detector::declivity_detector::MIN_LINE_PERIOD;

use crate::config::Config;
use crate::formats::SearchArea;
use crate::hdl::beats::{run_beats, Beat, BeatRun, OutBeat};
use crate::hdl::cosim::{CosimError, Options};
use crate::rng::VectorRng;

/// A class of camera fault.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Fault {
    ShortFrame,
    MixedWidths,
    MissingTlast,
    SofMidFrame,
    OutOfStep,
    IdleClocks,
}

impl Fault {
    pub const ALL: [Fault; 6] = [Fault::ShortFrame, Fault::MixedWidths, Fault::MissingTlast, Fault::SofMidFrame, Fault::OutOfStep, Fault::IdleClocks];

    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Fault::ShortFrame => "short_frame",
            Fault::MixedWidths => "mixed_widths",
            Fault::MissingTlast => "missing_tlast",
            Fault::SofMidFrame => "sof_mid_frame",
            Fault::OutOfStep => "out_of_step",
            Fault::IdleClocks => "idle_clocks",
        }
    }

    /// Every class's name, comma-separated.
    pub fn all_names() -> String {
        Fault::ALL.map(Fault::name).join(", ")
    }
}

/// The campaign's size and the frames' geometry.
#[derive(Debug, Clone)]
pub struct CampaignSpec {
    pub config: Config,
    /// Faulty frames (each followed by a clean one).
    pub frames: usize,
    pub seed: u64,
    /// The frames' width and rows (`height` on the core's input).
    pub width: usize,
    pub height: usize,
    /// Idle clocks after each line.
    pub hblank: u32,
    /// Line periods (`width + hblank`) between a frame's end and the next
    /// frame.
    pub gap_lines: usize,
    /// Only these classes (all when empty).
    pub classes: Vec<Fault>,
    /// Eq. 6's search area.
    pub area: SearchArea,
}

impl CampaignSpec {
    /// The classes the campaign draws from: the `classes` field, or every
    /// class when it is empty.
    pub fn classes(&self) -> Vec<Fault> {
        if self.classes.is_empty() { Fault::ALL.to_vec() } else { self.classes.clone() }
    }

    /// Clocks of a line period: `width + hblank`, at least the core's
    /// [`MIN_LINE_PERIOD`].
    fn line_period(&self) -> u64 {
        (self.width as u64 + self.hblank as u64).max(MIN_LINE_PERIOD as u64)
    }

    /// Clocks of the vertical gap between a frame's end and the next frame.
    fn gap_clocks(&self) -> u64 {
        self.gap_lines as u64 * self.line_period()
    }
}

/// One invariant broken, with where.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Violation {
    pub invariant: &'static str,
    /// The faulty frame before it (its index and classes), if any.
    pub frame: Option<usize>,
    pub detail: String,
}

/// What the campaign injected and found.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct CampaignReport {
    pub faulty_frames: usize,
    /// Faulty frames with each class (a mixed frame counts in each of its
    /// classes).
    pub injected: BTreeMap<&'static str, usize>,
    pub clean_frames: usize,
    pub clean_exact: usize,
    /// Clean frames sent right after a faulty frame whose last line ended
    /// only at their `tuser` (no vertical blanking before them), and not
    /// checked: the clean frame after each is.
    pub clean_unchecked: usize,
    /// Of those, the frames that came out [`LATE_START_MAX`] clocks later or
    /// less than a fresh run's (the line before ended only on their first
    /// pixel's `tuser`, which the detector then takes a clock later).
    pub clean_late: usize,
    pub output_lines: usize,
    pub cycles: u64,
    pub hung: bool,
    /// The status counters at the end.
    pub status: Vec<(String, u64)>,
    pub violations: Vec<Violation>,
    /// Violations per invariant.
    pub violated: BTreeMap<&'static str, usize>,
    /// Of the violations, those after a frame with each class.
    pub violated_after: BTreeMap<&'static str, usize>,
    pub sim_seconds: f64,
}

/// Clocks a clean frame may come out later than a fresh run of it, all
/// its beats alike: the clock on which the detector ends a line on the
/// frame's `tuser` (the line before had no `tlast`), the first pixel
/// waiting in the register slice.
pub const LATE_START_MAX: u64 = 1;

/// Rows of a faulty frame's width, besides its own, that the campaign
/// waits for its output to leave before the clean frame: the median's last
/// [`rtl::params::MEDIAN_HALF`] rows flushed, and the
/// pipeline's latency (a row or two).
const DRAIN_EXTRA_ROWS: usize = 8;

/// The invariants' names in reports.
pub const INVARIANTS: [&str; 4] = ["hang", "malformed_line", "misaligned_line", "clean_frame_inexact"];

/// One camera's line before it becomes beats.
#[derive(Debug, Clone)]
struct Line {
    px: Vec<u8>,
    /// `tuser` on the first beat.
    user: bool,
    /// `tlast` on the last beat.
    last: bool,
    /// Idle clocks before the line's first beat.
    lead: u32,
    /// Idle clocks before beats inside the line: (beat index, clocks).
    gaps: Vec<(usize, u32)>,
}

/// A frame as both cameras send it.
#[derive(Debug, Clone)]
struct CamFrames {
    left: Vec<Line>,
    right: Vec<Line>,
}

fn clean_lines(rows: &[Vec<u8>], hblank: u32) -> Vec<Line> {
    rows.iter().enumerate().map(|(y, px)| Line { px: px.clone(), user: y == 0, last: true, lead: if y == 0 { 0 } else { hblank }, gaps: Vec::new() }).collect()
}

/// The rows of `img` cropped to `w × h` at (`x0`, `y0`).
fn crop_rows(img: &GreyImage, x0: usize, y0: usize, w: usize, h: usize) -> Vec<Vec<u8>> {
    (y0..y0 + h).map(|y| img.row(y)[x0..x0 + w].to_vec()).collect()
}

impl VectorRng {
    /// A number in `lo ..= hi`.
    fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.next() % (hi - lo + 1)
    }

    /// True with probability `p`.
    fn chance(&mut self, p: f64) -> bool {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }
}

/// A generated pair of `w × h`: a texture of random steps and ramps, the
/// right view the left shifted by a disparity of 2 to 24 px, with noise.
fn generated_rows(rng: &mut VectorRng, w: usize, h: usize) -> (Vec<Vec<u8>>, Vec<Vec<u8>>) {
    let d = rng.range(2, 24) as usize;
    let mut left = Vec::with_capacity(h);
    let mut right = Vec::with_capacity(h);
    let base: Vec<i64> = {
        let mut v = Vec::with_capacity(w + d);
        let mut level = rng.range(40, 200) as i64;
        while v.len() < w + d {
            let run = rng.range(2, 12) as usize;
            let target = rng.range(10, 245) as i64;
            for k in 0..run {
                v.push(level + (target - level) * k as i64 / run as i64);
            }
            level = target;
        }
        v
    };
    for _ in 0..h {
        let noise = |rng: &mut VectorRng| rng.range(0, 4) as i64 - 2;
        left.push((0..w).map(|x| (base[x + d] + noise(rng)).clamp(0, 255) as u8).collect());
        right.push((0..w).map(|x| (base[x] + noise(rng)).clamp(0, 255) as u8).collect());
    }
    (left, right)
}

/// A frame of `spec`'s size from `sources` (crops of real pairs) or
/// generated.
fn source_frame(rng: &mut VectorRng, spec: &CampaignSpec, sources: &[(GreyImage, GreyImage)]) -> (Vec<Vec<u8>>, Vec<Vec<u8>>) {
    let fits: Vec<&(GreyImage, GreyImage)> = sources.iter().filter(|(l, _)| l.width() >= spec.width && l.height() >= spec.height).collect();
    if !fits.is_empty() && rng.chance(0.5) {
        let (l, r) = fits[rng.range(0, fits.len() as u64 - 1) as usize];
        let x0 = rng.range(0, (l.width() - spec.width) as u64) as usize;
        let y0 = rng.range(0, (l.height() - spec.height) as u64) as usize;
        (crop_rows(l, x0, y0, spec.width, spec.height), crop_rows(r, x0, y0, spec.width, spec.height))
    } else {
        generated_rows(rng, spec.width, spec.height)
    }
}

/// Applies `fault` to `f` (a frame of `spec`'s size as both cameras send
/// it).
fn inject(rng: &mut VectorRng, fault: Fault, f: &mut CamFrames, spec: &CampaignSpec) {
    let w_max = spec.config.sizes().w_max;
    let period = spec.width as u64 + spec.hblank as u64;
    match fault {
        Fault::ShortFrame => {
            let rows = f.left.len().min(f.right.len());
            if rows > 1 {
                let k = rng.range(1, rows as u64 - 1) as usize;
                f.left.truncate(k);
                f.right.truncate(k);
            }
        }
        Fault::MixedWidths => {
            let rows = f.left.len().min(f.right.len());
            for _ in 0..rng.range(1, 3) {
                let y = rng.range(0, rows as u64 - 1) as usize;
                let w = if rng.chance(0.1) { w_max + rng.range(1, 64) as usize } else { rng.range(1.max(spec.width as u64 / 4), 2 * spec.width as u64) as usize };
                for line in [&mut f.left[y], &mut f.right[y]] {
                    let old = line.px.clone();
                    line.px = (0..w).map(|x| old[x % old.len()]).collect();
                    line.gaps.retain(|&(i, _)| i < w);
                }
            }
        }
        Fault::MissingTlast => {
            let side = rng.range(0, 2);
            let rows = f.left.len().min(f.right.len());
            let y = rng.range(0, rows as u64 - 1) as usize;
            if side != 1 {
                f.left[y].last = false;
            }
            if side != 0 {
                f.right[y].last = false;
            }
        }
        Fault::SofMidFrame => {
            let rows = f.left.len().min(f.right.len());
            if rows > 1 {
                // The frame restarts at row k (inside row k with a partial
                // row, half the time), both cameras.
                let k = rng.range(1, rows as u64 - 1) as usize;
                let part = if rng.chance(0.5) { Some(rng.range(1, spec.width as u64 - 1) as usize) } else { None };
                for lines in [&mut f.left, &mut f.right] {
                    let mut restart: Vec<Line> = lines.clone();
                    restart[0].lead = spec.hblank;
                    let mut head: Vec<Line> = lines[..k].to_vec();
                    if let Some(j) = part {
                        let mut cut = lines[k].clone();
                        cut.px.truncate(j);
                        cut.last = false;
                        cut.gaps.retain(|&(i, _)| i < j);
                        head.push(cut);
                        restart[0].lead = 0;
                    }
                    head.extend(restart);
                    *lines = head;
                }
            }
        }
        Fault::OutOfStep => match rng.range(0, 3) {
            0 => f.right[0].lead += rng.range(1, 2 * period) as u32,
            1 => {
                let delta = rng.range(1, 8) as usize;
                let longer = rng.chance(0.5);
                for line in f.right.iter_mut() {
                    let w = if longer { line.px.len() + delta } else { line.px.len().saturating_sub(delta).max(1) };
                    let old = line.px.clone();
                    line.px = (0..w).map(|x| old[x % old.len()]).collect();
                    line.gaps.retain(|&(i, _)| i < w);
                }
            }
            2 => {
                if f.right.len() > 1 {
                    f.right.pop();
                }
            }
            _ => {
                let mut extra = f.right[f.right.len() - 1].clone();
                extra.user = false;
                extra.lead = spec.hblank;
                f.right.push(extra);
            }
        },
        Fault::IdleClocks => {
            for lines in [&mut f.left, &mut f.right] {
                for line in lines.iter_mut() {
                    for i in 1..line.px.len() {
                        if rng.chance(0.03) {
                            line.gaps.push((i, rng.range(1, 16) as u32));
                        }
                    }
                }
            }
        }
    }
}

/// Appends `lines` to `script`, the first beat offered not before `at`;
/// returns a clock by which every beat has been taken when the core keeps
/// up (each line at most `max(width, MIN_LINE_PERIOD)` clocks and its
/// idle ones).
fn append(script: &mut Vec<Beat>, lines: &[Line], at: u64) -> u64 {
    let mut end = at;
    for (y, line) in lines.iter().enumerate() {
        let gaps: u64 = line.gaps.iter().map(|&(_, g)| g as u64).sum();
        end += line.lead as u64 + gaps + line.px.len().max(MIN_LINE_PERIOD) as u64;
        for (i, &px) in line.px.iter().enumerate() {
            let idle = if i == 0 { line.lead } else { line.gaps.iter().filter(|&&(k, _)| k == i).map(|&(_, g)| g).sum() };
            script.push(Beat { at: if y == 0 && i == 0 { at } else { 0 }, idle, data: px, user: i == 0 && line.user, last: i + 1 == line.px.len() && line.last });
        }
    }
    end
}

/// The width of the frame that starts with `lines[0]` (a line with
/// `tuser`), as the detector stores it: its first line's pixels up to
/// `W_MAX`, run on into the next lines while `tlast` is missing (up to a
/// `tuser`).
fn frame_width(lines: &[Line], w_max: usize) -> usize {
    let mut w = 0;
    for (k, line) in lines.iter().enumerate() {
        if k > 0 && line.user {
            break;
        }
        w += line.px.len();
        if w >= w_max || line.last {
            break;
        }
    }
    w.min(w_max)
}

/// Whether the frame `lines` (one camera's) ends only at the next frame's
/// `tuser`: its last line has no `tlast` and stops short of the width its
/// frame's first line set, so the detector cannot end it sooner.
fn unended(lines: &[Line], w_max: usize) -> bool {
    let Some(last) = lines.last() else { return false };
    if last.last {
        return false;
    }
    let k = lines.iter().rposition(|l| l.user).unwrap_or(0);
    let limit = if k + 1 == lines.len() { w_max } else { frame_width(&lines[k..], w_max) };
    last.px.len() < limit
}

/// A clean frame to check: its fresh run, where it starts in each script
/// and on which clock, and the faulty frame before it.
#[derive(Debug, Clone)]
struct Check {
    reference: usize,
    left_index: usize,
    right_index: usize,
    at: u64,
    faulty: usize,
    classes: Vec<Fault>,
}

/// A clean frame's output from a fresh run: beats with clocks from its
/// first pixel.
#[derive(Debug, Clone)]
struct Reference {
    beats: Vec<OutBeat>,
}

/// The clock limit for scripts that end by `end`.
fn limit_after(end: u64, spec: &CampaignSpec) -> u64 {
    end + 64 * (spec.width as u64 + spec.hblank as u64) * (spec.height as u64 + 8) + 1_000_000
}

/// Quiet clocks that end a run: more than any gap inside the core's work
/// on a frame.
fn quiet_clocks(spec: &CampaignSpec) -> u64 {
    4 * (spec.width as u64 + spec.hblank as u64).max(MIN_LINE_PERIOD as u64) + 4096
}

/// The pairs of `data/stereo` the campaign crops real frames from by
/// default (loaded by [`crate::eval::io::load_image_pairs`]).
pub const DEFAULT_SOURCES: [&str; 4] = ["cones", "teddy", "venus", "tsukuba"];

/// The clocks between two frames' starts beyond which the core drops the
/// older unpaired ([`rtl::params::SOF_SKEW_MAX`] and a tick of the stamp).
fn sof_skew_limit(config: Config) -> u64 {
    const _: () = assert!(rtl_hd::params::STAMP_SHIFT == rtl::params::STAMP_SHIFT);
    (config.sizes().sof_skew_max + (1 << rtl::params::STAMP_SHIFT)) as u64
}

/// `spec` as the campaign can run it: frames of 1 to `W_MAX` pixels, 2 or
/// more rows within the `height` port, and a vertical gap between frames
/// longer than the skew within which the core pairs two cameras' frame
/// starts (a frame restarted on one camera only must be told from the
/// next frame).
pub fn check_spec(spec: &CampaignSpec) -> Result<(), CosimError> {
    let sizes = spec.config.sizes();
    if spec.width == 0 || spec.width > sizes.w_max || spec.height < 2 || spec.height >= 1 << sizes.height_bits {
        return Err(CosimError::Port(format!(
            "campaign frames of {}×{}: the {} line processor takes 1 to {} px wide and 2 to {} rows",
            spec.width,
            spec.height,
            spec.config,
            sizes.w_max,
            (1usize << sizes.height_bits) - 1
        )));
    }
    if spec.frames == 0 {
        return Err(CosimError::Port("a campaign of 0 faulty frames".into()));
    }
    let (period, gap) = (spec.line_period(), spec.gap_clocks());
    let limit = sof_skew_limit(spec.config);
    if gap <= limit {
        return Err(CosimError::Port(format!(
            "a vertical gap of {} line periods of {period} clocks ({gap} clocks): more than {limit} are needed, so that a frame started on one camera only \
             is told from the next frame (SOF_SKEW_MAX = {} clocks and a tick of the stamp)",
            spec.gap_lines, sizes.sof_skew_max
        )));
    }
    Ok(())
}

/// Runs the campaign on `design` (the Verilog of `spec.config`'s line
/// processor), the real frames cropped from `sources` (pairs of one size
/// each; any may be too small, generated frames then stand in).
/// `progress` is called with the phase's name and its fraction done.
pub fn run_campaign(spec: &CampaignSpec, sources: &[(GreyImage, GreyImage)], design: &str, opts: &Options, progress: &mut dyn FnMut(&str)) -> Result<CampaignReport, CosimError> {
    check_spec(spec)?;
    let mut rng = VectorRng(spec.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let classes = spec.classes();
    let gap = spec.gap_clocks();
    let (quiet, start) = (quiet_clocks(spec), 16u64);

    // The clean frames and their fresh runs.
    let cleans: Vec<(Vec<Vec<u8>>, Vec<Vec<u8>>)> = (0..4).map(|_| source_frame(&mut rng, spec, sources)).collect();
    let mut refs = Vec::new();
    for (i, (l, r)) in cleans.iter().enumerate() {
        progress(&format!("fresh run of clean frame {} of {}", i + 1, cleans.len()));
        let (mut ls, mut rs) = (Vec::new(), Vec::new());
        let end = append(&mut ls, &clean_lines(l, spec.hblank), start).max(append(&mut rs, &clean_lines(r, spec.hblank), start));
        let run = run_beats(spec.config, design, &ls, &rs, spec.area, spec.height, quiet, limit_after(end, spec), opts)?;
        let t0 = first_take(&run, 0, 0).ok_or_else(|| CosimError::Port("the fresh run took no frame".into()))?;
        if run.hung {
            return Err(CosimError::Port(format!("the fresh run of clean frame {i} did not end (a well-formed frame)")));
        }
        refs.push(Reference { beats: run.out.iter().map(|b| OutBeat { clock: b.clock - t0, ..*b }).collect() });
    }

    // The scripts.
    let mut report = CampaignReport { faulty_frames: spec.frames, ..Default::default() };
    let (mut ls, mut rs) = (Vec::new(), Vec::new());
    let mut frame_widths = std::collections::BTreeSet::new();
    let w_max = spec.config.sizes().w_max;
    frame_widths.insert(spec.width.min(w_max));
    let mut checks: Vec<Check> = Vec::new();
    let mut t = start;
    for n in 0..spec.frames {
        let (l, r) = source_frame(&mut rng, spec, sources);
        let mut f = CamFrames { left: clean_lines(&l, spec.hblank), right: clean_lines(&r, spec.hblank) };
        let count = match rng.range(0, 9) {
            0 => 3,
            1..=3 => 2,
            _ => 1,
        }
        .min(classes.len());
        let mut chosen: Vec<Fault> = Vec::new();
        while chosen.len() < count {
            let c = classes[rng.range(0, classes.len() as u64 - 1) as usize];
            if !chosen.contains(&c) {
                chosen.push(c);
            }
        }
        chosen.sort();
        // The restart first, the idle clocks last (over the lines as they end up).
        let order = [Fault::SofMidFrame, Fault::ShortFrame, Fault::MixedWidths, Fault::OutOfStep, Fault::MissingTlast, Fault::IdleClocks];
        for fault in order.iter().filter(|f| chosen.contains(f)) {
            inject(&mut rng, *fault, &mut f, spec);
            *report.injected.entry(fault.name()).or_default() += 1;
        }
        let widths: Vec<usize> = (0..f.left.len()).filter(|&k| f.left[k].user).map(|k| frame_width(&f.left[k..], w_max)).collect();
        frame_widths.extend(widths.iter().copied());
        // The faulty frame's output leaves one pixel a clock, each line of
        // its frame's width: a frame whose first line is wider than the
        // others takes longer to leave than to come in (its rows, and the
        // median's last rows flushed, with room to spare for the latency:
        // `DRAIN_EXTRA_ROWS`).
        let widest = widths.iter().copied().max().unwrap_or(0);
        let drain = if widest > spec.width { t + (f.left.len() + DRAIN_EXTRA_ROWS) as u64 * (widest + spec.hblank as usize) as u64 } else { 0 };
        let end = append(&mut ls, &f.left, t).max(append(&mut rs, &f.right, t)).max(drain);
        t = end + gap;
        // A frame whose last line has no end but the next `tuser` runs into
        // the next frame: that one is sent but not checked (it has no
        // vertical blanking before it), and a second clean frame follows.
        let unended = unended(&f.left, w_max) || unended(&f.right, w_max);
        for checked in if unended { vec![false, true] } else { vec![true] } {
            let c = rng.range(0, refs.len() as u64 - 1) as usize;
            let (cl, cr) = &cleans[c];
            if checked {
                checks.push(Check { reference: c, left_index: ls.len(), right_index: rs.len(), at: t, faulty: n, classes: chosen.clone() });
            } else {
                report.clean_unchecked += 1;
            }
            let end = append(&mut ls, &clean_lines(cl, spec.hblank), t).max(append(&mut rs, &clean_lines(cr, spec.hblank), t));
            t = end + gap;
        }
        if (n + 1) % 100 == 0 {
            progress(&format!("generated {} of {} faulty frames", n + 1, spec.frames));
        }
    }

    progress(&format!("simulating {} faulty and {} clean frames ({} beats)", spec.frames, spec.frames, ls.len() + rs.len()));
    let run = run_beats(spec.config, design, &ls, &rs, spec.area, spec.height, quiet, limit_after(t, spec), opts)?;
    report.cycles = run.cycles;
    report.hung = run.hung;
    report.status = run.status.clone();
    report.sim_seconds = run.sim.as_secs_f64();
    report.clean_frames = checks.len();

    let mut v = Vec::new();
    if run.hung || run.taken != [ls.len(), rs.len()] {
        v.push(Violation { invariant: "hang", frame: None, detail: format!("beats taken {:?} of {:?}, clock limit reached: {}", run.taken, [ls.len(), rs.len()], run.hung) });
    }
    // Lines and frames on the output.
    let (mut len, mut frame_w): (usize, Option<usize>) = (0, None);
    let mut lines = 0;
    for b in &run.out {
        if b.user && len != 0 {
            v.push(Violation { invariant: "malformed_line", frame: None, detail: format!("m_tuser on beat {} of a line, clock {}", len + 1, b.clock) });
        }
        if b.user {
            frame_w = None;
        }
        len += 1;
        if b.last {
            lines += 1;
            match frame_w {
                None => {
                    frame_w = Some(len);
                    if !frame_widths.contains(&len) {
                        v.push(Violation { invariant: "misaligned_line", frame: None, detail: format!("an output frame of lines {len} px wide (line ending on clock {}), no input frame's width", b.clock) });
                    }
                }
                Some(w) if w != len => v.push(Violation { invariant: "misaligned_line", frame: None, detail: format!("a line of {len} px in an output frame of {w} px lines (ending on clock {})", b.clock) }),
                _ => {}
            }
            len = 0;
        }
    }
    report.output_lines = lines;
    if len != 0 {
        v.push(Violation { invariant: "malformed_line", frame: None, detail: format!("the output ends inside a line of {len} beats") });
    }
    // The clean frames.
    for Check { reference: c, left_index: li, right_index: ri, at, faulty: n, classes: chosen } in &checks {
        let (tl, tr) = (first_take(&run, 0, *li), first_take(&run, 1, *ri));
        let classes = chosen.iter().map(|f| f.name()).collect::<Vec<_>>().join("+");
        let mut fail = |detail: String| v.push(Violation { invariant: "clean_frame_inexact", frame: Some(*n), detail: format!("after faulty frame {n} ({classes}): {detail}") });
        let (Some(tl), Some(tr)) = (tl, tr) else {
            fail("its first pixel was never taken with its tuser".into());
            continue;
        };
        if tl != *at || tr != *at {
            fail(format!("its first pixels were taken on clocks {tl} (left) and {tr} (right), not {at}: the cameras were held"));
            continue;
        }
        let want = &refs[*c].beats;
        let (Some(first), Some(last)) = (want.first(), want.last()) else { continue };
        let lo = run.out.partition_point(|b| b.clock < tl + first.clock);
        let hi = run.out.partition_point(|b| b.clock <= tl + last.clock + LATE_START_MAX);
        let got: Vec<OutBeat> = run.out[lo..hi].iter().map(|b| OutBeat { clock: b.clock - tl, ..*b }).collect();
        // The whole frame a clock or two later is the same run: its first
        // pixel waited in the register slice while the line before ended.
        let late = got.first().map_or(0, |b| b.clock - first.clock);
        let shifted: Vec<OutBeat> = want.iter().map(|b| OutBeat { clock: b.clock + late, ..*b }).collect();
        if late > LATE_START_MAX || got != shifted {
            let k = got.iter().zip(want.iter()).position(|(a, b)| a != b).unwrap_or(got.len().min(want.len()));
            fail(format!("{} beats where a fresh run gives {}; the first to differ is beat {k}: {:?} against {:?}", got.len(), want.len(), got.get(k), want.get(k)));
        } else {
            report.clean_exact += 1;
            if late > 0 {
                report.clean_late += 1;
            }
        }
    }
    for x in &v {
        *report.violated.entry(x.invariant).or_default() += 1;
        if let Some(check) = x.frame.and_then(|n| checks.iter().find(|k| k.faulty == n)) {
            for f in &check.classes {
                *report.violated_after.entry(f.name()).or_default() += 1;
            }
        }
    }
    report.violations = v;
    Ok(report)
}

/// The clock on which camera `cam` took the beat at `index` of its script,
/// if it was a `tuser` beat and was taken.
fn first_take(run: &BeatRun, cam: usize, index: usize) -> Option<u64> {
    run.user_taken[cam].iter().find(|&&(i, _)| i == index).map(|&(_, c)| c)
}
