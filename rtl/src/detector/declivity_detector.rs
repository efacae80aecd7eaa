//! The declivity detector of one camera (`DESIGN.md` §3): an AXI4-Stream
//! video line in, the line's characteristic declivities out, one pixel per
//! clock sustained over back-to-back lines.
//!
//! Three engines work on consecutive lines at once:
//! - **A, input**: writes the line into one bank of a ping-pong line buffer
//!   (`2 × W_MAX` grey levels, a [`BlockRam`] per bank read through its
//!   output register, the address a clock ahead) and counts its `|ΔI|` into the
//!   matching bank of the [`AdaptiveThreshold`] (eq. 2);
//! - **B, threshold**: scans the histogram for the median and `d_t`
//!   ([`THRESHOLD_LATENCY`] clocks, whatever the line);
//! - **C, extraction**: re-reads the line at one pixel per clock through the
//!   [`DeclivityTracker`] (extrema, eq. 3 sums, attributes, `|a_i| > d_t`)
//!   and the [`PositionDivider`] (eq. 3).
//!
//! A bank is released to A when C starts reading it: C reads address `x`
//! before A can write it again (C started first, both go at most one pixel
//! per clock), so line n + 2 streams in while line n is still being read.
//!
//! ## Ports
//! - `clock`; `reset`, synchronous and active high (see Reset).
//! - In: `s_tdata` (grey level), `s_tvalid`, `s_tuser` (start of frame, on
//!   a line's first pixel; on a later beat it ends the line first: see
//!   Faults), `s_tlast` (end of line); out: `s_tready`.
//! - Out: the record stream `m_valid` with `m_last` (the line's end marker),
//!   no back-pressure. A record carries `m_start`, `m_end` (the extrema
//!   `x_i`, `x_{i+1}`), `m_amp` (`a_i`, two's complement), `m_pos` (`X_i`
//!   with [`POS_FRAC_BITS`] fraction bits, eq. 3), `m_left0..2`
//!   (`I(x_i - k)`), `m_right0..2` (`I(x_{i+1} + k)`), `m_dt` (the line's
//!   `d_t`, [`DT_FRAC_BITS`] fraction bits). The marker carries `m_dt`,
//!   `m_count` (records of the line), `m_wide`, `m_full`, `m_sof` and, in
//!   `m_end`, the line's last stored pixel (its stored width − 1).
//!   Records come left to right, then the marker; lines in input order.
//!
//! ## Timing
//! Throughput: one pixel per clock, `s_tready` high, over back-to-back
//! lines of one width `W ≥` [`MIN_LINE_PERIOD`] (every real image here:
//! `W ≥ 384`). Line n + 2 is accepted once line n has started to be read;
//! [`line_starts`] gives, for any sequence of widths offered back to back,
//! the clock at which each line's first pixel is accepted, and so the
//! stalls of shorter or mixed lines (`s_tready` low between lines, never
//! inside one). Latency: the marker of
//! a line of `W` stored pixels leaves [`marker_latency`]`(W)` clocks after
//! its last stored pixel is accepted (the line's last, or where it is cut), when
//! the engines are free; a record of a
//! declivity that closes at pixel `x` leaves `W - 1 - x` clocks before the
//! marker, minus one. `s_tvalid` low inside a line only delays it.
//!
//! ## Overflow
//! - A line longer than [`W_MAX`] is cut: its first `W_MAX` pixels are
//!   stored and the line ends there (it is processed from then on, as if
//!   that pixel had `tlast`), the marker's `m_wide` is set, and its further
//!   beats are taken (`s_tready` high) and dropped until its `tlast`, or
//!   until a `tuser`, whose beat starts the next line. A line after a
//!   frame's first is cut the same way at the width its frame's first line
//!   stored (see Faults).
//! - More than [`N_MAX`] characteristic declivities: the first `N_MAX` are
//!   sent, the rest dropped, and `m_full` is set.
//!
//! ## Faults
//! - Lines of other widths in a frame: the frame's first line (the one
//!   with `tuser`) sets the frame's width, the pixels it stores; a later
//!   line of the frame wider than that is cut at it (see Overflow: a late
//!   end of line), and a shorter line is stored as it is (an early end of
//!   line; the line processor's output still has the frame's width). Lines
//!   before a camera's first `tuser` are cut at [`W_MAX`] only.
//! - A `tlast` missing: the line ends at the frame's width (at [`W_MAX`]
//!   for a frame's first line, which then runs on into the next) and the
//!   beats after it are dropped up to the next `tlast` or `tuser`: a line
//!   of the frame is lost, and the frame's last line, which has no line
//!   after it, is processed on time.
//! - `s_tuser` on a beat that is not a line's first (a camera that restarts
//!   its frame inside a line, or whose line before lost its `tlast`): the
//!   line ends on the beat before, as if it had `tlast` (its width the
//!   pixels taken), and the beat is not taken on that clock (`s_tready`
//!   low); on a later clock it is taken as the first pixel of a line that
//!   starts a frame. `s_tready` then depends on `s_tvalid` and `s_tuser`
//!   (the line processor's register slice keeps its own `tready` a
//!   register).
//!
//! golden's hardware-parity mode (`golden::hardware`) does the same.
//!
//! ## Reset
//! `reset` (synchronous, active high, one clock or more) returns every
//! register to its value after configuration: both banks free, the three
//! engines idle, a line cut short forgotten. The threshold's histograms
//! are then cleared, one bin a clock: `s_tready` stays low for
//! [`RESET_RECOVERY`] clocks after the reset's last clock, and the next
//! line is processed as after configuration.

use crate::primitives::block_ram::BlockRam;
use crate::detector::adaptive_threshold::{AdaptiveThreshold, CLEAR_CLOCKS, THRESHOLD_LATENCY};
use crate::detector::declivity_tracker::{DeclivityTracker, TRACKER_CENTER};
use crate::params::*;
use crate::detector::position_divider::{PositionDivider, DIVIDER_LATENCY};
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// The shortest width of back-to-back lines of one width that never stalls
/// the input: line n + 2 needs line n's bank, released one clock after its
/// reading starts, `THRESHOLD_LATENCY + 3` clocks after line n's last pixel
/// (see [`line_starts`]).
pub const MIN_LINE_PERIOD: usize = THRESHOLD_LATENCY + 3;

/// Clocks after a reset's last clock during which `s_tready` is low: the
/// threshold's histograms are cleared.
pub const RESET_RECOVERY: usize = CLEAR_CLOCKS;

/// The clock at which the first pixel of each line is accepted when lines of
/// `widths` pixels are offered back to back from clock 0 (`tvalid` always
/// high, no `tuser`: every line is cut at `W_MAX` alone), engines idle at
/// the start. The recurrence of the three engines, with `T` =
/// [`THRESHOLD_LATENCY`], `S_n` the clock of line n's first pixel,
/// `W'_n = min(W_n, W_MAX)` its stored width and `L_n = S_n + W'_n - 1` the
/// clock of its last stored pixel (a wider line's further pixels are taken
/// one a clock, to `S_n + W_n - 1`, and dropped):
/// - the threshold engine starts line n at `B_n = max(L_n + 1, B_(n-1) + T + 1)`;
/// - the reader decides to start it at `D_n = max(B_n + T + 1, D_(n-1) + W'_(n-1))`
///   (the clock of line n - 1's last read address) and reads from `D_n + 1`;
/// - line n + 1 is accepted from `S_n + W_n`, and line n + 2 (same bank)
///   from `D_n + 2`.
pub fn line_starts(widths: &[usize]) -> Vec<u64> {
    let t = THRESHOLD_LATENCY as u64;
    let mut starts: Vec<u64> = Vec::with_capacity(widths.len());
    let mut next_start: Vec<u64> = Vec::with_capacity(widths.len());
    let mut reads: Vec<u64> = Vec::with_capacity(widths.len());
    let (mut b_prev, mut d_prev, mut w_prev): (Option<u64>, Option<u64>, u64) = (None, None, 0);
    for (n, &w) in widths.iter().enumerate() {
        let w = w.max(1) as u64;
        let mut s = if n == 0 { 0 } else { next_start[n - 1] };
        if n >= 2 {
            s = s.max(reads[n - 2] + 2);
        }
        starts.push(s);
        let l = s + w.min(W_MAX as u64) - 1;
        next_start.push(s + w);
        let b = b_prev.map_or(l + 1, |bp| (l + 1).max(bp + t + 1));
        let d = d_prev.map_or(b + t + 1, |dp| (b + t + 1).max(dp + w_prev));
        reads.push(d);
        b_prev = Some(b);
        d_prev = Some(d);
        w_prev = w.min(W_MAX as u64);
    }
    starts
}

/// Clocks from the last pixel of a line of `width` stored pixels being
/// accepted to its marker on the outputs, when the threshold engine and the
/// reader are free: 1 (the line is marked full) + [`THRESHOLD_LATENCY`] +
/// 1 (the bank is marked ready) + 1 (the reader starts) + 1 (block RAM read)
/// + `width - 1` (the line's pixels) + [`TRACKER_CENTER`] + 1 (the window)
/// + 1 (the marker slot) + 1 (the item register) + [`DIVIDER_LATENCY`].
pub const fn marker_latency(width: usize) -> usize {
    1 + THRESHOLD_LATENCY + 1 + 1 + 1 + (width - 1) + TRACKER_CENTER + 1 + 1 + 1 + DIVIDER_LATENCY
}

/// [`marker_latency`] of a camera line `width` pixels wide: the detector
/// stores its first `W_MAX` pixels (a wider line is cut and flagged, its
/// latency counted from its `W_MAX`-th pixel), and a line has one pixel at
/// least.
pub const fn camera_marker_latency(width: usize) -> usize {
    let stored = if width > W_MAX { W_MAX } else if width == 0 { 1 } else { width };
    marker_latency(stored)
}

const BANK_FREE: u64 = 0;
const BANK_FULL: u64 = 1;
const BANK_READY: u64 = 2;

#[derive(LogicBlock)]
pub struct DeclivityDetector {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub s_tdata: Signal<In, Bits<PIXEL_BITS>>,
    pub s_tvalid: Signal<In, Bit>,
    pub s_tuser: Signal<In, Bit>,
    pub s_tlast: Signal<In, Bit>,
    pub s_tready: Signal<Out, Bit>,
    pub m_valid: Signal<Out, Bit>,
    pub m_last: Signal<Out, Bit>,
    pub m_start: Signal<Out, Bits<X_BITS>>,
    pub m_end: Signal<Out, Bits<X_BITS>>,
    pub m_amp: Signal<Out, Bits<AMP_BITS>>,
    pub m_pos: Signal<Out, Bits<POS_BITS>>,
    pub m_left0: Signal<Out, Bits<PIXEL_BITS>>,
    pub m_left1: Signal<Out, Bits<PIXEL_BITS>>,
    pub m_left2: Signal<Out, Bits<PIXEL_BITS>>,
    pub m_right0: Signal<Out, Bits<PIXEL_BITS>>,
    pub m_right1: Signal<Out, Bits<PIXEL_BITS>>,
    pub m_right2: Signal<Out, Bits<PIXEL_BITS>>,
    pub m_dt: Signal<Out, Bits<DT_BITS>>,
    pub m_count: Signal<Out, Bits<COUNT_BITS>>,
    pub m_wide: Signal<Out, Bit>,
    pub m_full: Signal<Out, Bit>,
    pub m_sof: Signal<Out, Bit>,
    // The ping-pong line buffer, one block RAM per bank with its output
    // register (two clocks a read: the reader's address is its next `rx`).
    line_buf0: BlockRam<PIXEL_BITS, X_BITS>,
    line_buf1: BlockRam<PIXEL_BITS, X_BITS>,
    threshold: AdaptiveThreshold,
    tracker: DeclivityTracker,
    divider: PositionDivider,
    // Per bank: state, stored width, flags, d_t.
    state0: ResetDff<Bits<2>>,
    state1: ResetDff<Bits<2>>,
    width0: ResetDff<Bits<LINE_BUF_ADDR_BITS>>,
    width1: ResetDff<Bits<LINE_BUF_ADDR_BITS>>,
    wide0: ResetDff<Bit>,
    wide1: ResetDff<Bit>,
    sof0: ResetDff<Bit>,
    sof1: ResetDff<Bit>,
    dt0: ResetDff<Bits<DT_BITS>>,
    dt1: ResetDff<Bits<DT_BITS>>,
    // A: input.
    wb: ResetDff<Bit>,
    wx: ResetDff<Bits<LINE_BUF_ADDR_BITS>>,
    // The last pixel a line may store: `W_MAX - 1` for a line that starts
    // a frame (and before the first), then that line's last for the rest of
    // its frame (see Faults).
    x_limit: ResetDff<Bits<X_BITS>>,
    // A line was cut at `x_limit`: its further beats are taken and dropped
    // until its `tlast` (or a `tuser`, which starts the next line).
    discard: ResetDff<Bit>,
    // The accepted beat is the line's last stored: at `x_limit`, or `tlast`.
    at_limit: Signal<Local, Bit>,
    ends: Signal<Local, Bit>,
    // The accepted beat's line starts a frame.
    sof_now: Signal<Local, Bit>,
    // The width a line that ends now stores.
    end_width: Signal<Local, Bits<LINE_BUF_ADDR_BITS>>,
    in_line: ResetDff<Bit>,
    prev_pix: ResetDff<Bits<PIXEL_BITS>>,
    line_sof: ResetDff<Bit>,
    // B: threshold.
    mb: ResetDff<Bit>,
    // C: reader.
    rb: ResetDff<Bit>,
    reading: ResetDff<Bit>,
    r_bank: ResetDff<Bit>,
    rx: ResetDff<Bits<X_BITS>>,
    r_last_x: ResetDff<Bits<X_BITS>>,
    r_dt: ResetDff<Bits<DT_BITS>>,
    r_thr: ResetDff<Bits<DT_INT_BITS>>,
    r_wide: ResetDff<Bit>,
    r_sof: ResetDff<Bit>,
    free_pending: ResetDff<Bit>,
    free_bank: ResetDff<Bit>,
    // `rx == r_last_x` while reading, computed a clock ahead: the reader's
    // decision starts at registers.
    r_at_end: ResetDff<Bit>,
    d_valid: ResetDff<Bit>,
    d_bank: ResetDff<Bit>,
    d_first: ResetDff<Bit>,
    d_last: ResetDff<Bit>,
    d_x: ResetDff<Bits<X_BITS>>,
    d_dt: ResetDff<Bits<DT_BITS>>,
    d_thr: ResetDff<Bits<DT_INT_BITS>>,
    d_wide: ResetDff<Bit>,
    d_sof: ResetDff<Bit>,
    // Combinational.
    write_state: Signal<Local, Bits<2>>,
    accept: Signal<Local, Bit>,
    // A start of frame inside a line: the line ends before this beat.
    early: Signal<Local, Bit>,
    x_now: Signal<Local, Bits<LINE_BUF_ADDR_BITS>>,
    diff: Signal<Local, Bits<PIXEL_BITS>>,
    scan_state: Signal<Local, Bits<2>>,
    scan_width: Signal<Local, Bits<LINE_BUF_ADDR_BITS>>,
    scan_diffs: Signal<Local, Bits<LINE_BUF_ADDR_BITS>>,
    read_state: Signal<Local, Bits<2>>,
    read_width: Signal<Local, Bits<LINE_BUF_ADDR_BITS>>,
    start_read: Signal<Local, Bit>,
    read_last_x: Signal<Local, Bits<X_BITS>>,
    rx_next: Signal<Local, Bits<X_BITS>>,
    rx_inc: Signal<Local, Bits<X_BITS>>,
    // Constants.
    x_max: Constant<Bits<X_BITS>>,
    bank_free: Constant<Bits<2>>,
    bank_full: Constant<Bits<2>>,
    bank_ready: Constant<Bits<2>>,
    dt_frac: Constant<Bits<8>>,
}

impl Default for DeclivityDetector {
    fn default() -> Self {
        let c8 = |v: usize| Constant::new((v as u64).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            s_tdata: Default::default(),
            s_tvalid: Default::default(),
            s_tuser: Default::default(),
            s_tlast: Default::default(),
            s_tready: Default::default(),
            m_valid: Default::default(),
            m_last: Default::default(),
            m_start: Default::default(),
            m_end: Default::default(),
            m_amp: Default::default(),
            m_pos: Default::default(),
            m_left0: Default::default(),
            m_left1: Default::default(),
            m_left2: Default::default(),
            m_right0: Default::default(),
            m_right1: Default::default(),
            m_right2: Default::default(),
            m_dt: Default::default(),
            m_count: Default::default(),
            m_wide: Default::default(),
            m_full: Default::default(),
            m_sof: Default::default(),
            line_buf0: Default::default(),
            line_buf1: Default::default(),
            threshold: Default::default(),
            tracker: Default::default(),
            divider: Default::default(),
            state0: Default::default(),
            state1: Default::default(),
            width0: Default::default(),
            width1: Default::default(),
            wide0: Default::default(),
            wide1: Default::default(),
            sof0: Default::default(),
            sof1: Default::default(),
            dt0: Default::default(),
            dt1: Default::default(),
            wb: Default::default(),
            wx: Default::default(),
            x_limit: ResetDff::new(((W_MAX - 1) as u64).into()),
            discard: Default::default(),
            at_limit: Default::default(),
            ends: Default::default(),
            sof_now: Default::default(),
            end_width: Default::default(),
            in_line: Default::default(),
            prev_pix: Default::default(),
            line_sof: Default::default(),
            mb: Default::default(),
            rb: Default::default(),
            reading: Default::default(),
            r_bank: Default::default(),
            rx: Default::default(),
            r_last_x: Default::default(),
            r_dt: Default::default(),
            r_thr: Default::default(),
            r_wide: Default::default(),
            r_sof: Default::default(),
            free_pending: Default::default(),
            free_bank: Default::default(),
            r_at_end: Default::default(),
            d_bank: Default::default(),
            d_valid: Default::default(),
            d_first: Default::default(),
            d_last: Default::default(),
            d_x: Default::default(),
            d_dt: Default::default(),
            d_thr: Default::default(),
            d_wide: Default::default(),
            d_sof: Default::default(),
            write_state: Default::default(),
            accept: Default::default(),
            early: Default::default(),
            x_now: Default::default(),
            diff: Default::default(),
            scan_state: Default::default(),
            scan_width: Default::default(),
            scan_diffs: Default::default(),
            read_state: Default::default(),
            read_width: Default::default(),
            start_read: Default::default(),
            read_last_x: Default::default(),
            rx_next: Default::default(),
            rx_inc: Default::default(),
            x_max: Constant::new(((W_MAX - 1) as u64).into()),
            bank_free: Constant::new(BANK_FREE.into()),
            bank_full: Constant::new(BANK_FULL.into()),
            bank_ready: Constant::new(BANK_READY.into()),
            dt_frac: c8(DT_FRAC_BITS),
        }
    }
}

impl Logic for DeclivityDetector {
    #[hdl_gen]
    fn update(&mut self) {
        self.line_buf0.clock.next = self.clock.val();
        self.line_buf1.clock.next = self.clock.val();
        self.threshold.clock.next = self.clock.val();
        self.threshold.reset.next = self.reset.val();
        self.tracker.clock.next = self.clock.val();
        self.tracker.reset.next = self.reset.val();
        self.divider.clock.next = self.clock.val();
        self.divider.reset.next = self.reset.val();
        dff_setup!(
            self, clock, x_limit, discard, state0, state1, width0, width1, wide0, wide1, sof0, sof1, dt0, dt1, wb, wx, in_line,
            prev_pix, line_sof, mb, rb, reading, r_bank, rx, r_last_x, r_dt, r_thr, r_wide, r_sof,
            free_pending, free_bank, r_at_end, d_valid, d_bank, d_first, d_last, d_x, d_dt, d_thr, d_wide, d_sof
        );
        self.state0.reset.next = self.reset.val();
        self.state1.reset.next = self.reset.val();
        self.width0.reset.next = self.reset.val();
        self.width1.reset.next = self.reset.val();
        self.wide0.reset.next = self.reset.val();
        self.wide1.reset.next = self.reset.val();
        self.sof0.reset.next = self.reset.val();
        self.sof1.reset.next = self.reset.val();
        self.dt0.reset.next = self.reset.val();
        self.dt1.reset.next = self.reset.val();
        self.wb.reset.next = self.reset.val();
        self.wx.reset.next = self.reset.val();
        self.in_line.reset.next = self.reset.val();
        self.prev_pix.reset.next = self.reset.val();
        self.line_sof.reset.next = self.reset.val();
        self.mb.reset.next = self.reset.val();
        self.rb.reset.next = self.reset.val();
        self.reading.reset.next = self.reset.val();
        self.r_bank.reset.next = self.reset.val();
        self.rx.reset.next = self.reset.val();
        self.r_last_x.reset.next = self.reset.val();
        self.r_dt.reset.next = self.reset.val();
        self.r_thr.reset.next = self.reset.val();
        self.r_wide.reset.next = self.reset.val();
        self.r_sof.reset.next = self.reset.val();
        self.free_pending.reset.next = self.reset.val();
        self.free_bank.reset.next = self.reset.val();
        self.r_at_end.reset.next = self.reset.val();
        self.d_valid.reset.next = self.reset.val();
        self.d_bank.reset.next = self.reset.val();
        self.d_first.reset.next = self.reset.val();
        self.d_last.reset.next = self.reset.val();
        self.d_x.reset.next = self.reset.val();
        self.x_limit.reset.next = self.reset.val();
        self.discard.reset.next = self.reset.val();
        self.d_dt.reset.next = self.reset.val();
        self.d_thr.reset.next = self.reset.val();
        self.d_wide.reset.next = self.reset.val();
        self.d_sof.reset.next = self.reset.val();

        // ---- A: input into bank wb, accepted while that bank is free.
        self.write_state.next = self.state0.q.val();
        if self.wb.q.val() {
            self.write_state.next = self.state1.q.val();
        }
        // A beat with `tuser` inside a line is not taken: the line ends on
        // the beat before (as if that beat had `tlast`), and the beat is
        // taken on a later clock as the first pixel of the next line.
        // After a cut, beats are taken and dropped (whatever the banks)
        // until `tlast`, or a `tuser`, which starts a line.
        self.early.next = self.s_tvalid.val() & self.s_tuser.val() & self.in_line.q.val();
        self.s_tready.next = ((self.write_state.val() == self.bank_free.val()) & !self.threshold.clearing.val() & !self.early.val())
            | (self.discard.q.val() & !self.s_tuser.val());
        self.accept.next = self.s_tvalid.val()
            & (self.write_state.val() == self.bank_free.val())
            & !self.threshold.clearing.val()
            & !self.early.val()
            & !(self.discard.q.val() & !self.s_tuser.val());
        if self.s_tvalid.val() & self.discard.q.val() & !self.s_tuser.val() & self.s_tlast.val() {
            self.discard.d.next = false;
        }
        self.x_now.next = 0.into();
        if self.in_line.q.val() {
            self.x_now.next = self.wx.q.val();
        }
        // (`x_now` never passes `x_limit`: the line ends there, and
        // `x_limit` changes only between lines; an equality, no carry
        // chain. A frame's first line is limited by `W_MAX` alone.)
        self.at_limit.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.x_now.val()) == self.x_limit.q.val();
        if !self.in_line.q.val() & self.s_tuser.val() {
            self.at_limit.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.x_now.val()) == self.x_max.val();
        }
        self.ends.next = self.s_tlast.val() | self.at_limit.val();
        self.sof_now.next = self.s_tuser.val();
        if self.in_line.q.val() {
            self.sof_now.next = self.line_sof.q.val();
        }
        self.diff.next = self.s_tdata.val() - self.prev_pix.q.val();
        if self.prev_pix.q.val() > self.s_tdata.val() {
            self.diff.next = self.prev_pix.q.val() - self.s_tdata.val();
        }
        self.line_buf0.write_address.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.x_now.val());
        self.line_buf1.write_address.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.x_now.val());
        self.line_buf0.write_data.next = self.s_tdata.val();
        self.line_buf1.write_data.next = self.s_tdata.val();
        self.line_buf0.write_enable.next = self.accept.val() & !self.wb.q.val();
        self.line_buf1.write_enable.next = self.accept.val() & self.wb.q.val();
        self.threshold.inc_valid.next = self.accept.val() & self.in_line.q.val();
        self.threshold.inc_bank.next = self.wb.q.val();
        self.threshold.inc_bin.next = self.diff.val();
        if self.early.val() {
            self.in_line.d.next = false;
        }
        if self.accept.val() {
            self.prev_pix.d.next = self.s_tdata.val();
            self.in_line.d.next = !self.ends.val();
            self.discard.d.next = !self.s_tlast.val() & self.at_limit.val();
            self.wx.d.next = self.x_now.val() + 1;
            if !self.in_line.q.val() {
                self.line_sof.d.next = self.s_tuser.val();
                if self.s_tuser.val() {
                    self.x_limit.d.next = self.x_max.val();
                }
            }
        }

        // ---- C: the reader (decided before the bank states change below).
        self.read_state.next = self.state0.q.val();
        self.read_width.next = self.width0.q.val();
        if self.rb.q.val() {
            self.read_state.next = self.state1.q.val();
            self.read_width.next = self.width1.q.val();
        }
        self.start_read.next =
            (self.read_state.val() == self.bank_ready.val()) & (!self.reading.q.val() | self.r_at_end.q.val());
        self.read_last_x.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.read_width.val() - 1);
        // The line buffer reads `rx`'s next value (both banks: the data are
        // picked by `d_bank` after the RAMs' output registers), so that its
        // word is out on the same clock as the pixel's other fields.
        // (`rx + 1` through a signal of its width: it wraps in the
        // comparison below as in the model.)
        self.rx_inc.next = self.rx.q.val() + 1;
        self.rx_next.next = self.rx.q.val();
        if self.reading.q.val() {
            self.rx_next.next = self.rx_inc.val();
        }
        if self.start_read.val() {
            self.rx_next.next = 0.into();
        }
        self.line_buf0.read_address.next = self.rx_next.val();
        self.line_buf1.read_address.next = self.rx_next.val();
        self.d_valid.d.next = self.reading.q.val();
        self.d_bank.d.next = self.r_bank.q.val();
        self.d_first.d.next = self.rx.q.val() == 0;
        self.d_last.d.next = self.rx.q.val() == self.r_last_x.q.val();
        self.d_x.d.next = self.rx.q.val();
        self.d_dt.d.next = self.r_dt.q.val();
        self.d_thr.d.next = self.r_thr.q.val();
        self.d_wide.d.next = self.r_wide.q.val();
        self.d_sof.d.next = self.r_sof.q.val();
        self.rx.d.next = self.rx_next.val();
        if self.reading.q.val() {
            self.r_at_end.d.next = self.rx_inc.val() == self.r_last_x.q.val();
            if self.r_at_end.q.val() {
                self.reading.d.next = false;
            }
        }
        self.free_pending.d.next = false;
        if self.start_read.val() {
            self.reading.d.next = true;
            self.r_bank.d.next = self.rb.q.val();
            self.r_last_x.d.next = self.read_last_x.val();
            self.r_at_end.d.next = !self.read_last_x.val().any();
            self.r_dt.d.next = self.dt0.q.val();
            self.r_wide.d.next = self.wide0.q.val();
            self.r_sof.d.next = self.sof0.q.val();
            // ⌊d_t⌋ once per line.
            self.r_thr.d.next = bit_cast::<DT_INT_BITS, DT_BITS>(self.dt0.q.val() >> self.dt_frac.val());
            if self.rb.q.val() {
                self.r_thr.d.next = bit_cast::<DT_INT_BITS, DT_BITS>(self.dt1.q.val() >> self.dt_frac.val());
                self.r_dt.d.next = self.dt1.q.val();
                self.r_wide.d.next = self.wide1.q.val();
                self.r_sof.d.next = self.sof1.q.val();
            }
            self.rb.d.next = !self.rb.q.val();
            // The bank is released once its first address has been read.
            self.free_pending.d.next = true;
            self.free_bank.d.next = self.rb.q.val();
        }

        // ---- B: the threshold engine takes full banks in order.
        self.scan_state.next = self.state0.q.val();
        self.scan_width.next = self.width0.q.val();
        if self.mb.q.val() {
            self.scan_state.next = self.state1.q.val();
            self.scan_width.next = self.width1.q.val();
        }
        // Through a signal of its own width (see `amag` in the tracker).
        self.scan_diffs.next = self.scan_width.val() - 1;
        self.threshold.scan_n.next = bit_cast::<HIST_COUNT_BITS, LINE_BUF_ADDR_BITS>(self.scan_diffs.val());
        self.threshold.scan_bank.next = self.mb.q.val();
        self.threshold.scan_start.next =
            (self.scan_state.val() == self.bank_full.val()) & !self.threshold.busy.val() & !self.threshold.done.val();

        // ---- Bank state changes (each targets a bank in a different state).
        // A frame's first line sets the frame's last pixel at its end (its
        // last stored, or, cut short, the one before the next `tuser`).
        self.end_width.next = self.x_now.val() + 1;
        if self.accept.val() & self.ends.val() & self.sof_now.val() {
            self.x_limit.d.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.x_now.val());
        }
        if self.early.val() & self.line_sof.q.val() {
            self.x_limit.d.next = bit_cast::<X_BITS, LINE_BUF_ADDR_BITS>(self.x_now.val() - 1);
        }
        // (A line is cut, `wide`, when its last stored pixel is not its
        // `tlast`.)
        if self.accept.val() & self.ends.val() {
            self.wb.d.next = !self.wb.q.val();
            if self.wb.q.val() {
                self.state1.d.next = self.bank_full.val();
                self.width1.d.next = self.end_width.val();
                self.wide1.d.next = !self.s_tlast.val();
                self.sof1.d.next = self.sof_now.val();
            } else {
                self.state0.d.next = self.bank_full.val();
                self.width0.d.next = self.end_width.val();
                self.wide0.d.next = !self.s_tlast.val();
                self.sof0.d.next = self.sof_now.val();
            }
        }
        // A line ended early (its `x_now` pixels stored, all of them taken
        // on earlier clocks).
        if self.early.val() {
            self.wb.d.next = !self.wb.q.val();
            if self.wb.q.val() {
                self.state1.d.next = self.bank_full.val();
                self.width1.d.next = self.x_now.val();
                self.wide1.d.next = false;
                self.sof1.d.next = self.line_sof.q.val();
            } else {
                self.state0.d.next = self.bank_full.val();
                self.width0.d.next = self.x_now.val();
                self.wide0.d.next = false;
                self.sof0.d.next = self.line_sof.q.val();
            }
        }
        if self.threshold.done.val() {
            self.mb.d.next = !self.mb.q.val();
            if self.mb.q.val() {
                self.state1.d.next = self.bank_ready.val();
                self.dt1.d.next = self.threshold.dt.val();
            } else {
                self.state0.d.next = self.bank_ready.val();
                self.dt0.d.next = self.threshold.dt.val();
            }
        }
        if self.free_pending.q.val() {
            if self.free_bank.q.val() {
                self.state1.d.next = self.bank_free.val();
            } else {
                self.state0.d.next = self.bank_free.val();
            }
        }

        // ---- Extraction and eq. 3.
        self.tracker.in_valid.next = self.d_valid.q.val();
        self.tracker.in_first.next = self.d_first.q.val();
        self.tracker.in_last.next = self.d_last.q.val();
        self.tracker.in_pix.next = self.line_buf0.read_data.val();
        if self.d_bank.q.val() {
            self.tracker.in_pix.next = self.line_buf1.read_data.val();
        }
        self.tracker.in_x.next = self.d_x.q.val();
        self.tracker.in_dt.next = self.d_dt.q.val();
        self.tracker.in_thr.next = self.d_thr.q.val();
        self.tracker.in_wide.next = self.d_wide.q.val();
        self.tracker.in_sof.next = self.d_sof.q.val();
        self.divider.in_valid.next = self.tracker.item_valid.val();
        self.divider.in_dividend.next = self.tracker.item_dividend.val();
        self.divider.in_divisor.next = self.tracker.item_divisor.val();
        self.divider.in_tag0.next = self.tracker.item_tag0.val();
        self.divider.in_tag1.next = self.tracker.item_tag1.val();
        self.divider.in_tag2.next = self.tracker.item_tag2.val();
        self.divider.in_tag3.next = self.tracker.item_tag3.val();

        // ---- Outputs: the divider's registers, zero between beats.
        self.m_valid.next = self.divider.out_valid.val();
        self.m_last.next = false;
        self.m_start.next = 0.into();
        self.m_end.next = 0.into();
        self.m_amp.next = 0.into();
        self.m_pos.next = 0.into();
        self.m_left0.next = 0.into();
        self.m_left1.next = 0.into();
        self.m_left2.next = 0.into();
        self.m_right0.next = 0.into();
        self.m_right1.next = 0.into();
        self.m_right2.next = 0.into();
        self.m_dt.next = 0.into();
        self.m_count.next = 0.into();
        self.m_wide.next = false;
        self.m_full.next = false;
        self.m_sof.next = false;
        if self.divider.out_valid.val() {
            self.m_last.next = self.divider.out_marker.val();
            self.m_start.next = self.divider.out_start.val();
            self.m_end.next = self.divider.out_end.val();
            self.m_amp.next = self.divider.out_amp.val();
            self.m_pos.next = self.divider.out_quotient.val();
            self.m_left0.next = self.divider.out_left0.val();
            self.m_left1.next = self.divider.out_left1.val();
            self.m_left2.next = self.divider.out_left2.val();
            self.m_right0.next = self.divider.out_right0.val();
            self.m_right1.next = self.divider.out_right1.val();
            self.m_right2.next = self.divider.out_right2.val();
            self.m_dt.next = self.divider.out_dt.val();
            self.m_count.next = self.divider.out_count.val();
            self.m_wide.next = self.divider.out_wide.val();
            self.m_full.next = self.divider.out_full.val();
            self.m_sof.next = self.divider.out_sof.val();
        }
    }
}
