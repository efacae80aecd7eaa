//! # rtl — the declivity stereo sensor as cycle-accurate rust-hdl blocks
//!
//! The hardware half of the project (`DESIGN.md` §3), one block per file,
//! grouped by pipeline stage:
//!
//! - [`stream`]: the cameras' register slices and the record queues;
//! - [`detector`]: a declivity detector per camera (one pixel per clock,
//!   ping-pong line buffer, |ΔI| histogram and median for `d_t`, extrema
//!   tracking and the eq. 3 divider);
//! - [`matcher`]: a systolic array of gain cells, each holding
//!   [`params::ROWS_PER_CELL`] reference declivities and computing eq. 4–9
//!   in fixed point, and the traceback of the optimal path;
//! - [`post`]: the row check, the interpolator, the vertical median and the
//!   depth stage;
//! - [`primitives`]: block RAM, LUT RAM, logic ROM and DSP multipliers;
//! - [`stereo_line_processor`]: the top level joining them;
//! - [`params`]: the generation-time sizes and fixed-point formats, derived
//!   from the [`config`]uration.
//!
//! Each block generates Verilog that is co-simulated bit-exactly against the
//! Rust model and checked against `golden`.
//!
//! Conventions in every block: one clock input `clock`; one synchronous,
//! active-high `reset` that returns every register to its Verilog `initial`
//! value, the value after configuration (`primitives::reset_register`); and
//! arithmetic whose operands and result have the same width, so that Verilog's
//! context-sized expressions compute exactly what the Rust simulation does.

// The docs describe the design down to private items and link to them:
// read them with `cargo doc --document-private-items`.
#![allow(rustdoc::private_intra_doc_links)]

/// The configuration this crate is built for: `sd` (lines up to 1024
/// pixels, 128 declivities each).
#[path = "config/sd.rs"]
pub mod config;
include!("blocks.rs");
