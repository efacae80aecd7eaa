//! The vertical median of the default mode (`DESIGN.md` §3, golden's
//! `Features::median_rows`, `golden::disparity::vertical_median` with
//! `rows = MEDIAN_ROWS = 9`, step 5 of `golden::frame::process_frame`): the
//! interpolator's pixel stream in, each pixel replaced by the median of its
//! column over the rows `y - 4 ..= y + 4` ([`MEDIAN_HALF`] = 4 on each
//! side), one pixel per clock out. No paper equation: the median is
//! golden's default mode, not the paper's.
//!
//! Rows beyond the frame repeat its top or bottom row (golden's clamp), and
//! pixels without disparity (0) take part as 0. The values are unsigned
//! fixed point ([`POS_FRAC_BITS`] fraction bits); the median commutes with
//! that monotone map, so the output is exactly the fixed point of golden's
//! median of the same values.
//!
//! ## Structure
//! - Eight line buffers of [`W_MAX`] disparities ([`MEDIAN_LINE_BUFFERS`],
//!   [`BlockRam`]s, one `DP16KD` each): row `r` of a frame lives in buffer
//!   `r mod 8`. While row `k` comes in (its "slot"), each pixel reads its
//!   column from the eight buffers (rows `k-8 ..= k-1`) and is written into
//!   buffer `k mod 8` one clock later (after its old word, row `k-8`, was
//!   read: a `DP16KD` read and write of one address on one clock is
//!   undefined).
//! - The eight words are put in row order by a rotation by `k mod 8` (three
//!   stages of 2-to-1 multiplexers, by 1, 2 and 4) into registers. A read
//!   of the word being written on the same clock takes the written value
//!   instead (forwarding: rows of one pixel back to back). The forwarding
//!   acts after the rotation, on the tap of the written row (the previous
//!   row's, tap 7, or in a short frame's first flush slot the last row's),
//!   picked a stage ahead.
//! - Slot `k` emits row `y = k - 4`. Each of the nine taps (rows
//!   `k-8 ..= k`) takes the tap of its clamped row: in slots 4 to 7 the
//!   rows above the frame take row 0; after the frame's last row (`h - 1`,
//!   marked by `p_eof`) the block runs four slots of its own (the *flush*,
//!   slots `h ..= h + 3`, pixels from the buffers at one per clock) in
//!   which the rows below the frame take row `h - 1`. A frame of fewer
//!   than four rows runs only the flush slots that emit a row (`k >= 4`).
//!   Frames of 1 to 8 rows are clamped at both ends.
//! - The taps go through golden's network of 19 compare-exchanges
//!   (`golden::disparity::MEDIAN9_NETWORK`, Paeth's), one step per pipeline
//!   stage, each stage keeping only the values a later step reads.
//!
//! ## Ports
//! - In, the interpolator's stream (`rtl::post::interpolator`, its `p_*` ports)
//!   and one more flag: `p_valid`, `p_d` (disparity, [`POS_FRAC_BITS`]
//!   fraction bits, 0 = none), `p_last` (the row's last pixel), `p_sof` (the
//!   frame's first pixel), `p_eof` (the pixels of the frame's last row; read
//!   on the row's last pixel). All rows of a frame have the same width,
//!   `1 ..= W_MAX` pixels; the flush emits rows as wide as the last row.
//! - Out, no back-pressure: `v_valid`, `v_d` (the median, same format; 0
//!   when `v_valid` is low), `v_last` (the row's last pixel), `v_sof` (the
//!   frame's first pixel).
//! - `overflow`: high for one clock on the clock after each pixel that was
//!   dropped (see Timing).
//!
//! ## Timing
//! A pixel on `p_*` of slot `k >= 4` (row `k` of its frame) sends pixel
//! `(x, k - 4)` of the output out on `v_*` exactly [`MEDIAN_LAG`] clocks
//! later; the pixels of rows 0 to 3 send nothing. `p_valid` low only
//! delays. The flush starts on the clock after the last pixel of the `eof`
//! row: output rows `h - 4 ..= h - 1` (those `>= 0`), one pixel per clock,
//! back to back, each pixel [`MEDIAN_LAG`] clocks after its clock of the
//! flush; the next frame's rows are taken from the clock after the flush
//! (the sensor's vertical blanking must be at least [`MEDIAN_HALF`] line
//! widths). A
//! pixel that arrives during the flush is dropped, and with it the rest of
//! its row (`overflow` for each); the block then takes the next row as row
//! 0 of a new frame. `p_sof` on a row's first pixel starts a frame at that
//! row (a frame cut short without an `eof` row never emits its last four
//! rows). Throughput: one pixel per clock; latency [`MEDIAN_HALF`] rows and
//! [`MEDIAN_LAG`] clocks. The registers start from their Verilog
//! initial values (slot 0, not flushing: the first row taken is row 0 of a
//! frame); `reset` (synchronous, active high) returns them to these values.

use crate::primitives::block_ram::BlockRam;
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from a pixel on `p_*` (or a pixel's clock of the flush) to the
/// output pixel it completes on `v_*`: the buffers' two-clock read (the
/// write register and the forwarding beside it), the rotation into row
/// order, the tap selection, eight compare-exchange stages, and the last
/// step into the output register.
pub const MEDIAN_LAG: usize = 13;

/// Bits of a slot count `0 ..= 8` (saturating: only slots 0 to 7 differ).
const SLOT_BITS: usize = 4;
/// Bits of a line-buffer index (`k mod 8`).
const BUF_BITS: usize = 3;
/// Bits of the phase: 0 taking rows, 1 ..= [`MEDIAN_HALF`] the flush slots
/// `h ..= h + 3` (in phase `f` the taps of rows `h ..= h + f - 1` take row
/// `h - 1`).
const PHASE_BITS: usize = 3;
/// Compare-exchange stages between the taps and the output register.
const NET_STAGES: usize = 8;

// The rotation is three stages of 2-to-1 multiplexers, by 1, 2 and 4.
const _: () = assert!(MEDIAN_LINE_BUFFERS == 8 && MEDIAN_TAPS == 9 && MEDIAN_HALF == 4, "the network and rotation are written for nine rows");
const _: () = assert!(1 << BUF_BITS == MEDIAN_LINE_BUFFERS && (1 << SLOT_BITS) > MEDIAN_LINE_BUFFERS && (1 << PHASE_BITS) > MEDIAN_HALF);

#[derive(LogicBlock)]
pub struct VerticalMedian {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub p_valid: Signal<In, Bit>,
    pub p_d: Signal<In, Bits<POS_BITS>>,
    pub p_last: Signal<In, Bit>,
    pub p_sof: Signal<In, Bit>,
    pub p_eof: Signal<In, Bit>,
    pub v_valid: Signal<Out, Bit>,
    pub v_d: Signal<Out, Bits<POS_BITS>>,
    pub v_last: Signal<Out, Bit>,
    pub v_sof: Signal<Out, Bit>,
    pub overflow: Signal<Out, Bit>,
    // ---- The row being taken or flushed: its slot (saturated at 8), the
    // buffer of its row (k mod 8), the phase, the column, the last row's
    // last column, dropping the rest of a row.
    slot: ResetDff<Bits<SLOT_BITS>>,
    rot: ResetDff<Bits<BUF_BITS>>,
    phase: ResetDff<Bits<PHASE_BITS>>,
    col: ResetDff<Bits<X_BITS>>,
    last_col: ResetDff<Bits<X_BITS>>,
    dropping: ResetDff<Bit>,
    overflow_q: ResetDff<Bit>,
    // ---- The line buffers: row r in line[r mod 8].
    line: [BlockRam<POS_BITS, W_MAX_BITS>; MEDIAN_LINE_BUFFERS],
    // ---- S0: the pixel a clock later (its write), its output's flags,
    // slot and phase; the forwarding of the write beside the read.
    s0_write: ResetDff<Bit>,
    s0_col: ResetDff<Bits<X_BITS>>,
    s0_d: ResetDff<Bits<POS_BITS>>,
    s0_buf: ResetDff<Bits<BUF_BITS>>,
    s0_out: ResetDff<Bit>,
    s0_sof: ResetDff<Bit>,
    s0_last: ResetDff<Bit>,
    s0_k: ResetDff<Bits<SLOT_BITS>>,
    s0_ph: ResetDff<Bits<PHASE_BITS>>,
    s0_rot: ResetDff<Bits<BUF_BITS>>,
    s0_hit: ResetDff<Bit>,
    s0_hit_buf: ResetDff<Bits<BUF_BITS>>,
    s0_hit_d: ResetDff<Bits<POS_BITS>>,
    // ---- S1: beside the buffers' output registers.
    s1_d: ResetDff<Bits<POS_BITS>>,
    s1_out: ResetDff<Bit>,
    s1_sof: ResetDff<Bit>,
    s1_last: ResetDff<Bit>,
    s1_k: ResetDff<Bits<SLOT_BITS>>,
    s1_ph: ResetDff<Bits<PHASE_BITS>>,
    s1_rot: ResetDff<Bits<BUF_BITS>>,
    s1_hit_tap: [ResetDff<Bit>; MEDIAN_LINE_BUFFERS],
    s1_hit_d: ResetDff<Bits<POS_BITS>>,
    // ---- R: rows k-8+i in r_v[i]; the clamp's flags: r_lo_ge[j] = the
    // first row of the frame is tap j + 1 or later (slot k <= 7 - j),
    // r_hi_le[m] = the frame's last row is tap 4 + m or earlier (flush
    // phase >= 4 - m).
    r_v: [ResetDff<Bits<POS_BITS>>; MEDIAN_LINE_BUFFERS],
    r_d: ResetDff<Bits<POS_BITS>>,
    r_out: ResetDff<Bit>,
    r_sof: ResetDff<Bit>,
    r_last: ResetDff<Bit>,
    r_lo_ge: [ResetDff<Bit>; MEDIAN_HALF],
    r_hi_le: [ResetDff<Bit>; MEDIAN_HALF],
    // ---- T: the taps, rows y-4 ..= y+4, clamped to the frame.
    t: [ResetDff<Bits<POS_BITS>>; MEDIAN_TAPS],
    t_out: ResetDff<Bit>,
    t_sof: ResetDff<Bit>,
    t_last: ResetDff<Bit>,
    // ---- The network's stages (golden's MEDIAN9_NETWORK, values p0..p8):
    // n1..n3 hold p0..p8; n4 p1..p7 (n4[i] = p(i+1)); n5 p2, p4, p6, p7;
    // n6 and n7 p2, p4, p6; n8 p2, p4. The output step takes min(p4, p2).
    n1: [ResetDff<Bits<POS_BITS>>; MEDIAN_TAPS],
    n2: [ResetDff<Bits<POS_BITS>>; MEDIAN_TAPS],
    n3: [ResetDff<Bits<POS_BITS>>; MEDIAN_TAPS],
    n4: [ResetDff<Bits<POS_BITS>>; 7],
    n5: [ResetDff<Bits<POS_BITS>>; 4],
    n6: [ResetDff<Bits<POS_BITS>>; 3],
    n7: [ResetDff<Bits<POS_BITS>>; 3],
    n8: [ResetDff<Bits<POS_BITS>>; 2],
    g_out: [ResetDff<Bit>; NET_STAGES],
    g_sof: [ResetDff<Bit>; NET_STAGES],
    g_last: [ResetDff<Bit>; NET_STAGES],
    o_valid: ResetDff<Bit>,
    o_sof: ResetDff<Bit>,
    o_last: ResetDff<Bit>,
    o_d: ResetDff<Bits<POS_BITS>>,
    // ---- Locals.
    flushing: Signal<Local, Bit>,
    take: Signal<Local, Bit>,
    drop_px: Signal<Local, Bit>,
    k_eff: Signal<Local, Bits<SLOT_BITS>>,
    rot_eff: Signal<Local, Bits<BUF_BITS>>,
    k_next: Signal<Local, Bits<SLOT_BITS>>,
    flush_next: Signal<Local, Bits<SLOT_BITS>>,
    rot_next: Signal<Local, Bits<BUF_BITS>>,
    row_end: Signal<Local, Bit>,
    hit_tap: Signal<Local, Bits<BUF_BITS>>,
    rot1: [Signal<Local, Bits<POS_BITS>>; MEDIAN_LINE_BUFFERS],
    rot2: [Signal<Local, Bits<POS_BITS>>; MEDIAN_LINE_BUFFERS],
    // ---- Constants.
    k0: Constant<Bits<SLOT_BITS>>,
    k1: Constant<Bits<SLOT_BITS>>,
    k2: Constant<Bits<SLOT_BITS>>,
    k4: Constant<Bits<SLOT_BITS>>,
    k8: Constant<Bits<SLOT_BITS>>,
    kbuf: [Constant<Bits<BUF_BITS>>; MEDIAN_LINE_BUFFERS],
    c_lo: [Constant<Bits<SLOT_BITS>>; MEDIAN_HALF],
    c_hi: [Constant<Bits<PHASE_BITS>>; MEDIAN_HALF],
    ph1: Constant<Bits<PHASE_BITS>>,
    ph2: Constant<Bits<PHASE_BITS>>,
    ph3: Constant<Bits<PHASE_BITS>>,
    ph4: Constant<Bits<PHASE_BITS>>,
}

impl VerticalMedian {
    /// The vertical median (no generation-time parameters: nine rows,
    /// [`W_MAX`]-pixel rows).
    pub fn new() -> Self {
        let ck = |v: u64| Constant::<Bits<SLOT_BITS>>::new(v.into());
        let cp = |v: u64| Constant::<Bits<PHASE_BITS>>::new(v.into());
        VerticalMedian {
            clock: Default::default(),
            reset: Default::default(),
            p_valid: Default::default(),
            p_d: Default::default(),
            p_last: Default::default(),
            p_sof: Default::default(),
            p_eof: Default::default(),
            v_valid: Default::default(),
            v_d: Default::default(),
            v_last: Default::default(),
            v_sof: Default::default(),
            overflow: Default::default(),
            slot: Default::default(),
            rot: Default::default(),
            phase: Default::default(),
            col: Default::default(),
            last_col: Default::default(),
            dropping: Default::default(),
            overflow_q: Default::default(),
            line: Default::default(),
            s0_write: Default::default(),
            s0_col: Default::default(),
            s0_d: Default::default(),
            s0_buf: Default::default(),
            s0_out: Default::default(),
            s0_sof: Default::default(),
            s0_last: Default::default(),
            s0_k: Default::default(),
            s0_ph: Default::default(),
            s0_rot: Default::default(),
            s0_hit: Default::default(),
            s0_hit_buf: Default::default(),
            s0_hit_d: Default::default(),
            s1_d: Default::default(),
            s1_out: Default::default(),
            s1_sof: Default::default(),
            s1_last: Default::default(),
            s1_k: Default::default(),
            s1_ph: Default::default(),
            s1_rot: Default::default(),
            s1_hit_tap: Default::default(),
            s1_hit_d: Default::default(),
            r_v: Default::default(),
            r_d: Default::default(),
            r_out: Default::default(),
            r_sof: Default::default(),
            r_last: Default::default(),
            r_lo_ge: Default::default(),
            r_hi_le: Default::default(),
            t: Default::default(),
            t_out: Default::default(),
            t_sof: Default::default(),
            t_last: Default::default(),
            n1: Default::default(),
            n2: Default::default(),
            n3: Default::default(),
            n4: Default::default(),
            n5: Default::default(),
            n6: Default::default(),
            n7: Default::default(),
            n8: Default::default(),
            g_out: Default::default(),
            g_sof: Default::default(),
            g_last: Default::default(),
            o_valid: Default::default(),
            o_sof: Default::default(),
            o_last: Default::default(),
            o_d: Default::default(),
            flushing: Default::default(),
            take: Default::default(),
            drop_px: Default::default(),
            k_eff: Default::default(),
            rot_eff: Default::default(),
            k_next: Default::default(),
            flush_next: Default::default(),
            rot_next: Default::default(),
            row_end: Default::default(),
            hit_tap: Default::default(),
            rot1: Default::default(),
            rot2: Default::default(),
            k0: ck(0),
            k1: ck(1),
            k2: ck(2),
            k4: ck(4),
            k8: ck(8),
            kbuf: std::array::from_fn(|b| Constant::new((b as u64).into())),
            // Slot k <= 7 - j: rows above the frame reach tap j.
            c_lo: std::array::from_fn(|j| ck((MEDIAN_LINE_BUFFERS - 1 - j) as u64)),
            // Phase >= 4 - m: rows below the frame start at tap 5 + m.
            c_hi: std::array::from_fn(|m| cp((MEDIAN_HALF - m) as u64)),
            ph1: cp(1),
            ph2: cp(2),
            ph3: cp(3),
            ph4: cp(4),
        }
    }
}

impl Default for VerticalMedian {
    fn default() -> Self {
        VerticalMedian::new()
    }
}

impl Logic for VerticalMedian {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, slot, rot, phase, col, last_col, dropping, overflow_q, s0_write, s0_col, s0_d, s0_buf, s0_out, s0_sof, s0_last, s0_k, s0_ph, s0_rot, s0_hit, s0_hit_buf, s0_hit_d, s1_d, s1_out, s1_sof, s1_last, s1_k, s1_ph, s1_rot, s1_hit_d, r_d, r_out, r_sof, r_last, t_out, t_sof, t_last, o_valid, o_sof, o_last, o_d);
        self.slot.reset.next = self.reset.val();
        self.rot.reset.next = self.reset.val();
        self.phase.reset.next = self.reset.val();
        self.col.reset.next = self.reset.val();
        self.last_col.reset.next = self.reset.val();
        self.dropping.reset.next = self.reset.val();
        self.overflow_q.reset.next = self.reset.val();
        self.s0_write.reset.next = self.reset.val();
        self.s0_col.reset.next = self.reset.val();
        self.s0_d.reset.next = self.reset.val();
        self.s0_buf.reset.next = self.reset.val();
        self.s0_out.reset.next = self.reset.val();
        self.s0_sof.reset.next = self.reset.val();
        self.s0_last.reset.next = self.reset.val();
        self.s0_k.reset.next = self.reset.val();
        self.s0_ph.reset.next = self.reset.val();
        self.s0_rot.reset.next = self.reset.val();
        self.s0_hit.reset.next = self.reset.val();
        self.s0_hit_buf.reset.next = self.reset.val();
        self.s0_hit_d.reset.next = self.reset.val();
        self.s1_d.reset.next = self.reset.val();
        self.s1_out.reset.next = self.reset.val();
        self.s1_sof.reset.next = self.reset.val();
        self.s1_last.reset.next = self.reset.val();
        self.s1_k.reset.next = self.reset.val();
        self.s1_ph.reset.next = self.reset.val();
        self.s1_rot.reset.next = self.reset.val();
        self.s1_hit_d.reset.next = self.reset.val();
        self.r_d.reset.next = self.reset.val();
        self.r_out.reset.next = self.reset.val();
        self.r_sof.reset.next = self.reset.val();
        self.r_last.reset.next = self.reset.val();
        self.t_out.reset.next = self.reset.val();
        self.t_sof.reset.next = self.reset.val();
        self.t_last.reset.next = self.reset.val();
        self.o_valid.reset.next = self.reset.val();
        self.o_sof.reset.next = self.reset.val();
        self.o_last.reset.next = self.reset.val();
        self.o_d.reset.next = self.reset.val();
        for b in 0..MEDIAN_LINE_BUFFERS {
            self.line[b].clock.next = self.clock.val();
            self.s1_hit_tap[b].clock.next = self.clock.val();
            self.s1_hit_tap[b].reset.next = self.reset.val();
            self.r_v[b].clock.next = self.clock.val();
            self.r_v[b].reset.next = self.reset.val();
            self.r_v[b].d.next = self.r_v[b].q.val();
        }
        for j in 0..MEDIAN_HALF {
            self.r_lo_ge[j].clock.next = self.clock.val();
            self.r_lo_ge[j].reset.next = self.reset.val();
            self.r_lo_ge[j].d.next = self.r_lo_ge[j].q.val();
            self.r_hi_le[j].clock.next = self.clock.val();
            self.r_hi_le[j].reset.next = self.reset.val();
            self.r_hi_le[j].d.next = self.r_hi_le[j].q.val();
        }
        for i in 0..MEDIAN_TAPS {
            self.t[i].clock.next = self.clock.val();
            self.t[i].reset.next = self.reset.val();
            self.t[i].d.next = self.t[i].q.val();
            self.n1[i].clock.next = self.clock.val();
            self.n1[i].reset.next = self.reset.val();
            self.n2[i].clock.next = self.clock.val();
            self.n2[i].reset.next = self.reset.val();
            self.n3[i].clock.next = self.clock.val();
            self.n3[i].reset.next = self.reset.val();
        }
        for i in 0..7 {
            self.n4[i].clock.next = self.clock.val();
            self.n4[i].reset.next = self.reset.val();
        }
        for i in 0..4 {
            self.n5[i].clock.next = self.clock.val();
            self.n5[i].reset.next = self.reset.val();
        }
        for i in 0..3 {
            self.n6[i].clock.next = self.clock.val();
            self.n6[i].reset.next = self.reset.val();
            self.n7[i].clock.next = self.clock.val();
            self.n7[i].reset.next = self.reset.val();
        }
        for i in 0..2 {
            self.n8[i].clock.next = self.clock.val();
            self.n8[i].reset.next = self.reset.val();
        }
        for s in 0..NET_STAGES {
            self.g_out[s].clock.next = self.clock.val();
            self.g_out[s].reset.next = self.reset.val();
            self.g_sof[s].clock.next = self.clock.val();
            self.g_sof[s].reset.next = self.reset.val();
            self.g_last[s].clock.next = self.clock.val();
            self.g_last[s].reset.next = self.reset.val();
        }

        // ================= The row: taken, dropped or flushed =================
        self.flushing.next = self.phase.q.val().any();
        self.take.next = self.p_valid.val() & !self.flushing.val() & !self.dropping.q.val();
        self.drop_px.next = self.p_valid.val() & (self.flushing.val() | self.dropping.q.val());
        // A taken row's slot: a start of frame makes it slot 0.
        // The next row's slot and buffer, from the registers, the start of
        // frame picked last, so that the slot's increment is not behind the
        // taken pixel's start of frame.
        self.flush_next.next = self.slot.q.val() + 1;
        if self.slot.q.val() == self.k8.val() {
            self.flush_next.next = self.k8.val();
        }
        self.k_eff.next = self.slot.q.val();
        self.rot_eff.next = self.rot.q.val();
        self.k_next.next = self.flush_next.val();
        self.rot_next.next = self.rot.q.val() + 1;
        if self.take.val() & self.p_sof.val() {
            self.k_eff.next = self.k0.val();
            self.rot_eff.next = self.kbuf[0].val();
            self.k_next.next = self.k1.val();
            self.rot_next.next = self.kbuf[1].val();
        }
        self.row_end.next = self.col.q.val() == self.last_col.q.val();
        if self.take.val() {
            self.col.d.next = self.col.q.val() + 1;
            self.slot.d.next = self.k_eff.val();
            self.rot.d.next = self.rot_eff.val();
            if self.p_last.val() {
                self.col.d.next = 0.into();
                self.last_col.d.next = self.col.q.val();
                self.slot.d.next = self.k_next.val();
                self.rot.d.next = self.rot_next.val();
                if self.p_eof.val() {
                    self.phase.d.next = self.ph1.val();
                    // Fewer than four rows: the flush slots h ..= 3 would
                    // emit rows below 0; start at slot 4 (buffer 4), in the
                    // phase of that slot.
                    if self.k_eff.val() == self.k0.val() {
                        self.phase.d.next = self.ph4.val();
                    }
                    if self.k_eff.val() == self.k1.val() {
                        self.phase.d.next = self.ph3.val();
                    }
                    if self.k_eff.val() == self.k2.val() {
                        self.phase.d.next = self.ph2.val();
                    }
                    if self.k_eff.val() <= self.k2.val() {
                        self.slot.d.next = self.k4.val();
                        self.rot.d.next = self.kbuf[4].val();
                    }
                }
            }
        }
        if self.flushing.val() {
            self.col.d.next = self.col.q.val() + 1;
            if self.row_end.val() {
                self.col.d.next = 0.into();
                self.slot.d.next = self.flush_next.val();
                self.rot.d.next = self.rot.q.val() + 1;
                self.phase.d.next = self.phase.q.val() + 1;
                if self.phase.q.val() == self.ph4.val() {
                    self.phase.d.next = 0.into();
                    self.slot.d.next = self.k0.val();
                    self.rot.d.next = self.kbuf[0].val();
                }
            }
        }
        if self.drop_px.val() {
            self.dropping.d.next = !self.p_last.val();
        }
        self.overflow_q.d.next = self.drop_px.val();
        self.overflow.next = self.overflow_q.q.val();

        // ================= The line buffers =================
        // Every pixel reads its column; a taken pixel is written a clock
        // later into its row's buffer.
        for b in 0..MEDIAN_LINE_BUFFERS {
            self.line[b].read_address.next = self.col.q.val();
            self.line[b].write_address.next = self.s0_col.q.val();
            self.line[b].write_data.next = self.s0_d.q.val();
            self.line[b].write_enable.next = self.s0_write.q.val() & (self.s0_buf.q.val() == self.kbuf[b].val());
        }

        // S0: the pixel, its output's flags, slot and phase (for the tap
        // selection), and the forwarding of this clock's write to this
        // clock's read.
        self.s0_write.d.next = self.take.val();
        self.s0_col.d.next = self.col.q.val();
        self.s0_d.d.next = self.p_d.val();
        self.s0_buf.d.next = self.rot_eff.val();
        self.s0_out.d.next = (self.take.val() & (self.k_eff.val() >= self.k4.val())) | self.flushing.val();
        self.s0_sof.d.next = (self.take.val() | self.flushing.val()) & (self.k_eff.val() == self.k4.val()) & !self.col.q.val().any();
        self.s0_last.d.next = self.p_last.val();
        if self.flushing.val() {
            self.s0_last.d.next = self.row_end.val();
        }
        self.s0_k.d.next = self.k_eff.val();
        self.s0_ph.d.next = self.phase.q.val();
        self.s0_rot.d.next = self.rot_eff.val();
        self.s0_hit.d.next = self.s0_write.q.val() & (self.s0_col.q.val() == self.col.q.val());
        self.s0_hit_buf.d.next = self.s0_buf.q.val();
        self.s0_hit_d.d.next = self.s0_d.q.val();
        // S1: the buffers' words are on their way.
        self.s1_d.d.next = self.s0_d.q.val();
        self.s1_out.d.next = self.s0_out.q.val();
        self.s1_sof.d.next = self.s0_sof.q.val();
        self.s1_last.d.next = self.s0_last.q.val();
        self.s1_k.d.next = self.s0_k.q.val();
        self.s1_ph.d.next = self.s0_ph.q.val();
        self.s1_rot.d.next = self.s0_rot.q.val();
        // The forwarded word's tap: its buffer less the reading slot's
        // rotation (mod 8).
        self.hit_tap.next = self.s0_hit_buf.q.val() - self.s0_rot.q.val();
        for i in 0..MEDIAN_LINE_BUFFERS {
            self.s1_hit_tap[i].d.next = self.s0_hit.q.val() & (self.hit_tap.val() == self.kbuf[i].val());
        }
        self.s1_hit_d.d.next = self.s0_hit_d.q.val();

        // ================= R: the rows in order =================
        // Row k-8+i is in buffer (k + i) mod 8: rotate the buffers' words by
        // k mod 8, by 1, then 2, then 4.
        self.rot1[0].next = self.line[0].read_data.val();
        self.rot1[1].next = self.line[1].read_data.val();
        self.rot1[2].next = self.line[2].read_data.val();
        self.rot1[3].next = self.line[3].read_data.val();
        self.rot1[4].next = self.line[4].read_data.val();
        self.rot1[5].next = self.line[5].read_data.val();
        self.rot1[6].next = self.line[6].read_data.val();
        self.rot1[7].next = self.line[7].read_data.val();
        if self.s1_rot.q.val().get_bit(0) {
            self.rot1[0].next = self.line[1].read_data.val();
            self.rot1[1].next = self.line[2].read_data.val();
            self.rot1[2].next = self.line[3].read_data.val();
            self.rot1[3].next = self.line[4].read_data.val();
            self.rot1[4].next = self.line[5].read_data.val();
            self.rot1[5].next = self.line[6].read_data.val();
            self.rot1[6].next = self.line[7].read_data.val();
            self.rot1[7].next = self.line[0].read_data.val();
        }
        self.rot2[0].next = self.rot1[0].val();
        self.rot2[1].next = self.rot1[1].val();
        self.rot2[2].next = self.rot1[2].val();
        self.rot2[3].next = self.rot1[3].val();
        self.rot2[4].next = self.rot1[4].val();
        self.rot2[5].next = self.rot1[5].val();
        self.rot2[6].next = self.rot1[6].val();
        self.rot2[7].next = self.rot1[7].val();
        if self.s1_rot.q.val().get_bit(1) {
            self.rot2[0].next = self.rot1[2].val();
            self.rot2[1].next = self.rot1[3].val();
            self.rot2[2].next = self.rot1[4].val();
            self.rot2[3].next = self.rot1[5].val();
            self.rot2[4].next = self.rot1[6].val();
            self.rot2[5].next = self.rot1[7].val();
            self.rot2[6].next = self.rot1[0].val();
            self.rot2[7].next = self.rot1[1].val();
        }
        self.r_v[0].d.next = self.rot2[0].val();
        self.r_v[1].d.next = self.rot2[1].val();
        self.r_v[2].d.next = self.rot2[2].val();
        self.r_v[3].d.next = self.rot2[3].val();
        self.r_v[4].d.next = self.rot2[4].val();
        self.r_v[5].d.next = self.rot2[5].val();
        self.r_v[6].d.next = self.rot2[6].val();
        self.r_v[7].d.next = self.rot2[7].val();
        if self.s1_rot.q.val().get_bit(2) {
            self.r_v[0].d.next = self.rot2[4].val();
            self.r_v[1].d.next = self.rot2[5].val();
            self.r_v[2].d.next = self.rot2[6].val();
            self.r_v[3].d.next = self.rot2[7].val();
            self.r_v[4].d.next = self.rot2[0].val();
            self.r_v[5].d.next = self.rot2[1].val();
            self.r_v[6].d.next = self.rot2[2].val();
            self.r_v[7].d.next = self.rot2[3].val();
        }
        // A word written on its read's clock, on its tap.
        for i in 0..MEDIAN_LINE_BUFFERS {
            if self.s1_hit_tap[i].q.val() {
                self.r_v[i].d.next = self.s1_hit_d.q.val();
            }
        }
        // The clamp's flags.
        for j in 0..MEDIAN_HALF {
            self.r_lo_ge[j].d.next = self.s1_k.q.val() <= self.c_lo[j].val();
            self.r_hi_le[j].d.next = self.s1_ph.q.val() >= self.c_hi[j].val();
        }
        self.r_d.d.next = self.s1_d.q.val();
        self.r_out.d.next = self.s1_out.q.val();
        self.r_sof.d.next = self.s1_sof.q.val();
        self.r_last.d.next = self.s1_last.q.val();

        // ================= T: the taps, clamped =================
        // Tap i < 4 takes row max(i, first); tap i > 4 row min(i, last)
        // (tap 8 is the incoming pixel).
        self.t[0].d.next = self.r_v[0].q.val();
        if self.r_lo_ge[0].q.val() {
            self.t[0].d.next = self.r_v[1].q.val();
        }
        if self.r_lo_ge[1].q.val() {
            self.t[0].d.next = self.r_v[2].q.val();
        }
        if self.r_lo_ge[2].q.val() {
            self.t[0].d.next = self.r_v[3].q.val();
        }
        if self.r_lo_ge[3].q.val() {
            self.t[0].d.next = self.r_v[4].q.val();
        }
        self.t[1].d.next = self.r_v[1].q.val();
        if self.r_lo_ge[1].q.val() {
            self.t[1].d.next = self.r_v[2].q.val();
        }
        if self.r_lo_ge[2].q.val() {
            self.t[1].d.next = self.r_v[3].q.val();
        }
        if self.r_lo_ge[3].q.val() {
            self.t[1].d.next = self.r_v[4].q.val();
        }
        self.t[2].d.next = self.r_v[2].q.val();
        if self.r_lo_ge[2].q.val() {
            self.t[2].d.next = self.r_v[3].q.val();
        }
        if self.r_lo_ge[3].q.val() {
            self.t[2].d.next = self.r_v[4].q.val();
        }
        self.t[3].d.next = self.r_v[3].q.val();
        if self.r_lo_ge[3].q.val() {
            self.t[3].d.next = self.r_v[4].q.val();
        }
        self.t[4].d.next = self.r_v[4].q.val();
        self.t[5].d.next = self.r_v[5].q.val();
        if self.r_hi_le[0].q.val() {
            self.t[5].d.next = self.r_v[4].q.val();
        }
        self.t[6].d.next = self.r_v[6].q.val();
        if self.r_hi_le[1].q.val() {
            self.t[6].d.next = self.r_v[5].q.val();
        }
        if self.r_hi_le[0].q.val() {
            self.t[6].d.next = self.r_v[4].q.val();
        }
        self.t[7].d.next = self.r_v[7].q.val();
        if self.r_hi_le[2].q.val() {
            self.t[7].d.next = self.r_v[6].q.val();
        }
        if self.r_hi_le[1].q.val() {
            self.t[7].d.next = self.r_v[5].q.val();
        }
        if self.r_hi_le[0].q.val() {
            self.t[7].d.next = self.r_v[4].q.val();
        }
        self.t[8].d.next = self.r_d.q.val();
        if self.r_hi_le[3].q.val() {
            self.t[8].d.next = self.r_v[7].q.val();
        }
        if self.r_hi_le[2].q.val() {
            self.t[8].d.next = self.r_v[6].q.val();
        }
        if self.r_hi_le[1].q.val() {
            self.t[8].d.next = self.r_v[5].q.val();
        }
        if self.r_hi_le[0].q.val() {
            self.t[8].d.next = self.r_v[4].q.val();
        }
        self.t_out.d.next = self.r_out.q.val();
        self.t_sof.d.next = self.r_sof.q.val();
        self.t_last.d.next = self.r_last.q.val();

        // ================= The network =================
        // A compare-exchange (a, b) leaves min at a, max at b.
        // N1: (1,2) (4,5) (7,8).
        for i in 0..MEDIAN_TAPS {
            self.n1[i].d.next = self.t[i].q.val();
        }
        if self.t[2].q.val() < self.t[1].q.val() {
            self.n1[1].d.next = self.t[2].q.val();
            self.n1[2].d.next = self.t[1].q.val();
        }
        if self.t[5].q.val() < self.t[4].q.val() {
            self.n1[4].d.next = self.t[5].q.val();
            self.n1[5].d.next = self.t[4].q.val();
        }
        if self.t[8].q.val() < self.t[7].q.val() {
            self.n1[7].d.next = self.t[8].q.val();
            self.n1[8].d.next = self.t[7].q.val();
        }
        // N2: (0,1) (3,4) (6,7).
        for i in 0..MEDIAN_TAPS {
            self.n2[i].d.next = self.n1[i].q.val();
        }
        if self.n1[1].q.val() < self.n1[0].q.val() {
            self.n2[0].d.next = self.n1[1].q.val();
            self.n2[1].d.next = self.n1[0].q.val();
        }
        if self.n1[4].q.val() < self.n1[3].q.val() {
            self.n2[3].d.next = self.n1[4].q.val();
            self.n2[4].d.next = self.n1[3].q.val();
        }
        if self.n1[7].q.val() < self.n1[6].q.val() {
            self.n2[6].d.next = self.n1[7].q.val();
            self.n2[7].d.next = self.n1[6].q.val();
        }
        // N3: (1,2) (4,5) (7,8).
        for i in 0..MEDIAN_TAPS {
            self.n3[i].d.next = self.n2[i].q.val();
        }
        if self.n2[2].q.val() < self.n2[1].q.val() {
            self.n3[1].d.next = self.n2[2].q.val();
            self.n3[2].d.next = self.n2[1].q.val();
        }
        if self.n2[5].q.val() < self.n2[4].q.val() {
            self.n3[4].d.next = self.n2[5].q.val();
            self.n3[5].d.next = self.n2[4].q.val();
        }
        if self.n2[8].q.val() < self.n2[7].q.val() {
            self.n3[7].d.next = self.n2[8].q.val();
            self.n3[8].d.next = self.n2[7].q.val();
        }
        // N4: (0,3) (5,8) (4,7); p0 and p8 are read no more (n4[i] = p(i+1)).
        self.n4[0].d.next = self.n3[1].q.val();
        self.n4[1].d.next = self.n3[2].q.val();
        self.n4[5].d.next = self.n3[6].q.val();
        // p3 = max(p0, p3).
        self.n4[2].d.next = self.n3[3].q.val();
        if self.n3[3].q.val() < self.n3[0].q.val() {
            self.n4[2].d.next = self.n3[0].q.val();
        }
        // p5 = min(p5, p8).
        self.n4[4].d.next = self.n3[5].q.val();
        if self.n3[8].q.val() < self.n3[5].q.val() {
            self.n4[4].d.next = self.n3[8].q.val();
        }
        // (p4, p7) = (min, max).
        self.n4[3].d.next = self.n3[4].q.val();
        self.n4[6].d.next = self.n3[7].q.val();
        if self.n3[7].q.val() < self.n3[4].q.val() {
            self.n4[3].d.next = self.n3[7].q.val();
            self.n4[6].d.next = self.n3[4].q.val();
        }
        // N5: (3,6) (1,4) (2,5), keeping p2 = min(p2, p5), p4 = max(p1,
        // p4), p6 = max(p3, p6), and p7 (n5 = p2, p4, p6, p7).
        self.n5[0].d.next = self.n4[1].q.val();
        if self.n4[4].q.val() < self.n4[1].q.val() {
            self.n5[0].d.next = self.n4[4].q.val();
        }
        self.n5[1].d.next = self.n4[3].q.val();
        if self.n4[3].q.val() < self.n4[0].q.val() {
            self.n5[1].d.next = self.n4[0].q.val();
        }
        self.n5[2].d.next = self.n4[5].q.val();
        if self.n4[5].q.val() < self.n4[2].q.val() {
            self.n5[2].d.next = self.n4[2].q.val();
        }
        self.n5[3].d.next = self.n4[6].q.val();
        // N6: (4,7), keeping p4 = min(p4, p7) (n6 = p2, p4, p6).
        self.n6[0].d.next = self.n5[0].q.val();
        self.n6[1].d.next = self.n5[1].q.val();
        if self.n5[3].q.val() < self.n5[1].q.val() {
            self.n6[1].d.next = self.n5[3].q.val();
        }
        self.n6[2].d.next = self.n5[2].q.val();
        // N7: (4,2): (p4, p2) = (min, max) (n7 = p2, p4, p6).
        self.n7[0].d.next = self.n6[0].q.val();
        self.n7[1].d.next = self.n6[1].q.val();
        if self.n6[0].q.val() < self.n6[1].q.val() {
            self.n7[0].d.next = self.n6[1].q.val();
            self.n7[1].d.next = self.n6[0].q.val();
        }
        self.n7[2].d.next = self.n6[2].q.val();
        // N8: (6,4), keeping p4 = max(p6, p4) (n8 = p2, p4).
        self.n8[0].d.next = self.n7[0].q.val();
        self.n8[1].d.next = self.n7[1].q.val();
        if self.n7[1].q.val() < self.n7[2].q.val() {
            self.n8[1].d.next = self.n7[2].q.val();
        }
        // The flags along.
        self.g_out[0].d.next = self.t_out.q.val();
        self.g_sof[0].d.next = self.t_sof.q.val();
        self.g_last[0].d.next = self.t_last.q.val();
        for s in 1..NET_STAGES {
            self.g_out[s].d.next = self.g_out[s - 1].q.val();
            self.g_sof[s].d.next = self.g_sof[s - 1].q.val();
            self.g_last[s].d.next = self.g_last[s - 1].q.val();
        }
        // The median: the last step (4,2), p4 = min(p4, p2); 0 when no
        // pixel leaves.
        self.o_d.d.next = 0.into();
        if self.g_out[7].q.val() {
            self.o_d.d.next = self.n8[1].q.val();
            if self.n8[0].q.val() < self.n8[1].q.val() {
                self.o_d.d.next = self.n8[0].q.val();
            }
        }
        self.o_valid.d.next = self.g_out[7].q.val();
        self.o_sof.d.next = self.g_sof[7].q.val() & self.g_out[7].q.val();
        self.o_last.d.next = self.g_last[7].q.val() & self.g_out[7].q.val();
        self.v_valid.next = self.o_valid.q.val();
        self.v_d.next = self.o_d.q.val();
        self.v_sof.next = self.o_sof.q.val();
        self.v_last.next = self.o_last.q.val();
    }
}
