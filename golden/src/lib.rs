//! # golden — the floating-point model of the declivity stereo method
//!
//! The specification that runs: A. Bensrhair, P. Miché, R. Debrie, *High Speed
//! Self-Adaptive Algorithms for Implementation in a 3-D Vision Sensor*, with the
//! open points settled as in `DESIGN.md` §2. Every hardware block of the `rtl`
//! crate is checked against this crate. It uses `f64` and plain Rust only.
//!
//! Data flows one way, one module per step:
//!
//! | step | module | paper |
//! |---|---|---|
//! | line → noise σ → threshold `d_t` | [`noise`] | eq. 2 |
//! | line → declivities → characteristic declivities, positions, attributes | [`declivity`] | §II, eq. 3 |
//! | two lines' declivities → nodes and local gains | [`gain`] | eq. 4–8 |
//! | gains → optimal path | [`dp`] | eq. 9 |
//! | path → disparities → dense line | [`disparity`] | §IV |
//! | disparity → 3-D point | [`reconstruct`] | eq. 1 |
//!
//! [`line`](mod@line) chains these for one pair of epipolar lines and [`frame`] for a
//! whole image pair, over all cores with `rayon` (results identical to one
//! thread).

// The docs describe the design down to private items and link to them:
// read them with `cargo doc --document-private-items`.
#![allow(rustdoc::private_intra_doc_links)]

pub mod declivity;
pub mod disparity;
pub mod dp;
pub mod error;
pub mod frame;
pub mod gain;
pub mod hardware;
pub mod line;
pub mod noise;
pub mod params;
pub mod reconstruct;

#[cfg(test)]
mod test_rng;

pub use declivity::Declivity;
pub use error::GoldenError;
pub use frame::{process_frame, FrameResult, GreyImage, Threads};
pub use line::{process_line, LineResult, Match};
pub use params::{ContourSupport, EndRule, Features, Mode, Params, RefView};
