//! # rtl — the declivity stereo sensor as cycle-accurate rust-hdl blocks
//!
//! The hardware half of the project (`DESIGN.md` §3): a declivity detector
//! per camera (one pixel per clock, ping-pong line buffer, |ΔI| histogram and
//! median for `d_t`, extrema tracking and the eq. 3 divider), a systolic
//! matcher (processing elements of two reference declivities each computing
//! eq. 4–9 in fixed point), a traceback, an interpolator/depth stage and the top level
//! joining them. Each block generates Verilog that is co-simulated bit-exactly
//! against the Rust model and checked against `golden`.
//!
//! Conventions in every block: one clock input `clock`, no reset (registers
//! start from their Verilog `initial` values, which rust-hdl writes), and
//! arithmetic whose operands and result have the same width, so that Verilog's
//! context-sized expressions compute exactly what the Rust simulation does.

pub mod params;
pub mod pixel_window;
pub mod skid_buffer;
pub mod adaptive_threshold;
pub mod declivity_detector;
pub mod declivity_tracker;
pub mod position_divider;
pub mod gain_cell;
pub mod systolic_matcher;
pub mod choice_word;
pub mod traceback;
pub mod block_ram;
pub mod lut_ram;
pub mod logic_rom;
pub mod dsp_multiplier;
pub mod record_input;
pub mod record_memory;
pub mod declivity_matcher;
pub mod record_fifo;
pub mod interpolator;
pub mod stereo_line_processor;
pub mod row_check;
pub mod neighbour_window;
pub mod vertical_median;
pub mod depth_stage;

pub use rust_hdl;

/// One clock of a block under direct drive in the unit tests: rising edge,
/// settle, falling edge, settle.
#[cfg(test)]
pub(crate) fn tick<B: rust_hdl::prelude::Block>(uut: &mut B, clock: fn(&mut B) -> &mut rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock>) {
    use rust_hdl::prelude::*;
    clock(uut).next = Clock::from(true);
    assert!(simulate(uut, 100), "settles");
    clock(uut).next = Clock::from(false);
    assert!(simulate(uut, 100), "settles");
}
