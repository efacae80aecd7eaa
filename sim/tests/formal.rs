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
fn the_proof_fails_on_slices_that_lose_reorder_or_stall_beats_or_forget_the_reset() {
    check_broken(
        &skid_buffer(),
        &[
            ("s_tready = ~k_valid$q;", "s_tready = 1'b1;", Outcome::Fail),
            ("o_data$d = k_data$q;", "o_data$d = s_tdata;", Outcome::Fail),
            ("k_valid$d = 1'b0;", "k_valid$d = k_valid$q;", Outcome::Fail),
            // A reset that forgets the skid register.
            ("k_valid$reset = reset;", "k_valid$reset = 1'b0;", Outcome::Fail),
        ],
        proof_of,
    );
}

/// Each `(from, to, outcome)`: `good` with `from` replaced by `to`, proven
/// by `proof`, ends in `outcome` with the failed asserts named.
fn check_broken(good: &str, broken: &[(&str, &str, Outcome)], proof: fn(&str) -> sim::hdl::formal::Proof) {
    for &(from, to, outcome) in broken {
        assert!(good.contains(from), "the generated block has `{from}`");
        let p = proof(&good.replacen(from, to, 1));
        eprintln!("{to}: {p:?}");
        assert_eq!(p.outcome, outcome, "`{from}` → `{to}`: {p:?}");
        assert!(!p.failed_asserts.is_empty(), "{p:?}");
        if let Some(d) = p.workdir {
            let _ = std::fs::remove_dir_all(d);
        }
    }
}

// ---------------------------------------------------------------------------
// The record queue

/// Depth of the record queue's proof: the reads on their way and the ring
/// turn over within four clocks; the invariants carry the rest.
const FIFO_DEPTH: usize = 4;

fn record_fifo_proof(design: &str) -> sim::hdl::formal::Proof {
    use rtl::stream::record_fifo::{RECORD_FIFO_AHEAD, RECORD_FIFO_DEPTH};
    let params = [("PTR", RECORD_FIFO_DEPTH.trailing_zeros() as usize + 1), ("DEPTH", RECORD_FIFO_DEPTH), ("AHEAD", RECORD_FIFO_AHEAD)];
    let spliced = with_properties(design, sim::hdl::formal::RECORD_FIFO_PROPERTIES, &params).expect("module top");
    prove(&(spliced + &sim::hdl::formal::free_dp16kd()), FIFO_DEPTH).unwrap_or_else(|e| panic!("{e}"))
}

fn record_fifo() -> String {
    sim::hdl::cosim::verilog_of(rtl::stream::record_fifo::RecordFifo::default())
}

#[test]
fn record_queue_never_overflows_or_underflows_counts_writes_minus_reads_and_keeps_the_markers_place_proven_by_k_induction() {
    let p = record_fifo_proof(&record_fifo());
    eprintln!("{p:?}");
    assert_eq!(p.outcome, Outcome::Pass, "{p:?}");
}

/// Three queues that break the contract: a read issued from an empty RAM
/// (caught from the initial state); records let into the marker's last
/// place, and reads issued past the ring's room (not provable: the
/// induction finds the broken state, which the basecase cannot reach in
/// four clocks).
#[test]
fn the_record_queue_proof_fails_on_queues_that_underflow_overfill_take_the_markers_place_or_forget_the_reset() {
    check_broken(
        &record_fifo(),
        &[
            ("issue = (rp$q != wp$q) & (pending < ahead);", "issue = (pending < ahead);", Outcome::Fail),
            ("write = ~full_rec$q;", "write = ~full_mark$q;", Outcome::Unknown),
            ("issue = (rp$q != wp$q) & (pending < ahead);", "issue = (rp$q != wp$q) & (pending <= ahead);", Outcome::Unknown),
            // A reset that forgets the write pointer.
            ("wp$reset = reset;", "wp$reset = 1'b0;", Outcome::Fail),
        ],
        record_fifo_proof,
    );
}
