//! # sim — what users run
//!
//! Reading images and pair folders ([`io`]), evaluation against ground truth
//! ([`eval`]), the pictures of the paper's figures ([`pictures`]), the
//! cycle-accurate direct drive of the rtl declivity detector and its
//! comparison with golden ([`detector`]), the same for the matcher
//! ([`matcher`]) and the interpolator ([`interpolator`]), the latency budget
//! ([`budget`]), the Verilog of the blocks
//! ([`verilog`]), co-simulation under Icarus and Verilator ([`cosim`]),
//! ECP5 synthesis reports ([`synth`]), and the `declivity` command-line tool
//! built on them.

pub mod budget;
pub mod bundled;
pub mod cosim;
pub mod depth;
pub mod depth_stage;
pub mod detector;
pub mod error;
pub mod eval;
pub mod interpolator;
pub mod io;
pub mod matcher;
pub mod matcher_cosim;
pub mod pictures;
pub mod primitives;
pub mod row_check;
pub mod stereo;
pub mod synth;
pub mod verilog;
pub mod vertical_median;
pub mod workdir;

pub use error::SimError;
