//! Direct drive of the rtl depth stage (`rtl::post::depth_stage`) and
//! golden's depths of the same fixed-point disparities: its
//! hardware-parity depth stage (`golden::hardware::depth`), which must be
//! equal, and its eq. 1 in f64 (`golden::reconstruct::depth`).
//!
//! A disparity comes in the position format (`POS_FRAC_BITS` fraction
//! bits, 0 = none).

use golden::hardware::depth as parity;
use golden::reconstruct::{depth, Camera};
use rtl::post::depth_stage::{DepthCamera, DepthError, DepthStage};
use rtl::params::POS_FRAC_BITS;
use rtl::rust_hdl::prelude::*;

/// One clock's input beat.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DepthIn {
    pub valid: bool,
    /// Disparity, `POS_FRAC_BITS` fraction bits, below `2^POS_BITS`.
    pub d: u64,
    pub last: bool,
    pub sof: bool,
}

/// One clock's output.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DepthOut {
    pub valid: bool,
    /// Depth in millimetres, 0 = none, 65535 saturated.
    pub z_mm: u16,
    /// The pixel's disparity, as it came in.
    pub d: u64,
    pub last: bool,
    pub sof: bool,
}

/// A run's output: the depths line by line, and when each pixel went in and
/// came out.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DepthRun {
    /// One depth per pixel, line by line (a line ends at `z_last`).
    pub z: Vec<Vec<u16>>,
    /// Every output pixel in order (its disparity and flags).
    pub pixels: Vec<DepthOut>,
    /// Clock of each output pixel.
    pub out_cycles: Vec<u64>,
    /// Clock on which each input pixel was offered.
    pub in_cycles: Vec<u64>,
}

/// The depth stage under direct drive.
pub struct DepthStageSim {
    uut: Box<DepthStage>,
    /// Clocks simulated.
    pub cycle: u64,
}

impl DepthStageSim {
    /// A depth stage built for `camera`.
    pub fn new(camera: DepthCamera) -> Result<Self, DepthError> {
        let mut uut = Box::new(DepthStage::new(camera)?);
        uut.connect_all();
        Ok(DepthStageSim { uut, cycle: 0 })
    }

    /// One clock: `b` on the inputs; returns the outputs of this clock
    /// (before the edge).
    pub fn step(&mut self, b: DepthIn) -> DepthOut {
        let u = &mut *self.uut;
        u.clock.next = false.into();
        u.p_valid.next = b.valid;
        u.p_d.next = b.d.into();
        u.p_last.next = b.last;
        u.p_sof.next = b.sof;
        assert!(simulate(u, 100), "the depth stage's logic did not settle");
        let out = DepthOut {
            valid: u.z_valid.val(),
            z_mm: u.z_mm.val().index() as u16,
            d: u.z_d.val().index() as u64,
            last: u.z_last.val(),
            sof: u.z_sof.val(),
        };
        u.clock.next = true.into();
        assert!(simulate(u, 100), "the depth stage's logic did not settle");
        self.cycle += 1;
        out
    }

    /// Offers `lines` (disparity LSBs per pixel), one pixel per clock, each
    /// line taking at least `period` clocks (idle clocks after its last
    /// pixel), `p_sof` on the first pixel of the first line and `p_last` on
    /// each line's last pixel; collects the output until every pixel has
    /// come out (or a clock limit passes).
    pub fn run(&mut self, lines: &[Vec<u64>], period: usize) -> DepthRun {
        let mut beats = Vec::new();
        for (y, l) in lines.iter().enumerate() {
            for (x, &d) in l.iter().enumerate() {
                beats.push(DepthIn { valid: true, d, last: x + 1 == l.len(), sof: y == 0 && x == 0 });
            }
            beats.extend(std::iter::repeat_n(DepthIn::default(), period.saturating_sub(l.len())));
        }
        let pixels: usize = lines.iter().map(Vec::len).sum();
        let limit = self.cycle + beats.len() as u64 + 64;
        let mut run = DepthRun::default();
        let mut cur = Vec::new();
        let mut k = 0;
        while run.pixels.len() < pixels && self.cycle < limit {
            let b = beats.get(k).copied().unwrap_or_default();
            k += 1;
            let now = self.cycle;
            if b.valid {
                run.in_cycles.push(now);
            }
            let o = self.step(b);
            if o.valid {
                run.pixels.push(o);
                run.out_cycles.push(now);
                cur.push(o.z_mm);
                if o.last {
                    run.z.push(std::mem::take(&mut cur));
                }
            }
        }
        if !cur.is_empty() {
            run.z.push(cur);
        }
        run
    }
}

/// golden's camera of the depth stage: the same focal length and baseline.
pub fn golden_camera(camera: &DepthCamera) -> parity::DepthCamera {
    parity::DepthCamera { focal_px: camera.focal_px, baseline_mm: camera.baseline_mm }
}

/// golden's hardware-parity depth stage for `camera`
/// (`golden::hardware::depth::DepthStage`), in the `sd` configuration this
/// driver's block is.
pub fn golden_stage(camera: &DepthCamera) -> Result<parity::DepthStage, parity::DepthRangeError> {
    parity::DepthStage::new(&golden_camera(camera), crate::config::Config::Sd.limits())
}

/// golden's hardware-parity depth in millimetres of the disparity `d_lsb`
/// (`POS_FRAC_BITS` fraction bits) for `camera`, as the stage outputs it
/// (0 = none, 65535 = that far or farther).
///
/// # Panics
/// If the camera is outside the stage's range (no stage is built for it).
pub fn golden_depth_mm(d_lsb: u64, camera: &DepthCamera) -> u16 {
    golden_stage(camera).expect("a camera in the stage's range").depth_mm(d_lsb as u32)
}

/// golden's eq. 1 in `f64`, in millimetres, of the disparity `d_lsb`
/// (`POS_FRAC_BITS` fraction bits, `d = D / 16` px) for `camera`; `None`
/// for 0.
pub fn golden_eq1_mm(d_lsb: u64, camera: &DepthCamera) -> Option<f64> {
    let cam = Camera { focal_px: camera.focal_px, baseline_m: camera.baseline_mm / 1000.0, cx: 0.0, cy: 0.0 };
    depth(d_lsb as f64 / (1u64 << POS_FRAC_BITS) as f64, &cam).map(|z| z * 1000.0)
}

