//! What each command of the `declivity` CLI does, as functions that take
//! their inputs and return their reports (the CLI parses and prints).

pub mod depth;
pub mod rtl_depth;
pub mod eval;
pub mod rtl_detect;
pub mod rtl_match;
