//! Formal proofs of the stream blocks (`sim::hdl::formal`): the generated
//! Verilog with its contract spliced in, proven by k-induction with
//! SymbiYosys, and the same proof failing on slices changed to break the
//! contract (so that a pass means something).

use rtl::params::PIXEL_BITS;
use rtl::stream::skid_buffer::SkidBuffer;
use sim::hdl::formal::{prove, with_properties, Outcome, SKID_BUFFER_PROPERTIES};

/// Basecase and induction depth: the slice holds two beats, and a beat
/// reaches the skid register and leaves it within four clocks, so six
/// covers every state the queue can be in with a clock to spare.
const DEPTH: usize = 6;

fn skid_buffer() -> String {
    sim::hdl::cosim::verilog_of(SkidBuffer::<PIXEL_BITS>::default())
}

fn proof_of(design: &str) -> sim::hdl::formal::Proof {
    let spliced = with_properties(design, SKID_BUFFER_PROPERTIES, &[("WIDTH", PIXEL_BITS)]).expect("module top");
    prove(&spliced, DEPTH).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn camera_register_slice_keeps_every_beat_in_order_and_the_axi_stream_rules_proven_by_k_induction() {
    let p = proof_of(&skid_buffer());
    eprintln!("{p:?}");
    assert_eq!(p.outcome, Outcome::Pass, "{p:?}");
}

/// Three slices that break the contract, each caught from the initial state:
/// always ready (a beat overwrites the skid register), the skid register's
/// beat dropped for the camera's, the skid register never emptied.
#[test]
fn the_proof_fails_on_slices_that_lose_reorder_or_stall_beats() {
    let good = skid_buffer();
    for (from, to) in [
        ("s_tready = ~k_valid$q;", "s_tready = 1'b1;"),
        ("o_data$d = k_data$q;", "o_data$d = s_tdata;"),
        ("k_valid$d = 1'b0;", "k_valid$d = k_valid$q;"),
    ] {
        assert!(good.contains(from), "the generated slice has `{from}`");
        let p = proof_of(&good.replacen(from, to, 1));
        eprintln!("{to}: {p:?}");
        assert_eq!(p.outcome, Outcome::Fail, "`{from}` → `{to}` must fail: {p:?}");
        assert!(!p.failed_asserts.is_empty(), "{p:?}");
        if let Some(d) = p.workdir {
            let _ = std::fs::remove_dir_all(d);
        }
    }
}
