//! The vertical median of the default mode (`DESIGN.md` §3, golden's
//! `Features::median_rows`, `golden::disparity::vertical_median` with
//! `rows = MEDIAN_ROWS = 5`, step 5 of `golden::frame::process_frame`): the
//! interpolator's pixel stream in, each pixel replaced by the median of its
//! column over the rows `y - 2 ..= y + 2`, one pixel per clock out.
//!
//! Rows beyond the frame repeat its top or bottom row (golden's clamp), and
//! pixels without disparity (0) take part as 0. The values are unsigned
//! fixed point ([`POS_FRAC_BITS`] fraction bits); the median commutes with
//! that monotone map, so the output is exactly the fixed point of golden's
//! median of the same values.
//!
//! ## Structure
//! - Four line buffers of [`W_MAX`] disparities ([`MEDIAN_LINE_BUFFERS`],
//!   [`BlockRam`]s, one `DP16KD` each): row `r` of a frame lives in buffer
//!   `r mod 4`. While row `k` comes in (its "slot"), each pixel reads its
//!   column from the four buffers (rows `k-4 ..= k-1`) and is written into
//!   buffer `k mod 4` one clock later (after its old word, row `k-4`, was
//!   read: a `DP16KD` read and write of one address on one clock is
//!   undefined). A read of the word being written on the same clock takes
//!   the written value instead (forwarding: rows of one pixel back to back).
//! - Slot `k` emits row `y = k - 2`. Each of the five taps (rows
//!   `k-4 ..= k`) takes the tap of its clamped row: in slots 2 and 3 the
//!   rows above the frame take row 0; after the frame's last row (`h - 1`,
//!   marked by `p_eof`) the block runs two slots of its own (the *flush*,
//!   slots `h` and `h + 1`, pixels from the buffers at one per clock) in
//!   which the rows below the frame take row `h - 1`. A frame of one row
//!   runs only the second (slot `h - 1 = -1` emits nothing). Frames of 1 to
//!   4 rows are clamped at both ends.
//! - The taps go through golden's network of compare-exchanges, one per
//!   pipeline stage: `min`/`max` of `(a, b)` and `(c, d)` (rows `y-2, y-1`
//!   and `y+1, y+2`); `lo = max(min_ab, min_cd)`, `hi = min(max_ab,
//!   max_cd)`; `min`/`max` of `(lo, hi)`; `min(max(lo, hi), e)`; the median
//!   `max(min(lo, hi), min(max(lo, hi), e))` (`e` row `y`). Seven units.
//!
//! ## Ports
//! - In, the interpolator's stream (`rtl::interpolator`, its `p_*` ports)
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
//! A pixel on `p_*` of slot `k >= 2` (row `k` of its frame) sends pixel
//! `(x, k - 2)` of the output out on `v_*` exactly [`MEDIAN_LAG`] clocks
//! later; the pixels of rows 0 and 1 send nothing. `p_valid` low only
//! delays. The flush starts on the clock after the last pixel of the `eof`
//! row: output row `h - 2` (if `h >= 2`) then row `h - 1`, one pixel per
//! clock, back to back, each pixel [`MEDIAN_LAG`] clocks after its clock of
//! the flush; the next frame's rows are taken from the clock after the
//! flush (the sensor's vertical blanking must be at least two line
//! widths). A pixel that arrives during the flush is dropped, and with it
//! the rest of its row (`overflow` for each); the block then takes the
//! next row as row 0 of a new frame. `p_sof` on a row's first pixel starts
//! a frame at that row (a frame cut short without an `eof` row never emits
//! its last two rows). Throughput: one pixel per clock; latency two rows
//! and [`MEDIAN_LAG`] clocks.
//!
//! ## Cost
//! Alone on the ECP5-85K (speed 6; Yosys 0.70 `synth_ecp5`, nextpnr 0.11.1,
//! its pads included): 1 186 LUT4, 388 FF, 4 `DP16KD`, no DSP, 149.7 MHz
//! (critical: the forwarding flag through the tap selection).

use crate::block_ram::BlockRam;
use crate::params::*;
use rust_hdl::prelude::*;

/// Clocks from a pixel on `p_*` (or a pixel's clock of the flush) to the
/// output pixel it completes on `v_*`: the buffers' two-clock read (the
/// write register and the forwarding beside it), the tap selection, four
/// compare-exchange stages, and the last one into the output register.
pub const MEDIAN_LAG: usize = 8;

/// Bits of a slot count `0 ..= 4` (saturating: only slots 0 to 3 differ).
const SLOT_BITS: usize = 3;
/// Bits of a line-buffer index (`k mod 4`).
const BUF_BITS: usize = 2;
/// Bits of the phase: 0 taking rows, [`FLUSH_FIRST`], [`FLUSH_SECOND`].
const PHASE_BITS: usize = 2;
/// The phase of the first flush slot (`k = h`: the tap of row `h` takes
/// row `h - 1`).
const FLUSH_FIRST: u64 = 1;
/// The phase of the second flush slot (`k = h + 1`: the taps of rows `h`
/// and `h + 1` take row `h - 1`).
const FLUSH_SECOND: u64 = 2;

#[derive(LogicBlock)]
pub struct VerticalMedian {
    pub clock: Signal<In, Clock>,
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
    // ---- The row being taken or flushed: its slot (saturated at 4), the
    // buffer of its row (k mod 4), the phase, the column, the last row's
    // last column, dropping the rest of a row.
    slot: DFF<Bits<SLOT_BITS>>,
    rot: DFF<Bits<BUF_BITS>>,
    phase: DFF<Bits<PHASE_BITS>>,
    col: DFF<Bits<X_BITS>>,
    last_col: DFF<Bits<X_BITS>>,
    dropping: DFF<Bit>,
    overflow_q: DFF<Bit>,
    // ---- The line buffers.
    line0: BlockRam<POS_BITS, W_MAX_BITS>,
    line1: BlockRam<POS_BITS, W_MAX_BITS>,
    line2: BlockRam<POS_BITS, W_MAX_BITS>,
    line3: BlockRam<POS_BITS, W_MAX_BITS>,
    // ---- S0: the pixel a clock later (its write), its output's flags and
    // tap selection; the forwarding of the write beside the read.
    s0_write: DFF<Bit>,
    s0_col: DFF<Bits<X_BITS>>,
    s0_d: DFF<Bits<POS_BITS>>,
    s0_buf: DFF<Bits<BUF_BITS>>,
    s0_out: DFF<Bit>,
    s0_sof: DFF<Bit>,
    s0_last: DFF<Bit>,
    s0_lo: DFF<Bits<2>>,
    s0_hi: DFF<Bits<PHASE_BITS>>,
    s0_rot: DFF<Bits<BUF_BITS>>,
    s0_hit: DFF<Bit>,
    s0_hit_buf: DFF<Bits<BUF_BITS>>,
    s0_hit_d: DFF<Bits<POS_BITS>>,
    // ---- S1: beside the buffers' output registers.
    s1_d: DFF<Bits<POS_BITS>>,
    s1_out: DFF<Bit>,
    s1_sof: DFF<Bit>,
    s1_last: DFF<Bit>,
    s1_lo: DFF<Bits<2>>,
    s1_hi: DFF<Bits<PHASE_BITS>>,
    s1_rot: DFF<Bits<BUF_BITS>>,
    s1_hit: DFF<Bit>,
    s1_hit_buf: DFF<Bits<BUF_BITS>>,
    s1_hit_d: DFF<Bits<POS_BITS>>,
    // ---- The taps: rows y-2 (a), y-1 (b), y (e), y+1 (c), y+2 (d).
    t_out: DFF<Bit>,
    t_sof: DFF<Bit>,
    t_last: DFF<Bit>,
    t_a: DFF<Bits<POS_BITS>>,
    t_b: DFF<Bits<POS_BITS>>,
    t_e: DFF<Bits<POS_BITS>>,
    t_c: DFF<Bits<POS_BITS>>,
    t_d: DFF<Bits<POS_BITS>>,
    // ---- The network's stages.
    n1_out: DFF<Bit>,
    n1_sof: DFF<Bit>,
    n1_last: DFF<Bit>,
    n1_min_ab: DFF<Bits<POS_BITS>>,
    n1_max_ab: DFF<Bits<POS_BITS>>,
    n1_min_cd: DFF<Bits<POS_BITS>>,
    n1_max_cd: DFF<Bits<POS_BITS>>,
    n1_e: DFF<Bits<POS_BITS>>,
    n2_out: DFF<Bit>,
    n2_sof: DFF<Bit>,
    n2_last: DFF<Bit>,
    n2_lo: DFF<Bits<POS_BITS>>,
    n2_hi: DFF<Bits<POS_BITS>>,
    n2_e: DFF<Bits<POS_BITS>>,
    n3_out: DFF<Bit>,
    n3_sof: DFF<Bit>,
    n3_last: DFF<Bit>,
    n3_min: DFF<Bits<POS_BITS>>,
    n3_max: DFF<Bits<POS_BITS>>,
    n3_e: DFF<Bits<POS_BITS>>,
    n4_out: DFF<Bit>,
    n4_sof: DFF<Bit>,
    n4_last: DFF<Bit>,
    n4_min: DFF<Bits<POS_BITS>>,
    n4_upper: DFF<Bits<POS_BITS>>,
    o_valid: DFF<Bit>,
    o_sof: DFF<Bit>,
    o_last: DFF<Bit>,
    o_d: DFF<Bits<POS_BITS>>,
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
    bv0: Signal<Local, Bits<POS_BITS>>,
    bv1: Signal<Local, Bits<POS_BITS>>,
    bv2: Signal<Local, Bits<POS_BITS>>,
    bv3: Signal<Local, Bits<POS_BITS>>,
    v0: Signal<Local, Bits<POS_BITS>>,
    v1: Signal<Local, Bits<POS_BITS>>,
    v2: Signal<Local, Bits<POS_BITS>>,
    v3: Signal<Local, Bits<POS_BITS>>,
    // ---- Constants.
    k0: Constant<Bits<SLOT_BITS>>,
    k1: Constant<Bits<SLOT_BITS>>,
    k2: Constant<Bits<SLOT_BITS>>,
    k3: Constant<Bits<SLOT_BITS>>,
    k4: Constant<Bits<SLOT_BITS>>,
    b0: Constant<Bits<BUF_BITS>>,
    b1: Constant<Bits<BUF_BITS>>,
    b2: Constant<Bits<BUF_BITS>>,
    b3: Constant<Bits<BUF_BITS>>,
    lo1: Constant<Bits<2>>,
    lo2: Constant<Bits<2>>,
    flush_first: Constant<Bits<PHASE_BITS>>,
    flush_second: Constant<Bits<PHASE_BITS>>,
}

impl VerticalMedian {
    /// The vertical median (no generation-time parameters: five rows,
    /// [`W_MAX`]-pixel rows).
    pub fn new() -> Self {
        let ck = |v: u64| Constant::<Bits<SLOT_BITS>>::new(v.into());
        let cb = |v: u64| Constant::<Bits<BUF_BITS>>::new(v.into());
        VerticalMedian {
            clock: Default::default(),
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
            line0: Default::default(),
            line1: Default::default(),
            line2: Default::default(),
            line3: Default::default(),
            s0_write: Default::default(),
            s0_col: Default::default(),
            s0_d: Default::default(),
            s0_buf: Default::default(),
            s0_out: Default::default(),
            s0_sof: Default::default(),
            s0_last: Default::default(),
            s0_lo: Default::default(),
            s0_hi: Default::default(),
            s0_rot: Default::default(),
            s0_hit: Default::default(),
            s0_hit_buf: Default::default(),
            s0_hit_d: Default::default(),
            s1_d: Default::default(),
            s1_out: Default::default(),
            s1_sof: Default::default(),
            s1_last: Default::default(),
            s1_lo: Default::default(),
            s1_hi: Default::default(),
            s1_rot: Default::default(),
            s1_hit: Default::default(),
            s1_hit_buf: Default::default(),
            s1_hit_d: Default::default(),
            t_out: Default::default(),
            t_sof: Default::default(),
            t_last: Default::default(),
            t_a: Default::default(),
            t_b: Default::default(),
            t_e: Default::default(),
            t_c: Default::default(),
            t_d: Default::default(),
            n1_out: Default::default(),
            n1_sof: Default::default(),
            n1_last: Default::default(),
            n1_min_ab: Default::default(),
            n1_max_ab: Default::default(),
            n1_min_cd: Default::default(),
            n1_max_cd: Default::default(),
            n1_e: Default::default(),
            n2_out: Default::default(),
            n2_sof: Default::default(),
            n2_last: Default::default(),
            n2_lo: Default::default(),
            n2_hi: Default::default(),
            n2_e: Default::default(),
            n3_out: Default::default(),
            n3_sof: Default::default(),
            n3_last: Default::default(),
            n3_min: Default::default(),
            n3_max: Default::default(),
            n3_e: Default::default(),
            n4_out: Default::default(),
            n4_sof: Default::default(),
            n4_last: Default::default(),
            n4_min: Default::default(),
            n4_upper: Default::default(),
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
            bv0: Default::default(),
            bv1: Default::default(),
            bv2: Default::default(),
            bv3: Default::default(),
            v0: Default::default(),
            v1: Default::default(),
            v2: Default::default(),
            v3: Default::default(),
            k0: ck(0),
            k1: ck(1),
            k2: ck(2),
            k3: ck(3),
            k4: ck(4),
            b0: cb(0),
            b1: cb(1),
            b2: cb(2),
            b3: cb(3),
            lo1: Constant::new(1u64.into()),
            lo2: Constant::new(2u64.into()),
            flush_first: Constant::new(FLUSH_FIRST.into()),
            flush_second: Constant::new(FLUSH_SECOND.into()),
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
        dff_setup!(self, clock, slot, rot, phase, col, last_col, dropping, overflow_q, s0_write, s0_col, s0_d, s0_buf, s0_out, s0_sof, s0_last, s0_lo, s0_hi, s0_rot, s0_hit, s0_hit_buf, s0_hit_d, s1_d, s1_out, s1_sof, s1_last, s1_lo, s1_hi, s1_rot, s1_hit, s1_hit_buf, s1_hit_d, t_out, t_sof, t_last, t_a, t_b, t_e, t_c, t_d, n1_out, n1_sof, n1_last, n1_min_ab, n1_max_ab, n1_min_cd, n1_max_cd, n1_e, n2_out, n2_sof, n2_last, n2_lo, n2_hi, n2_e, n3_out, n3_sof, n3_last, n3_min, n3_max, n3_e, n4_out, n4_sof, n4_last, n4_min, n4_upper, o_valid, o_sof, o_last, o_d);
        self.line0.clock.next = self.clock.val();
        self.line1.clock.next = self.clock.val();
        self.line2.clock.next = self.clock.val();
        self.line3.clock.next = self.clock.val();

        // ================= The row: taken, dropped or flushed =================
        self.flushing.next = self.phase.q.val().any();
        self.take.next = self.p_valid.val() & !self.flushing.val() & !self.dropping.q.val();
        self.drop_px.next = self.p_valid.val() & (self.flushing.val() | self.dropping.q.val());
        // A taken row's slot: a start of frame makes it slot 0.
        // The next row's slot and buffer, from the registers, the start of
        // frame picked last (the slot's increment behind the taken pixel's
        // start of frame was 7.6 ns on a placed ECP5-85K).
        self.flush_next.next = self.slot.q.val() + 1;
        if self.slot.q.val() == self.k4.val() {
            self.flush_next.next = self.k4.val();
        }
        self.k_eff.next = self.slot.q.val();
        self.rot_eff.next = self.rot.q.val();
        self.k_next.next = self.flush_next.val();
        self.rot_next.next = self.rot.q.val() + 1;
        if self.take.val() & self.p_sof.val() {
            self.k_eff.next = self.k0.val();
            self.rot_eff.next = self.b0.val();
            self.k_next.next = self.k1.val();
            self.rot_next.next = self.b1.val();
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
                    self.phase.d.next = self.flush_first.val();
                    // One row: slot h = 1 would emit row -1; go to h + 1.
                    if self.k_eff.val() == self.k0.val() {
                        self.phase.d.next = self.flush_second.val();
                        self.slot.d.next = self.k2.val();
                        self.rot.d.next = self.b2.val();
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
                self.phase.d.next = self.flush_second.val();
                if self.phase.q.val() == self.flush_second.val() {
                    self.phase.d.next = 0.into();
                    self.slot.d.next = self.k0.val();
                    self.rot.d.next = self.b0.val();
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
        self.line0.read_address.next = self.col.q.val();
        self.line1.read_address.next = self.col.q.val();
        self.line2.read_address.next = self.col.q.val();
        self.line3.read_address.next = self.col.q.val();
        self.line0.write_address.next = self.s0_col.q.val();
        self.line1.write_address.next = self.s0_col.q.val();
        self.line2.write_address.next = self.s0_col.q.val();
        self.line3.write_address.next = self.s0_col.q.val();
        self.line0.write_data.next = self.s0_d.q.val();
        self.line1.write_data.next = self.s0_d.q.val();
        self.line2.write_data.next = self.s0_d.q.val();
        self.line3.write_data.next = self.s0_d.q.val();
        self.line0.write_enable.next = self.s0_write.q.val() & (self.s0_buf.q.val() == self.b0.val());
        self.line1.write_enable.next = self.s0_write.q.val() & (self.s0_buf.q.val() == self.b1.val());
        self.line2.write_enable.next = self.s0_write.q.val() & (self.s0_buf.q.val() == self.b2.val());
        self.line3.write_enable.next = self.s0_write.q.val() & (self.s0_buf.q.val() == self.b3.val());

        // S0: the pixel, its output's flags and tap selection (the low
        // taps from the slot, the high ones from the phase), and the
        // forwarding of this clock's write to this clock's read.
        self.s0_write.d.next = self.take.val();
        self.s0_col.d.next = self.col.q.val();
        self.s0_d.d.next = self.p_d.val();
        self.s0_buf.d.next = self.rot_eff.val();
        self.s0_out.d.next = (self.take.val() & (self.k_eff.val() >= self.k2.val())) | self.flushing.val();
        self.s0_sof.d.next = (self.take.val() | self.flushing.val()) & (self.k_eff.val() == self.k2.val()) & !self.col.q.val().any();
        self.s0_last.d.next = self.p_last.val();
        if self.flushing.val() {
            self.s0_last.d.next = self.row_end.val();
        }
        self.s0_lo.d.next = 0.into();
        if self.k_eff.val() == self.k2.val() {
            self.s0_lo.d.next = self.lo2.val();
        }
        if self.k_eff.val() == self.k3.val() {
            self.s0_lo.d.next = self.lo1.val();
        }
        self.s0_hi.d.next = self.phase.q.val();
        self.s0_rot.d.next = self.rot_eff.val();
        self.s0_hit.d.next = self.s0_write.q.val() & (self.s0_col.q.val() == self.col.q.val());
        self.s0_hit_buf.d.next = self.s0_buf.q.val();
        self.s0_hit_d.d.next = self.s0_d.q.val();
        // S1: the buffers' words are on their way.
        self.s1_d.d.next = self.s0_d.q.val();
        self.s1_out.d.next = self.s0_out.q.val();
        self.s1_sof.d.next = self.s0_sof.q.val();
        self.s1_last.d.next = self.s0_last.q.val();
        self.s1_lo.d.next = self.s0_lo.q.val();
        self.s1_hi.d.next = self.s0_hi.q.val();
        self.s1_rot.d.next = self.s0_rot.q.val();
        self.s1_hit.d.next = self.s0_hit.q.val();
        self.s1_hit_buf.d.next = self.s0_hit_buf.q.val();
        self.s1_hit_d.d.next = self.s0_hit_d.q.val();

        // ================= The taps =================
        // The buffers' words (a word written on its read's clock forwarded).
        self.bv0.next = self.line0.read_data.val();
        self.bv1.next = self.line1.read_data.val();
        self.bv2.next = self.line2.read_data.val();
        self.bv3.next = self.line3.read_data.val();
        if self.s1_hit.q.val() {
            if self.s1_hit_buf.q.val() == self.b0.val() {
                self.bv0.next = self.s1_hit_d.q.val();
            }
            if self.s1_hit_buf.q.val() == self.b1.val() {
                self.bv1.next = self.s1_hit_d.q.val();
            }
            if self.s1_hit_buf.q.val() == self.b2.val() {
                self.bv2.next = self.s1_hit_d.q.val();
            }
            if self.s1_hit_buf.q.val() == self.b3.val() {
                self.bv3.next = self.s1_hit_d.q.val();
            }
        }
        // Rows k-4+i from buffer (k + i) mod 4.
        self.v0.next = self.bv0.val();
        self.v1.next = self.bv1.val();
        self.v2.next = self.bv2.val();
        self.v3.next = self.bv3.val();
        if self.s1_rot.q.val() == self.b1.val() {
            self.v0.next = self.bv1.val();
            self.v1.next = self.bv2.val();
            self.v2.next = self.bv3.val();
            self.v3.next = self.bv0.val();
        }
        if self.s1_rot.q.val() == self.b2.val() {
            self.v0.next = self.bv2.val();
            self.v1.next = self.bv3.val();
            self.v2.next = self.bv0.val();
            self.v3.next = self.bv1.val();
        }
        if self.s1_rot.q.val() == self.b3.val() {
            self.v0.next = self.bv3.val();
            self.v1.next = self.bv0.val();
            self.v2.next = self.bv1.val();
            self.v3.next = self.bv2.val();
        }
        // The clamp: tap i takes tap clamp(i, lo, hi) (row y = tap 2).
        self.t_a.d.next = self.v0.val();
        self.t_b.d.next = self.v1.val();
        if self.s1_lo.q.val() == self.lo1.val() {
            self.t_a.d.next = self.v1.val();
        }
        if self.s1_lo.q.val() == self.lo2.val() {
            self.t_a.d.next = self.v2.val();
            self.t_b.d.next = self.v2.val();
        }
        self.t_e.d.next = self.v2.val();
        self.t_c.d.next = self.v3.val();
        self.t_d.d.next = self.s1_d.q.val();
        if self.s1_hi.q.val() == self.flush_first.val() {
            self.t_d.d.next = self.v3.val();
        }
        if self.s1_hi.q.val() == self.flush_second.val() {
            self.t_c.d.next = self.v2.val();
            self.t_d.d.next = self.v2.val();
        }
        self.t_out.d.next = self.s1_out.q.val();
        self.t_sof.d.next = self.s1_sof.q.val();
        self.t_last.d.next = self.s1_last.q.val();

        // ================= The network =================
        // N1: min/max of (a, b) and of (c, d).
        self.n1_min_ab.d.next = self.t_b.q.val();
        self.n1_max_ab.d.next = self.t_a.q.val();
        if self.t_a.q.val() < self.t_b.q.val() {
            self.n1_min_ab.d.next = self.t_a.q.val();
            self.n1_max_ab.d.next = self.t_b.q.val();
        }
        self.n1_min_cd.d.next = self.t_d.q.val();
        self.n1_max_cd.d.next = self.t_c.q.val();
        if self.t_c.q.val() < self.t_d.q.val() {
            self.n1_min_cd.d.next = self.t_c.q.val();
            self.n1_max_cd.d.next = self.t_d.q.val();
        }
        self.n1_e.d.next = self.t_e.q.val();
        self.n1_out.d.next = self.t_out.q.val();
        self.n1_sof.d.next = self.t_sof.q.val();
        self.n1_last.d.next = self.t_last.q.val();
        // N2: the two middle values of four bracket the median.
        self.n2_lo.d.next = self.n1_min_ab.q.val();
        if self.n1_min_ab.q.val() < self.n1_min_cd.q.val() {
            self.n2_lo.d.next = self.n1_min_cd.q.val();
        }
        self.n2_hi.d.next = self.n1_max_cd.q.val();
        if self.n1_max_ab.q.val() < self.n1_max_cd.q.val() {
            self.n2_hi.d.next = self.n1_max_ab.q.val();
        }
        self.n2_e.d.next = self.n1_e.q.val();
        self.n2_out.d.next = self.n1_out.q.val();
        self.n2_sof.d.next = self.n1_sof.q.val();
        self.n2_last.d.next = self.n1_last.q.val();
        // N3: min/max of (lo, hi).
        self.n3_min.d.next = self.n2_hi.q.val();
        self.n3_max.d.next = self.n2_lo.q.val();
        if self.n2_lo.q.val() < self.n2_hi.q.val() {
            self.n3_min.d.next = self.n2_lo.q.val();
            self.n3_max.d.next = self.n2_hi.q.val();
        }
        self.n3_e.d.next = self.n2_e.q.val();
        self.n3_out.d.next = self.n2_out.q.val();
        self.n3_sof.d.next = self.n2_sof.q.val();
        self.n3_last.d.next = self.n2_last.q.val();
        // N4: min(max(lo, hi), e).
        self.n4_min.d.next = self.n3_min.q.val();
        self.n4_upper.d.next = self.n3_e.q.val();
        if self.n3_max.q.val() < self.n3_e.q.val() {
            self.n4_upper.d.next = self.n3_max.q.val();
        }
        self.n4_out.d.next = self.n3_out.q.val();
        self.n4_sof.d.next = self.n3_sof.q.val();
        self.n4_last.d.next = self.n3_last.q.val();
        // The median: max(min(lo, hi), min(max(lo, hi), e)); 0 when no
        // pixel leaves.
        self.o_d.d.next = 0.into();
        if self.n4_out.q.val() {
            self.o_d.d.next = self.n4_upper.q.val();
            if self.n4_upper.q.val() < self.n4_min.q.val() {
                self.o_d.d.next = self.n4_min.q.val();
            }
        }
        self.o_valid.d.next = self.n4_out.q.val();
        self.o_sof.d.next = self.n4_sof.q.val() & self.n4_out.q.val();
        self.o_last.d.next = self.n4_last.q.val() & self.n4_out.q.val();
        self.v_valid.next = self.o_valid.q.val();
        self.v_d.next = self.o_d.q.val();
        self.v_sof.next = self.o_sof.q.val();
        self.v_last.next = self.o_last.q.val();
    }
}
