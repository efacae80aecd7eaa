//! # sim — what users run, as a library
//!
//! The `declivity` binary (crate `cli`) is a thin layer over this crate.
//! Its modules form layers; each uses only the layers listed before it:
//!
//! 1. [`config`]: the line processor's configurations and their sizes;
//!    [`formats`]: golden's real values in the hardware's fixed-point
//!    formats; [`blocks`]: building the large rtl blocks; [`rng`]: the
//!    seeded generator of test lines and vectors.
//! 2. [`drive`]: the rtl blocks under direct drive, clock by clock, with real
//!    lines, and the comparisons of each with golden.
//! 3. [`hdl`]: the blocks' Verilog, the simulation models of the primitives
//!    it instantiates, co-simulation under Icarus and Verilator, lint, and
//!    synthesis for the ECP5.
//! 4. [`budget`]: the latency budget of the line processor from the blocks'
//!    cycle formulas.
//! 5. [`eval`]: images and pair folders, scores against ground truth,
//!    failure diagnosis, pictures; [`error`]: the library's error.
//! 6. [`jobs`]: what each command of the CLI does, as functions that take
//!    their inputs and return their reports.

// The docs describe the design down to private items and link to them:
// read them with `cargo doc --document-private-items`.
#![allow(rustdoc::private_intra_doc_links)]

pub mod config;
pub mod formats;
pub mod blocks;
pub mod rng;
pub mod drive;
pub mod hdl;
pub mod budget;
pub mod eval;
pub mod error;
pub mod jobs;

pub use config::Config;
pub use error::SimError;
