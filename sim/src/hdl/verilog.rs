//! Verilog of the rtl blocks, as rust-hdl generates it.

use rtl::matcher::declivity_matcher::GainRule;

use crate::config::Config;

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
    /// the interpolator, the vertical median and the depth stage (the
    /// default camera).
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

/// The Verilog of `top` in `config` (the matcher with the configuration's
/// `N_CELLS` cells, `N_MAX` rows, and the default gain rule); its top
/// module is named `top`.
pub fn generate(config: Config, top: Top) -> String {
    generate_with(config, top, config.sizes().cells, GainRule::default()).expect("N_CELLS is a supported size")
}

/// The Verilog of `top` in `config`, the matcher with `cells` cells (one
/// of [`Config::matcher_cells`]) and the gain rule `rule`; `None` for
/// another size.
pub fn generate_with(config: Config, top: Top, cells: usize, rule: GainRule) -> Option<String> {
    match config {
        Config::Sd => sd::generate_with(top, cells, rule),
        Config::Hd => hd::generate_with(top, cells, rule),
    }
}

/// The generators of one configuration's crate `$k`, for the matcher sizes
/// `$n` (the same code for every configuration: only the crate differs).
macro_rules! generators {
    ($k:ident, [$($n:literal),*]) => {
        use $k::matcher::declivity_matcher::{DeclivityMatcher, GainRule as Rule};
        use $k::stereo_line_processor::StereoLineProcessor;
        use rust_hdl::prelude::*;

        use super::{mark_memories_no_rw_check, Top};
        use crate::blocks::{build_block, on_big_stack};

        /// The rule in this configuration's type.
        fn rule_of(rule: rtl::matcher::declivity_matcher::GainRule) -> Rule {
            match rule {
                rtl::matcher::declivity_matcher::GainRule::Paper => Rule::Paper,
                rtl::matcher::declivity_matcher::GainRule::Robust => Rule::Robust,
            }
        }

        pub(super) fn generate_with(top: Top, cells: usize, rule: rtl::matcher::declivity_matcher::GainRule) -> Option<String> {
            let rule = rule_of(rule);
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
                Top::Stereo => match cells {
                    $($n => Some(stereo_verilog::<$n>(rule)),)*
                    _ => None,
                },
                Top::Matcher => match cells {
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
        /// mode's edge jump, the default camera), built as
        /// [`matcher_verilog`] builds the matcher's.
        fn stereo_verilog<const N: usize>(rule: Rule) -> String {
            let camera = $k::post::depth_stage::DepthCamera::default();
            let uut = build_block("building the line processor", move || {
                StereoLineProcessor::<N>::new(rule, Some($k::params::EDGE_JUMP_LSB), camera).expect("the default camera fits")
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
