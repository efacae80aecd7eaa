//! Formal proofs of the stream blocks (`sim::hdl::formal`): the generated
//! Verilog with its contract spliced in, proven by k-induction with
//! SymbiYosys, and the same proof failing on slices changed to break the
//! contract (so that a pass means something).

use rtl::params::PIXEL_BITS;
use rtl::stream::skid_buffer::SkidBuffer;
use sim::hdl::formal::{free_primitive, prove, with_properties, Outcome, SKID_BUFFER_PROPERTIES};

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
    prove(&(spliced + &free_primitive("DP16KD").expect("a model")), FIFO_DEPTH).unwrap_or_else(|e| panic!("{e}"))
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

// ---------------------------------------------------------------------------
// The interpolator's line queue

/// Depth of the line queue's proof: a description reaches the pixel engine
/// through the write pointer's five-stage delay line and the engine's
/// ready register, seven clocks; the invariants carry the rest.
const LINE_QUEUE_DEPTH: usize = 8;

fn line_queue_proof(design: &str) -> sim::hdl::formal::Proof {
    use rtl::post::interpolator::{LINE_QUEUE, SEGMENT_LAG};
    let params = [("PTR", LINE_QUEUE.trailing_zeros() as usize + 1), ("LINES", LINE_QUEUE), ("LAG", SEGMENT_LAG)];
    let spliced = with_properties(design, sim::hdl::formal::INTERPOLATOR_LINE_QUEUE_PROPERTIES, &params).expect("module top");
    let primitives = ["DP16KD", "MULT18X18D"].map(|p| free_primitive(p).expect("a model")).concat();
    prove(&(spliced + &primitives), LINE_QUEUE_DEPTH).unwrap_or_else(|e| panic!("{e}"))
}

fn interpolator() -> String {
    sim::hdl::cosim::verilog_of(rtl::post::interpolator::Interpolator::default())
}

#[test]
fn interpolator_line_queue_never_overflows_or_underflows_counts_writes_minus_lines_done_and_admits_a_line_with_room_proven_by_k_induction() {
    let p = line_queue_proof(&interpolator());
    eprintln!("{p:?}");
    assert_eq!(p.outcome, Outcome::Pass, "{p:?}");
}

/// Queues that break the contract: a line shown a clock early (before its
/// description has passed the delay line), a line's end that moves the
/// read pointer without a line shown, and a reset that forgets the write
/// pointer, each caught from the initial state; a line admitted into a
/// full queue (its description written over one not done), not provable:
/// the induction finds the broken state, which the basecase cannot reach
/// in eight clocks (a full queue is nine markers away).
#[test]
fn the_line_queue_proof_fails_on_queues_that_overfill_show_a_line_early_or_underflow_or_forget_the_reset() {
    check_broken(
        &interpolator(),
        &[
            ("fits = ~seg_full$q & ~q_full$q;", "fits = ~seg_full$q;", Outcome::Unknown),
            ("line_ready$d = q_wp5$q != q_rp$q;", "line_ready$d = q_wp4$q != q_rp$q;", Outcome::Fail),
            ("line_done = line_ready$q & at_last_x;", "line_done = at_last_x;", Outcome::Fail),
            ("q_wp$reset = reset;", "q_wp$reset = 1'b0;", Outcome::Fail),
        ],
        line_queue_proof,
    );
}
