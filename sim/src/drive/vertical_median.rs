//! Direct drive of the rtl vertical median (`rtl::post::vertical_median`) and its
//! comparison with golden's (`golden::disparity::vertical_median`).
//!
//! A frame is rows of fixed-point disparities (`POS_FRAC_BITS` fraction
//! bits, 0 = none), as the interpolator sends them. golden takes the same
//! values as reals (`d / 16`, exact in `f64`); the median of the same values
//! is the same value, so the two must agree exactly.

use golden::disparity::vertical_median;
use golden::params::MEDIAN_ROWS;
use rtl::params::{MEDIAN_HALF, POS_BITS, POS_FRAC_BITS, W_MAX};
use rtl::rust_hdl::prelude::*;
use rtl::post::vertical_median::VerticalMedian;
use thiserror::Error;

/// A frame the vertical median cannot take.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum MedianInputError {
    /// A frame without rows.
    #[error("a frame without rows")]
    NoRows,
    /// A row of another width than the first, or of no pixel or more than
    /// `W_MAX`.
    #[error("row {row} has {width} pixels, the frame's rows have {want} (1 ..= {W_MAX})")]
    Width { row: usize, width: usize, want: usize },
    /// A disparity beyond `POS_BITS` bits.
    #[error("row {row}, pixel {x}: {d} does not fit {POS_BITS} bits")]
    Value { row: usize, x: usize, d: u64 },
    /// A row period shorter than the rows.
    #[error("a period of {period} clocks is shorter than a row of {width} pixels")]
    Period { period: usize, width: usize },
}

/// One clock's input beat.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MedianBeat {
    pub valid: bool,
    pub d: u64,
    pub last: bool,
    pub sof: bool,
    pub eof: bool,
}

/// One output pixel and the clock it was on `v_*`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MedianPixel {
    pub cycle: u64,
    pub d: u64,
    pub last: bool,
    pub sof: bool,
}

/// When things happened in a [`VerticalMedianSim::run`].
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct MedianTiming {
    /// The clock of each input pixel, by row.
    pub input: Vec<Vec<u64>>,
    /// The clock of each output pixel, by output row.
    pub output: Vec<Vec<u64>>,
    /// `v_sof` of each output row's first pixel.
    pub sof: Vec<bool>,
    /// Clocks on which `overflow` was high.
    pub overflows: u64,
}

/// The vertical median under direct drive.
pub struct VerticalMedianSim {
    uut: Box<VerticalMedian>,
    /// Clocks simulated.
    pub cycle: u64,
    /// Clocks on which `overflow` was high.
    pub overflows: u64,
}

impl Default for VerticalMedianSim {
    fn default() -> Self {
        Self::new()
    }
}

impl VerticalMedianSim {
    pub fn new() -> Self {
        let mut uut = Box::new(VerticalMedian::new());
        uut.connect_all();
        VerticalMedianSim { uut, cycle: 0, overflows: 0 }
    }

    /// One clock: `b` on the inputs; the outputs of that clock (the pixel,
    /// if `v_valid`).
    pub fn clock(&mut self, b: MedianBeat) -> Option<MedianPixel> {
        let u = &mut *self.uut;
        u.clock.next = false.into();
        u.p_valid.next = b.valid;
        u.p_d.next = b.d.into();
        u.p_last.next = b.last;
        u.p_sof.next = b.sof;
        u.p_eof.next = b.eof;
        assert!(simulate(u, 100), "the vertical median's logic did not settle");
        let out = u.v_valid.val().then(|| MedianPixel {
            cycle: self.cycle,
            d: u.v_d.val().index() as u64,
            last: u.v_last.val(),
            sof: u.v_sof.val(),
        });
        self.overflows += u.overflow.val() as u64;
        u.clock.next = true.into();
        assert!(simulate(u, 100), "the vertical median's logic did not settle");
        self.cycle += 1;
        out
    }

    /// The beats, then `tail` idle clocks; every output pixel.
    pub fn run_beats(&mut self, beats: &[MedianBeat], tail: usize) -> Vec<MedianPixel> {
        let idle = std::iter::repeat_n(MedianBeat::default(), tail);
        beats.iter().copied().chain(idle).filter_map(|b| self.clock(b)).collect()
    }

    /// One frame, a row every `period` clocks (its pixels on consecutive
    /// clocks from the row's start, `p_sof` on the first, `p_eof` on the
    /// last row), then idle clocks until the flush is out; the output rows
    /// (split at `v_last`) and when everything happened.
    pub fn run(&mut self, frame: &[Vec<u64>], period: usize) -> Result<(Vec<Vec<u64>>, MedianTiming), MedianInputError> {
        let beats = frame_beats(frame, period)?;
        let start = self.cycle;
        let overflows = self.overflows;
        let width = frame[0].len();
        let input = (0..frame.len()).map(|y| (0..width).map(|x| start + (y * period + x) as u64).collect()).collect();
        let pixels = self.run_beats(&beats, MEDIAN_HALF * width + rtl::post::vertical_median::MEDIAN_LAG + 4);
        let (rows, output, sof) = split_rows(&pixels);
        Ok((rows, MedianTiming { input, output, sof, overflows: self.overflows - overflows }))
    }
}

/// Output pixels split into rows at `v_last`: values, clocks, `v_sof` of
/// each row's first pixel (a row without its `v_last` at the end is kept).
pub fn split_rows(pixels: &[MedianPixel]) -> (Vec<Vec<u64>>, Vec<Vec<u64>>, Vec<bool>) {
    let (mut rows, mut clocks, mut sof) = (Vec::new(), Vec::new(), Vec::new());
    let (mut row, mut at) = (Vec::new(), Vec::new());
    for p in pixels {
        if row.is_empty() {
            sof.push(p.sof);
        }
        row.push(p.d);
        at.push(p.cycle);
        if p.last {
            rows.push(std::mem::take(&mut row));
            clocks.push(std::mem::take(&mut at));
        }
    }
    if !row.is_empty() {
        rows.push(row);
        clocks.push(at);
    }
    (rows, clocks, sof)
}

/// Checks a frame: rows, all of one width `1 ..= W_MAX`, values of
/// `POS_BITS` bits.
fn check_frame(frame: &[Vec<u64>]) -> Result<usize, MedianInputError> {
    let want = frame.first().ok_or(MedianInputError::NoRows)?.len();
    for (row, r) in frame.iter().enumerate() {
        if r.len() != want || want == 0 || want > W_MAX {
            return Err(MedianInputError::Width { row, width: r.len(), want });
        }
        if let Some((x, &d)) = r.iter().enumerate().find(|(_, &d)| d >> POS_BITS != 0) {
            return Err(MedianInputError::Value { row, x, d });
        }
    }
    Ok(want)
}

/// The input beats of one frame, a row every `period` clocks (see
/// [`VerticalMedianSim::run`]).
pub fn frame_beats(frame: &[Vec<u64>], period: usize) -> Result<Vec<MedianBeat>, MedianInputError> {
    let width = check_frame(frame)?;
    if period < width {
        return Err(MedianInputError::Period { period, width });
    }
    let h = frame.len();
    let mut beats = Vec::with_capacity(h * period);
    for (y, r) in frame.iter().enumerate() {
        for (x, &d) in r.iter().enumerate() {
            beats.push(MedianBeat { valid: true, d, last: x + 1 == width, sof: y == 0 && x == 0, eof: y + 1 == h });
        }
        if y + 1 < h {
            beats.extend(std::iter::repeat_n(MedianBeat::default(), period - width));
        }
    }
    Ok(beats)
}

/// golden's vertical median (`MEDIAN_ROWS` rows) of the same fixed-point
/// values, back in `POS_FRAC_BITS` units: the median golden's frame takes
/// in hardware parity (`golden::frame::finish_frame`, step 5) of the
/// interpolator's values `d / 16`, exact in `f64` (a median is one of its
/// inputs).
pub fn golden_median(frame: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, MedianInputError> {
    let width = check_frame(frame)?;
    let unit = (1u64 << POS_FRAC_BITS) as f64;
    let map: Vec<f64> = frame.iter().flatten().map(|&d| d as f64 / unit).collect();
    let mut out = Vec::with_capacity(frame.len());
    for y in 0..frame.len() {
        let mut row = vec![0.0; width];
        vertical_median(&map, width, MEDIAN_ROWS, &mut row, y);
        // Each value is one of the inputs: an exact multiple of 1/16.
        out.push(row.iter().map(|v| (v * unit) as u64).collect());
    }
    Ok(out)
}

/// A dense map (`f64` disparities, 0 = none) in the fixed point the
/// interpolator emits: `round(16·d)`, saturated to `POS_BITS` bits.
pub fn quantise_map(map: &[f64], width: usize) -> Vec<Vec<u64>> {
    let unit = (1u64 << POS_FRAC_BITS) as f64;
    let top = ((1u64 << POS_BITS) - 1) as f64;
    map.chunks(width).map(|r| r.iter().map(|&d| (d * unit).round().clamp(0.0, top) as u64).collect()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_pixel_frame_comes_back_as_it_went_in() {
        let mut sim = VerticalMedianSim::new();
        let (rows, t) = sim.run(&[vec![37]], 1).expect("a frame");
        assert_eq!(rows, vec![vec![37]]);
        assert_eq!(t.overflows, 0);
        assert_eq!(t.sof, vec![true]);
    }

    #[test]
    fn frames_that_do_not_fit_are_refused() {
        assert_eq!(check_frame(&[]), Err(MedianInputError::NoRows));
        assert!(matches!(check_frame(&[vec![1, 2], vec![3]]), Err(MedianInputError::Width { row: 1, .. })));
        assert!(matches!(check_frame(&[vec![1 << POS_BITS]]), Err(MedianInputError::Value { .. })));
        assert!(matches!(frame_beats(&[vec![1, 2]], 1), Err(MedianInputError::Period { .. })));
    }
}
