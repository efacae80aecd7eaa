//! # rtl — the declivity stereo sensor as cycle-accurate rust-hdl blocks
//!
//! The hardware half of the project (`DESIGN.md` §3): a declivity detector
//! per camera (one pixel per clock, ping-pong line buffer, |ΔI| histogram and
//! median for `d_t`, extrema tracking and the eq. 3 divider), a systolic
//! matcher (one processing element per reference declivity computing eq. 4–9
//! in fixed point), a traceback, an interpolator/depth stage and the top level
//! joining them. Each block generates Verilog that is co-simulated bit-exactly
//! against the Rust model and checked against `golden`.
//!
//! The blocks arrive with their own issues; this crate already depends on
//! `rust-hdl` 0.46 so that the toolchain and the HDL library build in CI.

pub use rust_hdl;
