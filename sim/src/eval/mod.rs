//! Evaluation: images and pair folders in ([`io`], the bundled pair in
//! [`bundled`]), scores against ground truth and the diagnosis of failures
//! ([`scores`]), and the pictures ([`pictures`]).

pub mod pictures;
pub mod io;
pub mod bundled;
pub mod scores;
