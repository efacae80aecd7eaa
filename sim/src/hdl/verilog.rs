//! Verilog of the rtl blocks, as rust-hdl generates it.

use rtl::matcher::declivity_matcher::GainRule;
use rtl::post::depth_stage::DepthCamera;

use crate::config::Config;
use crate::SimError;

/// A block that `declivity verilog` and `declivity synth` can generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Top {
    /// The declivity detector of one camera (`rtl::detector::declivity_detector`).
    Detector,
    /// The matcher: systolic array of gain cells and traceback
    /// (`rtl::matcher::declivity_matcher`), the configuration's N_CELLS
    /// cells of four rows holding its N_MAX reference declivities unless
    /// --cells says otherwise, the default gain rule (robust).
    Matcher,
    /// The interpolator (`rtl::post::interpolator`): a line's matches in, one
    /// disparity per pixel per clock out, the default mode's edge jump.
    Interpolator,
    /// The whole line processor (`rtl::stereo_line_processor`): two
    /// detectors, the record queues, the matcher (--cells), the row check,
    /// the interpolator, the vertical median and the depth stage (its
    /// camera: --focal-px, --baseline-m).
    Stereo,
}

impl Top {
    /// Name used for files.
    pub fn name(self) -> &'static str {
        match self {
            Top::Detector => "detector",
            Top::Matcher => "matcher",
            Top::Interpolator => "interpolator",
            Top::Stereo => "stereo",
        }
    }
}

/// What the Verilog is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Target {
    /// The Lattice ECP5: `DP16KD`, `MULT18X18D`, `TRELLIS_DPR16X4` and
    /// (the line processor's reset) `DCCA` instantiated by name (the
    /// measured and timed target).
    #[default]
    Ecp5,
    /// Any FPGA or ASIC flow: each primitive replaced by its behavioural
    /// model (memories with registered reads, `*`), renamed into the block
    /// (`top$DP16KD`, …), which Yosys, Vivado and Quartus infer.
    Generic,
}

impl Target {
    /// Its name on the command line (`ecp5`, `generic`).
    pub fn name(self) -> &'static str {
        match self {
            Target::Ecp5 => "ecp5",
            Target::Generic => "generic",
        }
    }

    /// `design` as [`generate_block`] writes it (for the ECP5), written
    /// for this target.
    pub fn retarget(self, design: String) -> String {
        match self {
            Target::Ecp5 => design,
            Target::Generic => crate::hdl::primitives::to_generic(&design),
        }
    }
}

/// What a block is generated with besides its configuration: the
/// matcher's cells and gain rule (`matcher`, `stereo`), the depth stage's
/// camera (`stereo`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Generation {
    /// Gain cells of the matcher (one of [`Config::matcher_cells`]).
    pub cells: usize,
    pub rule: GainRule,
    /// The camera pair whose eq. 1 the depth stage's table holds.
    pub camera: DepthCamera,
}

impl Generation {
    /// The sensor of `config`: its `N_CELLS` cells, the default gain rule,
    /// the default camera ([`DepthCamera::default`]).
    pub fn of(config: Config) -> Self {
        Generation { cells: config.sizes().cells, rule: GainRule::default(), camera: DepthCamera::default() }
    }
}

/// A camera as reports give it (`declivity synth`, `rtl depth`, the IP
/// folder's README).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CameraReport {
    /// Focal length in pixels (`f / p`).
    pub focal_px: f64,
    /// Baseline in millimetres.
    pub baseline_mm: f64,
}

impl From<DepthCamera> for CameraReport {
    fn from(c: DepthCamera) -> Self {
        CameraReport { focal_px: c.focal_px, baseline_mm: c.baseline_mm }
    }
}

impl std::fmt::Display for CameraReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "focal length {} px, baseline {} mm", self.focal_px, self.baseline_mm)
    }
}

/// The Verilog of `top` in `config` (the matcher with the configuration's
/// `N_CELLS` cells, `N_MAX` rows, and the default gain rule); its top
/// module is named `top`.
pub fn generate(config: Config, top: Top) -> String {
    generate_block(config, top, &Generation::of(config)).expect("the sensor's generation parameters are supported")
}

/// The Verilog of `top` in `config`, the matcher with `cells` cells (one
/// of [`Config::matcher_cells`]) and the gain rule `rule`, the default
/// camera; `None` for another size.
pub fn generate_with(config: Config, top: Top, cells: usize, rule: GainRule) -> Option<String> {
    generate_block(config, top, &Generation { cells, rule, ..Generation::of(config) }).ok()
}

/// The Verilog of `top` in `config` with the parameters `g`; an error
/// names a matcher size the configuration does not generate, or a camera
/// whose depths the depth stage cannot hold (`DepthScale::of`).
pub fn generate_block(config: Config, top: Top, g: &Generation) -> Result<String, SimError> {
    if top == Top::Stereo {
        check_camera(config, &g.camera)?;
    }
    let v = match config {
        Config::Sd => sd::generate_with(top, g),
        Config::Hd => hd::generate_with(top, g),
    };
    v.ok_or_else(|| SimError::Argument(format!("--cells {}: the {config} matcher is generated with {:?} cells", g.cells, config.matcher_cells())))
}

/// Checks that `config`'s depth stage can hold `camera`'s depths
/// (`DepthScale::of` of its crate): an error names why not.
pub fn check_camera(config: Config, camera: &DepthCamera) -> Result<(), SimError> {
    let why = match config {
        Config::Sd => rtl::post::depth_stage::DepthScale::of(camera).err().map(|e| e.to_string()),
        Config::Hd => {
            let c = rtl_hd::post::depth_stage::DepthCamera { focal_px: camera.focal_px, baseline_mm: camera.baseline_mm };
            rtl_hd::post::depth_stage::DepthScale::of(&c).err().map(|e| e.to_string())
        }
    };
    why.map_or(Ok(()), |why| Err(SimError::Argument(format!("the depth stage's camera: {why}"))))
}

/// The generators of one configuration's crate `$k`, for the matcher sizes
/// `$n` (the same code for every configuration: only the crate differs).
macro_rules! generators {
    ($k:ident, [$($n:literal),*]) => {
        use $k::matcher::declivity_matcher::{DeclivityMatcher, GainRule as Rule};
        use $k::stereo_line_processor::StereoLineProcessor;
        use rust_hdl::prelude::*;

        use super::{mark_memories_no_rw_check, Generation, Top};
        use crate::blocks::{build_block, on_big_stack};

        /// The rule in this configuration's type.
        fn rule_of(rule: rtl::matcher::declivity_matcher::GainRule) -> Rule {
            match rule {
                rtl::matcher::declivity_matcher::GainRule::Paper => Rule::Paper,
                rtl::matcher::declivity_matcher::GainRule::Robust => Rule::Robust,
            }
        }

        /// The Verilog of `top` with `g` (its camera checked by the
        /// caller); `None` for a matcher size not generated.
        pub(super) fn generate_with(top: Top, g: &Generation) -> Option<String> {
            let rule = rule_of(g.rule);
            match top {
                Top::Detector => {
                    let mut uut = $k::detector::declivity_detector::DeclivityDetector::default();
                    uut.connect_all();
                    Some(generate_verilog(&uut))
                }
                Top::Interpolator => {
                    let mut uut = $k::post::interpolator::Interpolator::default();
                    uut.connect_all();
                    Some(mark_memories_no_rw_check(&generate_verilog(&uut)))
                }
                Top::Stereo => {
                    let camera = $k::post::depth_stage::DepthCamera { focal_px: g.camera.focal_px, baseline_mm: g.camera.baseline_mm };
                    match g.cells {
                        $($n => Some(stereo_verilog::<$n>(rule, camera)),)*
                        _ => None,
                    }
                }
                Top::Matcher => match g.cells {
                    $($n => Some(matcher_verilog::<$n>(rule)),)*
                    _ => None,
                },
            }
        }

        /// The matcher's Verilog, built on a thread with room for the block
        /// (see [`crate::blocks::build_block`]).
        ///
        /// Every memory rust-hdl declares in the matcher is marked
        /// `no_rw_check`: no read whose data is used is at an address on the
        /// clock that address is written (the traceback's stack is written
        /// while walking and read while emitting), so Yosys needs no bypass
        /// logic behind it. (The record and choice memories are `DP16KD`
        /// instances, `rtl::primitives::block_ram`, whose write and read
        /// never meet either: the loader writes one bank of the record
        /// memories while the engine reads the other; the choice memory is
        /// written during the sweep and read during the traceback that
        /// follows it. Their rust-hdl models' `RAM` declarations are left in
        /// the text unused, and marked too.)
        fn matcher_verilog<const N: usize>(rule: Rule) -> String {
            let uut = build_block("building the matcher", move || DeclivityMatcher::<N>::new(rule));
            let v = on_big_stack("generating the matcher's Verilog", move || generate_verilog(&*uut));
            mark_memories_no_rw_check(&v)
        }

        /// The line processor's Verilog (the matcher's rule, the default
        /// mode's edge jump, `camera`, which the caller has checked), built
        /// as [`matcher_verilog`] builds the matcher's.
        fn stereo_verilog<const N: usize>(rule: Rule, camera: $k::post::depth_stage::DepthCamera) -> String {
            let uut = build_block("building the line processor", move || {
                StereoLineProcessor::<N>::new(rule, Some($k::params::EDGE_JUMP_LSB), camera).expect("the camera was checked")
            });
            let v = on_big_stack("generating the line processor's Verilog", move || generate_verilog(&*uut));
            mark_memories_no_rw_check(&v)
        }
    };
}

/// The `sd` configuration's generators (`rtl`).
mod sd {
    generators!(rtl, [2, 4, 8, 16, 32]);
}

/// The `hd` configuration's generators (`rtl-hd`).
mod hd {
    generators!(rtl_hd, [2, 4, 8, 16, 32, 64]);
}

/// `v` with the attribute `(* no_rw_check *)` on each memory rust-hdl's
/// `RAM` declares (`reg[W:0] mem[D:0];`).
fn mark_memories_no_rw_check(v: &str) -> String {
    let mut out = String::with_capacity(v.len() + 4096);
    for line in v.lines() {
        let t = line.trim_start();
        if t.starts_with("reg[") && t.contains("] mem[") {
            out.push_str(&line[..line.len() - t.len()]);
            out.push_str("(* no_rw_check *) ");
            out.push_str(t);
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}
