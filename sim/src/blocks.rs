//! Building the large rtl blocks: rust-hdl builds a block by value, and a
//! matcher of 32 cells of signals does not fit on a default stack, so they
//! are built (and their Verilog generated) on a thread with a large one.

use rtl::matcher::declivity_matcher::GainRule;
use rtl::post::depth_stage::{DepthCamera, DepthError};
use rtl::stereo_line_processor::StereoLineProcessor;
use rust_hdl::prelude::*;

/// Stack of the threads that build and generate the large blocks.
const BIG_STACK: usize = 1 << 30;

/// Runs `f` on a thread with [`BIG_STACK`] of stack and returns its result;
/// `what` names the work if it panics.
pub(crate) fn on_big_stack<T: Send + 'static>(what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(BIG_STACK)
        .spawn(f)
        .and_then(|h| h.join().map_err(|_| std::io::Error::other(format!("{what} panicked"))))
        .unwrap_or_else(|e| panic!("{what}: {e}"))
}

/// Builds a block with `make` on a thread with [`BIG_STACK`] of stack and
/// connects it; `what` names the work if it panics.
pub(crate) fn build_block<B: Block + Send + 'static>(what: &str, make: impl FnOnce() -> B + Send + 'static) -> Box<B> {
    on_big_stack(what, move || {
        let mut uut = Box::new(make());
        uut.connect_all();
        uut
    })
}

/// Builds and connects the line processor: the matcher of `N` cells for
/// `rule`, the interpolator's edge jump `jump`, the depth stage for
/// `camera`.
pub(crate) fn build_stereo<const N: usize>(rule: GainRule, jump: Option<u64>, camera: DepthCamera) -> Result<Box<StereoLineProcessor<N>>, DepthError> {
    on_big_stack("building the line processor", move || {
        let mut uut = Box::new(StereoLineProcessor::<N>::new(rule, jump, camera)?);
        uut.connect_all();
        Ok(uut)
    })
}
