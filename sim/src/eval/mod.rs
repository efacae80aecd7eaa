//! Evaluation: images and pair folders in ([`io`], the bundled pair in
//! [`bundled`]), scores against ground truth and the diagnosis of failures
//! ([`scores`]), the pictures ([`pictures`]), and pairs up-scaled to HD
//! widths ([`upscale`]).

pub mod pictures;
pub mod io;
pub mod bundled;
pub mod scores;
pub mod upscale;
