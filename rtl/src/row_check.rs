//! The row check (`DESIGN.md` §2.2, golden's default mode, issue 6;
//! `golden::frame::confirmed_matches`): a match of row `y` is kept iff row
//! `y - 1` or row `y + 1` of its frame has a match within
//! [`CONSISTENT_DX_LSB`] (3 px) in position whose disparity differs by at
//! most [`CONSISTENT_DD_LSB`] (1 px), both bounds inclusive. A frame's
//! first row is checked against the row below only, its last against the
//! row above only; a one-row frame keeps nothing. It sits between the
//! matcher's match output and the interpolator's input and works on the
//! matcher's fixed-point values ([`POS_FRAC_BITS`] fraction bits), on which
//! it is exact: golden fed the same values (`x / 16`, `d / 16`, exact in
//! `f64`) keeps the same matches.
//!
//! - **Loader**: each incoming row's matches go into one of four banks of
//!   [`N_MAX`] entries (`X`, `d`); three copies of the memory (block RAMs
//!   with their output registers, [`BlockRam`]) give the engine three read
//!   ports: the checked row and the row above and below it.
//! - **Engine**: row `y` is checked once row `y + 1`'s marker has arrived,
//!   or right after its own marker if `y` is the frame's last row (so after
//!   the last row's marker rows `h - 2` and `h - 1` leave back to back).
//!   Its matches are read in order into a 4-entry prefetch ring; each
//!   neighbour is read in order into a window ring ([`RowWindow`],
//!   [`ROW_WINDOW`] entries) that drops the matches left of the checked
//!   match's window as the checked match moves right (a merge: positions
//!   increase in every row) and compares every held entry with the checked
//!   match in one clock. A match is decided on the clock either window
//!   holds a confirming entry, or both windows hold every neighbour match
//!   up to `X + DX`; a kept match leaves on the next clock.
//!
//! Exactness needs at most `ROW_WINDOW - 1` = 7 matches of a row within
//! any 6 px (so that a window and the first match beyond it fit the ring):
//! always true of the matcher's output, whose positions are declivities at
//! least a pixel apart (16 LSB). Denser rows are decided without the
//! matches that do not fit (a match may then be dropped that golden keeps)
//! and `crowded` flags it.
//!
//! ## Ports
//! - In, the matcher's stream (`rtl::declivity_matcher`): `m_valid` with
//!   `m_last` low is a match, `m_x_ref` (`X`), `m_disp` (its disparity),
//!   both [`POS_FRAC_BITS`] fraction bits, strictly increasing `m_x_ref`
//!   within a row, at most [`N_MAX`] per row (later ones are not stored);
//!   `m_valid` with `m_last` high ends the row: `m_sof` (it starts a
//!   frame), `m_eof` (it ends the frame; required on every frame's last
//!   row). Matches at most one per clock, rows back to back or with gaps.
//! - Out, the same stream one row later, no back-pressure: `c_valid`,
//!   `c_last`; on a kept match `c_x_ref`, `c_disp`; on the marker `c_sof`,
//!   `c_eof` (the row's flags) and `c_count` (matches kept); all zero while
//!   `c_valid` is low.
//! - `overflow`: high for a clock, on the marker's clock of a row that
//!   found all four banks in use when it started (its first match or its
//!   marker): that row is dropped whole (its matches are not stored, it
//!   never leaves, and the rows around it are checked against each other
//!   as neighbours). `crowded`: high for a clock with a match decided
//!   without the whole of a neighbour's window (see above).
//!
//! ## Timing
//! The engine starts row `y` on the clock after the marker that makes it
//! ready ([`ROW_START_LAG`]), or on the clock after it finished the
//! previous row. From its start clock `s` it finishes on clock `s + c`, `c`
//! at most [`row_check_cycles`]`(n_above, n, n_below)` (exactly `1` for an
//! empty row and `n + 4` when neither neighbour has a match); its kept
//! matches leave in order, at most one per clock, the first at
//! `s + ` [`ROW_FIRST_LAG`] at the earliest, and its marker leaves at
//! `s + c + 1`. The engine takes the next row on the clock after it
//! finished. A row is dropped only if, when it starts, the engine has not
//! finished the row two before it; with row markers at least
//! [`row_check_period`]` = row_check_cycles(N_MAX, N_MAX, N_MAX) + 1`
//! clocks apart (within and across frames) no row is dropped.

mod window;

use crate::block_ram::BlockRam;
use crate::params::*;
use rust_hdl::prelude::*;
pub use window::RowWindow;

/// Clocks from the marker that makes a row ready to its start clock.
pub const ROW_START_LAG: usize = 1;
/// Clocks from a row's start to its first match leaving at the earliest:
/// the first reads' address (the clock after the start), the memory's two
/// clocks, the rings' write, the decision's output register.
pub const ROW_FIRST_LAG: usize = 5;
/// Entries of the checked row's prefetch ring.
const CUR_RING: usize = 4;
/// Bits of a slot of that ring.
const CUR_SLOT_BITS: usize = 2;
/// Bits of its fill `0 ..= CUR_RING`.
const CUR_FILL_BITS: usize = 3;
/// Bits of a row number modulo twice the banks (so that full and empty
/// differ).
const ROW_PTR_BITS: usize = ROW_BANK_BITS + 1;

/// Clocks from a row's start to its finish (the clock of its marker's
/// decision), at most, for a row of `n` matches between rows of `above`
/// and `below` (0 for a missing neighbour), when no window is crowded.
///
/// Exactly 1 for `n = 0`. Otherwise the first decision is 4 clocks after
/// the start, the matches are decided at most one per clock, and a match
/// waits only for a neighbour's entries not yet in its ring: entries are
/// read one per clock and arrive 3 clocks after their read, so the wait
/// for a neighbour of `m` matches adds over the row at most `m` clocks
/// (one per entry read) plus 2 per wait (the last entry's memory latency),
/// and each of at most `min(n, m + 1)` matches waits once for it (each
/// wait is for a different first entry right of the window, or the end
/// of the row).
pub const fn row_check_cycles(above: usize, n: usize, below: usize) -> usize {
    if n == 0 {
        return 1;
    }
    4 + n + neighbour_wait(n, above) + neighbour_wait(n, below)
}

/// The clocks a row of `n` matches waits at most for a neighbour of `m`.
const fn neighbour_wait(n: usize, m: usize) -> usize {
    if m == 0 {
        return 0;
    }
    let waits = if n < m + 1 { n } else { m + 1 };
    m + 2 * waits
}

/// The smallest clocks between row markers (within and across frames)
/// with which no row is dropped whatever the rows' matches.
pub const fn row_check_period() -> usize {
    row_check_cycles(N_MAX, N_MAX, N_MAX) + 1
}

#[derive(LogicBlock)]
pub struct RowCheck {
    pub clock: Signal<In, Clock>,
    pub m_valid: Signal<In, Bit>,
    pub m_last: Signal<In, Bit>,
    pub m_x_ref: Signal<In, Bits<POS_BITS>>,
    pub m_disp: Signal<In, Bits<POS_BITS>>,
    pub m_sof: Signal<In, Bit>,
    pub m_eof: Signal<In, Bit>,
    pub c_valid: Signal<Out, Bit>,
    pub c_last: Signal<Out, Bit>,
    pub c_x_ref: Signal<Out, Bits<POS_BITS>>,
    pub c_disp: Signal<Out, Bits<POS_BITS>>,
    pub c_sof: Signal<Out, Bit>,
    pub c_eof: Signal<Out, Bit>,
    pub c_count: Signal<Out, Bits<COUNT_BITS>>,
    pub overflow: Signal<Out, Bit>,
    pub crowded: Signal<Out, Bit>,
    // ---- The neighbours' windows and the checked row's memory copy.
    above: RowWindow,
    below: RowWindow,
    cur_mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    // ---- Loader: the row being received (admission, its next index), the
    // rows stored (modulo 8; the bank is the low bits), each bank's row.
    in_line: DFF<Bit>,
    dropping: DFF<Bit>,
    widx: DFF<Bits<COUNT_BITS>>,
    wl: DFF<Bits<ROW_PTR_BITS>>,
    cnt0: DFF<Bits<COUNT_BITS>>,
    sof0: DFF<Bit>,
    eof0: DFF<Bit>,
    cnt1: DFF<Bits<COUNT_BITS>>,
    sof1: DFF<Bit>,
    eof1: DFF<Bit>,
    cnt2: DFF<Bits<COUNT_BITS>>,
    sof2: DFF<Bit>,
    eof2: DFF<Bit>,
    cnt3: DFF<Bits<COUNT_BITS>>,
    sof3: DFF<Bit>,
    eof3: DFF<Bit>,
    // ---- Engine: the row checked (or next), whether the row before it is
    // still needed as its row above, the row's matches, flags, decisions
    // and kept matches.
    el: DFF<Bits<ROW_PTR_BITS>>,
    prev_needed: DFF<Bit>,
    busy: DFF<Bit>,
    n_cur: DFF<Bits<COUNT_BITS>>,
    sof_cur: DFF<Bit>,
    eof_cur: DFF<Bit>,
    dec: DFF<Bits<COUNT_BITS>>,
    kept: DFF<Bits<COUNT_BITS>>,
    // The checked row's prefetch ring.
    crd: DFF<Bits<COUNT_BITS>>,
    crd1: DFF<Bit>,
    crd2: DFF<Bit>,
    cfill: DFF<Bits<CUR_FILL_BITS>>,
    cwi: DFF<Bits<CUR_SLOT_BITS>>,
    cri: DFF<Bits<CUR_SLOT_BITS>>,
    cx0: DFF<Bits<POS_BITS>>,
    cd0: DFF<Bits<POS_BITS>>,
    cx1: DFF<Bits<POS_BITS>>,
    cd1: DFF<Bits<POS_BITS>>,
    cx2: DFF<Bits<POS_BITS>>,
    cd2: DFF<Bits<POS_BITS>>,
    cx3: DFF<Bits<POS_BITS>>,
    cd3: DFF<Bits<POS_BITS>>,
    // ---- Output registers.
    o_valid: DFF<Bit>,
    o_last: DFF<Bit>,
    o_x: DFF<Bits<POS_BITS>>,
    o_d: DFF<Bits<POS_BITS>>,
    o_sof: DFF<Bit>,
    o_eof: DFF<Bit>,
    o_count: DFF<Bits<COUNT_BITS>>,
    overflow_q: DFF<Bit>,
    crowded_q: DFF<Bit>,
    // ---- Locals.
    first_event: Signal<Local, Bit>,
    used: Signal<Local, Bits<ROW_PTR_BITS>>,
    drop_now: Signal<Local, Bit>,
    take_match: Signal<Local, Bit>,
    take_marker: Signal<Local, Bit>,
    wbank: Signal<Local, Bits<ROW_BANK_BITS>>,
    waddr: Signal<Local, Bits<ROW_ADDR_BITS>>,
    wdata: Signal<Local, Bits<ROW_ENTRY_BITS>>,
    pend: Signal<Local, Bits<ROW_PTR_BITS>>,
    bank_cur: Signal<Local, Bits<ROW_BANK_BITS>>,
    bank_up: Signal<Local, Bits<ROW_BANK_BITS>>,
    bank_dn: Signal<Local, Bits<ROW_BANK_BITS>>,
    cnt_cur: Signal<Local, Bits<COUNT_BITS>>,
    cnt_up: Signal<Local, Bits<COUNT_BITS>>,
    cnt_dn: Signal<Local, Bits<COUNT_BITS>>,
    sof_el: Signal<Local, Bit>,
    eof_el: Signal<Local, Bit>,
    start: Signal<Local, Bit>,
    head_x: Signal<Local, Bits<POS_BITS>>,
    head_d: Signal<Local, Bits<POS_BITS>>,
    q_valid: Signal<Local, Bit>,
    keep: Signal<Local, Bit>,
    up_ready: Signal<Local, Bit>,
    dn_ready: Signal<Local, Bit>,
    decide: Signal<Local, Bit>,
    finish: Signal<Local, Bit>,
    ckept: Signal<Local, Bits<CUR_FILL_BITS>>,
    cocc: Signal<Local, Bits<CUR_FILL_BITS>>,
    cissue: Signal<Local, Bit>,
    rx: Signal<Local, Bits<POS_BITS>>,
    rdd: Signal<Local, Bits<POS_BITS>>,
    // ---- Constants.
    bank0: Constant<Bits<ROW_BANK_BITS>>,
    bank1: Constant<Bits<ROW_BANK_BITS>>,
    bank2: Constant<Bits<ROW_BANK_BITS>>,
    bank3: Constant<Bits<ROW_BANK_BITS>>,
    slot1: Constant<Bits<CUR_SLOT_BITS>>,
    slot2: Constant<Bits<CUR_SLOT_BITS>>,
    slot3: Constant<Bits<CUR_SLOT_BITS>>,
    banks: Constant<Bits<ROW_PTR_BITS>>,
    two: Constant<Bits<ROW_PTR_BITS>>,
    cur_ring: Constant<Bits<CUR_FILL_BITS>>,
    one_fill: Constant<Bits<CUR_FILL_BITS>>,
    n_max: Constant<Bits<COUNT_BITS>>,
    index_bits: Constant<Bits<8>>,
    pos_bits: Constant<Bits<8>>,
}

impl Default for RowCheck {
    fn default() -> Self {
        Self::new()
    }
}

impl RowCheck {
    /// The row check (no generation-time parameter: the thresholds are
    /// golden's, [`CONSISTENT_DX_LSB`] and [`CONSISTENT_DD_LSB`]).
    pub fn new() -> Self {
        let bank = |b: u64| Constant::<Bits<ROW_BANK_BITS>>::new(b.into());
        let slot = |b: u64| Constant::<Bits<CUR_SLOT_BITS>>::new(b.into());
        RowCheck {
            clock: Default::default(),
            m_valid: Default::default(),
            m_last: Default::default(),
            m_x_ref: Default::default(),
            m_disp: Default::default(),
            m_sof: Default::default(),
            m_eof: Default::default(),
            c_valid: Default::default(),
            c_last: Default::default(),
            c_x_ref: Default::default(),
            c_disp: Default::default(),
            c_sof: Default::default(),
            c_eof: Default::default(),
            c_count: Default::default(),
            overflow: Default::default(),
            crowded: Default::default(),
            above: Default::default(),
            below: Default::default(),
            cur_mem: Default::default(),
            in_line: Default::default(),
            dropping: Default::default(),
            widx: Default::default(),
            wl: Default::default(),
            cnt0: Default::default(),
            sof0: Default::default(),
            eof0: Default::default(),
            cnt1: Default::default(),
            sof1: Default::default(),
            eof1: Default::default(),
            cnt2: Default::default(),
            sof2: Default::default(),
            eof2: Default::default(),
            cnt3: Default::default(),
            sof3: Default::default(),
            eof3: Default::default(),
            el: Default::default(),
            prev_needed: Default::default(),
            busy: Default::default(),
            n_cur: Default::default(),
            sof_cur: Default::default(),
            eof_cur: Default::default(),
            dec: Default::default(),
            kept: Default::default(),
            crd: Default::default(),
            crd1: Default::default(),
            crd2: Default::default(),
            cfill: Default::default(),
            cwi: Default::default(),
            cri: Default::default(),
            cx0: Default::default(),
            cd0: Default::default(),
            cx1: Default::default(),
            cd1: Default::default(),
            cx2: Default::default(),
            cd2: Default::default(),
            cx3: Default::default(),
            cd3: Default::default(),
            o_valid: Default::default(),
            o_last: Default::default(),
            o_x: Default::default(),
            o_d: Default::default(),
            o_sof: Default::default(),
            o_eof: Default::default(),
            o_count: Default::default(),
            overflow_q: Default::default(),
            crowded_q: Default::default(),
            first_event: Default::default(),
            used: Default::default(),
            drop_now: Default::default(),
            take_match: Default::default(),
            take_marker: Default::default(),
            wbank: Default::default(),
            waddr: Default::default(),
            wdata: Default::default(),
            pend: Default::default(),
            bank_cur: Default::default(),
            bank_up: Default::default(),
            bank_dn: Default::default(),
            cnt_cur: Default::default(),
            cnt_up: Default::default(),
            cnt_dn: Default::default(),
            sof_el: Default::default(),
            eof_el: Default::default(),
            start: Default::default(),
            head_x: Default::default(),
            head_d: Default::default(),
            q_valid: Default::default(),
            keep: Default::default(),
            up_ready: Default::default(),
            dn_ready: Default::default(),
            decide: Default::default(),
            finish: Default::default(),
            ckept: Default::default(),
            cocc: Default::default(),
            cissue: Default::default(),
            rx: Default::default(),
            rdd: Default::default(),
            bank0: bank(0),
            bank1: bank(1),
            bank2: bank(2),
            bank3: bank(3),
            slot1: slot(1),
            slot2: slot(2),
            slot3: slot(3),
            banks: Constant::new(((1u64 << ROW_BANK_BITS) as u64).into()),
            two: Constant::new(2u64.into()),
            cur_ring: Constant::new((CUR_RING as u64).into()),
            one_fill: Constant::new(1u64.into()),
            n_max: Constant::new((N_MAX as u64).into()),
            index_bits: Constant::new((INDEX_BITS as u64).into()),
            pos_bits: Constant::new((POS_BITS as u64).into()),
        }
    }
}

impl Logic for RowCheck {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, in_line, dropping, widx, wl, cnt0, sof0, eof0, cnt1, sof1, eof1, cnt2, sof2, eof2, cnt3, sof3, eof3, el, prev_needed, busy, n_cur, sof_cur, eof_cur, dec, kept, crd, crd1, crd2, cfill, cwi, cri, cx0, cd0, cx1, cd1, cx2, cd2, cx3, cd3, o_valid, o_last, o_x, o_d, o_sof, o_eof, o_count, overflow_q, crowded_q);
        self.above.clock.next = self.clock.val();
        self.below.clock.next = self.clock.val();
        self.cur_mem.clock.next = self.clock.val();

        // ================= Loader =================
        // A row is admitted on its first beat if a bank is free: the rows
        // stored and not yet checked, and the row before the checked one
        // while it is still needed as the row above.
        self.pend.next = self.wl.q.val() - self.el.q.val();
        self.used.next = self.pend.val();
        if self.prev_needed.q.val() {
            self.used.next = self.pend.val() + 1;
        }
        self.first_event.next = self.m_valid.val() & !self.in_line.q.val();
        self.drop_now.next = self.dropping.q.val();
        if self.first_event.val() {
            self.drop_now.next = self.used.val() >= self.banks.val();
            self.dropping.d.next = self.used.val() >= self.banks.val();
        }
        self.take_match.next = self.m_valid.val() & !self.m_last.val() & !self.drop_now.val() & (self.widx.q.val() < self.n_max.val());
        self.take_marker.next = self.m_valid.val() & self.m_last.val() & !self.drop_now.val();
        self.wbank.next = bit_cast::<ROW_BANK_BITS, ROW_PTR_BITS>(self.wl.q.val());
        self.waddr.next = (bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.wbank.val()) << self.index_bits.val()) + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.widx.q.val());
        self.wdata.next = (bit_cast::<ROW_ENTRY_BITS, POS_BITS>(self.m_x_ref.val()) << self.pos_bits.val()) | bit_cast::<ROW_ENTRY_BITS, POS_BITS>(self.m_disp.val());
        self.above.w_en.next = self.take_match.val();
        self.above.w_addr.next = self.waddr.val();
        self.above.w_data.next = self.wdata.val();
        self.below.w_en.next = self.take_match.val();
        self.below.w_addr.next = self.waddr.val();
        self.below.w_data.next = self.wdata.val();
        self.cur_mem.write_enable.next = self.take_match.val();
        self.cur_mem.write_address.next = self.waddr.val();
        self.cur_mem.write_data.next = self.wdata.val();
        if self.m_valid.val() & !self.m_last.val() {
            self.in_line.d.next = true;
        }
        if self.take_match.val() {
            self.widx.d.next = self.widx.q.val() + 1;
        }
        self.overflow_q.d.next = false;
        if self.m_valid.val() & self.m_last.val() {
            self.in_line.d.next = false;
            self.dropping.d.next = false;
            self.widx.d.next = 0.into();
            self.overflow_q.d.next = self.drop_now.val();
        }
        if self.take_marker.val() {
            self.wl.d.next = self.wl.q.val() + 1;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank0.val()) {
            self.cnt0.d.next = self.widx.q.val();
            self.sof0.d.next = self.m_sof.val();
            self.eof0.d.next = self.m_eof.val();
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank1.val()) {
            self.cnt1.d.next = self.widx.q.val();
            self.sof1.d.next = self.m_sof.val();
            self.eof1.d.next = self.m_eof.val();
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank2.val()) {
            self.cnt2.d.next = self.widx.q.val();
            self.sof2.d.next = self.m_sof.val();
            self.eof2.d.next = self.m_eof.val();
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank3.val()) {
            self.cnt3.d.next = self.widx.q.val();
            self.sof3.d.next = self.m_sof.val();
            self.eof3.d.next = self.m_eof.val();
        }

        // ================= Engine =================
        // The row at `el`, its neighbours' banks, counts and flags.
        self.bank_cur.next = bit_cast::<ROW_BANK_BITS, ROW_PTR_BITS>(self.el.q.val());
        self.bank_up.next = self.bank_cur.val() - 1;
        self.bank_dn.next = self.bank_cur.val() + 1;
        self.cnt_cur.next = self.cnt0.q.val();
        if self.bank_cur.val() == self.bank1.val() {
            self.cnt_cur.next = self.cnt1.q.val();
        }
        if self.bank_cur.val() == self.bank2.val() {
            self.cnt_cur.next = self.cnt2.q.val();
        }
        if self.bank_cur.val() == self.bank3.val() {
            self.cnt_cur.next = self.cnt3.q.val();
        }
        self.cnt_up.next = self.cnt0.q.val();
        if self.bank_up.val() == self.bank1.val() {
            self.cnt_up.next = self.cnt1.q.val();
        }
        if self.bank_up.val() == self.bank2.val() {
            self.cnt_up.next = self.cnt2.q.val();
        }
        if self.bank_up.val() == self.bank3.val() {
            self.cnt_up.next = self.cnt3.q.val();
        }
        self.cnt_dn.next = self.cnt0.q.val();
        if self.bank_dn.val() == self.bank1.val() {
            self.cnt_dn.next = self.cnt1.q.val();
        }
        if self.bank_dn.val() == self.bank2.val() {
            self.cnt_dn.next = self.cnt2.q.val();
        }
        if self.bank_dn.val() == self.bank3.val() {
            self.cnt_dn.next = self.cnt3.q.val();
        }
        self.sof_el.next = self.sof0.q.val();
        if self.bank_cur.val() == self.bank1.val() {
            self.sof_el.next = self.sof1.q.val();
        }
        if self.bank_cur.val() == self.bank2.val() {
            self.sof_el.next = self.sof2.q.val();
        }
        if self.bank_cur.val() == self.bank3.val() {
            self.sof_el.next = self.sof3.q.val();
        }
        self.eof_el.next = self.eof0.q.val();
        if self.bank_cur.val() == self.bank1.val() {
            self.eof_el.next = self.eof1.q.val();
        }
        if self.bank_cur.val() == self.bank2.val() {
            self.eof_el.next = self.eof2.q.val();
        }
        if self.bank_cur.val() == self.bank3.val() {
            self.eof_el.next = self.eof3.q.val();
        }
        // Ready: the row below has arrived, or this row ends its frame.
        self.start.next = !self.busy.q.val() & ((self.pend.val() >= self.two.val()) | (self.pend.val().any() & self.eof_el.val()));
        self.above.start.next = self.start.val();
        self.above.bank.next = self.bank_up.val();
        self.above.count.next = 0.into();
        if !self.sof_el.val() & self.prev_needed.q.val() {
            self.above.count.next = self.cnt_up.val();
        }
        self.below.start.next = self.start.val();
        self.below.bank.next = self.bank_dn.val();
        self.below.count.next = 0.into();
        if !self.eof_el.val() {
            self.below.count.next = self.cnt_dn.val();
        }
        // The checked match: the prefetch ring's head.
        self.head_x.next = self.cx0.q.val();
        self.head_d.next = self.cd0.q.val();
        if self.cri.q.val() == self.slot1.val() {
            self.head_x.next = self.cx1.q.val();
            self.head_d.next = self.cd1.q.val();
        }
        if self.cri.q.val() == self.slot2.val() {
            self.head_x.next = self.cx2.q.val();
            self.head_d.next = self.cd2.q.val();
        }
        if self.cri.q.val() == self.slot3.val() {
            self.head_x.next = self.cx3.q.val();
            self.head_d.next = self.cd3.q.val();
        }
        self.q_valid.next = self.busy.q.val() & self.cfill.q.val().any();
        self.above.q_valid.next = self.q_valid.val();
        self.above.q_x.next = self.head_x.val();
        self.above.q_d.next = self.head_d.val();
        self.below.q_valid.next = self.q_valid.val();
        self.below.q_x.next = self.head_x.val();
        self.below.q_d.next = self.head_d.val();
        // The decision: a confirming entry, or both windows complete (a
        // crowded window counts as complete, flagged).
        self.keep.next = self.above.hit.val() | self.below.hit.val();
        self.up_ready.next = self.above.done.val() | self.above.crowded.val();
        self.dn_ready.next = self.below.done.val() | self.below.crowded.val();
        self.decide.next = self.q_valid.val() & (self.keep.val() | (self.up_ready.val() & self.dn_ready.val()));
        self.crowded_q.d.next = self.decide.val() & !self.keep.val() & ((self.above.crowded.val() & !self.above.done.val()) | (self.below.crowded.val() & !self.below.done.val()));
        self.finish.next = self.busy.q.val() & (self.dec.q.val() == self.n_cur.q.val());
        if self.decide.val() {
            self.dec.d.next = self.dec.q.val() + 1;
        }
        if self.decide.val() & self.keep.val() {
            self.kept.d.next = self.kept.q.val() + 1;
        }
        // The checked row's prefetch ring: a read while the entries kept and
        // in flight leave a slot free; a decided match leaves it.
        self.ckept.next = self.cfill.q.val();
        if self.decide.val() {
            self.ckept.next = self.cfill.q.val() - self.one_fill.val();
            self.cri.d.next = self.cri.q.val() + 1;
        }
        self.cocc.next = self.ckept.val();
        if self.crd1.q.val() {
            self.cocc.next = self.ckept.val() + self.one_fill.val();
        }
        self.cfill.d.next = self.ckept.val();
        if self.crd2.q.val() {
            self.cfill.d.next = self.ckept.val() + self.one_fill.val();
            self.cocc.next = self.ckept.val() + self.one_fill.val();
            if self.crd1.q.val() {
                self.cocc.next = self.ckept.val() + self.one_fill.val() + self.one_fill.val();
            }
            self.cwi.d.next = self.cwi.q.val() + 1;
        }
        self.cissue.next = self.busy.q.val() & (self.crd.q.val() != self.n_cur.q.val()) & (self.cocc.val() < self.cur_ring.val());
        self.crd1.d.next = self.cissue.val();
        self.crd2.d.next = self.crd1.q.val();
        if self.cissue.val() {
            self.crd.d.next = self.crd.q.val() + 1;
        }
        self.cur_mem.read_address.next = (bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.bank_cur.val()) << self.index_bits.val()) + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.crd.q.val());
        self.rx.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.cur_mem.read_data.val() >> self.pos_bits.val());
        self.rdd.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.cur_mem.read_data.val());
        if self.crd2.q.val() & !self.cwi.q.val().any() {
            self.cx0.d.next = self.rx.val();
            self.cd0.d.next = self.rdd.val();
        }
        if self.crd2.q.val() & (self.cwi.q.val() == self.slot1.val()) {
            self.cx1.d.next = self.rx.val();
            self.cd1.d.next = self.rdd.val();
        }
        if self.crd2.q.val() & (self.cwi.q.val() == self.slot2.val()) {
            self.cx2.d.next = self.rx.val();
            self.cd2.d.next = self.rdd.val();
        }
        if self.crd2.q.val() & (self.cwi.q.val() == self.slot3.val()) {
            self.cx3.d.next = self.rx.val();
            self.cd3.d.next = self.rdd.val();
        }
        // The row's end: the marker, the next row.
        if self.finish.val() {
            self.busy.d.next = false;
            self.el.d.next = self.el.q.val() + 1;
            self.prev_needed.d.next = !self.eof_cur.q.val();
        }
        if self.start.val() {
            self.busy.d.next = true;
            self.n_cur.d.next = self.cnt_cur.val();
            self.sof_cur.d.next = self.sof_el.val();
            self.eof_cur.d.next = self.eof_el.val();
            self.dec.d.next = 0.into();
            self.kept.d.next = 0.into();
            self.crd.d.next = 0.into();
            self.crd1.d.next = false;
            self.crd2.d.next = false;
            self.cfill.d.next = 0.into();
            self.cwi.d.next = 0.into();
            self.cri.d.next = 0.into();
        }
        // Outputs (zero while not valid).
        self.o_valid.d.next = (self.decide.val() & self.keep.val()) | self.finish.val();
        self.o_last.d.next = self.finish.val();
        self.o_x.d.next = 0.into();
        self.o_d.d.next = 0.into();
        if self.decide.val() & self.keep.val() {
            self.o_x.d.next = self.head_x.val();
            self.o_d.d.next = self.head_d.val();
        }
        self.o_sof.d.next = self.finish.val() & self.sof_cur.q.val();
        self.o_eof.d.next = self.finish.val() & self.eof_cur.q.val();
        self.o_count.d.next = 0.into();
        if self.finish.val() {
            self.o_count.d.next = self.kept.q.val();
        }
        self.c_valid.next = self.o_valid.q.val();
        self.c_last.next = self.o_last.q.val();
        self.c_x_ref.next = self.o_x.q.val();
        self.c_disp.next = self.o_d.q.val();
        self.c_sof.next = self.o_sof.q.val();
        self.c_eof.next = self.o_eof.q.val();
        self.c_count.next = self.o_count.q.val();
        self.overflow.next = self.overflow_q.q.val();
        self.crowded.next = self.crowded_q.q.val();
    }
}
