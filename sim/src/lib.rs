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
pub mod stereo_cosim;
pub mod synth;
pub mod verilog;
pub mod vertical_median;
pub mod workdir;

pub use error::SimError;

/// Stack of the threads that build and generate the large blocks: rust-hdl
/// builds a block by value, and 32 cells of signals do not fit on a default
/// stack.
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

/// Settles a block under direct drive: `passes` evaluations of every block
/// without asking whether anything changed (rust-hdl's `simulate` asks
/// after each, a walk over the whole design), then `simulate` for at most
/// `limit` rounds until nothing changes. Extra passes over settled logic
/// change nothing, so the result is the same. `what` names the block if it
/// does not settle.
pub(crate) fn settle_block<B: rust_hdl::prelude::Block>(u: &mut B, passes: usize, limit: usize, what: &str) {
    for _ in 0..passes {
        u.update_all();
    }
    assert!(rust_hdl::prelude::simulate(u, limit), "{what}'s logic did not settle");
}
