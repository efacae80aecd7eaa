//! Verilog of the rtl blocks, as rust-hdl generates it.

use rtl::matcher::declivity_matcher::{DeclivityMatcher, GainRule};
use rust_hdl::prelude::*;

/// A block that `declivity verilog` and `declivity synth` can generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Top {
    /// The declivity detector of one camera (`rtl::detector::declivity_detector`).
    Detector,
    /// The matcher: systolic array of gain cells and traceback
    /// (`rtl::matcher::declivity_matcher`), N_CELLS = 32 cells of four rows holding
    /// N_MAX = 128 reference declivities unless --cells says otherwise, the
    /// default gain rule (robust).
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

/// The Verilog of `top` (the matcher with `N_CELLS` cells, `N_MAX` rows,
/// and the default gain rule); its top module is named `top`.
pub fn generate(top: Top) -> String {
    generate_with(top, rtl::params::N_CELLS, GainRule::default()).expect("N_CELLS is a supported size")
}

/// The Verilog of `top`, the matcher with `cells` cells (one of
/// [`MATCHER_CELLS`](crate::blocks::MATCHER_CELLS)) and the gain rule `rule`; `None` for another size.
pub fn generate_with(top: Top, cells: usize, rule: GainRule) -> Option<String> {
    match top {
        Top::Detector => {
            let mut uut = rtl::detector::declivity_detector::DeclivityDetector::default();
            uut.connect_all();
            Some(generate_verilog(&uut))
        }
        Top::Interpolator => {
            let mut uut = rtl::post::interpolator::Interpolator::default();
            uut.connect_all();
            Some(mark_memories_no_rw_check(&generate_verilog(&uut)))
        }
        Top::Stereo => match cells {
            2 => Some(stereo_verilog::<2>(rule)),
            4 => Some(stereo_verilog::<4>(rule)),
            8 => Some(stereo_verilog::<8>(rule)),
            16 => Some(stereo_verilog::<16>(rule)),
            32 => Some(stereo_verilog::<32>(rule)),
            _ => None,
        },
        Top::Matcher => match cells {
            2 => Some(matcher_verilog::<2>(rule)),
            4 => Some(matcher_verilog::<4>(rule)),
            8 => Some(matcher_verilog::<8>(rule)),
            16 => Some(matcher_verilog::<16>(rule)),
            32 => Some(matcher_verilog::<32>(rule)),
            _ => None,
        },
    }
}

/// The matcher's Verilog, built on a thread with room for the block (see
/// [`crate::blocks::build_matcher`]).
///
/// Every memory rust-hdl declares in the matcher is marked `no_rw_check`:
/// no read whose data is used is at an address on the clock that address is
/// written (the traceback's stack is written while walking and read while
/// emitting), so Yosys needs no bypass logic behind it. (The record and
/// choice memories are `DP16KD` instances, `rtl::primitives::block_ram`, whose write and
/// read never meet either: the loader writes one bank of the record
/// memories while the engine reads the other; the choice memory is written
/// during the sweep and read during the traceback that follows it. Their
/// rust-hdl models' `RAM` declarations are left in the text unused, and
/// marked too.)
fn matcher_verilog<const N: usize>(rule: GainRule) -> String {
    let uut: Box<DeclivityMatcher<N>> = crate::blocks::build_matcher::<N>(rule);
    let v = crate::blocks::on_big_stack("generating the matcher's Verilog", move || generate_verilog(&*uut));
    mark_memories_no_rw_check(&v)
}

/// The line processor's Verilog (the matcher's rule, the default mode's
/// edge jump), built as [`matcher_verilog`] builds the matcher's.
fn stereo_verilog<const N: usize>(rule: GainRule) -> String {
    let uut = crate::blocks::build_stereo::<N>(rule, Some(rtl::params::EDGE_JUMP_LSB), rtl::post::depth_stage::DepthCamera::default()).expect("the default camera fits");
    let v = crate::blocks::on_big_stack("generating the line processor's Verilog", move || generate_verilog(&*uut));
    mark_memories_no_rw_check(&v)
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
