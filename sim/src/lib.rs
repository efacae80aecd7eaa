//! # sim — what users run
//!
//! Reading images and pair folders ([`io`]), evaluation against ground truth
//! ([`eval`]), the pictures of the paper's figures ([`pictures`]), and the
//! `declivity` command-line tool built on them. Later: cycle-accurate drivers
//! of the `rtl` blocks, co-simulation and synthesis reports.

pub mod bundled;
pub mod cosim;
pub mod depth;
pub mod detector;
pub mod error;
pub mod eval;
pub mod io;
pub mod pictures;
pub mod synth;
pub mod verilog;

pub use error::SimError;
