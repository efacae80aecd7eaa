//! Building the large rtl blocks: rust-hdl builds a block by value, and a
//! matcher of 32 cells of signals does not fit on a default stack, so they
//! are built (and their Verilog generated) on a thread with a large one.

use rtl::matcher::declivity_matcher::{DeclivityMatcher, GainRule};
use rtl::post::depth_stage::{DepthCamera, DepthError};
use rtl::stereo_line_processor::StereoLineProcessor;
use rust_hdl::prelude::*;

/// Stack of the threads that build and generate the large blocks.
const BIG_STACK: usize = 1 << 30;

/// The array sizes the matcher can be generated with (`--cells`): up to
/// the sensor's `N_CELLS` cells of `ROWS_PER_CELL` rows, arrays of fewer
/// than 16 cells dividing 16 (their phases share a word of the choice
/// memory, `rtl::matcher::choice_word`).
pub const MATCHER_CELLS: [usize; 5] = [2, 4, 8, 16, 32];

/// Runs `f` on a thread with [`BIG_STACK`] of stack and returns its result;
/// `what` names the work if it panics.
pub(crate) fn on_big_stack<T: Send + 'static>(what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(BIG_STACK)
        .spawn(f)
        .and_then(|h| h.join().map_err(|_| std::io::Error::other(format!("{what} panicked"))))
        .unwrap_or_else(|e| panic!("{what}: {e}"))
}

/// Builds and connects the matcher of `N` cells for the gain rule `rule`.
pub(crate) fn build_matcher<const N: usize>(rule: GainRule) -> Box<DeclivityMatcher<N>> {
    on_big_stack("building the matcher", move || {
        let mut uut = Box::new(DeclivityMatcher::<N>::new(rule));
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
