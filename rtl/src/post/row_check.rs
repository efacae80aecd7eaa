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
//!   Its matches are read in order into an 8-entry (`CUR_RING`) prefetch
//!   ring; each
//!   neighbour is read in order into a window ring ([`ROW_WINDOW`]
//!   entries, each held with its bounds `X ± DX`, `d ± DD`), a
//!   [`NeighbourWindow`] each. Two pipeline
//!   stages check one match per clock:
//!   - the **compare stage** presents a match and compares it with every
//!     held entry of both windows (each comparison is the borrow of one
//!     subtraction): left of the match's window, confirming, and whether
//!     the newest entry is right of it; the results are registered;
//!   - the **decision stage** decides the compared match if it is the
//!     row's next undecided one: kept if a window holds a confirming entry,
//!     dropped if both windows are complete (each has an entry right of the
//!     match's window, or holds its whole row); a kept match leaves on the
//!     next clock. The entries left of the window leave their ring (a
//!     merge: positions increase in every row), and each ring reads its
//!     row's next entry while a slot is free.
//!
//!   While a match is decided the compare stage already presents the next
//!   one; if the match cannot be decided yet (its windows wait for entries
//!   still being read: a miss) the compare stage presents it again on the
//!   next clock, and the clock after a miss decides nothing.
//!
//! Exactness needs at most `ROW_WINDOW - 1` = 7 matches of a row within
//! any 6 px (so that a window and the first match beyond it fit the ring):
//! always true of the matcher's output, whose positions are declivities at
//! least a pixel apart (16 LSB). Denser rows are decided without the
//! matches that do not fit (a match may then be dropped that golden keeps)
//! and `crowded` flags it.
//!
//! ## Ports
//! - In, the matcher's stream (`rtl::matcher::declivity_matcher`): `m_valid` with
//!   `m_last` low is a match, `m_x_ref` (`X`), `m_disp` (its disparity),
//!   both [`POS_FRAC_BITS`] fraction bits, strictly increasing `m_x_ref`
//!   within a row, at most [`N_MAX`] per row (later ones are not stored);
//!   `m_valid` with `m_last` high ends the row: `m_sof` (it starts a
//!   frame), `m_eof` (it ends the frame; required on every frame's last
//!   row), `m_x_ref` (the row's last pixel, an integer). Matches at most one per clock, rows back to back or with gaps.
//! - Out, the same stream one row later, no back-pressure: `c_valid`,
//!   `c_last`; on a kept match `c_x_ref`, `c_disp`; on the marker `c_sof`,
//!   `c_eof` (the row's flags), `c_x_ref` (its `m_x_ref`) and `c_count`
//!   (matches kept); all zero while `c_valid` is low.
//! - `overflow`: high for a clock, on the marker's clock of a row that
//!   found all four banks in use when it started (its first match or its
//!   marker): that row is dropped whole (its matches are not stored, it
//!   never leaves, and the rows around it are checked against each other
//!   as neighbours; its `m_sof` goes to the next row stored, its `m_eof`
//!   to the last row stored, so that frames still start and end). `crowded`: high for a clock with a match decided
//!   without the whole of a neighbour's window (see above).
//! - `cut`: high for a clock when the last row of a frame cut short is
//!   dropped: a row that does not end its frame (`m_eof` low) and whose
//!   next row starts a frame. Such a row can be checked only when the next
//!   frame has begun; it is dropped (checked as a row without matches, its
//!   matches and marker not sent) so that the next frame's rows do not
//!   wait behind its pixels.
//!
//! ## Timing
//! The engine starts row `y` (its start clock `s`) [`ROW_START_LAG`]
//! clocks after the marker that makes it ready, or [`ROW_RESTART_LAG`]
//! clocks after it finished the previous row, whichever is later. It
//! finishes on clock `s + c`, `c` at most [`row_check_cycles`]`(n_above, n,
//! n_below)` (exactly `1` for an empty row and `n + ROW_FIRST_LAG - 1` when
//! neither neighbour has a match); its kept matches leave in order, at
//! most one per clock, the first at `s + ` [`ROW_FIRST_LAG`] at the
//! earliest, and its marker leaves at `s + c + 1`.
//!
//! Throughput: one match decided per clock while no match waits for a
//! neighbour's entries; a match that waits is compared again every other
//! clock until its windows are complete. A row is dropped only if, when it
//! starts, the engine has not finished the row two before it; with row
//! markers at least [`row_check_period`]` = row_check_cycles(N_MAX, N_MAX,
//! N_MAX) + ROW_RESTART_LAG` clocks apart (within and across frames) no
//! row is dropped. The bound is loose (`tests/rtl_row_check.rs` has rows
//! that take far fewer clocks): a row whose matches do not wait takes
//! about `n + `[`ROW_FIRST_LAG`] clocks, far inside its line.
//!
//! `m_valid` low is a gap: nothing is stored. The registers start
//! from their Verilog initial values, with every bank free and the engine
//! idle; `reset` (synchronous, active high) returns them to these values. The row memories need no
//! clearing: a row is read only after it is written in the same frame.
//!
//! No paper equation: the check is golden's default mode (`DESIGN.md`
//! §2.2), not the paper's.

use crate::primitives::block_ram::BlockRam;
use crate::post::neighbour_window::NeighbourWindow;
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from the marker that makes a row ready to its start clock (the
/// marker's write, the registered start).
pub const ROW_START_LAG: usize = 2;
/// Clocks from a row's finish to the next row's start clock at the
/// earliest (the engine free, the registered start).
pub const ROW_RESTART_LAG: usize = 2;
/// Clocks from a row's start to its first match leaving at the earliest:
/// the first reads' address (the clock after the start), the memory's two
/// clocks, the ring's write, the compare stage, the decision stage, the
/// output register.
pub const ROW_FIRST_LAG: usize = 7;
/// Entries of the checked row's prefetch ring.
const CUR_RING: usize = 8;
/// Bits of a slot of that ring.
const CUR_SLOT_BITS: usize = 3;
/// Bits of a ring slot and one above it (to tell a full ring from an
/// empty one).
const CUR_PTR_BITS: usize = CUR_SLOT_BITS + 1;
/// Bits of the comparisons' operands and differences: a position plus a
/// threshold (below `2^(POS_BITS + 1)`), and the borrow of a difference of
/// two of them (its top bit).
pub(crate) const WIDE: usize = POS_BITS + 2;
/// Bits of a row number modulo twice the banks (so that full and empty
/// differ).
const ROW_PTR_BITS: usize = ROW_BANK_BITS + 1;
// The banks in use, plus a change of up to two, fit a row pointer (`nofree`).
const _: () = assert!((1 << ROW_BANK_BITS) + 2 < 1 << ROW_PTR_BITS);

// The slot-by-slot logic below is written for these sizes.
const _: () = assert!(ROW_WINDOW == 8 && CUR_RING == 8 && CUR_RING == 1 << CUR_SLOT_BITS);

/// Clocks a match that waits for its neighbours' entries costs at most
/// beyond their reads (see [`row_check_cycles`]).
const ROW_WAIT_LAG: usize = 6;

/// Clocks from a row's start to its finish (the clock of its marker's
/// decision), at most, for a row of `n` matches between rows of `above`
/// and `below` matches (0 for a missing neighbour), when no window is
/// crowded.
///
/// Exactly 1 for `n = 0`. Otherwise the first match is decided
/// `ROW_FIRST_LAG - 1` clocks after the start (the reads, the compare
/// stage) and every later one on the clock after the one before it,
/// unless it waits: the clocks of the row are its `n` decisions and the
/// clocks its matches wait. A match waits (from its first comparison at
/// the decision stage to its decision) when a neighbour's window misses
/// entries not yet arrived; the window then reads them one per clock (once
/// the entries left of the match's window have left, its held entries are
/// at most 7 — matches at least a pixel apart — and the first beyond them
/// fits the eighth slot), the last arrives 3 clocks after its read, is
/// compared on the next clock the match is presented (every other clock)
/// and decided on the clock after: at most its reads plus 4 clocks, plus 2
/// while entries left of the window that arrived since the last
/// comparison still hold slots ([`ROW_WAIT_LAG`] = 6). The waits take
/// disjoint stretches of the neighbours' reads (`above + below` entries
/// in all), and each sees at least one of them arrive, so at most
/// `min(n, above + below)` matches wait.
pub const fn row_check_cycles(above: usize, n: usize, below: usize) -> usize {
    if n == 0 {
        return 1;
    }
    let m = above + below;
    let waits = if n < m { n } else { m };
    ROW_FIRST_LAG - 1 + n + m + ROW_WAIT_LAG * waits
}

/// The smallest clocks between row markers (within and across frames)
/// with which no row is dropped whatever the rows' matches.
pub const fn row_check_period() -> usize {
    row_check_cycles(N_MAX, N_MAX, N_MAX) + ROW_RESTART_LAG
}

#[derive(LogicBlock)]
pub struct RowCheck {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
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
    pub cut: Signal<Out, Bit>,
    pub crowded: Signal<Out, Bit>,
    // ---- The windows of the rows above and below (see the module doc
    // and `crate::post::neighbour_window`), and the counts they start with.
    above: NeighbourWindow,
    below: NeighbourWindow,
    a_count: Signal<Local, Bits<COUNT_BITS>>,
    b_count: Signal<Local, Bits<COUNT_BITS>>,
    // A window found crowded for the row's next undecided match stays so
    // until that match is decided (`stuck`).
    a_stuck: ResetDff<Bit>,
    b_stuck: ResetDff<Bit>,
    a_stuck_n: Signal<Local, Bit>,
    b_stuck_n: Signal<Local, Bit>,
    // ---- The checked row's memory copy.
    cur_mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    // ---- Loader: the row being received (admission, its next index), the
    // rows stored (modulo 8; the bank is the low bits), each bank's row.
    in_line: ResetDff<Bit>,
    dropping: ResetDff<Bit>,
    widx: ResetDff<Bits<COUNT_BITS>>,
    wl: ResetDff<Bits<ROW_PTR_BITS>>,
    sof_pending: ResetDff<Bit>,
    nofree: ResetDff<Bit>,
    cnt0: ResetDff<Bits<COUNT_BITS>>,
    sof0: ResetDff<Bit>,
    lx0: ResetDff<Bits<X_BITS>>,
    eof0: ResetDff<Bit>,
    cnt1: ResetDff<Bits<COUNT_BITS>>,
    sof1: ResetDff<Bit>,
    lx1: ResetDff<Bits<X_BITS>>,
    eof1: ResetDff<Bit>,
    cnt2: ResetDff<Bits<COUNT_BITS>>,
    sof2: ResetDff<Bit>,
    lx2: ResetDff<Bits<X_BITS>>,
    eof2: ResetDff<Bit>,
    cnt3: ResetDff<Bits<COUNT_BITS>>,
    sof3: ResetDff<Bit>,
    lx3: ResetDff<Bits<X_BITS>>,
    eof3: ResetDff<Bit>,
    // ---- Engine: the row checked (or next), whether the row before it is
    // still needed as its row above, the row's matches, flags, decisions
    // and kept matches.
    el: ResetDff<Bits<ROW_PTR_BITS>>,
    start_q: ResetDff<Bit>,
    prev_needed: ResetDff<Bit>,
    busy: ResetDff<Bit>,
    n_cur: ResetDff<Bits<COUNT_BITS>>,
    sof_cur: ResetDff<Bit>,
    cut_cur: ResetDff<Bit>,
    cut_q: ResetDff<Bit>,
    lx_cur: ResetDff<Bits<X_BITS>>,
    eof_cur: ResetDff<Bit>,
    dec: ResetDff<Bits<COUNT_BITS>>,
    dec1: ResetDff<Bits<COUNT_BITS>>,
    kept: ResetDff<Bits<COUNT_BITS>>,
    // The checked row's prefetch ring: reads issued, in flight, arrived.
    crd: ResetDff<Bits<COUNT_BITS>>,
    crd1: ResetDff<Bit>,
    crd2: ResetDff<Bit>,
    cwr: ResetDff<Bits<COUNT_BITS>>,
    cx: [ResetDff<Bits<POS_BITS>>; CUR_RING],
    cd: [ResetDff<Bits<POS_BITS>>; CUR_RING],
    // The compare stage: the presented match (its index, whether there is
    // one, its `X` and `d` in WIDE bits), the index presented next.
    pvalid: ResetDff<Bit>,
    pidx: ResetDff<Bits<COUNT_BITS>>,
    pn: ResetDff<Bits<COUNT_BITS>>,
    // `pn`'s ring slot and `dec + 1`'s, one-hot (the ring's read is an
    // AND-OR of its slots).
    pn_oh: [ResetDff<Bit>; CUR_RING],
    dec1_oh: [ResetDff<Bit>; CUR_RING],
    px: ResetDff<Bits<WIDE>>,
    pd: ResetDff<Bits<WIDE>>,
    // The decision stage: the compared match (the row's next undecided one
    // when `dvalid`), its `X` and `d`.
    dvalid: ResetDff<Bit>,
    // Both windows complete for the compared match (registered with the
    // comparisons).
    both_ready: ResetDff<Bit>,
    qx: ResetDff<Bits<POS_BITS>>,
    qd: ResetDff<Bits<POS_BITS>>,
    // ---- Output registers.
    o_valid: ResetDff<Bit>,
    o_last: ResetDff<Bit>,
    o_x: ResetDff<Bits<POS_BITS>>,
    o_d: ResetDff<Bits<POS_BITS>>,
    o_sof: ResetDff<Bit>,
    o_eof: ResetDff<Bit>,
    o_count: ResetDff<Bits<COUNT_BITS>>,
    overflow_q: ResetDff<Bit>,
    crowded_q: ResetDff<Bit>,
    // ---- Locals.
    first_event: Signal<Local, Bit>,
    used_now: Signal<Local, Bits<ROW_PTR_BITS>>,
    drop_now: Signal<Local, Bit>,
    take_match: Signal<Local, Bit>,
    take_marker: Signal<Local, Bit>,
    wbank: Signal<Local, Bits<ROW_BANK_BITS>>,
    lbank: Signal<Local, Bits<ROW_BANK_BITS>>,
    drop_eof: Signal<Local, Bit>,
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
    sof_dn: Signal<Local, Bit>,
    cut_el: Signal<Local, Bit>,
    lx_el: Signal<Local, Bits<X_BITS>>,
    eof_el: Signal<Local, Bit>,
    start: Signal<Local, Bit>,
    keep: Signal<Local, Bit>,
    decide: Signal<Local, Bit>,
    miss: Signal<Local, Bit>,
    finish: Signal<Local, Bit>,
    cfull: Signal<Local, Bit>,
    cissue: Signal<Local, Bit>,
    cwslot: Signal<Local, Bits<CUR_SLOT_BITS>>,
    cmask: [Signal<Local, Bits<POS_BITS>>; CUR_RING],
    n_here: Signal<Local, Bit>,
    nx: Signal<Local, Bits<POS_BITS>>,
    nd: Signal<Local, Bits<POS_BITS>>,
    rx: Signal<Local, Bits<POS_BITS>>,
    rdd: Signal<Local, Bits<POS_BITS>>,
    // ---- Constants.
    bank0: Constant<Bits<ROW_BANK_BITS>>,
    bank1: Constant<Bits<ROW_BANK_BITS>>,
    bank2: Constant<Bits<ROW_BANK_BITS>>,
    bank3: Constant<Bits<ROW_BANK_BITS>>,
    banks: Constant<Bits<ROW_PTR_BITS>>,
    banks_m1: Constant<Bits<ROW_PTR_BITS>>,
    banks_p1: Constant<Bits<ROW_PTR_BITS>>,
    banks_p2: Constant<Bits<ROW_PTR_BITS>>,
    two: Constant<Bits<ROW_PTR_BITS>>,
    n_max: Constant<Bits<COUNT_BITS>>,
    cur_wrap: Constant<Bits<CUR_PTR_BITS>>,
    cslot: [Constant<Bits<CUR_SLOT_BITS>>; CUR_RING],
    pos_ones: Constant<Bits<POS_BITS>>,
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
        RowCheck {
            clock: Default::default(),
            reset: Default::default(),
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
            cut: Default::default(),
            crowded: Default::default(),
            above: Default::default(),
            below: Default::default(),
            a_count: Default::default(),
            b_count: Default::default(),
            a_stuck: Default::default(),
            b_stuck: Default::default(),
            a_stuck_n: Default::default(),
            b_stuck_n: Default::default(),
            cur_mem: Default::default(),
            in_line: Default::default(),
            dropping: Default::default(),
            widx: Default::default(),
            wl: Default::default(),
            sof_pending: Default::default(),
            nofree: Default::default(),
            cnt0: Default::default(),
            sof0: Default::default(),
            lx0: Default::default(),
            eof0: Default::default(),
            cnt1: Default::default(),
            sof1: Default::default(),
            lx1: Default::default(),
            eof1: Default::default(),
            cnt2: Default::default(),
            sof2: Default::default(),
            lx2: Default::default(),
            eof2: Default::default(),
            cnt3: Default::default(),
            sof3: Default::default(),
            lx3: Default::default(),
            eof3: Default::default(),
            el: Default::default(),
            start_q: Default::default(),
            prev_needed: Default::default(),
            busy: Default::default(),
            n_cur: Default::default(),
            sof_cur: Default::default(),
            cut_cur: Default::default(),
            cut_q: Default::default(),
            lx_cur: Default::default(),
            eof_cur: Default::default(),
            dec: Default::default(),
            dec1: Default::default(),
            kept: Default::default(),
            crd: Default::default(),
            crd1: Default::default(),
            crd2: Default::default(),
            cwr: Default::default(),
            cx: Default::default(),
            cd: Default::default(),
            pvalid: Default::default(),
            pidx: Default::default(),
            pn: Default::default(),
            pn_oh: Default::default(),
            dec1_oh: Default::default(),
            px: Default::default(),
            pd: Default::default(),
            dvalid: Default::default(),
            both_ready: Default::default(),
            qx: Default::default(),
            qd: Default::default(),
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
            used_now: Default::default(),
            drop_now: Default::default(),
            take_match: Default::default(),
            take_marker: Default::default(),
            wbank: Default::default(),
            lbank: Default::default(),
            drop_eof: Default::default(),
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
            sof_dn: Default::default(),
            cut_el: Default::default(),
            lx_el: Default::default(),
            eof_el: Default::default(),
            start: Default::default(),
            keep: Default::default(),
            decide: Default::default(),
            miss: Default::default(),
            finish: Default::default(),
            cfull: Default::default(),
            cissue: Default::default(),
            cwslot: Default::default(),
            cmask: Default::default(),
            n_here: Default::default(),
            nx: Default::default(),
            nd: Default::default(),
            rx: Default::default(),
            rdd: Default::default(),
            bank0: bank(0),
            bank1: bank(1),
            bank2: bank(2),
            bank3: bank(3),
            banks: Constant::new((1u64 << ROW_BANK_BITS).into()),
            banks_m1: Constant::new(((1u64 << ROW_BANK_BITS) - 1).into()),
            banks_p1: Constant::new(((1u64 << ROW_BANK_BITS) + 1).into()),
            banks_p2: Constant::new(((1u64 << ROW_BANK_BITS) + 2).into()),
            two: Constant::new(2u64.into()),
            n_max: Constant::new((N_MAX as u64).into()),
            cur_wrap: Constant::new((CUR_RING as u64).into()),
            cslot: core::array::from_fn(|i| Constant::new((i as u64).into())),
            pos_ones: Constant::new(((1u64 << POS_BITS) - 1).into()),
            index_bits: Constant::new((INDEX_BITS as u64).into()),
            pos_bits: Constant::new((POS_BITS as u64).into()),
        }
    }
}

impl Logic for RowCheck {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, a_stuck, b_stuck, in_line, dropping, widx, wl, sof_pending, nofree, cnt0, sof0, eof0, cnt1, sof1, eof1, cnt2, sof2, eof2, cnt3, sof3, eof3, lx0, lx1, lx2, lx3, lx_cur, cut_cur, cut_q, el, start_q, prev_needed, busy, n_cur, sof_cur, eof_cur, dec, dec1, kept, crd, crd1, crd2, cwr, pvalid, pidx, pn, px, pd, dvalid, both_ready, qx, qd, o_valid, o_last, o_x, o_d, o_sof, o_eof, o_count, overflow_q, crowded_q);
        self.a_stuck.reset.next = self.reset.val();
        self.b_stuck.reset.next = self.reset.val();
        self.in_line.reset.next = self.reset.val();
        self.dropping.reset.next = self.reset.val();
        self.widx.reset.next = self.reset.val();
        self.wl.reset.next = self.reset.val();
        self.sof_pending.reset.next = self.reset.val();
        self.nofree.reset.next = self.reset.val();
        self.cnt0.reset.next = self.reset.val();
        self.sof0.reset.next = self.reset.val();
        self.lx0.reset.next = self.reset.val();
        self.eof0.reset.next = self.reset.val();
        self.cnt1.reset.next = self.reset.val();
        self.sof1.reset.next = self.reset.val();
        self.lx1.reset.next = self.reset.val();
        self.eof1.reset.next = self.reset.val();
        self.cnt2.reset.next = self.reset.val();
        self.sof2.reset.next = self.reset.val();
        self.lx2.reset.next = self.reset.val();
        self.eof2.reset.next = self.reset.val();
        self.cnt3.reset.next = self.reset.val();
        self.sof3.reset.next = self.reset.val();
        self.lx3.reset.next = self.reset.val();
        self.eof3.reset.next = self.reset.val();
        self.el.reset.next = self.reset.val();
        self.start_q.reset.next = self.reset.val();
        self.prev_needed.reset.next = self.reset.val();
        self.busy.reset.next = self.reset.val();
        self.n_cur.reset.next = self.reset.val();
        self.sof_cur.reset.next = self.reset.val();
        self.cut_cur.reset.next = self.reset.val();
        self.cut_q.reset.next = self.reset.val();
        self.lx_cur.reset.next = self.reset.val();
        self.eof_cur.reset.next = self.reset.val();
        self.dec.reset.next = self.reset.val();
        self.dec1.reset.next = self.reset.val();
        self.kept.reset.next = self.reset.val();
        self.crd.reset.next = self.reset.val();
        self.crd1.reset.next = self.reset.val();
        self.crd2.reset.next = self.reset.val();
        self.cwr.reset.next = self.reset.val();
        self.pvalid.reset.next = self.reset.val();
        self.pidx.reset.next = self.reset.val();
        self.pn.reset.next = self.reset.val();
        self.px.reset.next = self.reset.val();
        self.pd.reset.next = self.reset.val();
        self.dvalid.reset.next = self.reset.val();
        self.both_ready.reset.next = self.reset.val();
        self.qx.reset.next = self.reset.val();
        self.qd.reset.next = self.reset.val();
        self.o_valid.reset.next = self.reset.val();
        self.o_last.reset.next = self.reset.val();
        self.o_x.reset.next = self.reset.val();
        self.o_d.reset.next = self.reset.val();
        self.o_sof.reset.next = self.reset.val();
        self.o_eof.reset.next = self.reset.val();
        self.o_count.reset.next = self.reset.val();
        self.overflow_q.reset.next = self.reset.val();
        self.crowded_q.reset.next = self.reset.val();
        self.cur_mem.clock.next = self.clock.val();

        // ================= Loader =================
        // A row is admitted on its first beat if a bank is free: the rows
        // stored and not yet checked, and the row before the checked one
        // while it is still needed as the row above (`nofree`, registered
        // from the next values of these registers: see the end).
        self.pend.next = self.wl.q.val() - self.el.q.val();
        self.first_event.next = self.m_valid.val() & !self.in_line.q.val();
        self.drop_now.next = self.dropping.q.val();
        if self.first_event.val() {
            self.drop_now.next = self.nofree.q.val();
            self.dropping.d.next = self.nofree.q.val();
        }
        self.take_match.next = self.m_valid.val() & !self.m_last.val() & !self.drop_now.val() & (self.widx.q.val() < self.n_max.val());
        self.take_marker.next = self.m_valid.val() & self.m_last.val() & !self.drop_now.val();
        self.wbank.next = bit_cast::<ROW_BANK_BITS, ROW_PTR_BITS>(self.wl.q.val());
        self.waddr.next = (bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.wbank.val()) << self.index_bits.val()) + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.widx.q.val());
        self.wdata.next = (bit_cast::<ROW_ENTRY_BITS, POS_BITS>(self.m_x_ref.val()) << self.pos_bits.val()) | bit_cast::<ROW_ENTRY_BITS, POS_BITS>(self.m_disp.val());
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
            self.sof_pending.d.next = false;
        }
        // A dropped row's flags: its start of frame goes to the next row
        // stored, its end of frame to the last row stored if that one is
        // not yet checked (so that the frame still ends).
        self.lbank.next = self.wbank.val() - 1;
        self.drop_eof.next = self.m_valid.val() & self.m_last.val() & self.drop_now.val() & self.m_eof.val() & self.pend.val().any();
        if self.m_valid.val() & self.m_last.val() & self.drop_now.val() & self.m_sof.val() {
            self.sof_pending.d.next = true;
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank0.val()) {
            self.eof0.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank0.val()) {
            self.cnt0.d.next = self.widx.q.val();
            self.sof0.d.next = self.m_sof.val() | self.sof_pending.q.val();
            self.lx0.d.next = bit_cast::<X_BITS, POS_BITS>(self.m_x_ref.val());
            self.eof0.d.next = self.m_eof.val();
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank1.val()) {
            self.eof1.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank1.val()) {
            self.cnt1.d.next = self.widx.q.val();
            self.sof1.d.next = self.m_sof.val() | self.sof_pending.q.val();
            self.lx1.d.next = bit_cast::<X_BITS, POS_BITS>(self.m_x_ref.val());
            self.eof1.d.next = self.m_eof.val();
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank2.val()) {
            self.eof2.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank2.val()) {
            self.cnt2.d.next = self.widx.q.val();
            self.sof2.d.next = self.m_sof.val() | self.sof_pending.q.val();
            self.lx2.d.next = bit_cast::<X_BITS, POS_BITS>(self.m_x_ref.val());
            self.eof2.d.next = self.m_eof.val();
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank3.val()) {
            self.eof3.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank3.val()) {
            self.cnt3.d.next = self.widx.q.val();
            self.sof3.d.next = self.m_sof.val() | self.sof_pending.q.val();
            self.lx3.d.next = bit_cast::<X_BITS, POS_BITS>(self.m_x_ref.val());
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
        self.sof_dn.next = self.sof0.q.val();
        if self.bank_dn.val() == self.bank1.val() {
            self.sof_dn.next = self.sof1.q.val();
        }
        if self.bank_dn.val() == self.bank2.val() {
            self.sof_dn.next = self.sof2.q.val();
        }
        if self.bank_dn.val() == self.bank3.val() {
            self.sof_dn.next = self.sof3.q.val();
        }
        self.lx_el.next = self.lx0.q.val();
        if self.bank_cur.val() == self.bank1.val() {
            self.lx_el.next = self.lx1.q.val();
        }
        if self.bank_cur.val() == self.bank2.val() {
            self.lx_el.next = self.lx2.q.val();
        }
        if self.bank_cur.val() == self.bank3.val() {
            self.lx_el.next = self.lx3.q.val();
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
        // The row is the last of a frame cut short: the row below starts a
        // frame and this one does not end its own. It is dropped (checked as
        // a row without matches, and not sent).
        self.cut_el.next = (self.pend.val() >= self.two.val()) & self.sof_dn.val() & !self.eof_el.val();
        // Ready: the row below has arrived, or this row ends its frame; the
        // start is registered (it resets most of the engine).
        self.start_q.d.next = !self.busy.q.val() & !self.start_q.q.val() & ((self.pend.val() >= self.two.val()) | (self.pend.val().any() & self.eof_el.val()));
        self.start.next = self.start_q.q.val();
        self.above.bank.next = self.bank_up.val();
        self.a_count.next = 0.into();
        if !self.sof_el.val() & self.prev_needed.q.val() {
            self.a_count.next = self.cnt_up.val();
        }
        self.below.bank.next = self.bank_dn.val();
        self.b_count.next = 0.into();
        if !self.eof_el.val() {
            self.b_count.next = self.cnt_dn.val();
        }
        // ---- The windows of the rows above and below: each copy of the
        // row memory takes the loader's writes; each window starts with the
        // engine's row and compares its entries with the presented match.
        self.above.clock.next = self.clock.val();
        self.above.reset.next = self.reset.val();
        self.above.w_enable.next = self.take_match.val();
        self.above.w_address.next = self.waddr.val();
        self.above.w_data.next = self.wdata.val();
        self.above.start.next = self.start.val();
        self.above.count.next = self.a_count.val();
        self.above.px.next = self.px.q.val();
        self.above.pd.next = self.pd.q.val();
        self.above.dvalid.next = self.dvalid.q.val();
        self.below.clock.next = self.clock.val();
        self.below.reset.next = self.reset.val();
        self.below.w_enable.next = self.take_match.val();
        self.below.w_address.next = self.waddr.val();
        self.below.w_data.next = self.wdata.val();
        self.below.start.next = self.start.val();
        self.below.count.next = self.b_count.val();
        self.below.px.next = self.px.q.val();
        self.below.pd.next = self.pd.q.val();
        self.below.dvalid.next = self.dvalid.q.val();
        // ---- The checked row's prefetch ring: a read while fewer than
        // CUR_RING of the row's matches are read and undecided (`crd - dec`
        // is 0 ..= CUR_RING: it is CUR_RING when the two agree on the ring's
        // slot but not on the bit above); arrivals in order at `cwr`.
        self.cur_mem.read_address.next = (bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.bank_cur.val()) << self.index_bits.val()) + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.crd.q.val());
        self.cfull.next = (bit_cast::<CUR_PTR_BITS, COUNT_BITS>(self.crd.q.val()) ^ bit_cast::<CUR_PTR_BITS, COUNT_BITS>(self.dec.q.val())) == self.cur_wrap.val();
        self.cissue.next = self.busy.q.val() & (self.crd.q.val() != self.n_cur.q.val()) & !self.cfull.val();
        self.crd1.d.next = self.cissue.val();
        self.crd2.d.next = self.crd1.q.val();
        if self.cissue.val() {
            self.crd.d.next = self.crd.q.val() + 1;
        }
        self.rx.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.cur_mem.read_data.val() >> self.pos_bits.val());
        self.rdd.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.cur_mem.read_data.val());
        self.cwslot.next = bit_cast::<CUR_SLOT_BITS, COUNT_BITS>(self.cwr.q.val());
        for i in 0..CUR_RING {
            self.cx[i].clock.next = self.clock.val();
            self.cx[i].reset.next = self.reset.val();
            self.cd[i].clock.next = self.clock.val();
            self.cd[i].reset.next = self.reset.val();
            self.cx[i].d.next = self.cx[i].q.val();
            self.cd[i].d.next = self.cd[i].q.val();
            if self.crd2.q.val() & (self.cwslot.val() == self.cslot[i].val()) {
                self.cx[i].d.next = self.rx.val();
                self.cd[i].d.next = self.rdd.val();
            }
        }
        if self.crd2.q.val() {
            self.cwr.d.next = self.cwr.q.val() + 1;
        }
        // ---- The one-hot slots of `pn` and `dec + 1` (the ring's read is an
        // AND-OR of its slots).
        for i in 0..CUR_RING {
            self.pn_oh[i].clock.next = self.clock.val();
            self.pn_oh[i].reset.next = self.reset.val();
            self.dec1_oh[i].clock.next = self.clock.val();
            self.dec1_oh[i].reset.next = self.reset.val();
            self.pn_oh[i].d.next = self.pn_oh[i].q.val();
            self.dec1_oh[i].d.next = self.dec1_oh[i].q.val();
            self.cmask[i].next = 0.into();
            if self.pn_oh[i].q.val() {
                self.cmask[i].next = self.pos_ones.val();
            }
        }
        // ---- The decision on the compared match (the registered
        // comparisons of the decision stage): kept if a window confirms it,
        // dropped once both windows are complete (`both_ready`: each has its
        // newest entry right of the match's window, or its row all read and
        // arrived, or is stuck: crowded, which counts as complete, flagged).
        self.keep.next = self.above.found.val() | self.below.found.val();
        self.decide.next = self.dvalid.q.val() & (self.keep.val() | self.both_ready.q.val());
        self.crowded_q.d.next = self.decide.val() & !self.keep.val() & (self.a_stuck.q.val() | self.b_stuck.q.val());
        self.a_stuck_n.next = self.a_stuck.q.val() | self.above.crowd.val();
        self.b_stuck_n.next = self.b_stuck.q.val() | self.below.crowd.val();
        if self.decide.val() {
            self.a_stuck_n.next = false;
            self.b_stuck_n.next = false;
        }
        self.a_stuck.d.next = self.a_stuck_n.val();
        self.b_stuck.d.next = self.b_stuck_n.val();
        self.both_ready.d.next = (self.above.complete.val() | self.a_stuck_n.val()) & (self.below.complete.val() | self.b_stuck_n.val());
        self.finish.next = self.busy.q.val() & (self.dec.q.val() == self.n_cur.q.val());
        if self.decide.val() {
            self.dec.d.next = self.dec.q.val() + 1;
            self.dec1.d.next = self.dec1.q.val() + 1;
            for i in 1..CUR_RING {
                self.dec1_oh[i].d.next = self.dec1_oh[i - 1].q.val();
            }
            self.dec1_oh[0].d.next = self.dec1_oh[7].q.val();
        }
        if self.dvalid.q.val() & self.keep.val() {
            self.kept.d.next = self.kept.q.val() + 1;
        }
        // ---- The match presented next: the compared one again if it was
        // not decided (a miss), else the next one of the ring if it has
        // arrived. The decision stage takes the presented match; its
        // comparisons count when it is the row's next undecided one.
        self.nx.next = (self.cx[0].q.val() & self.cmask[0].val()) | (self.cx[1].q.val() & self.cmask[1].val()) | (self.cx[2].q.val() & self.cmask[2].val()) | (self.cx[3].q.val() & self.cmask[3].val()) | (self.cx[4].q.val() & self.cmask[4].val()) | (self.cx[5].q.val() & self.cmask[5].val()) | (self.cx[6].q.val() & self.cmask[6].val()) | (self.cx[7].q.val() & self.cmask[7].val());
        self.nd.next = (self.cd[0].q.val() & self.cmask[0].val()) | (self.cd[1].q.val() & self.cmask[1].val()) | (self.cd[2].q.val() & self.cmask[2].val()) | (self.cd[3].q.val() & self.cmask[3].val()) | (self.cd[4].q.val() & self.cmask[4].val()) | (self.cd[5].q.val() & self.cmask[5].val()) | (self.cd[6].q.val() & self.cmask[6].val()) | (self.cd[7].q.val() & self.cmask[7].val());
        self.n_here.next = self.pn.q.val() != self.cwr.q.val();
        self.miss.next = self.dvalid.q.val() & !self.decide.val();
        if self.miss.val() {
            self.px.d.next = bit_cast::<WIDE, POS_BITS>(self.qx.q.val());
            self.pd.d.next = bit_cast::<WIDE, POS_BITS>(self.qd.q.val());
            self.pidx.d.next = self.dec.q.val();
            self.pn.d.next = self.dec1.q.val();
            for i in 0..CUR_RING {
                self.pn_oh[i].d.next = self.dec1_oh[i].q.val();
            }
            self.pvalid.d.next = true;
        } else {
            self.px.d.next = bit_cast::<WIDE, POS_BITS>(self.nx.val());
            self.pd.d.next = bit_cast::<WIDE, POS_BITS>(self.nd.val());
            self.pidx.d.next = self.pn.q.val();
            self.pvalid.d.next = self.busy.q.val() & self.n_here.val();
            if self.n_here.val() {
                self.pn.d.next = self.pn.q.val() + 1;
                for i in 1..CUR_RING {
                    self.pn_oh[i].d.next = self.pn_oh[i - 1].q.val();
                }
                self.pn_oh[0].d.next = self.pn_oh[7].q.val();
            }
        }
        self.qx.d.next = bit_cast::<POS_BITS, WIDE>(self.px.q.val());
        self.qd.d.next = bit_cast::<POS_BITS, WIDE>(self.pd.q.val());
        self.dvalid.d.next = self.pvalid.q.val() & (self.pidx.q.val() == self.dec.q.val());
        if self.decide.val() {
            self.dvalid.d.next = self.pvalid.q.val() & (self.pidx.q.val() == self.dec1.q.val());
        }
        // ---- The row's end: the marker, the next row.
        if self.finish.val() {
            self.busy.d.next = false;
            self.el.d.next = self.el.q.val() + 1;
            self.prev_needed.d.next = !self.eof_cur.q.val();
        }
        if self.start.val() {
            self.busy.d.next = true;
            self.n_cur.d.next = self.cnt_cur.val();
            if self.cut_el.val() {
                self.n_cur.d.next = 0.into();
            }
            self.cut_cur.d.next = self.cut_el.val();
            self.sof_cur.d.next = self.sof_el.val();
            self.lx_cur.d.next = self.lx_el.val();
            self.eof_cur.d.next = self.eof_el.val();
            self.dec.d.next = 0.into();
            self.dec1.d.next = 1.into();
            self.kept.d.next = 0.into();
            self.crd.d.next = 0.into();
            self.crd1.d.next = false;
            self.crd2.d.next = false;
            self.cwr.d.next = 0.into();
            self.pvalid.d.next = false;
            self.pn.d.next = 0.into();
            for i in 0..CUR_RING {
                self.pn_oh[i].d.next = false;
                self.dec1_oh[i].d.next = false;
            }
            self.pn_oh[0].d.next = true;
            self.dec1_oh[1].d.next = true;
            self.dvalid.d.next = false;
            self.a_stuck.d.next = false;
            self.b_stuck.d.next = false;
        }
        // No bank free for a row starting on the next clock (all banks in
        // use: the rows stored and not yet checked, and the row before the
        // checked one while it is still needed): the banks in use now,
        // `wl - el + prev_needed`, change by `Δ = take_marker` without a
        // finish and by `Δ = take_marker - prev_needed - eof_cur` with one
        // (`el` + 1, `prev_needed` becomes `!eof_cur`); the flag is `used
        // + Δ ≥ banks`, picked from the four comparisons of `used` made
        // from registers beside the logic that decides Δ, not after the
        // next values of `wl`, `el` and `prev_needed`.
        self.used_now.next = self.wl.q.val() - self.el.q.val();
        if self.prev_needed.q.val() {
            self.used_now.next = self.wl.q.val() - self.el.q.val() + 1;
        }
        self.nofree.d.next = self.used_now.val() >= self.banks.val();
        if self.take_marker.val() {
            self.nofree.d.next = self.used_now.val() >= self.banks_m1.val();
        }
        if self.finish.val() {
            // Δ = take_marker - prev_needed - eof_cur, from -2 to 1.
            if self.prev_needed.q.val() & self.eof_cur.q.val() {
                self.nofree.d.next = self.used_now.val() >= self.banks_p2.val();
                if self.take_marker.val() {
                    self.nofree.d.next = self.used_now.val() >= self.banks_p1.val();
                }
            } else if self.prev_needed.q.val() | self.eof_cur.q.val() {
                self.nofree.d.next = self.used_now.val() >= self.banks_p1.val();
                if self.take_marker.val() {
                    self.nofree.d.next = self.used_now.val() >= self.banks.val();
                }
            }
        }
        // Outputs (zero while not valid).
        // (A compared match that is kept is decided: `decide & keep` is
        // `dvalid & keep`.)
        self.o_valid.d.next = (self.dvalid.q.val() & self.keep.val()) | (self.finish.val() & !self.cut_cur.q.val());
        self.o_last.d.next = self.finish.val() & !self.cut_cur.q.val();
        self.cut_q.d.next = self.finish.val() & self.cut_cur.q.val();
        self.o_x.d.next = 0.into();
        self.o_d.d.next = 0.into();
        if self.dvalid.q.val() & self.keep.val() {
            self.o_x.d.next = self.qx.q.val();
            self.o_d.d.next = self.qd.q.val();
        }
        self.o_sof.d.next = self.finish.val() & self.sof_cur.q.val() & !self.cut_cur.q.val();
        self.o_eof.d.next = self.finish.val() & self.eof_cur.q.val() & !self.cut_cur.q.val();
        self.o_count.d.next = 0.into();
        if self.finish.val() & !self.cut_cur.q.val() {
            self.o_count.d.next = self.kept.q.val();
            self.o_x.d.next = bit_cast::<POS_BITS, X_BITS>(self.lx_cur.q.val());
        }
        self.c_valid.next = self.o_valid.q.val();
        self.c_last.next = self.o_last.q.val();
        self.c_x_ref.next = self.o_x.q.val();
        self.c_disp.next = self.o_d.q.val();
        self.c_sof.next = self.o_sof.q.val();
        self.c_eof.next = self.o_eof.q.val();
        self.c_count.next = self.o_count.q.val();
        self.overflow.next = self.overflow_q.q.val();
        self.cut.next = self.cut_q.q.val();
        self.crowded.next = self.crowded_q.q.val();
    }
}
