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
//!   neighbour is read in order into a window ring ([`ROW_WINDOW`] entries) that drops the matches left of the checked
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
//!   as neighbours; its `m_sof` goes to the next row stored, its `m_eof`
//!   to the last row stored, so that frames still start and end). `crowded`: high for a clock with a match decided
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
//! clocks apart (within and across frames) no row is dropped. The bound is
//! loose: measured (`tests/rtl_row_check.rs`), a row of 128 matches a
//! pixel apart between two such rows takes 132 clocks, one of 128 matches
//! 17 LSB apart between them 276 (the bound says 900); real rows take
//! about `n + 5` (tsukuba at most 59 clocks for 54 matches, cones 66 for
//! 58), far inside their line of 384 or 450 pixels.

use crate::block_ram::BlockRam;
use crate::params::*;
use rust_hdl::prelude::*;

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
/// Bits of the position comparisons: a position plus a threshold.
const WIDE: usize = POS_BITS + 1;
/// Bits of a window ring's fill `0 ..= ROW_WINDOW`.
const WIN_FILL_BITS: usize = ROW_WINDOW_BITS + 1;
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
    // ---- The window of the row above (see the module doc).
    a_mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    a_base: DFF<Bits<ROW_ADDR_BITS>>,
    a_n: DFF<Bits<COUNT_BITS>>,
    a_rd: DFF<Bits<COUNT_BITS>>,
    a_rd1: DFF<Bit>,
    a_rd2: DFF<Bit>,
    a_head: DFF<Bits<ROW_WINDOW_BITS>>,
    a_wi: DFF<Bits<ROW_WINDOW_BITS>>,
    a_fill: DFF<Bits<WIN_FILL_BITS>>,
    a_x0: DFF<Bits<POS_BITS>>,
    a_x1: DFF<Bits<POS_BITS>>,
    a_x2: DFF<Bits<POS_BITS>>,
    a_x3: DFF<Bits<POS_BITS>>,
    a_x4: DFF<Bits<POS_BITS>>,
    a_x5: DFF<Bits<POS_BITS>>,
    a_x6: DFF<Bits<POS_BITS>>,
    a_x7: DFF<Bits<POS_BITS>>,
    a_d0: DFF<Bits<POS_BITS>>,
    a_d1: DFF<Bits<POS_BITS>>,
    a_d2: DFF<Bits<POS_BITS>>,
    a_d3: DFF<Bits<POS_BITS>>,
    a_d4: DFF<Bits<POS_BITS>>,
    a_d5: DFF<Bits<POS_BITS>>,
    a_d6: DFF<Bits<POS_BITS>>,
    a_d7: DFF<Bits<POS_BITS>>,
    a_r0: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v0: Signal<Local, Bit>,
    a_ex0: Signal<Local, Bits<WIDE>>,
    a_ed0: Signal<Local, Bits<WIDE>>,
    a_lt0: Signal<Local, Bit>,
    a_gt0: Signal<Local, Bit>,
    a_ok0: Signal<Local, Bit>,
    a_p0: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r1: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v1: Signal<Local, Bit>,
    a_ex1: Signal<Local, Bits<WIDE>>,
    a_ed1: Signal<Local, Bits<WIDE>>,
    a_lt1: Signal<Local, Bit>,
    a_gt1: Signal<Local, Bit>,
    a_ok1: Signal<Local, Bit>,
    a_p1: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r2: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v2: Signal<Local, Bit>,
    a_ex2: Signal<Local, Bits<WIDE>>,
    a_ed2: Signal<Local, Bits<WIDE>>,
    a_lt2: Signal<Local, Bit>,
    a_gt2: Signal<Local, Bit>,
    a_ok2: Signal<Local, Bit>,
    a_p2: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r3: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v3: Signal<Local, Bit>,
    a_ex3: Signal<Local, Bits<WIDE>>,
    a_ed3: Signal<Local, Bits<WIDE>>,
    a_lt3: Signal<Local, Bit>,
    a_gt3: Signal<Local, Bit>,
    a_ok3: Signal<Local, Bit>,
    a_p3: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r4: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v4: Signal<Local, Bit>,
    a_ex4: Signal<Local, Bits<WIDE>>,
    a_ed4: Signal<Local, Bits<WIDE>>,
    a_lt4: Signal<Local, Bit>,
    a_gt4: Signal<Local, Bit>,
    a_ok4: Signal<Local, Bit>,
    a_p4: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r5: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v5: Signal<Local, Bit>,
    a_ex5: Signal<Local, Bits<WIDE>>,
    a_ed5: Signal<Local, Bits<WIDE>>,
    a_lt5: Signal<Local, Bit>,
    a_gt5: Signal<Local, Bit>,
    a_ok5: Signal<Local, Bit>,
    a_p5: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r6: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v6: Signal<Local, Bit>,
    a_ex6: Signal<Local, Bits<WIDE>>,
    a_ed6: Signal<Local, Bits<WIDE>>,
    a_lt6: Signal<Local, Bit>,
    a_gt6: Signal<Local, Bit>,
    a_ok6: Signal<Local, Bit>,
    a_p6: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_r7: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    a_v7: Signal<Local, Bit>,
    a_ex7: Signal<Local, Bits<WIDE>>,
    a_ed7: Signal<Local, Bits<WIDE>>,
    a_lt7: Signal<Local, Bit>,
    a_gt7: Signal<Local, Bit>,
    a_ok7: Signal<Local, Bit>,
    a_p7: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_beyond: Signal<Local, Bit>,
    a_found: Signal<Local, Bit>,
    a_npop: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_kept: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_occ: Signal<Local, Bits<WIN_FILL_BITS>>,
    a_loaded: Signal<Local, Bit>,
    a_issue: Signal<Local, Bit>,
    a_rx: Signal<Local, Bits<POS_BITS>>,
    a_rdd: Signal<Local, Bits<POS_BITS>>,
    a_hit: Signal<Local, Bit>,
    a_done: Signal<Local, Bit>,
    a_crowded: Signal<Local, Bit>,
    a_count: Signal<Local, Bits<COUNT_BITS>>,
    a_bank: Signal<Local, Bits<ROW_BANK_BITS>>,
    // ---- The window of the row below (see the module doc).
    b_mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    b_base: DFF<Bits<ROW_ADDR_BITS>>,
    b_n: DFF<Bits<COUNT_BITS>>,
    b_rd: DFF<Bits<COUNT_BITS>>,
    b_rd1: DFF<Bit>,
    b_rd2: DFF<Bit>,
    b_head: DFF<Bits<ROW_WINDOW_BITS>>,
    b_wi: DFF<Bits<ROW_WINDOW_BITS>>,
    b_fill: DFF<Bits<WIN_FILL_BITS>>,
    b_x0: DFF<Bits<POS_BITS>>,
    b_x1: DFF<Bits<POS_BITS>>,
    b_x2: DFF<Bits<POS_BITS>>,
    b_x3: DFF<Bits<POS_BITS>>,
    b_x4: DFF<Bits<POS_BITS>>,
    b_x5: DFF<Bits<POS_BITS>>,
    b_x6: DFF<Bits<POS_BITS>>,
    b_x7: DFF<Bits<POS_BITS>>,
    b_d0: DFF<Bits<POS_BITS>>,
    b_d1: DFF<Bits<POS_BITS>>,
    b_d2: DFF<Bits<POS_BITS>>,
    b_d3: DFF<Bits<POS_BITS>>,
    b_d4: DFF<Bits<POS_BITS>>,
    b_d5: DFF<Bits<POS_BITS>>,
    b_d6: DFF<Bits<POS_BITS>>,
    b_d7: DFF<Bits<POS_BITS>>,
    b_r0: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v0: Signal<Local, Bit>,
    b_ex0: Signal<Local, Bits<WIDE>>,
    b_ed0: Signal<Local, Bits<WIDE>>,
    b_lt0: Signal<Local, Bit>,
    b_gt0: Signal<Local, Bit>,
    b_ok0: Signal<Local, Bit>,
    b_p0: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r1: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v1: Signal<Local, Bit>,
    b_ex1: Signal<Local, Bits<WIDE>>,
    b_ed1: Signal<Local, Bits<WIDE>>,
    b_lt1: Signal<Local, Bit>,
    b_gt1: Signal<Local, Bit>,
    b_ok1: Signal<Local, Bit>,
    b_p1: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r2: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v2: Signal<Local, Bit>,
    b_ex2: Signal<Local, Bits<WIDE>>,
    b_ed2: Signal<Local, Bits<WIDE>>,
    b_lt2: Signal<Local, Bit>,
    b_gt2: Signal<Local, Bit>,
    b_ok2: Signal<Local, Bit>,
    b_p2: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r3: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v3: Signal<Local, Bit>,
    b_ex3: Signal<Local, Bits<WIDE>>,
    b_ed3: Signal<Local, Bits<WIDE>>,
    b_lt3: Signal<Local, Bit>,
    b_gt3: Signal<Local, Bit>,
    b_ok3: Signal<Local, Bit>,
    b_p3: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r4: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v4: Signal<Local, Bit>,
    b_ex4: Signal<Local, Bits<WIDE>>,
    b_ed4: Signal<Local, Bits<WIDE>>,
    b_lt4: Signal<Local, Bit>,
    b_gt4: Signal<Local, Bit>,
    b_ok4: Signal<Local, Bit>,
    b_p4: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r5: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v5: Signal<Local, Bit>,
    b_ex5: Signal<Local, Bits<WIDE>>,
    b_ed5: Signal<Local, Bits<WIDE>>,
    b_lt5: Signal<Local, Bit>,
    b_gt5: Signal<Local, Bit>,
    b_ok5: Signal<Local, Bit>,
    b_p5: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r6: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v6: Signal<Local, Bit>,
    b_ex6: Signal<Local, Bits<WIDE>>,
    b_ed6: Signal<Local, Bits<WIDE>>,
    b_lt6: Signal<Local, Bit>,
    b_gt6: Signal<Local, Bit>,
    b_ok6: Signal<Local, Bit>,
    b_p6: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_r7: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    b_v7: Signal<Local, Bit>,
    b_ex7: Signal<Local, Bits<WIDE>>,
    b_ed7: Signal<Local, Bits<WIDE>>,
    b_lt7: Signal<Local, Bit>,
    b_gt7: Signal<Local, Bit>,
    b_ok7: Signal<Local, Bit>,
    b_p7: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_beyond: Signal<Local, Bit>,
    b_found: Signal<Local, Bit>,
    b_npop: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_kept: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_occ: Signal<Local, Bits<WIN_FILL_BITS>>,
    b_loaded: Signal<Local, Bit>,
    b_issue: Signal<Local, Bit>,
    b_rx: Signal<Local, Bits<POS_BITS>>,
    b_rdd: Signal<Local, Bits<POS_BITS>>,
    b_hit: Signal<Local, Bit>,
    b_done: Signal<Local, Bit>,
    b_crowded: Signal<Local, Bit>,
    b_count: Signal<Local, Bits<COUNT_BITS>>,
    b_bank: Signal<Local, Bits<ROW_BANK_BITS>>,
    // ---- The checked match's window bounds: [X - DX, X + DX] (no left
    // bound below DX), [d - DD, d + DD] (from 0 below DD), one bit wider
    // than a position.
    qx: Signal<Local, Bits<WIDE>>,
    qx_hi: Signal<Local, Bits<WIDE>>,
    qx_lo: Signal<Local, Bits<WIDE>>,
    qd: Signal<Local, Bits<WIDE>>,
    qd_hi: Signal<Local, Bits<WIDE>>,
    qd_lo: Signal<Local, Bits<WIDE>>,
    any_left: Signal<Local, Bit>,
    // ---- The checked row's memory copy.
    cur_mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    // ---- Loader: the row being received (admission, its next index), the
    // rows stored (modulo 8; the bank is the low bits), each bank's row.
    in_line: DFF<Bit>,
    dropping: DFF<Bit>,
    widx: DFF<Bits<COUNT_BITS>>,
    wl: DFF<Bits<ROW_PTR_BITS>>,
    sof_pending: DFF<Bit>,
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
    wslot0: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot1: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot2: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot3: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot4: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot5: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot6: Constant<Bits<ROW_WINDOW_BITS>>,
    wslot7: Constant<Bits<ROW_WINDOW_BITS>>,
    dx: Constant<Bits<WIDE>>,
    dd: Constant<Bits<WIDE>>,
    one: Constant<Bits<WIN_FILL_BITS>>,
    ring_size: Constant<Bits<WIN_FILL_BITS>>,
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
            a_mem: Default::default(),
            a_base: Default::default(),
            a_n: Default::default(),
            a_rd: Default::default(),
            a_rd1: Default::default(),
            a_rd2: Default::default(),
            a_head: Default::default(),
            a_wi: Default::default(),
            a_fill: Default::default(),
            a_x0: Default::default(),
            a_x1: Default::default(),
            a_x2: Default::default(),
            a_x3: Default::default(),
            a_x4: Default::default(),
            a_x5: Default::default(),
            a_x6: Default::default(),
            a_x7: Default::default(),
            a_d0: Default::default(),
            a_d1: Default::default(),
            a_d2: Default::default(),
            a_d3: Default::default(),
            a_d4: Default::default(),
            a_d5: Default::default(),
            a_d6: Default::default(),
            a_d7: Default::default(),
            a_r0: Default::default(),
            a_v0: Default::default(),
            a_ex0: Default::default(),
            a_ed0: Default::default(),
            a_lt0: Default::default(),
            a_gt0: Default::default(),
            a_ok0: Default::default(),
            a_p0: Default::default(),
            a_r1: Default::default(),
            a_v1: Default::default(),
            a_ex1: Default::default(),
            a_ed1: Default::default(),
            a_lt1: Default::default(),
            a_gt1: Default::default(),
            a_ok1: Default::default(),
            a_p1: Default::default(),
            a_r2: Default::default(),
            a_v2: Default::default(),
            a_ex2: Default::default(),
            a_ed2: Default::default(),
            a_lt2: Default::default(),
            a_gt2: Default::default(),
            a_ok2: Default::default(),
            a_p2: Default::default(),
            a_r3: Default::default(),
            a_v3: Default::default(),
            a_ex3: Default::default(),
            a_ed3: Default::default(),
            a_lt3: Default::default(),
            a_gt3: Default::default(),
            a_ok3: Default::default(),
            a_p3: Default::default(),
            a_r4: Default::default(),
            a_v4: Default::default(),
            a_ex4: Default::default(),
            a_ed4: Default::default(),
            a_lt4: Default::default(),
            a_gt4: Default::default(),
            a_ok4: Default::default(),
            a_p4: Default::default(),
            a_r5: Default::default(),
            a_v5: Default::default(),
            a_ex5: Default::default(),
            a_ed5: Default::default(),
            a_lt5: Default::default(),
            a_gt5: Default::default(),
            a_ok5: Default::default(),
            a_p5: Default::default(),
            a_r6: Default::default(),
            a_v6: Default::default(),
            a_ex6: Default::default(),
            a_ed6: Default::default(),
            a_lt6: Default::default(),
            a_gt6: Default::default(),
            a_ok6: Default::default(),
            a_p6: Default::default(),
            a_r7: Default::default(),
            a_v7: Default::default(),
            a_ex7: Default::default(),
            a_ed7: Default::default(),
            a_lt7: Default::default(),
            a_gt7: Default::default(),
            a_ok7: Default::default(),
            a_p7: Default::default(),
            a_beyond: Default::default(),
            a_found: Default::default(),
            a_npop: Default::default(),
            a_kept: Default::default(),
            a_occ: Default::default(),
            a_loaded: Default::default(),
            a_issue: Default::default(),
            a_rx: Default::default(),
            a_rdd: Default::default(),
            a_hit: Default::default(),
            a_done: Default::default(),
            a_crowded: Default::default(),
            a_count: Default::default(),
            a_bank: Default::default(),
            b_mem: Default::default(),
            b_base: Default::default(),
            b_n: Default::default(),
            b_rd: Default::default(),
            b_rd1: Default::default(),
            b_rd2: Default::default(),
            b_head: Default::default(),
            b_wi: Default::default(),
            b_fill: Default::default(),
            b_x0: Default::default(),
            b_x1: Default::default(),
            b_x2: Default::default(),
            b_x3: Default::default(),
            b_x4: Default::default(),
            b_x5: Default::default(),
            b_x6: Default::default(),
            b_x7: Default::default(),
            b_d0: Default::default(),
            b_d1: Default::default(),
            b_d2: Default::default(),
            b_d3: Default::default(),
            b_d4: Default::default(),
            b_d5: Default::default(),
            b_d6: Default::default(),
            b_d7: Default::default(),
            b_r0: Default::default(),
            b_v0: Default::default(),
            b_ex0: Default::default(),
            b_ed0: Default::default(),
            b_lt0: Default::default(),
            b_gt0: Default::default(),
            b_ok0: Default::default(),
            b_p0: Default::default(),
            b_r1: Default::default(),
            b_v1: Default::default(),
            b_ex1: Default::default(),
            b_ed1: Default::default(),
            b_lt1: Default::default(),
            b_gt1: Default::default(),
            b_ok1: Default::default(),
            b_p1: Default::default(),
            b_r2: Default::default(),
            b_v2: Default::default(),
            b_ex2: Default::default(),
            b_ed2: Default::default(),
            b_lt2: Default::default(),
            b_gt2: Default::default(),
            b_ok2: Default::default(),
            b_p2: Default::default(),
            b_r3: Default::default(),
            b_v3: Default::default(),
            b_ex3: Default::default(),
            b_ed3: Default::default(),
            b_lt3: Default::default(),
            b_gt3: Default::default(),
            b_ok3: Default::default(),
            b_p3: Default::default(),
            b_r4: Default::default(),
            b_v4: Default::default(),
            b_ex4: Default::default(),
            b_ed4: Default::default(),
            b_lt4: Default::default(),
            b_gt4: Default::default(),
            b_ok4: Default::default(),
            b_p4: Default::default(),
            b_r5: Default::default(),
            b_v5: Default::default(),
            b_ex5: Default::default(),
            b_ed5: Default::default(),
            b_lt5: Default::default(),
            b_gt5: Default::default(),
            b_ok5: Default::default(),
            b_p5: Default::default(),
            b_r6: Default::default(),
            b_v6: Default::default(),
            b_ex6: Default::default(),
            b_ed6: Default::default(),
            b_lt6: Default::default(),
            b_gt6: Default::default(),
            b_ok6: Default::default(),
            b_p6: Default::default(),
            b_r7: Default::default(),
            b_v7: Default::default(),
            b_ex7: Default::default(),
            b_ed7: Default::default(),
            b_lt7: Default::default(),
            b_gt7: Default::default(),
            b_ok7: Default::default(),
            b_p7: Default::default(),
            b_beyond: Default::default(),
            b_found: Default::default(),
            b_npop: Default::default(),
            b_kept: Default::default(),
            b_occ: Default::default(),
            b_loaded: Default::default(),
            b_issue: Default::default(),
            b_rx: Default::default(),
            b_rdd: Default::default(),
            b_hit: Default::default(),
            b_done: Default::default(),
            b_crowded: Default::default(),
            b_count: Default::default(),
            b_bank: Default::default(),
            qx: Default::default(),
            qx_hi: Default::default(),
            qx_lo: Default::default(),
            qd: Default::default(),
            qd_hi: Default::default(),
            qd_lo: Default::default(),
            any_left: Default::default(),
            cur_mem: Default::default(),
            in_line: Default::default(),
            dropping: Default::default(),
            widx: Default::default(),
            wl: Default::default(),
            sof_pending: Default::default(),
            lbank: Default::default(),
            drop_eof: Default::default(),
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
            banks: Constant::new((1u64 << ROW_BANK_BITS).into()),
            two: Constant::new(2u64.into()),
            cur_ring: Constant::new((CUR_RING as u64).into()),
            one_fill: Constant::new(1u64.into()),
            n_max: Constant::new((N_MAX as u64).into()),
            wslot0: Constant::new(0u64.into()),
            wslot1: Constant::new(1u64.into()),
            wslot2: Constant::new(2u64.into()),
            wslot3: Constant::new(3u64.into()),
            wslot4: Constant::new(4u64.into()),
            wslot5: Constant::new(5u64.into()),
            wslot6: Constant::new(6u64.into()),
            wslot7: Constant::new(7u64.into()),
            dx: Constant::new(CONSISTENT_DX_LSB.into()),
            dd: Constant::new(CONSISTENT_DD_LSB.into()),
            one: Constant::new(1u64.into()),
            ring_size: Constant::new((ROW_WINDOW as u64).into()),
            index_bits: Constant::new((INDEX_BITS as u64).into()),
            pos_bits: Constant::new((POS_BITS as u64).into()),
        }
    }
}

impl Logic for RowCheck {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, a_base, a_n, a_rd, a_rd1, a_rd2, a_head, a_wi, a_fill, a_x0, a_x1, a_x2, a_x3, a_x4, a_x5, a_x6, a_x7, a_d0, a_d1, a_d2, a_d3, a_d4, a_d5, a_d6, a_d7, b_base, b_n, b_rd, b_rd1, b_rd2, b_head, b_wi, b_fill, b_x0, b_x1, b_x2, b_x3, b_x4, b_x5, b_x6, b_x7, b_d0, b_d1, b_d2, b_d3, b_d4, b_d5, b_d6, b_d7, in_line, dropping, widx, wl, sof_pending, cnt0, sof0, eof0, cnt1, sof1, eof1, cnt2, sof2, eof2, cnt3, sof3, eof3, el, prev_needed, busy, n_cur, sof_cur, eof_cur, dec, kept, crd, crd1, crd2, cfill, cwi, cri, cx0, cd0, cx1, cd1, cx2, cd2, cx3, cd3, o_valid, o_last, o_x, o_d, o_sof, o_eof, o_count, overflow_q, crowded_q);
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
            self.eof0.d.next = self.m_eof.val();
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank1.val()) {
            self.eof1.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank1.val()) {
            self.cnt1.d.next = self.widx.q.val();
            self.sof1.d.next = self.m_sof.val() | self.sof_pending.q.val();
            self.eof1.d.next = self.m_eof.val();
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank2.val()) {
            self.eof2.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank2.val()) {
            self.cnt2.d.next = self.widx.q.val();
            self.sof2.d.next = self.m_sof.val() | self.sof_pending.q.val();
            self.eof2.d.next = self.m_eof.val();
        }
        if self.drop_eof.val() & (self.lbank.val() == self.bank3.val()) {
            self.eof3.d.next = true;
        }
        if self.take_marker.val() & (self.wbank.val() == self.bank3.val()) {
            self.cnt3.d.next = self.widx.q.val();
            self.sof3.d.next = self.m_sof.val() | self.sof_pending.q.val();
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
        self.a_bank.next = self.bank_up.val();
        self.a_count.next = 0.into();
        if !self.sof_el.val() & self.prev_needed.q.val() {
            self.a_count.next = self.cnt_up.val();
        }
        self.b_bank.next = self.bank_dn.val();
        self.b_count.next = 0.into();
        if !self.eof_el.val() {
            self.b_count.next = self.cnt_dn.val();
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
        // ---- The windows (one per neighbour): each reads its row in order into
        // its ring and compares every entry with the checked match.
        // The window's bounds: [q_x - DX, q_x + DX] (no left bound below DX),
        // [q_d - DD, q_d + DD] (from 0 below DD), one bit wider than a
        // position.
        self.qx.next = bit_cast::<WIDE, POS_BITS>(self.head_x.val());
        self.qd.next = bit_cast::<WIDE, POS_BITS>(self.head_d.val());
        self.qx_hi.next = self.qx.val() + self.dx.val();
        self.qd_hi.next = self.qd.val() + self.dd.val();
        self.any_left.next = self.q_valid.val() & (self.qx.val() >= self.dx.val());
        self.qx_lo.next = self.qx.val() - self.dx.val();
        self.qd_lo.next = 0.into();
        if self.qd.val() >= self.dd.val() {
            self.qd_lo.next = self.qd.val() - self.dd.val();
        }
        self.a_mem.clock.next = self.clock.val();
        self.a_mem.write_enable.next = self.take_match.val();
        self.a_mem.write_address.next = self.waddr.val();
        self.a_mem.write_data.next = self.wdata.val();
        // Each slot: held (its place after the head below the fill), left
        // of the window (popped), right of it, confirming.
        self.a_r0.next = self.wslot0.val() - self.a_head.q.val();
        self.a_v0.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r0.val()) < self.a_fill.q.val();
        self.a_ex0.next = bit_cast::<WIDE, POS_BITS>(self.a_x0.q.val());
        self.a_ed0.next = bit_cast::<WIDE, POS_BITS>(self.a_d0.q.val());
        self.a_lt0.next = self.a_v0.val() & self.any_left.val() & (self.a_ex0.val() < self.qx_lo.val());
        self.a_gt0.next = self.a_v0.val() & (self.a_ex0.val() > self.qx_hi.val());
        self.a_ok0.next = self.a_v0.val() & !self.a_lt0.val() & !self.a_gt0.val() & (self.a_ed0.val() >= self.qd_lo.val()) & (self.a_ed0.val() <= self.qd_hi.val());
        self.a_p0.next = 0.into();
        if self.a_lt0.val() {
            self.a_p0.next = self.one.val();
        }
        self.a_r1.next = self.wslot1.val() - self.a_head.q.val();
        self.a_v1.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r1.val()) < self.a_fill.q.val();
        self.a_ex1.next = bit_cast::<WIDE, POS_BITS>(self.a_x1.q.val());
        self.a_ed1.next = bit_cast::<WIDE, POS_BITS>(self.a_d1.q.val());
        self.a_lt1.next = self.a_v1.val() & self.any_left.val() & (self.a_ex1.val() < self.qx_lo.val());
        self.a_gt1.next = self.a_v1.val() & (self.a_ex1.val() > self.qx_hi.val());
        self.a_ok1.next = self.a_v1.val() & !self.a_lt1.val() & !self.a_gt1.val() & (self.a_ed1.val() >= self.qd_lo.val()) & (self.a_ed1.val() <= self.qd_hi.val());
        self.a_p1.next = 0.into();
        if self.a_lt1.val() {
            self.a_p1.next = self.one.val();
        }
        self.a_r2.next = self.wslot2.val() - self.a_head.q.val();
        self.a_v2.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r2.val()) < self.a_fill.q.val();
        self.a_ex2.next = bit_cast::<WIDE, POS_BITS>(self.a_x2.q.val());
        self.a_ed2.next = bit_cast::<WIDE, POS_BITS>(self.a_d2.q.val());
        self.a_lt2.next = self.a_v2.val() & self.any_left.val() & (self.a_ex2.val() < self.qx_lo.val());
        self.a_gt2.next = self.a_v2.val() & (self.a_ex2.val() > self.qx_hi.val());
        self.a_ok2.next = self.a_v2.val() & !self.a_lt2.val() & !self.a_gt2.val() & (self.a_ed2.val() >= self.qd_lo.val()) & (self.a_ed2.val() <= self.qd_hi.val());
        self.a_p2.next = 0.into();
        if self.a_lt2.val() {
            self.a_p2.next = self.one.val();
        }
        self.a_r3.next = self.wslot3.val() - self.a_head.q.val();
        self.a_v3.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r3.val()) < self.a_fill.q.val();
        self.a_ex3.next = bit_cast::<WIDE, POS_BITS>(self.a_x3.q.val());
        self.a_ed3.next = bit_cast::<WIDE, POS_BITS>(self.a_d3.q.val());
        self.a_lt3.next = self.a_v3.val() & self.any_left.val() & (self.a_ex3.val() < self.qx_lo.val());
        self.a_gt3.next = self.a_v3.val() & (self.a_ex3.val() > self.qx_hi.val());
        self.a_ok3.next = self.a_v3.val() & !self.a_lt3.val() & !self.a_gt3.val() & (self.a_ed3.val() >= self.qd_lo.val()) & (self.a_ed3.val() <= self.qd_hi.val());
        self.a_p3.next = 0.into();
        if self.a_lt3.val() {
            self.a_p3.next = self.one.val();
        }
        self.a_r4.next = self.wslot4.val() - self.a_head.q.val();
        self.a_v4.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r4.val()) < self.a_fill.q.val();
        self.a_ex4.next = bit_cast::<WIDE, POS_BITS>(self.a_x4.q.val());
        self.a_ed4.next = bit_cast::<WIDE, POS_BITS>(self.a_d4.q.val());
        self.a_lt4.next = self.a_v4.val() & self.any_left.val() & (self.a_ex4.val() < self.qx_lo.val());
        self.a_gt4.next = self.a_v4.val() & (self.a_ex4.val() > self.qx_hi.val());
        self.a_ok4.next = self.a_v4.val() & !self.a_lt4.val() & !self.a_gt4.val() & (self.a_ed4.val() >= self.qd_lo.val()) & (self.a_ed4.val() <= self.qd_hi.val());
        self.a_p4.next = 0.into();
        if self.a_lt4.val() {
            self.a_p4.next = self.one.val();
        }
        self.a_r5.next = self.wslot5.val() - self.a_head.q.val();
        self.a_v5.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r5.val()) < self.a_fill.q.val();
        self.a_ex5.next = bit_cast::<WIDE, POS_BITS>(self.a_x5.q.val());
        self.a_ed5.next = bit_cast::<WIDE, POS_BITS>(self.a_d5.q.val());
        self.a_lt5.next = self.a_v5.val() & self.any_left.val() & (self.a_ex5.val() < self.qx_lo.val());
        self.a_gt5.next = self.a_v5.val() & (self.a_ex5.val() > self.qx_hi.val());
        self.a_ok5.next = self.a_v5.val() & !self.a_lt5.val() & !self.a_gt5.val() & (self.a_ed5.val() >= self.qd_lo.val()) & (self.a_ed5.val() <= self.qd_hi.val());
        self.a_p5.next = 0.into();
        if self.a_lt5.val() {
            self.a_p5.next = self.one.val();
        }
        self.a_r6.next = self.wslot6.val() - self.a_head.q.val();
        self.a_v6.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r6.val()) < self.a_fill.q.val();
        self.a_ex6.next = bit_cast::<WIDE, POS_BITS>(self.a_x6.q.val());
        self.a_ed6.next = bit_cast::<WIDE, POS_BITS>(self.a_d6.q.val());
        self.a_lt6.next = self.a_v6.val() & self.any_left.val() & (self.a_ex6.val() < self.qx_lo.val());
        self.a_gt6.next = self.a_v6.val() & (self.a_ex6.val() > self.qx_hi.val());
        self.a_ok6.next = self.a_v6.val() & !self.a_lt6.val() & !self.a_gt6.val() & (self.a_ed6.val() >= self.qd_lo.val()) & (self.a_ed6.val() <= self.qd_hi.val());
        self.a_p6.next = 0.into();
        if self.a_lt6.val() {
            self.a_p6.next = self.one.val();
        }
        self.a_r7.next = self.wslot7.val() - self.a_head.q.val();
        self.a_v7.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.a_r7.val()) < self.a_fill.q.val();
        self.a_ex7.next = bit_cast::<WIDE, POS_BITS>(self.a_x7.q.val());
        self.a_ed7.next = bit_cast::<WIDE, POS_BITS>(self.a_d7.q.val());
        self.a_lt7.next = self.a_v7.val() & self.any_left.val() & (self.a_ex7.val() < self.qx_lo.val());
        self.a_gt7.next = self.a_v7.val() & (self.a_ex7.val() > self.qx_hi.val());
        self.a_ok7.next = self.a_v7.val() & !self.a_lt7.val() & !self.a_gt7.val() & (self.a_ed7.val() >= self.qd_lo.val()) & (self.a_ed7.val() <= self.qd_hi.val());
        self.a_p7.next = 0.into();
        if self.a_lt7.val() {
            self.a_p7.next = self.one.val();
        }
        self.a_beyond.next = self.a_gt0.val() | self.a_gt1.val() | self.a_gt2.val() | self.a_gt3.val() | self.a_gt4.val() | self.a_gt5.val() | self.a_gt6.val() | self.a_gt7.val();
        self.a_found.next = self.q_valid.val() & (self.a_ok0.val() | self.a_ok1.val() | self.a_ok2.val() | self.a_ok3.val() | self.a_ok4.val() | self.a_ok5.val() | self.a_ok6.val() | self.a_ok7.val());
        self.a_npop.next = self.a_p0.val() + self.a_p1.val() + self.a_p2.val() + self.a_p3.val() + self.a_p4.val() + self.a_p5.val() + self.a_p6.val() + self.a_p7.val();
        // Every match of the row read and arrived.
        self.a_loaded.next = (self.a_rd.q.val() == self.a_n.q.val()) & !self.a_rd1.q.val() & !self.a_rd2.q.val();
        self.a_hit.next = self.a_found.val();
        self.a_done.next = self.a_beyond.val() | self.a_loaded.val();
        self.a_crowded.next = (self.a_fill.q.val() == self.ring_size.val()) & !self.a_npop.val().any() & !self.a_beyond.val() & !self.a_found.val() & !self.a_loaded.val();
        // The ring: pops at the head, the arriving read at `wi`; a read is
        // issued while the entries kept and in flight leave a slot free.
        self.a_kept.next = self.a_fill.q.val() - self.a_npop.val();
        self.a_head.d.next = self.a_head.q.val() + bit_cast::<ROW_WINDOW_BITS, WIN_FILL_BITS>(self.a_npop.val());
        self.a_occ.next = self.a_kept.val();
        if self.a_rd1.q.val() {
            self.a_occ.next = self.a_kept.val() + self.one.val();
        }
        self.a_fill.d.next = self.a_kept.val();
        if self.a_rd2.q.val() {
            self.a_fill.d.next = self.a_kept.val() + self.one.val();
            self.a_occ.next = self.a_kept.val() + self.one.val();
            if self.a_rd1.q.val() {
                self.a_occ.next = self.a_kept.val() + self.one.val() + self.one.val();
            }
            self.a_wi.d.next = self.a_wi.q.val() + 1;
        }
        self.a_issue.next = (self.a_rd.q.val() != self.a_n.q.val()) & (self.a_occ.val() < self.ring_size.val());
        self.a_rd1.d.next = self.a_issue.val();
        self.a_rd2.d.next = self.a_rd1.q.val();
        if self.a_issue.val() {
            self.a_rd.d.next = self.a_rd.q.val() + 1;
        }
        self.a_mem.read_address.next = self.a_base.q.val() + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.a_rd.q.val());
        self.a_rx.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.a_mem.read_data.val() >> self.pos_bits.val());
        self.a_rdd.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.a_mem.read_data.val());
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot0.val()) {
            self.a_x0.d.next = self.a_rx.val();
            self.a_d0.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot1.val()) {
            self.a_x1.d.next = self.a_rx.val();
            self.a_d1.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot2.val()) {
            self.a_x2.d.next = self.a_rx.val();
            self.a_d2.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot3.val()) {
            self.a_x3.d.next = self.a_rx.val();
            self.a_d3.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot4.val()) {
            self.a_x4.d.next = self.a_rx.val();
            self.a_d4.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot5.val()) {
            self.a_x5.d.next = self.a_rx.val();
            self.a_d5.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot6.val()) {
            self.a_x6.d.next = self.a_rx.val();
            self.a_d6.d.next = self.a_rdd.val();
        }
        if self.a_rd2.q.val() & (self.a_wi.q.val() == self.wslot7.val()) {
            self.a_x7.d.next = self.a_rx.val();
            self.a_d7.d.next = self.a_rdd.val();
        }
        // A new row: the ring empties, the reads in flight are forgotten.
        if self.start.val() {
            self.a_base.d.next = bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.a_bank.val()) << self.index_bits.val();
            self.a_n.d.next = self.a_count.val();
            self.a_rd.d.next = 0.into();
            self.a_rd1.d.next = false;
            self.a_rd2.d.next = false;
            self.a_head.d.next = 0.into();
            self.a_wi.d.next = 0.into();
            self.a_fill.d.next = 0.into();
        }
        self.b_mem.clock.next = self.clock.val();
        self.b_mem.write_enable.next = self.take_match.val();
        self.b_mem.write_address.next = self.waddr.val();
        self.b_mem.write_data.next = self.wdata.val();
        // Each slot: held (its place after the head below the fill), left
        // of the window (popped), right of it, confirming.
        self.b_r0.next = self.wslot0.val() - self.b_head.q.val();
        self.b_v0.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r0.val()) < self.b_fill.q.val();
        self.b_ex0.next = bit_cast::<WIDE, POS_BITS>(self.b_x0.q.val());
        self.b_ed0.next = bit_cast::<WIDE, POS_BITS>(self.b_d0.q.val());
        self.b_lt0.next = self.b_v0.val() & self.any_left.val() & (self.b_ex0.val() < self.qx_lo.val());
        self.b_gt0.next = self.b_v0.val() & (self.b_ex0.val() > self.qx_hi.val());
        self.b_ok0.next = self.b_v0.val() & !self.b_lt0.val() & !self.b_gt0.val() & (self.b_ed0.val() >= self.qd_lo.val()) & (self.b_ed0.val() <= self.qd_hi.val());
        self.b_p0.next = 0.into();
        if self.b_lt0.val() {
            self.b_p0.next = self.one.val();
        }
        self.b_r1.next = self.wslot1.val() - self.b_head.q.val();
        self.b_v1.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r1.val()) < self.b_fill.q.val();
        self.b_ex1.next = bit_cast::<WIDE, POS_BITS>(self.b_x1.q.val());
        self.b_ed1.next = bit_cast::<WIDE, POS_BITS>(self.b_d1.q.val());
        self.b_lt1.next = self.b_v1.val() & self.any_left.val() & (self.b_ex1.val() < self.qx_lo.val());
        self.b_gt1.next = self.b_v1.val() & (self.b_ex1.val() > self.qx_hi.val());
        self.b_ok1.next = self.b_v1.val() & !self.b_lt1.val() & !self.b_gt1.val() & (self.b_ed1.val() >= self.qd_lo.val()) & (self.b_ed1.val() <= self.qd_hi.val());
        self.b_p1.next = 0.into();
        if self.b_lt1.val() {
            self.b_p1.next = self.one.val();
        }
        self.b_r2.next = self.wslot2.val() - self.b_head.q.val();
        self.b_v2.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r2.val()) < self.b_fill.q.val();
        self.b_ex2.next = bit_cast::<WIDE, POS_BITS>(self.b_x2.q.val());
        self.b_ed2.next = bit_cast::<WIDE, POS_BITS>(self.b_d2.q.val());
        self.b_lt2.next = self.b_v2.val() & self.any_left.val() & (self.b_ex2.val() < self.qx_lo.val());
        self.b_gt2.next = self.b_v2.val() & (self.b_ex2.val() > self.qx_hi.val());
        self.b_ok2.next = self.b_v2.val() & !self.b_lt2.val() & !self.b_gt2.val() & (self.b_ed2.val() >= self.qd_lo.val()) & (self.b_ed2.val() <= self.qd_hi.val());
        self.b_p2.next = 0.into();
        if self.b_lt2.val() {
            self.b_p2.next = self.one.val();
        }
        self.b_r3.next = self.wslot3.val() - self.b_head.q.val();
        self.b_v3.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r3.val()) < self.b_fill.q.val();
        self.b_ex3.next = bit_cast::<WIDE, POS_BITS>(self.b_x3.q.val());
        self.b_ed3.next = bit_cast::<WIDE, POS_BITS>(self.b_d3.q.val());
        self.b_lt3.next = self.b_v3.val() & self.any_left.val() & (self.b_ex3.val() < self.qx_lo.val());
        self.b_gt3.next = self.b_v3.val() & (self.b_ex3.val() > self.qx_hi.val());
        self.b_ok3.next = self.b_v3.val() & !self.b_lt3.val() & !self.b_gt3.val() & (self.b_ed3.val() >= self.qd_lo.val()) & (self.b_ed3.val() <= self.qd_hi.val());
        self.b_p3.next = 0.into();
        if self.b_lt3.val() {
            self.b_p3.next = self.one.val();
        }
        self.b_r4.next = self.wslot4.val() - self.b_head.q.val();
        self.b_v4.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r4.val()) < self.b_fill.q.val();
        self.b_ex4.next = bit_cast::<WIDE, POS_BITS>(self.b_x4.q.val());
        self.b_ed4.next = bit_cast::<WIDE, POS_BITS>(self.b_d4.q.val());
        self.b_lt4.next = self.b_v4.val() & self.any_left.val() & (self.b_ex4.val() < self.qx_lo.val());
        self.b_gt4.next = self.b_v4.val() & (self.b_ex4.val() > self.qx_hi.val());
        self.b_ok4.next = self.b_v4.val() & !self.b_lt4.val() & !self.b_gt4.val() & (self.b_ed4.val() >= self.qd_lo.val()) & (self.b_ed4.val() <= self.qd_hi.val());
        self.b_p4.next = 0.into();
        if self.b_lt4.val() {
            self.b_p4.next = self.one.val();
        }
        self.b_r5.next = self.wslot5.val() - self.b_head.q.val();
        self.b_v5.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r5.val()) < self.b_fill.q.val();
        self.b_ex5.next = bit_cast::<WIDE, POS_BITS>(self.b_x5.q.val());
        self.b_ed5.next = bit_cast::<WIDE, POS_BITS>(self.b_d5.q.val());
        self.b_lt5.next = self.b_v5.val() & self.any_left.val() & (self.b_ex5.val() < self.qx_lo.val());
        self.b_gt5.next = self.b_v5.val() & (self.b_ex5.val() > self.qx_hi.val());
        self.b_ok5.next = self.b_v5.val() & !self.b_lt5.val() & !self.b_gt5.val() & (self.b_ed5.val() >= self.qd_lo.val()) & (self.b_ed5.val() <= self.qd_hi.val());
        self.b_p5.next = 0.into();
        if self.b_lt5.val() {
            self.b_p5.next = self.one.val();
        }
        self.b_r6.next = self.wslot6.val() - self.b_head.q.val();
        self.b_v6.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r6.val()) < self.b_fill.q.val();
        self.b_ex6.next = bit_cast::<WIDE, POS_BITS>(self.b_x6.q.val());
        self.b_ed6.next = bit_cast::<WIDE, POS_BITS>(self.b_d6.q.val());
        self.b_lt6.next = self.b_v6.val() & self.any_left.val() & (self.b_ex6.val() < self.qx_lo.val());
        self.b_gt6.next = self.b_v6.val() & (self.b_ex6.val() > self.qx_hi.val());
        self.b_ok6.next = self.b_v6.val() & !self.b_lt6.val() & !self.b_gt6.val() & (self.b_ed6.val() >= self.qd_lo.val()) & (self.b_ed6.val() <= self.qd_hi.val());
        self.b_p6.next = 0.into();
        if self.b_lt6.val() {
            self.b_p6.next = self.one.val();
        }
        self.b_r7.next = self.wslot7.val() - self.b_head.q.val();
        self.b_v7.next = bit_cast::<WIN_FILL_BITS, ROW_WINDOW_BITS>(self.b_r7.val()) < self.b_fill.q.val();
        self.b_ex7.next = bit_cast::<WIDE, POS_BITS>(self.b_x7.q.val());
        self.b_ed7.next = bit_cast::<WIDE, POS_BITS>(self.b_d7.q.val());
        self.b_lt7.next = self.b_v7.val() & self.any_left.val() & (self.b_ex7.val() < self.qx_lo.val());
        self.b_gt7.next = self.b_v7.val() & (self.b_ex7.val() > self.qx_hi.val());
        self.b_ok7.next = self.b_v7.val() & !self.b_lt7.val() & !self.b_gt7.val() & (self.b_ed7.val() >= self.qd_lo.val()) & (self.b_ed7.val() <= self.qd_hi.val());
        self.b_p7.next = 0.into();
        if self.b_lt7.val() {
            self.b_p7.next = self.one.val();
        }
        self.b_beyond.next = self.b_gt0.val() | self.b_gt1.val() | self.b_gt2.val() | self.b_gt3.val() | self.b_gt4.val() | self.b_gt5.val() | self.b_gt6.val() | self.b_gt7.val();
        self.b_found.next = self.q_valid.val() & (self.b_ok0.val() | self.b_ok1.val() | self.b_ok2.val() | self.b_ok3.val() | self.b_ok4.val() | self.b_ok5.val() | self.b_ok6.val() | self.b_ok7.val());
        self.b_npop.next = self.b_p0.val() + self.b_p1.val() + self.b_p2.val() + self.b_p3.val() + self.b_p4.val() + self.b_p5.val() + self.b_p6.val() + self.b_p7.val();
        // Every match of the row read and arrived.
        self.b_loaded.next = (self.b_rd.q.val() == self.b_n.q.val()) & !self.b_rd1.q.val() & !self.b_rd2.q.val();
        self.b_hit.next = self.b_found.val();
        self.b_done.next = self.b_beyond.val() | self.b_loaded.val();
        self.b_crowded.next = (self.b_fill.q.val() == self.ring_size.val()) & !self.b_npop.val().any() & !self.b_beyond.val() & !self.b_found.val() & !self.b_loaded.val();
        // The ring: pops at the head, the arriving read at `wi`; a read is
        // issued while the entries kept and in flight leave a slot free.
        self.b_kept.next = self.b_fill.q.val() - self.b_npop.val();
        self.b_head.d.next = self.b_head.q.val() + bit_cast::<ROW_WINDOW_BITS, WIN_FILL_BITS>(self.b_npop.val());
        self.b_occ.next = self.b_kept.val();
        if self.b_rd1.q.val() {
            self.b_occ.next = self.b_kept.val() + self.one.val();
        }
        self.b_fill.d.next = self.b_kept.val();
        if self.b_rd2.q.val() {
            self.b_fill.d.next = self.b_kept.val() + self.one.val();
            self.b_occ.next = self.b_kept.val() + self.one.val();
            if self.b_rd1.q.val() {
                self.b_occ.next = self.b_kept.val() + self.one.val() + self.one.val();
            }
            self.b_wi.d.next = self.b_wi.q.val() + 1;
        }
        self.b_issue.next = (self.b_rd.q.val() != self.b_n.q.val()) & (self.b_occ.val() < self.ring_size.val());
        self.b_rd1.d.next = self.b_issue.val();
        self.b_rd2.d.next = self.b_rd1.q.val();
        if self.b_issue.val() {
            self.b_rd.d.next = self.b_rd.q.val() + 1;
        }
        self.b_mem.read_address.next = self.b_base.q.val() + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.b_rd.q.val());
        self.b_rx.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.b_mem.read_data.val() >> self.pos_bits.val());
        self.b_rdd.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.b_mem.read_data.val());
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot0.val()) {
            self.b_x0.d.next = self.b_rx.val();
            self.b_d0.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot1.val()) {
            self.b_x1.d.next = self.b_rx.val();
            self.b_d1.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot2.val()) {
            self.b_x2.d.next = self.b_rx.val();
            self.b_d2.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot3.val()) {
            self.b_x3.d.next = self.b_rx.val();
            self.b_d3.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot4.val()) {
            self.b_x4.d.next = self.b_rx.val();
            self.b_d4.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot5.val()) {
            self.b_x5.d.next = self.b_rx.val();
            self.b_d5.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot6.val()) {
            self.b_x6.d.next = self.b_rx.val();
            self.b_d6.d.next = self.b_rdd.val();
        }
        if self.b_rd2.q.val() & (self.b_wi.q.val() == self.wslot7.val()) {
            self.b_x7.d.next = self.b_rx.val();
            self.b_d7.d.next = self.b_rdd.val();
        }
        // A new row: the ring empties, the reads in flight are forgotten.
        if self.start.val() {
            self.b_base.d.next = bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.b_bank.val()) << self.index_bits.val();
            self.b_n.d.next = self.b_count.val();
            self.b_rd.d.next = 0.into();
            self.b_rd1.d.next = false;
            self.b_rd2.d.next = false;
            self.b_head.d.next = 0.into();
            self.b_wi.d.next = 0.into();
            self.b_fill.d.next = 0.into();
        }
        // The decision: a confirming entry, or both windows complete (a
        // crowded window counts as complete, flagged).
        self.keep.next = self.a_hit.val() | self.b_hit.val();
        self.up_ready.next = self.a_done.val() | self.a_crowded.val();
        self.dn_ready.next = self.b_done.val() | self.b_crowded.val();
        self.decide.next = self.q_valid.val() & (self.keep.val() | (self.up_ready.val() & self.dn_ready.val()));
        self.crowded_q.d.next = self.decide.val() & !self.keep.val() & ((self.a_crowded.val() & !self.a_done.val()) | (self.b_crowded.val() & !self.b_done.val()));
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
