//! The record buffer between a detector and the matcher (`DESIGN.md` §3,
//! "top level"): a first-in first-out queue of [`RECORD_FIFO_DEPTH`]
//! detector beats (records and line markers) in block RAM.
//!
//! The detector emits its records without back-pressure, the matcher takes
//! them only while it has a free bank (`r_ready`/`o_ready` of
//! [`crate::matcher::declivity_matcher::DeclivityMatcher`]). A line whose matching
//! takes longer than a line period (the budget's worst line, or a busy line
//! of a real image: `declivity budget`) would otherwise lose the next line's
//! records. Here they wait: the matcher catches up on the lighter lines that
//! follow, and the camera is never stalled.
//!
//! The beat is [`RECORD_FIFO_LANES`] lanes of [`DP16KD_WIDTH`] bits, one
//! `DP16KD` each ([`BlockRam`]); the top packs a record's fields into them.
//! Reads go ahead into a ring of [`RECORD_FIFO_AHEAD`] registers, so the
//! output is a register and the RAM's two clocks of read latency are hidden.
//!
//! ## Ports
//! - In: `w_valid` (a beat), `w_marker` (the beat ends a line),
//!   `w_lane0..4`. No back-pressure.
//! - Out: `r_valid`, `r_lane0..4`; in: `r_ready`. A beat leaves on a clock
//!   with `r_valid && r_ready` (AXI4-Stream's rule: `r_valid` does not wait
//!   for `r_ready`).
//! - `dropped`: high for a clock, the clock after a beat that found no
//!   room and was dropped. A record is written only while at least two places are free
//!   (a beat that left counted free from the clock after it left),
//!   so that the last place is kept for a line's marker: on overflow a line
//!   loses records from its end, and lines stay aligned between the two
//!   sides as long as the markers fit.
//!
//! ## Timing
//! A beat written at clock `t` (into an empty queue) is on the outputs at
//! `t + `[`RECORD_FIFO_LAG`] and leaves one per clock while `r_ready` is
//! high. Throughput: one beat in and one out per clock. `w_valid` low
//! writes nothing. The pointers and counts start at zero (an empty
//! queue) from their Verilog initial values; `reset` (synchronous, active high) returns them there.
//!
//! No paper equation: stream plumbing.

use crate::primitives::block_ram::{BlockRam, DP16KD_ADDR_BITS, DP16KD_WIDTH};
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Lanes of a beat: a record's 72 bits plus its marker's fields need five
/// 18-bit lanes (one `DP16KD` each).
pub const RECORD_FIFO_LANES: usize = 5;
/// Address bits of the queue: one `DP16KD` deep (1024 beats, eight lines
/// of `N_MAX` records).
const RECORD_FIFO_ADDR_BITS: usize = DP16KD_ADDR_BITS;
/// Beats the queue holds.
pub const RECORD_FIFO_DEPTH: usize = 1 << RECORD_FIFO_ADDR_BITS;
/// Registers the reads go ahead into.
pub const RECORD_FIFO_AHEAD: usize = 4;
/// Clocks from a beat's write into an empty queue to its being on the
/// outputs: the write, the RAM's read and output registers, the ring.
pub const RECORD_FIFO_LAG: usize = 4;

/// Pointer bits: one above the address, so that full and empty differ.
const PTR_BITS: usize = RECORD_FIFO_ADDR_BITS + 1;
/// Bits of a ring index (with a wrap bit) and of its fill count.
const RING_BITS: usize = 3;

/// One lane's word.
type Lane = Bits<DP16KD_WIDTH>;

#[derive(LogicBlock)]
pub struct RecordFifo {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub w_valid: Signal<In, Bit>,
    pub w_marker: Signal<In, Bit>,
    pub w_lane0: Signal<In, Lane>,
    pub w_lane1: Signal<In, Lane>,
    pub w_lane2: Signal<In, Lane>,
    pub w_lane3: Signal<In, Lane>,
    pub w_lane4: Signal<In, Lane>,
    pub r_valid: Signal<Out, Bit>,
    pub r_ready: Signal<In, Bit>,
    pub r_lane0: Signal<Out, Lane>,
    pub r_lane1: Signal<Out, Lane>,
    pub r_lane2: Signal<Out, Lane>,
    pub r_lane3: Signal<Out, Lane>,
    pub r_lane4: Signal<Out, Lane>,
    pub dropped: Signal<Out, Bit>,
    mem0: BlockRam<DP16KD_WIDTH, RECORD_FIFO_ADDR_BITS>,
    mem1: BlockRam<DP16KD_WIDTH, RECORD_FIFO_ADDR_BITS>,
    mem2: BlockRam<DP16KD_WIDTH, RECORD_FIFO_ADDR_BITS>,
    mem3: BlockRam<DP16KD_WIDTH, RECORD_FIFO_ADDR_BITS>,
    mem4: BlockRam<DP16KD_WIDTH, RECORD_FIFO_ADDR_BITS>,
    // Written beats, beats read from the RAM, beats that left; `used` is
    // `wp - popped` kept as a register, counting a beat that left a clock
    // after it left (`popped`), so that the reader's `r_ready`, which comes
    // from across the die, is not in one clock with `used`'s ± 1 and the
    // flags' choice. The flags are so one place too cautious for the clock
    // after a pop.
    wp: ResetDff<Bits<PTR_BITS>>,
    rp: ResetDff<Bits<PTR_BITS>>,
    used: ResetDff<Bits<PTR_BITS>>,
    // `used` has no room left for a record (`used ≥ DEPTH − 1`) / for a
    // marker (`used ≥ DEPTH`), kept as registers beside it: the next
    // clock's flags are picked from comparisons of `used` with constants,
    // made while the clock decides whether `used` moves, so that the
    // comparison, the write and `used`'s ± 1 are not in one clock.
    full_rec: ResetDff<Bit>,
    full_mark: ResetDff<Bit>,
    // Reads on their way (RAM register, output register).
    rd1: ResetDff<Bit>,
    rd2: ResetDff<Bit>,
    // The ring: written at `wi`, read at `ri`; `fill` = beats in it.
    wi: ResetDff<Bits<RING_BITS>>,
    ri: ResetDff<Bits<RING_BITS>>,
    fill: ResetDff<Bits<RING_BITS>>,
    e0: [ResetDff<Lane>; RECORD_FIFO_LANES],
    e1: [ResetDff<Lane>; RECORD_FIFO_LANES],
    e2: [ResetDff<Lane>; RECORD_FIFO_LANES],
    e3: [ResetDff<Lane>; RECORD_FIFO_LANES],
    dropped_q: ResetDff<Bit>,
    popped: ResetDff<Bit>,
    write: Signal<Local, Bit>,
    pending: Signal<Local, Bits<RING_BITS>>,
    issue: Signal<Local, Bit>,
    pop: Signal<Local, Bit>,
    // `used` against DEPTH − 2 ..= DEPTH + 1: the flags' next values.
    depth_m2: Constant<Bits<PTR_BITS>>,
    depth_m1: Constant<Bits<PTR_BITS>>,
    depth: Constant<Bits<PTR_BITS>>,
    depth_p1: Constant<Bits<PTR_BITS>>,
    ahead: Constant<Bits<RING_BITS>>,
    slot_mask: Constant<Bits<RING_BITS>>,
    slot1: Constant<Bits<RING_BITS>>,
    slot2: Constant<Bits<RING_BITS>>,
    slot3: Constant<Bits<RING_BITS>>,
}

impl Default for RecordFifo {
    fn default() -> Self {
        let cp = |v: usize| Constant::<Bits<PTR_BITS>>::new((v as u64).into());
        let cr = |v: usize| Constant::<Bits<RING_BITS>>::new((v as u64).into());
        RecordFifo {
            clock: Default::default(),
            reset: Default::default(),
            w_valid: Default::default(),
            w_marker: Default::default(),
            w_lane0: Default::default(),
            w_lane1: Default::default(),
            w_lane2: Default::default(),
            w_lane3: Default::default(),
            w_lane4: Default::default(),
            r_valid: Default::default(),
            r_ready: Default::default(),
            r_lane0: Default::default(),
            r_lane1: Default::default(),
            r_lane2: Default::default(),
            r_lane3: Default::default(),
            r_lane4: Default::default(),
            dropped: Default::default(),
            mem0: Default::default(),
            mem1: Default::default(),
            mem2: Default::default(),
            mem3: Default::default(),
            mem4: Default::default(),
            wp: Default::default(),
            rp: Default::default(),
            used: Default::default(),
            full_rec: Default::default(),
            full_mark: Default::default(),
            rd1: Default::default(),
            rd2: Default::default(),
            wi: Default::default(),
            ri: Default::default(),
            fill: Default::default(),
            e0: Default::default(),
            e1: Default::default(),
            e2: Default::default(),
            e3: Default::default(),
            dropped_q: Default::default(),
            popped: Default::default(),
            write: Default::default(),
            pending: Default::default(),
            issue: Default::default(),
            pop: Default::default(),
            // A record needs two free places (the last is a marker's), a
            // marker one.
            depth_m2: cp(RECORD_FIFO_DEPTH - 2),
            depth_m1: cp(RECORD_FIFO_DEPTH - 1),
            depth: cp(RECORD_FIFO_DEPTH),
            depth_p1: cp(RECORD_FIFO_DEPTH + 1),
            ahead: cr(RECORD_FIFO_AHEAD),
            slot_mask: cr(RECORD_FIFO_AHEAD - 1),
            slot1: cr(1),
            slot2: cr(2),
            slot3: cr(3),
        }
    }
}

impl Logic for RecordFifo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, wp, rp, used, full_rec, full_mark, rd1, rd2, wi, ri, fill, dropped_q, popped);
        self.wp.reset.next = self.reset.val();
        self.rp.reset.next = self.reset.val();
        self.used.reset.next = self.reset.val();
        self.full_rec.reset.next = self.reset.val();
        self.full_mark.reset.next = self.reset.val();
        self.rd1.reset.next = self.reset.val();
        self.rd2.reset.next = self.reset.val();
        self.wi.reset.next = self.reset.val();
        self.ri.reset.next = self.reset.val();
        self.fill.reset.next = self.reset.val();
        self.dropped_q.reset.next = self.reset.val();
        self.popped.reset.next = self.reset.val();
        for l in 0..RECORD_FIFO_LANES {
            self.e0[l].clock.next = self.clock.val();
            self.e0[l].reset.next = self.reset.val();
            self.e1[l].clock.next = self.clock.val();
            self.e1[l].reset.next = self.reset.val();
            self.e2[l].clock.next = self.clock.val();
            self.e2[l].reset.next = self.reset.val();
            self.e3[l].clock.next = self.clock.val();
            self.e3[l].reset.next = self.reset.val();
            self.e0[l].d.next = self.e0[l].q.val();
            self.e1[l].d.next = self.e1[l].q.val();
            self.e2[l].d.next = self.e2[l].q.val();
            self.e3[l].d.next = self.e3[l].q.val();
        }
        self.mem0.clock.next = self.clock.val();
        self.mem1.clock.next = self.clock.val();
        self.mem2.clock.next = self.clock.val();
        self.mem3.clock.next = self.clock.val();
        self.mem4.clock.next = self.clock.val();

        // Write: a record while two places are free, a marker while one is.
        self.write.next = false;
        if self.w_valid.val() {
            if self.w_marker.val() {
                self.write.next = !self.full_mark.q.val();
            } else {
                self.write.next = !self.full_rec.q.val();
            }
        }
        self.dropped_q.d.next = self.w_valid.val() & !self.write.val();
        self.dropped.next = self.dropped_q.q.val();
                self.mem0.write_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.wp.q.val());
        self.mem1.write_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.wp.q.val());
        self.mem2.write_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.wp.q.val());
        self.mem3.write_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.wp.q.val());
        self.mem4.write_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.wp.q.val());
        self.mem0.write_enable.next = self.write.val();
        self.mem1.write_enable.next = self.write.val();
        self.mem2.write_enable.next = self.write.val();
        self.mem3.write_enable.next = self.write.val();
        self.mem4.write_enable.next = self.write.val();
        self.mem0.write_data.next = self.w_lane0.val();
        self.mem1.write_data.next = self.w_lane1.val();
        self.mem2.write_data.next = self.w_lane2.val();
        self.mem3.write_data.next = self.w_lane3.val();
        self.mem4.write_data.next = self.w_lane4.val();
        if self.write.val() {
            self.wp.d.next = self.wp.q.val() + 1;
        }

        // Read ahead: a written beat is read when the ring will have room
        // for it (the ring's beats and the reads on their way).
        self.pending.next = self.fill.q.val();
        if self.rd1.q.val() {
            self.pending.next = self.pending.val() + 1;
        }
        if self.rd2.q.val() {
            self.pending.next = self.pending.val() + 1;
        }
        self.issue.next = (self.rp.q.val() != self.wp.q.val()) & (self.pending.val() < self.ahead.val());
                self.mem0.read_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.rp.q.val());
        self.mem1.read_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.rp.q.val());
        self.mem2.read_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.rp.q.val());
        self.mem3.read_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.rp.q.val());
        self.mem4.read_address.next = bit_cast::<RECORD_FIFO_ADDR_BITS, PTR_BITS>(self.rp.q.val());
        if self.issue.val() {
            self.rp.d.next = self.rp.q.val() + 1;
        }
        self.rd1.d.next = self.issue.val();
        self.rd2.d.next = self.rd1.q.val();
        // The read's data arrives with `rd2`: into the ring at `wi`.
        if self.rd2.q.val() {
            self.wi.d.next = self.wi.q.val() + 1;
            if (self.wi.q.val() & self.slot_mask.val()) == self.slot3.val() {
                self.e3[0].d.next = self.mem0.read_data.val();
                self.e3[1].d.next = self.mem1.read_data.val();
                self.e3[2].d.next = self.mem2.read_data.val();
                self.e3[3].d.next = self.mem3.read_data.val();
                self.e3[4].d.next = self.mem4.read_data.val();
            } else if (self.wi.q.val() & self.slot_mask.val()) == self.slot2.val() {
                self.e2[0].d.next = self.mem0.read_data.val();
                self.e2[1].d.next = self.mem1.read_data.val();
                self.e2[2].d.next = self.mem2.read_data.val();
                self.e2[3].d.next = self.mem3.read_data.val();
                self.e2[4].d.next = self.mem4.read_data.val();
            } else if (self.wi.q.val() & self.slot_mask.val()) == self.slot1.val() {
                self.e1[0].d.next = self.mem0.read_data.val();
                self.e1[1].d.next = self.mem1.read_data.val();
                self.e1[2].d.next = self.mem2.read_data.val();
                self.e1[3].d.next = self.mem3.read_data.val();
                self.e1[4].d.next = self.mem4.read_data.val();
            } else {
                self.e0[0].d.next = self.mem0.read_data.val();
                self.e0[1].d.next = self.mem1.read_data.val();
                self.e0[2].d.next = self.mem2.read_data.val();
                self.e0[3].d.next = self.mem3.read_data.val();
                self.e0[4].d.next = self.mem4.read_data.val();
            }
        }

        // Out: the ring's beat at `ri`.
        self.r_valid.next = self.fill.q.val() != 0;
        self.r_lane0.next = self.e0[0].q.val();
        self.r_lane1.next = self.e0[1].q.val();
        self.r_lane2.next = self.e0[2].q.val();
        self.r_lane3.next = self.e0[3].q.val();
        self.r_lane4.next = self.e0[4].q.val();
        if (self.ri.q.val() & self.slot_mask.val()) == self.slot1.val() {
            self.r_lane0.next = self.e1[0].q.val();
            self.r_lane1.next = self.e1[1].q.val();
            self.r_lane2.next = self.e1[2].q.val();
            self.r_lane3.next = self.e1[3].q.val();
            self.r_lane4.next = self.e1[4].q.val();
        } else if (self.ri.q.val() & self.slot_mask.val()) == self.slot2.val() {
            self.r_lane0.next = self.e2[0].q.val();
            self.r_lane1.next = self.e2[1].q.val();
            self.r_lane2.next = self.e2[2].q.val();
            self.r_lane3.next = self.e2[3].q.val();
            self.r_lane4.next = self.e2[4].q.val();
        } else if (self.ri.q.val() & self.slot_mask.val()) == self.slot3.val() {
            self.r_lane0.next = self.e3[0].q.val();
            self.r_lane1.next = self.e3[1].q.val();
            self.r_lane2.next = self.e3[2].q.val();
            self.r_lane3.next = self.e3[3].q.val();
            self.r_lane4.next = self.e3[4].q.val();
        }
        self.pop.next = (self.fill.q.val() != 0) & self.r_ready.val();
        if self.pop.val() {
            self.ri.d.next = self.ri.q.val() + 1;
        }
        // The ring's count and the queue's.
        if self.rd2.q.val() & !self.pop.val() {
            self.fill.d.next = self.fill.q.val() + 1;
        } else if !self.rd2.q.val() & self.pop.val() {
            self.fill.d.next = self.fill.q.val() - 1;
        }
        self.full_rec.d.next = self.used.q.val() >= self.depth_m1.val();
        self.full_mark.d.next = self.used.q.val() >= self.depth.val();
        self.popped.d.next = self.pop.val();
        if self.write.val() & !self.popped.q.val() {
            self.used.d.next = self.used.q.val() + 1;
            self.full_rec.d.next = self.used.q.val() >= self.depth_m2.val();
            self.full_mark.d.next = self.used.q.val() >= self.depth_m1.val();
        } else if !self.write.val() & self.popped.q.val() {
            self.used.d.next = self.used.q.val() - 1;
            self.full_rec.d.next = self.used.q.val() >= self.depth.val();
            self.full_mark.d.next = self.used.q.val() >= self.depth_p1.val();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes beats with gaps while the reader takes them at random, and
    /// returns what was sent, what left (lane 0) and the clocks `dropped`
    /// was high.
    fn run(beats: usize, write_every: u64, ready_one_in: u64, seed: u64) -> (Vec<u64>, Vec<u64>, Vec<u64>) {
        let mut uut = RecordFifo::default();
        uut.connect_all();
        let mut s = seed | 1;
        let mut rnd = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let (mut out, mut dropped, mut sent) = (Vec::new(), Vec::new(), Vec::new());
        let mut next = 0u64;
        let mut cycle = 0u64;
        while cycle < 40 * beats as u64 + 100 {
            let write = next < beats as u64 && rnd() % write_every == 0;
            let marker = next % 7 == 6;
            uut.w_valid.next = write;
            uut.w_marker.next = marker;
            uut.w_lane0.next = (next & 0x3ffff).into();
            uut.w_lane1.next = ((next * 3) & 0x3ffff).into();
            uut.w_lane4.next = ((next * 5) & 0x3ffff).into();
            let ready = rnd() % ready_one_in == 0;
            uut.r_ready.next = ready;
            assert!(simulate(&mut uut, 100));
            if uut.dropped.val() {
                dropped.push(cycle);
            }
            if uut.r_valid.val() && ready {
                let v = uut.r_lane0.val().to_u64();
                assert_eq!(uut.r_lane1.val().to_u64(), (v * 3) & 0x3ffff, "the lanes stay together");
                assert_eq!(uut.r_lane4.val().to_u64(), (v * 5) & 0x3ffff, "the lanes stay together");
                out.push(v);
            }
            if write {
                sent.push(next);
                next += 1;
            }
            crate::tick(&mut uut, |u| &mut u.clock);
            cycle += 1;
        }
        (sent, out, dropped)
    }

    #[test]
    fn beats_leave_in_order_and_none_is_lost_while_the_reader_keeps_up() {
        // The reader takes a beat on two clocks of three, the writer writes
        // one in three: the queue never fills.
        let (sent, out, dropped) = run(3000, 3, 1, 7);
        assert!(dropped.is_empty(), "nothing dropped");
        assert_eq!(out, sent, "every beat, in order");
    }

    #[test]
    fn a_full_queue_drops_records_keeps_a_place_for_markers_and_stays_in_order() {
        // A reader taking one beat in eight falls behind a writer writing
        // every clock: the queue fills.
        let (sent, out, dropped) = run(4000, 1, 8, 11);
        assert!(!dropped.is_empty(), "the queue overflowed");
        // What left is a subsequence of what was sent, in order.
        let mut k = 0;
        for v in &out {
            while k < sent.len() && sent[k] != *v {
                k += 1;
            }
            assert!(k < sent.len(), "beat {v} left out of order");
        }
        // The place kept for markers: a marker (every seventh beat) is
        // dropped only when a record could not be written just before.
        let markers_lost = sent.iter().filter(|&&v| v % 7 == 6 && !out.contains(&v)).count();
        let records_lost = sent.iter().filter(|&&v| v % 7 != 6 && !out.contains(&v)).count();
        assert!(records_lost > 0 && markers_lost * 6 < records_lost, "records go before markers ({records_lost} records, {markers_lost} markers lost)");
        assert_eq!(records_lost + markers_lost, dropped.len(), "each lost beat raised `dropped` once");
    }

    #[test]
    fn a_beat_into_an_empty_queue_leaves_after_the_documented_lag() {
        let mut uut = RecordFifo::default();
        uut.connect_all();
        uut.r_ready.next = true;
        uut.w_valid.next = true;
        uut.w_lane0.next = 42u64.into();
        assert!(simulate(&mut uut, 100));
        for t in 0..=RECORD_FIFO_LAG + 2 {
            assert!(simulate(&mut uut, 100));
            let here = uut.r_valid.val();
            assert_eq!(here, t == RECORD_FIFO_LAG, "valid at clock {t}");
            if here {
                assert_eq!(uut.r_lane0.val().to_u64(), 42);
            }
            crate::tick(&mut uut, |u| &mut u.clock);
            uut.w_valid.next = false;
        }
    }
}
