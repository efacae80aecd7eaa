//! Direct drive of the rtl interpolator (`rtl::post::interpolator`) and its
//! comparison with golden's hardware-parity interpolation
//! (`golden::hardware::interpolate`).
//!
//! A line's anchors are the matcher's outputs: the reference position and
//! the disparity, both with `POS_FRAC_BITS` fraction bits. golden's parity
//! interpolator takes the same fixed-point anchors and computes what the
//! hardware computes, so the two are equal on every pixel.

use golden::hardware::interpolate;
use golden::hardware::row_check::FixedMatch;
use rtl::post::interpolator::Interpolator;
use rtl::params::{EDGE_JUMP_LSB, W_MAX};
use rtl::rust_hdl::prelude::*;

/// One fixed-point anchor: the position `X` and the disparity, both with
/// `POS_FRAC_BITS` fraction bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FixedAnchor {
    pub x: u32,
    pub d: u32,
}

/// A line's matches as the interpolator takes them.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct AnchorLine {
    /// Anchors by strictly increasing `x`, every `x < 16 · width`.
    pub anchors: Vec<FixedAnchor>,
    /// Pixels of the line, `1 ..= W_MAX`.
    pub width: usize,
    /// The line starts a frame.
    pub sof: bool,
}

/// A line of pixels as the interpolator sent it.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PixelLine {
    /// One disparity per pixel, `POS_FRAC_BITS` fraction bits, 0 = none.
    pub d: Vec<u32>,
    /// `p_empty` of its pixels (all alike).
    pub empty: bool,
    /// `p_sof` on its first pixel.
    pub sof: bool,
    /// Clock of its first and last pixel.
    pub first_cycle: u64,
    pub last_cycle: u64,
}

/// The interpolator under direct drive.
pub struct InterpolatorSim {
    uut: Box<Interpolator>,
    /// Clocks simulated.
    pub cycle: u64,
    /// Clocks on which `overflow` was high.
    pub overflows: u64,
}

/// One clock's input beat: an anchor (`x`, `d`) or, with `last`, a line's
/// marker (`width`, `sof`); nothing when `valid` is low.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Beat {
    pub valid: bool,
    pub last: bool,
    pub x: u32,
    pub d: u32,
    pub width: usize,
    pub sof: bool,
}

/// One clock's output.
#[derive(Debug, Clone, Copy)]
struct Pixel {
    d: u32,
    last: bool,
    sof: bool,
    empty: bool,
}

impl InterpolatorSim {
    /// An interpolator with edge jump `jump` (`POS_FRAC_BITS` fixed point;
    /// `None` bridges every pair of matches).
    pub fn new(jump: Option<u64>) -> Self {
        let mut uut = Box::new(Interpolator::new(jump));
        uut.connect_all();
        InterpolatorSim { uut, cycle: 0, overflows: 0 }
    }

    /// The default mode's interpolator (edge jump `EDGE_JUMP_LSB`).
    pub fn robust() -> Self {
        Self::new(Some(EDGE_JUMP_LSB))
    }

    fn clock(&mut self, b: Beat) -> Option<Pixel> {
        let u = &mut *self.uut;
        u.clock.next = false.into();
        u.a_valid.next = b.valid;
        u.a_last.next = b.last;
        u.a_x.next = (b.x as u64).into();
        u.a_d.next = (b.d as u64).into();
        u.a_width.next = (b.width as u64).into();
        u.a_sof.next = b.sof;
        assert!(simulate(u, 100), "the interpolator's logic did not settle");
        let out = u.p_valid.val().then(|| Pixel {
            d: u.p_d.val().index() as u32,
            last: u.p_last.val(),
            sof: u.p_sof.val(),
            empty: u.p_empty.val(),
        });
        self.overflows += u.overflow.val() as u64;
        u.clock.next = true.into();
        assert!(simulate(u, 100), "the interpolator's logic did not settle");
        self.cycle += 1;
        out
    }

    /// Offers the lines' anchors and markers, one beat per clock, each line
    /// taking at least `period` clocks (idle clocks after its marker; a
    /// sensor's lines come one per line period), and collects the pixel
    /// lines until every offered line has come out (dropped lines, counted
    /// in `overflows`, do not); returns the lines and the clock of each
    /// marker.
    pub fn run(&mut self, lines: &[AnchorLine], period: usize) -> (Vec<PixelLine>, Vec<u64>) {
        let (beats, marker_at) = beats(lines, period);
        let (start, dropped_before) = (self.cycle, self.overflows);
        let pixels: usize = lines.iter().map(|l| l.width).sum();
        let limit = self.cycle + beats.len() as u64 + pixels as u64 + 64;
        let mut out: Vec<PixelLine> = Vec::new();
        let mut cur = PixelLine::default();
        let mut k = 0usize;
        while self.cycle < limit && out.len() + ((self.overflows - dropped_before) as usize) < lines.len() {
            let b = beats.get(k).copied().unwrap_or_default();
            k += 1;
            let now = self.cycle;
            if let Some(p) = self.clock(b) {
                if cur.d.is_empty() {
                    cur.first_cycle = now;
                    cur.sof = p.sof;
                    cur.empty = p.empty;
                }
                cur.d.push(p.d);
                if p.last {
                    cur.last_cycle = now;
                    out.push(std::mem::take(&mut cur));
                }
            }
        }
        (out, marker_at.into_iter().map(|m| start + m as u64).collect())
    }
}

/// The input beats of `lines`, each line taking at least `period` clocks
/// (see [`InterpolatorSim::run`]), and the index of each line's marker.
fn beats(lines: &[AnchorLine], period: usize) -> (Vec<Beat>, Vec<usize>) {
    let timed: Vec<(&AnchorLine, usize)> = lines.iter().map(|l| (l, period)).collect();
    timed_beats(&timed)
}

/// [`beats`] with a period of its own for each line.
pub(crate) fn timed_beats(lines: &[(&AnchorLine, usize)]) -> (Vec<Beat>, Vec<usize>) {
    let mut beats: Vec<Beat> = Vec::new();
    let mut marker_at: Vec<usize> = Vec::with_capacity(lines.len());
    for &(l, period) in lines {
        for a in &l.anchors {
            beats.push(Beat { valid: true, x: a.x, d: a.d, ..Beat::default() });
        }
        marker_at.push(beats.len());
        beats.push(Beat { valid: true, last: true, width: l.width, sof: l.sof, ..Beat::default() });
        beats.extend(std::iter::repeat_n(Beat::default(), period.saturating_sub(l.anchors.len() + 1)));
    }
    (beats, marker_at)
}

/// golden's hardware-parity interpolation (`golden::hardware::interpolate`,
/// ends held, edge jump `jump` in `POS_FRAC_BITS` fixed point) of the same
/// anchors: one disparity per pixel in `POS_FRAC_BITS` units, 0 = none.
pub fn golden_line(line: &AnchorLine, jump: Option<u64>) -> Vec<u32> {
    let limits = crate::config::Config::Sd.limits();
    let interpolator = interpolate::Interpolator::new(limits, jump.map(|j| j as u32));
    let matches: Vec<FixedMatch> = line.anchors.iter().map(|a| FixedMatch { x: a.x, d: a.d }).collect();
    let mut out = vec![0u16; line.width];
    interpolator.row(&matches, &mut out);
    out.into_iter().map(u32::from).collect()
}

/// The anchors the matcher would emit for golden's matches of a line: the
/// reference and other positions as the detector quantises them (`⌊16·X⌋`)
/// and their difference. Lines wider than `W_MAX` keep their first `W_MAX`
/// pixels, as the hardware does.
pub fn fixed_anchors(matches: &[golden::line::Match], width: usize, sof: bool) -> AnchorLine {
    let anchors = matches
        .iter()
        .map(|m| {
            let (x, o) = (crate::formats::position_lsb(m.x_ref), crate::formats::position_lsb(m.x_other));
            FixedAnchor { x, d: x - o }
        })
        .collect();
    AnchorLine { anchors, width: width.min(W_MAX), sof }
}
