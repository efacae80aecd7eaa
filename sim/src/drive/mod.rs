//! The rtl blocks under direct drive: inputs set, logic settled, outputs
//! sampled, clock by clock, with real lines and frames; each driver also
//! gives what golden computes for the same inputs, to compare with.

pub mod detector;
pub mod matcher;
pub mod row_check;
pub mod interpolator;
pub mod vertical_median;
pub mod depth_stage;
pub mod stereo;

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
