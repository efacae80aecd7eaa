//! The matcher (`DESIGN.md` §3, paper §III–IV): the two detectors' record
//! streams of a line pair in, the matches of the optimal path out.
//!
//! - **Loader**: each side's records go into one bank of its record memory
//!   (two banks of `N_MAX` entries per field), the neighbour levels already
//!   in the [`LEVEL_BITS`] format of the gain rule. A line pair is complete
//!   when both markers have arrived; it then waits in a one-line slot for
//!   the engine, and the next pair loads into the other bank.
//! - **Engine**: sweeps the pair through the [`SystolicMatcher`] (the
//!   reference declivities broadcast to their cells one per clock ahead of
//!   the wavefront, the other view's streamed into the array once per
//!   phase: two phases, interleaved clock by clock, for a line of at most
//!   `2·N` reference declivities, four for a longer one), then runs the [`Traceback`]
//!   and turns its pairs into matches with their positions. The per-line
//!   gain constants use `d_t` rounded down to [`MATCH_DT_FRAC_BITS`].
//!
//! The gain rule is a generation-time choice: [`GainRule::Paper`] is eq. 4–8
//! as written, [`GainRule::Robust`] the default mode of golden (`Robust`:
//! offset-compensated distances, one polarity, one-sided nodes scored on
//! their similar side). The reference view is the left one.
//!
//! ## Ports
//! - `clock`; `reset`, synchronous and active high.
//! - In, per side (`r_` reference = left, `o_` other = right), named as the
//!   detector's outputs: `valid`, `last` (the line's marker), `pos`, `amp`,
//!   `left0..2`, `right0..2`; on the marker `dt`, `wide`, `full`, `sof`
//!   (the line starts a frame), `stamp` (when the marker left its detector,
//!   in ticks of `2^`[`STAMP_SHIFT`] clocks, [`STAMP_BITS`] bits, wrapping)
//!   and, on the reference side, `pos` the line's last pixel (an integer,
//!   no fraction bits). Out: `r_ready`, `o_ready`: records and markers are
//!   taken only while ready (a side is not ready from its marker until the
//!   pair is handed to the engine, nor while a complete pair waits). A
//!   side's records beyond `4·N` (four per cell; [`N_MAX`] in the sensor's
//!   [`N_CELLS`] cells) are dropped and the line flagged full.
//! - `dispmin`, `dispmax`: eq. 6's search area `dispmin < X_i - X_j <
//!   dispmax`, [`POS_FRAC_BITS`] fraction bits (the paper's area is
//!   `dispmin` = 0). Read every clock, as the line's columns enter the
//!   array: change them between frames. A `dispmax` of at most `dispmin + 1`
//!   LSB leaves no node.
//! - Out, a stream without back-pressure: `m_valid` with `m_last` low is a
//!   match, reference order: `m_ref`, `m_other` (indices in their lines),
//!   `m_x_ref` (`X_i`), `m_disp` (`X_i - X_j`, [`POS_FRAC_BITS`] fraction
//!   bits); `m_valid` with `m_last` high ends the line: `m_count` (matches),
//!   `m_n`, `m_m` (declivities of each side), `m_wide`, `m_full` (either
//!   side), `m_sof`, and `m_x_ref` the reference marker's `pos` (the line's
//!   last pixel, for the line processor's frame width).
//! - `r_unpaired`, `o_unpaired`: high for a clock when a reference line, or
//!   an other line, was dropped unpaired (see Pairing).
//!
//! ## Pairing
//! The two sides' lines are paired in order within a frame. When both
//! markers are in and one line starts a frame (`sof`) and the other does
//! not, the other is a line of the frame before that its camera sent
//! beyond the lines of the first camera (a frame cut short on one camera,
//! a line more on the other, or a `tlast` missing on one): it is dropped
//! (its `_unpaired` output high for a clock, on the clock the pair would
//! have entered the waiting slot: see Timing) and its side loads its next
//! line, into the same bank.
//! So a frame with unequal line counts loses its extra lines, and the next
//! frame is paired from its first line on.
//!
//! Two lines that both start a frame are paired only when their markers'
//! stamps are at most `SOF_SKEW_MAX >> STAMP_SHIFT` ticks apart, modulo
//! `2^STAMP_BITS` (the line processor stamps each marker as it leaves
//! its detector: markers at most [`SOF_SKEW_MAX`] clocks apart are paired,
//! more than `SOF_SKEW_MAX + 2^STAMP_SHIFT` apart are not).
//! Further apart, the older has lost its partner (its camera restarted a
//! frame and the other camera's restart line was lost) and is dropped the
//! same way; the younger then meets the older side's next line. Without
//! this the two cameras' frames would stay paired a frame apart from then
//! on. Lines paired (both or neither starting a frame, within the skew)
//! go on as before, on the same clocks: well-formed streams are not
//! affected.
//!
//! ## Timing
//! With the engine idle, a pair whose second marker is taken at clock `t`
//! is in the input register at `t + 1`, waits in the slot from `t + 2` and
//! is taken by the engine at `t +` [`TAKE_AFTER_MARKER`];
//! its marker leaves [`line_cycles`] clocks after that (the sweep,
//! [`sweep_cycles`], the traceback, [`traceback_cycles`], [`OUTPUT_LAG`] output
//! registers), its matches on the clocks just before, one per clock. The
//! traceback of a line overlaps the sweep of the next (two banks of the
//! choice memory, and the positions the matches carry read from copies of
//! the record memories' positions): the sweep engine takes the next pair
//! the clock after its sweep ends, once the traceback has started this one
//! ([`schedule`] has the rules). Loading the next pair overlaps the
//! engine's work on this one; back to back, the worst line, `n = m =
//! N_MAX`, takes `line_period(N_MAX, N_MAX, 0, N_MAX, N_CELLS)` = 845
//! clocks of the engine, inside the 1024 of a `W_MAX` line.
//!
//! `r_valid` / `o_valid` low takes nothing. The registers start from
//! their Verilog initial values, with no line loading, no pair waiting, and
//! the engine and the traceback idle; `reset` (synchronous, active high, one
//! clock or more) returns them there, forgetting the lines in flight.

use crate::params::*;
use crate::matcher::record_input::RecordInput;
use crate::matcher::record_memory::{RecordMemory, COPY_ADDR_BITS, WRITE_LAG};
use crate::matcher::systolic_matcher::{SystolicMatcher, CHOICE_LAG};
use crate::matcher::traceback::{traceback_cycles, Traceback};
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// The local-gain rule the matcher is generated for (golden's modes that
/// change eq. 4–8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GainRule {
    /// Eq. 4–8 as the paper writes them (`golden` mode `paper`).
    Paper,
    /// Offset-compensated distances between declivities of one polarity,
    /// one-sided nodes scored on their similar side (`golden` modes
    /// `relative` + `one-sided`, as in the default `robust`).
    #[default]
    Robust,
}

impl GainRule {
    /// Distances relative to each declivity's end-level mean, and nodes only
    /// between declivities of one polarity.
    fn relative(self) -> bool {
        matches!(self, GainRule::Robust)
    }

    /// One-sided nodes scored on their similar side.
    fn one_sided(self) -> bool {
        matches!(self, GainRule::Robust)
    }
}

/// Clocks from the engine's sweep clock `sc` reading the column of node
/// `(i, j)` (row `i = c + k·N` of cell `c` in phase `k`; `sc = 2j + (2N +
/// 1)·k` with two phases, `4j + (2N + 1)·k` with four) to the node's choice
/// in the array's word registers, less the cell's `2c` (and, with four
/// phases, its skew of `2c` more): the record memory's address register, its
/// read, its output register, the register that drives the array, then the
/// array's [`CHOICE_LAG`].
pub const ENGINE_LAG: usize = 4 + CHOICE_LAG;

/// Clocks of a sweep of `n` reference and `m` other declivities through
/// `cells` cells, from the clock after the engine takes the pair to the
/// traceback's `start` (on the sweep's last clock, which writes the last
/// choice the traceback can need), counted from the sweep's first read `sc
/// = 0`: that choice is in the array's word registers [`ENGINE_LAG`] clocks
/// after the read of its column,
/// - with two phases (`n ≤ 2·cells`), the last node `(n-1, m-1)`'s, read at
///   `2·(n + m - 2) + [n > cells]`;
/// - with four, whichever is later of the last row's (`n - 1 = c_last +
///   k_last·cells`) last node, read at `4·(m - 1) + 4·c_last + (2·cells +
///   1)·k_last` (its column's read plus its cell's skew), and the last node
///   of the phase before's last row, `4·(m - 1) + 4·(cells - 1) + (2·cells +
///   1)·(k_last - 1)`: on one anti-diagonal an earlier phase's node comes
///   later, and the traceback, which walks an anti-diagonal a clock, may
///   step up into that phase a clock after it starts (a later row of its
///   own phase comes later still, by four clocks a row).
pub const fn sweep_cycles(n: usize, m: usize, cells: usize) -> usize {
    if n <= 2 * cells {
        2 * (n + m) + (n > cells) as usize + ENGINE_LAG - 3
    } else {
        let (k_last, c_last) = ((n - 1) / cells, (n - 1) % cells);
        let wrap = 2 * cells + 1;
        let own = 4 * c_last + wrap;
        let before = 4 * (cells - 1);
        4 * m + (k_last - 1) * wrap + if own > before { own } else { before } + ENGINE_LAG - 3
    }
}

/// Clocks from the engine taking a line pair to its marker on the outputs,
/// when the traceback is free at the sweep's end: the sweep, the traceback
/// (its walk stopping on anti-diagonal `stop_diag` with `k` pairs; see
/// [`traceback_cycles`]) and [`OUTPUT_LAG`] output registers.
pub const fn line_cycles(n: usize, m: usize, stop_diag: usize, k: usize, cells: usize) -> usize {
    sweep_cycles(n, m, cells) + traceback_cycles(n, m, stop_diag, k) + OUTPUT_LAG
}

/// Clocks between the takes, and between the markers, of back-to-back line
/// pairs of this work, each waiting when the one before is taken: the next
/// pair is taken the clock after the sweep ends (the traceback of this one
/// overlaps the sweep of the next) or, when the traceback is the longer,
/// the clock after the next traceback starts, which is the clock after this
/// one's marker leaves the traceback. See [`schedule`].
pub const fn line_period(n: usize, m: usize, stop_diag: usize, k: usize, cells: usize) -> usize {
    let (sweep, walk) = (sweep_cycles(n, m, cells), traceback_cycles(n, m, stop_diag, k));
    1 + if sweep > walk { sweep } else { walk }
}

/// One line pair as the engine sees it: the clock its second marker is
/// taken on the ports, and its [`sweep_cycles`] and [`traceback_cycles`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EngineLine {
    pub input_done: u64,
    pub sweep: u64,
    pub traceback: u64,
}

/// When the engine takes a line pair, starts its traceback and sends its
/// marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EngineTimes {
    pub take: u64,
    pub start: u64,
    pub marker: u64,
}

/// The engine's timing, line after line, as its logic has it: the sweep
/// engine takes pair `L` when it is in (`input_done + TAKE_AFTER_MARKER`)
/// and the traceback of pair `L - 1` has started, from the clock after
/// that (`take_L = max(input_done_L + 3, start_{L-1} + 1)`: then the
/// sweep of `L - 1` is over, no swept line waits, and the traceback is on
/// the other bank of the choice memory); the sweep ends `sweep` clocks
/// after the take; the traceback starts on that clock if the one of `L - 1`
/// has sent its marker on an earlier clock, else the clock after it does
/// (`start_L = max(take_L + sweep_L, walk_end_{L-1} + 1)`), and its marker
/// leaves `traceback + OUTPUT_LAG` clocks after the start.
pub fn schedule(lines: &[EngineLine]) -> Vec<EngineTimes> {
    let mut out: Vec<EngineTimes> = Vec::with_capacity(lines.len());
    for l in lines {
        let take = match out.last() {
            None => l.input_done + TAKE_AFTER_MARKER,
            Some(p) => (l.input_done + TAKE_AFTER_MARKER).max(p.start + 1),
        };
        let start = match out.last() {
            None => take + l.sweep,
            Some(p) => (take + l.sweep).max(p.marker - OUTPUT_LAG as u64 + 1),
        };
        out.push(EngineTimes { take, start, marker: start + l.traceback + OUTPUT_LAG as u64 });
    }
    out
}

/// Clocks from the traceback's marker to the matcher's: the record
/// memory's address register, its read and output register (the pair's
/// positions), the difference.
pub const OUTPUT_LAG: usize = 4;

/// Clocks from a line pair's second marker taken on the ports to the
/// engine taking the pair, when the engine is idle: the input register,
/// the marker's flag (`done`), the waiting slot.
pub const TAKE_AFTER_MARKER: u64 = 3;

// A pair's last record, taken on the ports at clock `p`, is on the record
// memory's write ports at `p + 1` and on its RAMs' at `p + 1 +`
// [`WRITE_LAG`] (written at that clock's end); its marker is taken at
// `p + 1` at the earliest, the engine takes the pair `TAKE_AFTER_MARKER`
// clocks later and its first read (which may be of that record: index 0)
// is on the RAMs' read ports two clocks after that (the sweep's first
// clock, the address register). The write must come first, on an earlier
// clock (the RAMs' reads of an address written on the same clock are left
// undefined).
const _: () = assert!(WRITE_LAG < TAKE_AFTER_MARKER as usize + 2);

/// Bits of `d_t,ref + d_t,other` (each [`MATCH_DT_BITS`]).
const DT_SUM_BITS: usize = MATCH_DT_BITS + 1;
/// Integer bits of that sum.
const DT_SUM_INT_BITS: usize = DT_SUM_BITS - MATCH_DT_FRAC_BITS;
/// Bits of the detector's `d_t` above those the matcher keeps: any of them
/// set saturates it (see [`MATCH_DT_INT_BITS`]).
const DT_SAT_BITS: usize = DT_BITS - (DT_FRAC_BITS - MATCH_DT_FRAC_BITS) - MATCH_DT_BITS;


const ENG_IDLE: u64 = 0;
const ENG_SWEEP: u64 = 1;

#[derive(LogicBlock)]
pub struct DeclivityMatcher<const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub r_valid: Signal<In, Bit>,
    pub r_last: Signal<In, Bit>,
    pub r_pos: Signal<In, Bits<POS_BITS>>,
    pub r_amp: Signal<In, Bits<AMP_BITS>>,
    pub r_left0: Signal<In, Bits<PIXEL_BITS>>,
    pub r_left1: Signal<In, Bits<PIXEL_BITS>>,
    pub r_left2: Signal<In, Bits<PIXEL_BITS>>,
    pub r_right0: Signal<In, Bits<PIXEL_BITS>>,
    pub r_right1: Signal<In, Bits<PIXEL_BITS>>,
    pub r_right2: Signal<In, Bits<PIXEL_BITS>>,
    pub r_dt: Signal<In, Bits<DT_BITS>>,
    pub r_wide: Signal<In, Bit>,
    pub r_full: Signal<In, Bit>,
    pub r_sof: Signal<In, Bit>,
    pub r_stamp: Signal<In, Bits<STAMP_BITS>>,
    pub r_ready: Signal<Out, Bit>,
    pub o_valid: Signal<In, Bit>,
    pub o_last: Signal<In, Bit>,
    pub o_pos: Signal<In, Bits<POS_BITS>>,
    pub o_amp: Signal<In, Bits<AMP_BITS>>,
    pub o_left0: Signal<In, Bits<PIXEL_BITS>>,
    pub o_left1: Signal<In, Bits<PIXEL_BITS>>,
    pub o_left2: Signal<In, Bits<PIXEL_BITS>>,
    pub o_right0: Signal<In, Bits<PIXEL_BITS>>,
    pub o_right1: Signal<In, Bits<PIXEL_BITS>>,
    pub o_right2: Signal<In, Bits<PIXEL_BITS>>,
    pub o_dt: Signal<In, Bits<DT_BITS>>,
    pub o_wide: Signal<In, Bit>,
    pub o_full: Signal<In, Bit>,
    pub o_sof: Signal<In, Bit>,
    pub o_stamp: Signal<In, Bits<STAMP_BITS>>,
    pub o_ready: Signal<Out, Bit>,
    pub dispmin: Signal<In, Bits<DISPMAX_BITS>>,
    pub dispmax: Signal<In, Bits<DISPMAX_BITS>>,
    pub m_valid: Signal<Out, Bit>,
    pub m_last: Signal<Out, Bit>,
    pub m_ref: Signal<Out, Bits<INDEX_BITS>>,
    pub m_other: Signal<Out, Bits<INDEX_BITS>>,
    pub m_x_ref: Signal<Out, Bits<POS_BITS>>,
    pub m_disp: Signal<Out, Bits<POS_BITS>>,
    pub m_count: Signal<Out, Bits<COUNT_BITS>>,
    pub m_n: Signal<Out, Bits<COUNT_BITS>>,
    pub m_m: Signal<Out, Bits<COUNT_BITS>>,
    pub m_wide: Signal<Out, Bit>,
    pub m_full: Signal<Out, Bit>,
    pub m_sof: Signal<Out, Bit>,
    /// A reference line, or an other line, dropped unpaired (high for a
    /// clock; see "Pairing").
    pub r_unpaired: Signal<Out, Bit>,
    pub o_unpaired: Signal<Out, Bit>,
    pub array: SystolicMatcher<N>,
    pub traceback: Traceback,
    // The input registers of the two streams.
    r_in: RecordInput,
    o_in: RecordInput,
    r_sof_in: ResetDff<Bit>,
    o_sof_in: ResetDff<Bit>,
    r_stamp_in: ResetDff<Bits<STAMP_BITS>>,
    o_stamp_in: ResetDff<Bits<STAMP_BITS>>,
    // Record memories, two banks each (bank bit on top of the index).
    r_mem: RecordMemory,
    o_mem: RecordMemory,
    // Loader: the line's bank, in the records (`lbank`) and in the
    // position copies (`lpbank` above it).
    lbank: ResetDff<Bit>,
    lpbank: ResetDff<Bit>,
    r_count: ResetDff<Bits<COUNT_BITS>>,
    o_count: ResetDff<Bits<COUNT_BITS>>,
    r_done: ResetDff<Bit>,
    o_done: ResetDff<Bit>,
    r_dt_reg: ResetDff<Bits<DT_BITS>>,
    o_dt_reg: ResetDff<Bits<DT_BITS>>,
    r_flags_wide: ResetDff<Bit>,
    r_flags_full: ResetDff<Bit>,
    o_flags_wide: ResetDff<Bit>,
    o_flags_full: ResetDff<Bit>,
    r_sof_reg: ResetDff<Bit>,
    r_lastx: ResetDff<Bits<X_BITS>>,
    o_sof_reg: ResetDff<Bit>,
    r_stamp_reg: ResetDff<Bits<STAMP_BITS>>,
    o_stamp_reg: ResetDff<Bits<STAMP_BITS>>,
    // Both markers in and not a pair: one line starting a frame and the
    // other not, or both starting one too far apart in time (`far`, the
    // reference's the older when `r_older`); the line dropped (`r_drop`,
    // `o_drop`, then registered).
    stamp_diff: Signal<Local, Bits<STAMP_BITS>>,
    far: Signal<Local, Bit>,
    r_older: Signal<Local, Bit>,
    mismatch: Signal<Local, Bit>,
    r_drop: Signal<Local, Bit>,
    o_drop: Signal<Local, Bit>,
    r_drop_q: ResetDff<Bit>,
    o_drop_q: ResetDff<Bit>,
    // The waiting pair.
    pend: ResetDff<Bit>,
    pend_bank: ResetDff<Bit>,
    pend_pbank: ResetDff<Bit>,
    pend_n: ResetDff<Bits<COUNT_BITS>>,
    pend_m: ResetDff<Bits<COUNT_BITS>>,
    pend_dt_sum: ResetDff<Bits<DT_SUM_BITS>>,
    pend_wide: ResetDff<Bit>,
    pend_full: ResetDff<Bit>,
    pend_sof: ResetDff<Bit>,
    pend_lastx: ResetDff<Bits<X_BITS>>,
    // Engine.
    eng: ResetDff<Bits<2>>,
    ebank: ResetDff<Bit>,
    epbank: ResetDff<Bit>,
    // The traceback: busy from its start to its marker, with its line's
    // counts, banks and flags; a swept line waiting for it (`tq`).
    // (Busy is `tb_begun ^ tb_ended`: each flips on its own event, so that
    // no register's input depends on both the traceback's marker and the
    // logic that starts it; Verilator then sees no loop through the
    // traceback.)
    tb_begun: ResetDff<Bit>,
    tb_ended: ResetDff<Bit>,
    t_n: ResetDff<Bits<COUNT_BITS>>,
    t_m: ResetDff<Bits<COUNT_BITS>>,
    t_bank: ResetDff<Bit>,
    t_pbank: ResetDff<Bit>,
    t_wide: ResetDff<Bit>,
    t_full: ResetDff<Bit>,
    t_sof: ResetDff<Bit>,
    t_lastx: ResetDff<Bits<X_BITS>>,
    tq: ResetDff<Bit>,
    tq_n: ResetDff<Bits<COUNT_BITS>>,
    tq_m: ResetDff<Bits<COUNT_BITS>>,
    // The traceback's walk start (`n - 1`, `m - 1`, `n + m - 2`, `n` or
    // `m` zero) of the swept line and of the waiting one, in registers
    // (see `Traceback`'s ports).
    e_wi0: ResetDff<Bits<INDEX_BITS>>,
    e_wj0: ResetDff<Bits<INDEX_BITS>>,
    e_diag0: ResetDff<Bits<DIAG_BITS>>,
    e_empty: ResetDff<Bit>,
    tq_wi0: ResetDff<Bits<INDEX_BITS>>,
    tq_wj0: ResetDff<Bits<INDEX_BITS>>,
    tq_diag0: ResetDff<Bits<DIAG_BITS>>,
    tq_empty: ResetDff<Bit>,
    tq_bank: ResetDff<Bit>,
    tq_pbank: ResetDff<Bit>,
    tq_wide: ResetDff<Bit>,
    tq_full: ResetDff<Bit>,
    tq_sof: ResetDff<Bit>,
    tq_lastx: ResetDff<Bits<X_BITS>>,
    // The position copies' read addresses (the traceback's pairs).
    p_addr_r: ResetDff<Bits<COPY_ADDR_BITS>>,
    p_addr_o: ResetDff<Bits<COPY_ADDR_BITS>>,
    en: ResetDff<Bits<COUNT_BITS>>,
    em: ResetDff<Bits<COUNT_BITS>>,
    sc: ResetDff<Bits<SWEEP_BITS>>,
    sweep_end_m1: ResetDff<Bits<SWEEP_BITS>>,
    sweep_done: ResetDff<Bit>,
    // `take`, registered: it loads the taken pair's d_t sum and flags a
    // clock later, near where they are used (the pair's `pend_*` registers
    // hold until the clock after), so that `take` stays near the engine.
    take_q: ResetDff<Bit>,
    // The taken pair's d_t sum (loaded on `take_q`) and the line's
    // constants computed from it every clock.
    e_dt_sum: ResetDff<Bits<DT_SUM_BITS>>,
    below2_reg: ResetDff<Bits<DIST_BITS>>,
    dm1_reg: ResetDff<Bits<{ POS_BITS + 1 }>>,
    f1_reg: ResetDff<Bits<GAIN_BITS>>,
    f3_reg: ResetDff<Bits<GAIN_BITS>>,
    e_wide: ResetDff<Bit>,
    e_full: ResetDff<Bit>,
    e_sof: ResetDff<Bit>,
    e_lastx: ResetDff<Bits<X_BITS>>,
    e_fold: ResetDff<Bit>,
    // The taken line's rows have four clocks per node (more than 2·N
    // reference declivities), and its last phase.
    e_p4: ResetDff<Bit>,
    e_klast: ResetDff<Bits<PHASE_BITS>>,
    ld_valid_d: ResetDff<Bit>,
    ld_valid_e: ResetDff<Bit>,
    ld_index_e: ResetDff<Bits<INDEX_BITS>>,
    c_valid_e2: ResetDff<Bit>,
    c_phase_e2: ResetDff<Bits<PHASE_BITS>>,
    r_addr_q: ResetDff<Bits<DIAG_BITS>>,
    o_addr_q: ResetDff<Bits<DIAG_BITS>>,
    q2_valid: ResetDff<Bit>,
    q2_last: ResetDff<Bit>,
    q2_i: ResetDff<Bits<INDEX_BITS>>,
    q2_j: ResetDff<Bits<INDEX_BITS>>,
    q2_count: ResetDff<Bits<COUNT_BITS>>,
    ld_index_d: ResetDff<Bits<INDEX_BITS>>,
    c_valid_d: ResetDff<Bit>,
    c_phase_d: ResetDff<Bits<PHASE_BITS>>,
    // The record memories' outputs (already registered inside the block
    // RAMs) registered again into the registers that drive the broadcast
    // and the array; the control bits alongside.
    c_valid_e: ResetDff<Bit>,
    ld_first: ResetDff<Bit>,
    ld_phase: ResetDff<Bits<PHASE_BITS>>,
    c_phase_e: ResetDff<Bits<PHASE_BITS>>,
    ld_pos_q: ResetDff<Bits<POS_BITS>>,
    ld_levs_q: ResetDff<Bits<LEVELS_BITS>>,
    ld_rising_q: ResetDff<Bit>,
    c_valid_q: ResetDff<Bit>,
    c_phase_q: ResetDff<Bits<PHASE_BITS>>,
    c_pos_q: ResetDff<Bits<POS_BITS>>,
    c_levs_q: ResetDff<Bits<LEVELS_BITS>>,
    c_rising_q: ResetDff<Bit>,
    // Output pipeline: RAM read, then the output registers.
    q_valid: ResetDff<Bit>,
    q_last: ResetDff<Bit>,
    q_i: ResetDff<Bits<INDEX_BITS>>,
    q_j: ResetDff<Bits<INDEX_BITS>>,
    q_count: ResetDff<Bits<COUNT_BITS>>,
    w_valid: ResetDff<Bit>,
    w_last: ResetDff<Bit>,
    w_i: ResetDff<Bits<INDEX_BITS>>,
    w_j: ResetDff<Bits<INDEX_BITS>>,
    w_count: ResetDff<Bits<COUNT_BITS>>,
    w_n: ResetDff<Bits<COUNT_BITS>>,
    w_m: ResetDff<Bits<COUNT_BITS>>,
    w_wide: ResetDff<Bit>,
    w_full: ResetDff<Bit>,
    w_sof: ResetDff<Bit>,
    w_lastx: ResetDff<Bits<X_BITS>>,
    out_valid: ResetDff<Bit>,
    out_last: ResetDff<Bit>,
    out_ref: ResetDff<Bits<INDEX_BITS>>,
    out_other: ResetDff<Bits<INDEX_BITS>>,
    out_x_ref: ResetDff<Bits<POS_BITS>>,
    out_disp: ResetDff<Bits<POS_BITS>>,
    out_count: ResetDff<Bits<COUNT_BITS>>,
    out_n: ResetDff<Bits<COUNT_BITS>>,
    out_m: ResetDff<Bits<COUNT_BITS>>,
    out_wide: ResetDff<Bit>,
    out_full: ResetDff<Bit>,
    out_sof: ResetDff<Bit>,
    // Combinational.
    r_take: Signal<Local, Bit>,
    o_take: Signal<Local, Bit>,
    r_addr: Signal<Local, Bits<COPY_ADDR_BITS>>,
    o_addr: Signal<Local, Bits<COPY_ADDR_BITS>>,
    line_base: Signal<Local, Bits<COPY_ADDR_BITS>>,
    tb_base: Signal<Local, Bits<COPY_ADDR_BITS>>,
    tb_start: Signal<Local, Bit>,
    tb_busy: Signal<Local, Bit>,
    tb_from_q: Signal<Local, Bit>,
    handoff: Signal<Local, Bit>,
    take: Signal<Local, Bit>,
    r_dt_m: Signal<Local, Bits<MATCH_DT_BITS>>,
    o_dt_m: Signal<Local, Bits<MATCH_DT_BITS>>,
    dt_sum: Signal<Local, Bits<DT_SUM_BITS>>,
    sc_idx: Signal<Local, Bits<INDEX_BITS>>,
    // The loading line's sweep as far as its reference count decides it,
    // from the count of a clock ago (final by the handoff): four phases or
    // two, the last phase, and `sweep_end_m1` less the other side's part
    // (see `sweep_cycles`).
    n_p4: ResetDff<Bit>,
    n_klast: ResetDff<Bits<PHASE_BITS>>,
    n_part: ResetDff<Bits<SWEEP_BITS>>,
    // n - 1 (the count before the last record: the loader keeps it beside
    // the count, so that no subtraction is on the way to `n_part`).
    r_count_m1: ResetDff<Bits<COUNT_BITS>>,
    n_kl: Signal<Local, Bits<PHASE_BITS>>,
    n_c: Signal<Local, Bits<INDEX_BITS>>,
    n_own: Signal<Local, Bits<SWEEP_BITS>>,
    n_before: Signal<Local, Bits<SWEEP_BITS>>,
    m_part: Signal<Local, Bits<SWEEP_BITS>>,
    // The waiting pair's sweep: its last clock less one, its phases.
    pend_end_m1: ResetDff<Bits<SWEEP_BITS>>,
    pend_fold: ResetDff<Bit>,
    pend_p4: ResetDff<Bit>,
    pend_klast: ResetDff<Bits<PHASE_BITS>>,
    sc_phase: Signal<Local, Bits<PHASE_BITS>>,
    sc_base: Signal<Local, Bits<SWEEP_BITS>>,
    sc_off: Signal<Local, Bits<SWEEP_BITS>>,
    sc_j: Signal<Local, Bits<SWEEP_BITS>>,
    c_pos_min: Signal<Local, Bits<{ POS_BITS + 1 }>>,
    band: Signal<Local, Bits<{ POS_BITS + 1 }>>,
    col_ok: Signal<Local, Bit>,
    col_j: Signal<Local, Bits<INDEX_BITS>>,
    tw: Signal<Local, Bits<SWEEP_BITS>>,
    base2: Signal<Local, Bits<SWEEP_BITS>>,
    base4: Signal<Local, Bits<SWEEP_BITS>>,
    em_w: Signal<Local, Bits<SWEEP_BITS>>,
    in2_0: Signal<Local, Bit>,
    in2_1: Signal<Local, Bit>,
    in4_0: Signal<Local, Bit>,
    in4_1: Signal<Local, Bit>,
    in4_2: Signal<Local, Bit>,
    in4_3: Signal<Local, Bit>,
    in_window: Signal<Local, Bit>,
    lim1: ResetDff<Bits<SWEEP_BITS>>,
    lim2: ResetDff<Bits<SWEEP_BITS>>,
    lim3: ResetDff<Bits<SWEEP_BITS>>,
    cw_diag_q: ResetDff<Bits<DIAG_BITS>>,
    cw_phase_q: ResetDff<Bits<PHASE_BITS>>,
    tw_phase: Signal<Local, Bits<PHASE_BITS>>,
    tw_diag: Signal<Local, Bits<SWEEP_BITS>>,
    ld_levs: Signal<Local, Bits<LEVELS_BITS>>,
    c_levs: Signal<Local, Bits<LEVELS_BITS>>,
    rd_bank_base: Signal<Local, Bits<DIAG_BITS>>,
    r_rd: Signal<Local, Bits<DIAG_BITS>>,
    o_rd: Signal<Local, Bits<DIAG_BITS>>,
    // Constants.
    relative: Constant<Bit>,
    one_sided: Constant<Bit>,
    bank_size: Constant<Bits<DIAG_BITS>>,
    copy_bank_size: Constant<Bits<COPY_ADDR_BITS>>,
    copy_bank2_size: Constant<Bits<COPY_ADDR_BITS>>,
    n_max: Constant<Bits<COUNT_BITS>>,
    skew_ticks: Constant<Bits<STAMP_BITS>>,
    skew_ticks_neg: Constant<Bits<STAMP_BITS>>,
    stamp_msb: Constant<Bits<8>>,
    eng_idle: Constant<Bits<2>>,
    eng_sweep: Constant<Bits<2>>,
    sweep_tail: Constant<Bits<SWEEP_BITS>>,
    sweep_tail1: Constant<Bits<SWEEP_BITS>>,
    own_k2: Constant<Bits<SWEEP_BITS>>,
    own_k3: Constant<Bits<SWEEP_BITS>>,
    before_k2: Constant<Bits<SWEEP_BITS>>,
    before_k3: Constant<Bits<SWEEP_BITS>>,
    own_from: Constant<Bits<INDEX_BITS>>,
    engine_lag: Constant<Bits<SWEEP_BITS>>,
    engine_lag_m1: Constant<Bits<SWEEP_BITS>>,
    diag_two: Constant<Bits<DIAG_BITS>>,
    off1: Constant<Bits<SWEEP_BITS>>,
    off2: Constant<Bits<SWEEP_BITS>>,
    off3: Constant<Bits<SWEEP_BITS>>,
    off1_p4: Constant<Bits<SWEEP_BITS>>,
    off2_p4: Constant<Bits<SWEEP_BITS>>,
    off3_p4: Constant<Bits<SWEEP_BITS>>,
    cells_c: Constant<Bits<COUNT_BITS>>,
    cells_2c: Constant<Bits<COUNT_BITS>>,
    cells_log2: Constant<Bits<8>>,
    cells_mask: Constant<Bits<INDEX_BITS>>,
    lev_at1: Constant<Bits<8>>,
    lev_at2: Constant<Bits<8>>,
    lev_at3: Constant<Bits<8>>,
    lev_at4: Constant<Bits<8>>,
    lev_at5: Constant<Bits<8>>,
    bit0: Constant<Bits<8>>,
    pos_carry: Constant<Bits<8>>,
    pos_max: Constant<Bits<POS_BITS>>,
    bit1: Constant<Bits<8>>,
    bit2: Constant<Bits<8>>,
    dt_frac: Constant<Bits<8>>,
    dt_drop: Constant<Bits<8>>,
    dt_sat: Constant<Bits<8>>,
    dt_max: Constant<Bits<MATCH_DT_BITS>>,
}

impl<const N: usize> DeclivityMatcher<N> {
    /// A matcher of `N` cells with the gain rule `rule`.
    pub fn new(rule: GainRule) -> Self {
        DeclivityMatcher {
            clock: Default::default(),
            reset: Default::default(),
            r_valid: Default::default(),
            r_last: Default::default(),
            r_pos: Default::default(),
            r_amp: Default::default(),
            r_left0: Default::default(),
            r_left1: Default::default(),
            r_left2: Default::default(),
            r_right0: Default::default(),
            r_right1: Default::default(),
            r_right2: Default::default(),
            r_dt: Default::default(),
            r_wide: Default::default(),
            r_full: Default::default(),
            r_sof: Default::default(),
            r_stamp: Default::default(),
            o_sof: Default::default(),
            o_stamp: Default::default(),
            r_ready: Default::default(),
            o_valid: Default::default(),
            o_last: Default::default(),
            o_pos: Default::default(),
            o_amp: Default::default(),
            o_left0: Default::default(),
            o_left1: Default::default(),
            o_left2: Default::default(),
            o_right0: Default::default(),
            o_right1: Default::default(),
            o_right2: Default::default(),
            o_dt: Default::default(),
            o_wide: Default::default(),
            o_full: Default::default(),
            o_ready: Default::default(),
            dispmin: Default::default(),
            dispmax: Default::default(),
            m_valid: Default::default(),
            m_last: Default::default(),
            m_ref: Default::default(),
            m_other: Default::default(),
            m_x_ref: Default::default(),
            m_disp: Default::default(),
            m_count: Default::default(),
            m_n: Default::default(),
            m_m: Default::default(),
            m_wide: Default::default(),
            m_full: Default::default(),
            m_sof: Default::default(),
            r_unpaired: Default::default(),
            o_unpaired: Default::default(),
            array: Default::default(),
            traceback: Default::default(),
            r_in: Default::default(),
            o_in: Default::default(),
            r_sof_in: Default::default(),
            o_stamp_in: Default::default(),
            r_stamp_in: Default::default(),
            o_sof_in: Default::default(),
            r_mem: Default::default(),
            o_mem: Default::default(),
            lbank: Default::default(),
            lpbank: Default::default(),
            r_count: Default::default(),
            o_count: Default::default(),
            r_done: Default::default(),
            o_done: Default::default(),
            r_dt_reg: Default::default(),
            o_dt_reg: Default::default(),
            r_flags_wide: Default::default(),
            r_flags_full: Default::default(),
            o_flags_wide: Default::default(),
            o_flags_full: Default::default(),
            r_sof_reg: Default::default(),
            r_lastx: Default::default(),
            o_sof_reg: Default::default(),
            r_stamp_reg: Default::default(),
            o_stamp_reg: Default::default(),
            stamp_diff: Default::default(),
            far: Default::default(),
            r_older: Default::default(),
            mismatch: Default::default(),
            r_drop: Default::default(),
            o_drop: Default::default(),
            r_drop_q: Default::default(),
            o_drop_q: Default::default(),
            pend: Default::default(),
            pend_bank: Default::default(),
            pend_pbank: Default::default(),
            pend_n: Default::default(),
            pend_m: Default::default(),
            pend_dt_sum: Default::default(),
            pend_wide: Default::default(),
            pend_full: Default::default(),
            pend_sof: Default::default(),
            pend_lastx: Default::default(),
            eng: Default::default(),
            ebank: Default::default(),
            epbank: Default::default(),
            tb_begun: Default::default(),
            tb_ended: Default::default(),
            tb_busy: Default::default(),
            t_n: Default::default(),
            t_m: Default::default(),
            t_bank: Default::default(),
            t_pbank: Default::default(),
            t_wide: Default::default(),
            t_full: Default::default(),
            t_sof: Default::default(),
            t_lastx: Default::default(),
            tq: Default::default(),
            tq_n: Default::default(),
            tq_m: Default::default(),
            e_wi0: Default::default(),
            e_wj0: Default::default(),
            e_diag0: Default::default(),
            e_empty: Default::default(),
            tq_wi0: Default::default(),
            tq_wj0: Default::default(),
            tq_diag0: Default::default(),
            tq_empty: Default::default(),
            tq_bank: Default::default(),
            tq_pbank: Default::default(),
            tq_wide: Default::default(),
            tq_full: Default::default(),
            tq_sof: Default::default(),
            tq_lastx: Default::default(),
            p_addr_r: Default::default(),
            p_addr_o: Default::default(),
            en: Default::default(),
            em: Default::default(),
            sc: Default::default(),
            sweep_end_m1: Default::default(),
            sweep_done: Default::default(),
            take_q: Default::default(),
            e_dt_sum: Default::default(),
            below2_reg: Default::default(),
            dm1_reg: Default::default(),
            f1_reg: Default::default(),
            f3_reg: Default::default(),
            e_wide: Default::default(),
            e_full: Default::default(),
            e_sof: Default::default(),
            e_lastx: Default::default(),
            e_fold: Default::default(),
            e_p4: Default::default(),
            e_klast: Default::default(),
            ld_valid_d: Default::default(),
            ld_valid_e: Default::default(),
            ld_index_e: Default::default(),
            c_valid_e2: Default::default(),
            c_phase_e2: Default::default(),
            r_addr_q: Default::default(),
            o_addr_q: Default::default(),
            q2_valid: Default::default(),
            q2_last: Default::default(),
            q2_i: Default::default(),
            q2_j: Default::default(),
            q2_count: Default::default(),
            ld_index_d: Default::default(),
            c_valid_d: Default::default(),
            c_phase_d: Default::default(),
            c_valid_e: Default::default(),
            ld_first: Default::default(),
            ld_phase: Default::default(),
            c_phase_e: Default::default(),
            ld_pos_q: Default::default(),
            ld_levs_q: Default::default(),
            ld_rising_q: Default::default(),
            c_valid_q: Default::default(),
            c_phase_q: Default::default(),
            c_pos_q: Default::default(),
            c_levs_q: Default::default(),
            c_rising_q: Default::default(),
            q_valid: Default::default(),
            q_last: Default::default(),
            q_i: Default::default(),
            q_j: Default::default(),
            q_count: Default::default(),
            w_valid: Default::default(),
            w_last: Default::default(),
            w_i: Default::default(),
            w_j: Default::default(),
            w_count: Default::default(),
            w_n: Default::default(),
            w_m: Default::default(),
            w_wide: Default::default(),
            w_full: Default::default(),
            w_sof: Default::default(),
            w_lastx: Default::default(),
            out_valid: Default::default(),
            out_last: Default::default(),
            out_ref: Default::default(),
            out_other: Default::default(),
            out_x_ref: Default::default(),
            out_disp: Default::default(),
            out_count: Default::default(),
            out_n: Default::default(),
            out_m: Default::default(),
            out_wide: Default::default(),
            out_full: Default::default(),
            out_sof: Default::default(),
            r_take: Default::default(),
            o_take: Default::default(),
            r_addr: Default::default(),
            o_addr: Default::default(),
            line_base: Default::default(),
            tb_base: Default::default(),
            tb_start: Default::default(),
            tb_from_q: Default::default(),
            handoff: Default::default(),
            take: Default::default(),
            r_dt_m: Default::default(),
            o_dt_m: Default::default(),
            dt_sum: Default::default(),
            sc_idx: Default::default(),
            n_p4: Default::default(),
            n_klast: Default::default(),
            n_part: Default::default(),
            r_count_m1: Default::default(),
            n_kl: Default::default(),
            n_c: Default::default(),
            n_own: Default::default(),
            n_before: Default::default(),
            m_part: Default::default(),
            pend_end_m1: Default::default(),
            pend_fold: Default::default(),
            pend_p4: Default::default(),
            pend_klast: Default::default(),
            sc_phase: Default::default(),
            sc_base: Default::default(),
            sc_off: Default::default(),
            sc_j: Default::default(),
            c_pos_min: Default::default(),
            band: Default::default(),
            col_ok: Default::default(),
            col_j: Default::default(),
            tw: Default::default(),
            base2: Default::default(),
            base4: Default::default(),
            em_w: Default::default(),
            in2_0: Default::default(),
            in2_1: Default::default(),
            in4_0: Default::default(),
            in4_1: Default::default(),
            in4_2: Default::default(),
            in4_3: Default::default(),
            in_window: Default::default(),
            lim1: Default::default(),
            lim2: Default::default(),
            lim3: Default::default(),
            cw_diag_q: Default::default(),
            cw_phase_q: Default::default(),
            tw_phase: Default::default(),
            tw_diag: Default::default(),
            ld_levs: Default::default(),
            c_levs: Default::default(),
            rd_bank_base: Default::default(),
            r_rd: Default::default(),
            o_rd: Default::default(),
            relative: Constant::new(rule.relative()),
            one_sided: Constant::new(rule.one_sided()),
            bank_size: Constant::new(((N_MAX as u64) as u64).into()),
            copy_bank_size: Constant::new((N_MAX as u64).into()),
            copy_bank2_size: Constant::new((2 * N_MAX as u64).into()),
            n_max: Constant::new(((ROWS_PER_CELL * N) as u64).into()),
            skew_ticks: Constant::new((SKEW_TICKS as u64).into()),
            skew_ticks_neg: Constant::new((((1u64 << STAMP_BITS) - SKEW_TICKS as u64)).into()),
            stamp_msb: Constant::new(((STAMP_BITS - 1) as u64).into()),
            eng_idle: Constant::new(((ENG_IDLE) as u64).into()),
            eng_sweep: Constant::new(((ENG_SWEEP) as u64).into()),
            sweep_tail: Constant::new(((ENGINE_LAG - 5) as u64).into()),
            sweep_tail1: Constant::new(((ENGINE_LAG - 4) as u64).into()),
            own_k2: Constant::new(((2 * (2 * N + 1) + ENGINE_LAG - 5) as u64).into()),
            own_k3: Constant::new(((3 * (2 * N + 1) + ENGINE_LAG - 5) as u64).into()),
            before_k2: Constant::new(((4 * (N - 1) + (2 * N + 1) + ENGINE_LAG - 5) as u64).into()),
            before_k3: Constant::new(((4 * (N - 1) + 2 * (2 * N + 1) + ENGINE_LAG - 5) as u64).into()),
            own_from: Constant::new((((2 * N) as u64).saturating_sub(5).div_ceil(4)).into()),
            engine_lag: Constant::new((ENGINE_LAG as u64).into()),
            engine_lag_m1: Constant::new(((ENGINE_LAG - 1) as u64).into()),
            diag_two: Constant::new(2u64.into()),
            off1: Constant::new((N as u64).into()),
            off2: Constant::new((2 * N as u64).into()),
            off3: Constant::new((3 * N as u64).into()),
            off1_p4: Constant::new((N as u64 / 2).into()),
            off2_p4: Constant::new((N as u64).into()),
            off3_p4: Constant::new((3 * N as u64 / 2).into()),
            cells_c: Constant::new((N as u64).into()),
            cells_2c: Constant::new(((2 * N) as u64).into()),
            cells_log2: Constant::new((N.trailing_zeros() as u64).into()),
            cells_mask: Constant::new(((N - 1) as u64).into()),
            lev_at1: Constant::new((LEVEL_BITS as u64).into()),
            lev_at2: Constant::new((2 * LEVEL_BITS as u64).into()),
            lev_at3: Constant::new((3 * LEVEL_BITS as u64).into()),
            lev_at4: Constant::new((4 * LEVEL_BITS as u64).into()),
            lev_at5: Constant::new((5 * LEVEL_BITS as u64).into()),
            bit0: Constant::new(0u64.into()),
            pos_carry: Constant::new((POS_BITS as u64).into()),
            pos_max: Constant::new(((1u64 << POS_BITS) - 1).into()),
            bit1: Constant::new(1u64.into()),
            bit2: Constant::new(2u64.into()),
            dt_frac: Constant::new((MATCH_DT_FRAC_BITS as u64).into()),
            dt_drop: Constant::new(((DT_FRAC_BITS - MATCH_DT_FRAC_BITS) as u64).into()),
            dt_sat: Constant::new(((DT_BITS - DT_SAT_BITS) as u64).into()),
            dt_max: Constant::new(((1u64 << MATCH_DT_BITS) - 1).into()),
        }
    }
}

impl<const N: usize> Default for DeclivityMatcher<N> {
    fn default() -> Self {
        Self::new(GainRule::default())
    }
}

impl<const N: usize> Logic for DeclivityMatcher<N> {
    #[hdl_gen]
    fn update(&mut self) {
        self.array.clock.next = self.clock.val();
        self.array.reset.next = self.reset.val();
        self.traceback.clock.next = self.clock.val();
        self.traceback.reset.next = self.reset.val();
        self.r_mem.clock.next = self.clock.val();
        self.r_mem.reset.next = self.reset.val();
        self.o_mem.clock.next = self.clock.val();
        self.o_mem.reset.next = self.reset.val();
        self.r_mem.relative.next = self.relative.val();
        self.o_mem.relative.next = self.relative.val();
        dff_setup!(
            self, clock, r_sof_in, o_sof_in, o_sof_reg, r_drop_q, o_drop_q, lbank, lpbank, r_count, o_count, r_done, o_done, r_dt_reg, o_dt_reg, r_flags_wide, r_flags_full,
            o_flags_wide, o_flags_full, r_sof_reg, pend, pend_bank, pend_pbank, pend_n, pend_m, pend_dt_sum, pend_wide,
            pend_full, pend_sof, eng, ebank, epbank, tb_begun, tb_ended, t_n, t_m, t_bank, t_pbank, t_wide, t_full, t_sof, tq, tq_n, tq_m, e_wi0, e_wj0, e_diag0, e_empty, tq_wi0, tq_wj0, tq_diag0, tq_empty, tq_bank, tq_pbank, tq_wide, tq_full, tq_sof, p_addr_r, p_addr_o, en, em, sc, sweep_end_m1, sweep_done, lim1, lim2, lim3, cw_diag_q, cw_phase_q, n_p4, n_klast, n_part, r_count_m1, pend_end_m1, pend_fold, pend_p4, pend_klast, take_q, e_dt_sum, below2_reg, dm1_reg, f1_reg, f3_reg, e_wide, e_full,
            e_sof, e_fold, e_p4, e_klast, ld_valid_d, ld_index_d, c_valid_d, c_phase_d, c_valid_e, ld_valid_e, ld_index_e, c_valid_e2, c_phase_e2, r_addr_q, o_addr_q, q2_valid, q2_last, q2_i, q2_j, q2_count, ld_first, ld_phase, c_phase_e, ld_pos_q, ld_levs_q, ld_rising_q, c_valid_q, c_phase_q, c_pos_q, c_levs_q, c_rising_q, q_valid, q_last, q_i, q_j, q_count, w_valid, w_last, w_i, w_j, w_count, w_n, w_m, w_wide, w_full, w_sof, out_valid,
            out_last, out_ref, out_other, out_x_ref, out_disp, out_count, out_n, out_m, out_wide, out_full,
            out_sof, r_lastx, pend_lastx, t_lastx, tq_lastx, e_lastx, w_lastx, r_stamp_in, o_stamp_in, r_stamp_reg, o_stamp_reg
        );
        self.r_stamp_in.reset.next = self.reset.val();
        self.o_stamp_in.reset.next = self.reset.val();
        self.r_stamp_reg.reset.next = self.reset.val();
        self.o_stamp_reg.reset.next = self.reset.val();
        self.r_sof_in.reset.next = self.reset.val();
        self.o_sof_in.reset.next = self.reset.val();
        self.o_sof_reg.reset.next = self.reset.val();
        self.r_drop_q.reset.next = self.reset.val();
        self.o_drop_q.reset.next = self.reset.val();
        self.lbank.reset.next = self.reset.val();
        self.lpbank.reset.next = self.reset.val();
        self.r_count.reset.next = self.reset.val();
        self.o_count.reset.next = self.reset.val();
        self.r_done.reset.next = self.reset.val();
        self.o_done.reset.next = self.reset.val();
        self.r_dt_reg.reset.next = self.reset.val();
        self.o_dt_reg.reset.next = self.reset.val();
        self.r_flags_wide.reset.next = self.reset.val();
        self.r_flags_full.reset.next = self.reset.val();
        self.o_flags_wide.reset.next = self.reset.val();
        self.o_flags_full.reset.next = self.reset.val();
        self.r_sof_reg.reset.next = self.reset.val();
        self.r_lastx.reset.next = self.reset.val();
        self.pend.reset.next = self.reset.val();
        self.pend_bank.reset.next = self.reset.val();
        self.pend_pbank.reset.next = self.reset.val();
        self.pend_n.reset.next = self.reset.val();
        self.pend_m.reset.next = self.reset.val();
        self.pend_dt_sum.reset.next = self.reset.val();
        self.pend_wide.reset.next = self.reset.val();
        self.pend_full.reset.next = self.reset.val();
        self.pend_sof.reset.next = self.reset.val();
        self.pend_lastx.reset.next = self.reset.val();
        self.eng.reset.next = self.reset.val();
        self.ebank.reset.next = self.reset.val();
        self.epbank.reset.next = self.reset.val();
        self.tb_begun.reset.next = self.reset.val();
        self.tb_ended.reset.next = self.reset.val();
        self.t_n.reset.next = self.reset.val();
        self.t_m.reset.next = self.reset.val();
        self.t_bank.reset.next = self.reset.val();
        self.t_pbank.reset.next = self.reset.val();
        self.t_wide.reset.next = self.reset.val();
        self.t_full.reset.next = self.reset.val();
        self.t_sof.reset.next = self.reset.val();
        self.t_lastx.reset.next = self.reset.val();
        self.tq.reset.next = self.reset.val();
        self.tq_n.reset.next = self.reset.val();
        self.tq_m.reset.next = self.reset.val();
        self.e_wi0.reset.next = self.reset.val();
        self.e_wj0.reset.next = self.reset.val();
        self.e_diag0.reset.next = self.reset.val();
        self.e_empty.reset.next = self.reset.val();
        self.tq_wi0.reset.next = self.reset.val();
        self.tq_wj0.reset.next = self.reset.val();
        self.tq_diag0.reset.next = self.reset.val();
        self.tq_empty.reset.next = self.reset.val();
        self.tq_bank.reset.next = self.reset.val();
        self.tq_pbank.reset.next = self.reset.val();
        self.tq_wide.reset.next = self.reset.val();
        self.tq_full.reset.next = self.reset.val();
        self.tq_sof.reset.next = self.reset.val();
        self.tq_lastx.reset.next = self.reset.val();
        self.p_addr_r.reset.next = self.reset.val();
        self.p_addr_o.reset.next = self.reset.val();
        self.en.reset.next = self.reset.val();
        self.em.reset.next = self.reset.val();
        self.sc.reset.next = self.reset.val();
        self.sweep_end_m1.reset.next = self.reset.val();
        self.sweep_done.reset.next = self.reset.val();
        self.lim1.reset.next = self.reset.val();
        self.lim2.reset.next = self.reset.val();
        self.lim3.reset.next = self.reset.val();
        self.cw_diag_q.reset.next = self.reset.val();
        self.cw_phase_q.reset.next = self.reset.val();
        self.n_p4.reset.next = self.reset.val();
        self.n_klast.reset.next = self.reset.val();
        self.n_part.reset.next = self.reset.val();
        self.r_count_m1.reset.next = self.reset.val();
        self.pend_end_m1.reset.next = self.reset.val();
        self.pend_fold.reset.next = self.reset.val();
        self.pend_p4.reset.next = self.reset.val();
        self.pend_klast.reset.next = self.reset.val();
        self.take_q.reset.next = self.reset.val();
        self.e_dt_sum.reset.next = self.reset.val();
        self.below2_reg.reset.next = self.reset.val();
        self.dm1_reg.reset.next = self.reset.val();
        self.f1_reg.reset.next = self.reset.val();
        self.f3_reg.reset.next = self.reset.val();
        self.e_wide.reset.next = self.reset.val();
        self.e_full.reset.next = self.reset.val();
        self.e_sof.reset.next = self.reset.val();
        self.e_lastx.reset.next = self.reset.val();
        self.e_fold.reset.next = self.reset.val();
        self.e_p4.reset.next = self.reset.val();
        self.e_klast.reset.next = self.reset.val();
        self.ld_valid_d.reset.next = self.reset.val();
        self.ld_index_d.reset.next = self.reset.val();
        self.c_valid_d.reset.next = self.reset.val();
        self.c_phase_d.reset.next = self.reset.val();
        self.c_valid_e.reset.next = self.reset.val();
        self.ld_valid_e.reset.next = self.reset.val();
        self.ld_index_e.reset.next = self.reset.val();
        self.c_valid_e2.reset.next = self.reset.val();
        self.c_phase_e2.reset.next = self.reset.val();
        self.r_addr_q.reset.next = self.reset.val();
        self.o_addr_q.reset.next = self.reset.val();
        self.q2_valid.reset.next = self.reset.val();
        self.q2_last.reset.next = self.reset.val();
        self.q2_i.reset.next = self.reset.val();
        self.q2_j.reset.next = self.reset.val();
        self.q2_count.reset.next = self.reset.val();
        self.ld_first.reset.next = self.reset.val();
        self.ld_phase.reset.next = self.reset.val();
        self.c_phase_e.reset.next = self.reset.val();
        self.ld_pos_q.reset.next = self.reset.val();
        self.ld_levs_q.reset.next = self.reset.val();
        self.ld_rising_q.reset.next = self.reset.val();
        self.c_valid_q.reset.next = self.reset.val();
        self.c_phase_q.reset.next = self.reset.val();
        self.c_pos_q.reset.next = self.reset.val();
        self.c_levs_q.reset.next = self.reset.val();
        self.c_rising_q.reset.next = self.reset.val();
        self.q_valid.reset.next = self.reset.val();
        self.q_last.reset.next = self.reset.val();
        self.q_i.reset.next = self.reset.val();
        self.q_j.reset.next = self.reset.val();
        self.q_count.reset.next = self.reset.val();
        self.w_valid.reset.next = self.reset.val();
        self.w_last.reset.next = self.reset.val();
        self.w_i.reset.next = self.reset.val();
        self.w_j.reset.next = self.reset.val();
        self.w_count.reset.next = self.reset.val();
        self.w_n.reset.next = self.reset.val();
        self.w_m.reset.next = self.reset.val();
        self.w_wide.reset.next = self.reset.val();
        self.w_full.reset.next = self.reset.val();
        self.w_sof.reset.next = self.reset.val();
        self.w_lastx.reset.next = self.reset.val();
        self.out_valid.reset.next = self.reset.val();
        self.out_last.reset.next = self.reset.val();
        self.out_ref.reset.next = self.reset.val();
        self.out_other.reset.next = self.reset.val();
        self.out_x_ref.reset.next = self.reset.val();
        self.out_disp.reset.next = self.reset.val();
        self.out_count.reset.next = self.reset.val();
        self.out_n.reset.next = self.reset.val();
        self.out_m.reset.next = self.reset.val();
        self.out_wide.reset.next = self.reset.val();
        self.out_full.reset.next = self.reset.val();
        self.out_sof.reset.next = self.reset.val();

        // ---- Loader: a side takes records until its marker, while no
        // complete pair waits, and not on the clock after its marker (which
        // is then in the input register). A beat in the input register was
        // taken with neither its side's marker in nor a pair waiting, and
        // neither can have arrived since: it is written as it is.
        self.r_ready.next = !self.r_done.q.val() & !self.pend.q.val() & !(self.r_in.q_valid.val() & self.r_in.q_last.val());
        self.o_ready.next = !self.o_done.q.val() & !self.pend.q.val() & !(self.o_in.q_valid.val() & self.o_in.q_last.val());
        self.r_in.clock.next = self.clock.val();
        self.r_in.reset.next = self.reset.val();
        self.r_in.ready.next = self.r_ready.val();
        self.r_in.valid.next = self.r_valid.val();
        self.r_in.last.next = self.r_last.val();
        self.r_in.pos.next = self.r_pos.val();
        self.r_in.amp.next = self.r_amp.val();
        self.r_in.left0.next = self.r_left0.val();
        self.r_in.left1.next = self.r_left1.val();
        self.r_in.left2.next = self.r_left2.val();
        self.r_in.right0.next = self.r_right0.val();
        self.r_in.right1.next = self.r_right1.val();
        self.r_in.right2.next = self.r_right2.val();
        self.r_in.dt.next = self.r_dt.val();
        self.r_in.wide.next = self.r_wide.val();
        self.r_in.full.next = self.r_full.val();
        self.r_sof_in.d.next = self.r_sof.val();
        self.o_sof_in.d.next = self.o_sof.val();
        self.r_stamp_in.d.next = self.r_stamp.val();
        self.o_stamp_in.d.next = self.o_stamp.val();

        self.o_in.clock.next = self.clock.val();
        self.o_in.reset.next = self.reset.val();
        self.o_in.ready.next = self.o_ready.val();
        self.o_in.valid.next = self.o_valid.val();
        self.o_in.last.next = self.o_last.val();
        self.o_in.pos.next = self.o_pos.val();
        self.o_in.amp.next = self.o_amp.val();
        self.o_in.left0.next = self.o_left0.val();
        self.o_in.left1.next = self.o_left1.val();
        self.o_in.left2.next = self.o_left2.val();
        self.o_in.right0.next = self.o_right0.val();
        self.o_in.right1.next = self.o_right1.val();
        self.o_in.right2.next = self.o_right2.val();
        self.o_in.dt.next = self.o_dt.val();
        self.o_in.wide.next = self.o_wide.val();
        self.o_in.full.next = self.o_full.val();
        self.r_take.next = self.r_in.q_valid.val() & !self.r_in.q_last.val();
        self.o_take.next = self.o_in.q_valid.val() & !self.o_in.q_last.val();
        // The line's banks above the index: the records' bank, then the
        // position copies' second bit.
        self.line_base.next = 0.into();
        if self.lbank.q.val() {
            self.line_base.next = self.copy_bank_size.val();
        }
        if self.lpbank.q.val() {
            self.line_base.next = self.line_base.val() + self.copy_bank2_size.val();
        }
        self.r_addr.next = bit_cast::<COPY_ADDR_BITS, COUNT_BITS>(self.r_count.q.val()) + self.line_base.val();
        self.o_addr.next = bit_cast::<COPY_ADDR_BITS, COUNT_BITS>(self.o_count.q.val()) + self.line_base.val();
        // Records beyond `ROWS_PER_CELL·N` (`n_max`) are dropped (the line
        // is then full).
        self.r_mem.w_enable.next = self.r_take.val() & (self.r_count.q.val() < self.n_max.val());
        self.r_mem.w_addr.next = self.r_addr.val();
        self.r_mem.w_pos.next = self.r_in.q_pos.val();
        self.r_mem.w_amp.next = self.r_in.q_amp.val();
        self.r_mem.w_left0.next = self.r_in.q_left0.val();
        self.r_mem.w_left1.next = self.r_in.q_left1.val();
        self.r_mem.w_left2.next = self.r_in.q_left2.val();
        self.r_mem.w_right0.next = self.r_in.q_right0.val();
        self.r_mem.w_right1.next = self.r_in.q_right1.val();
        self.r_mem.w_right2.next = self.r_in.q_right2.val();
        self.o_mem.w_enable.next = self.o_take.val() & (self.o_count.q.val() < self.n_max.val());
        self.o_mem.w_addr.next = self.o_addr.val();
        self.o_mem.w_pos.next = self.o_in.q_pos.val();
        self.o_mem.w_amp.next = self.o_in.q_amp.val();
        self.o_mem.w_left0.next = self.o_in.q_left0.val();
        self.o_mem.w_left1.next = self.o_in.q_left1.val();
        self.o_mem.w_left2.next = self.o_in.q_left2.val();
        self.o_mem.w_right0.next = self.o_in.q_right0.val();
        self.o_mem.w_right1.next = self.o_in.q_right1.val();
        self.o_mem.w_right2.next = self.o_in.q_right2.val();
        if self.r_take.val() {
            if self.r_count.q.val() < self.n_max.val() {
                self.r_count.d.next = self.r_count.q.val() + 1;
                self.r_count_m1.d.next = self.r_count.q.val();
            } else {
                self.r_flags_full.d.next = true;
            }
        }
        if self.o_take.val() {
            if self.o_count.q.val() < self.n_max.val() {
                self.o_count.d.next = self.o_count.q.val() + 1;
            } else {
                self.o_flags_full.d.next = true;
            }
        }
        if self.r_in.q_valid.val() & self.r_in.q_last.val() {
            self.r_done.d.next = true;
            self.r_dt_reg.d.next = self.r_in.q_dt.val();
            self.r_flags_wide.d.next = self.r_in.q_wide.val();
            self.r_flags_full.d.next = self.r_flags_full.q.val() | self.r_in.q_full.val();
            self.r_sof_reg.d.next = self.r_sof_in.q.val();
            self.r_stamp_reg.d.next = self.r_stamp_in.q.val();
            self.r_lastx.d.next = bit_cast::<X_BITS, POS_BITS>(self.r_in.q_pos.val());
        }
        if self.o_in.q_valid.val() & self.o_in.q_last.val() {
            self.o_done.d.next = true;
            self.o_dt_reg.d.next = self.o_in.q_dt.val();
            self.o_flags_wide.d.next = self.o_in.q_wide.val();
            self.o_flags_full.d.next = self.o_flags_full.q.val() | self.o_in.q_full.val();
            self.o_sof_reg.d.next = self.o_sof_in.q.val();
            self.o_stamp_reg.d.next = self.o_stamp_in.q.val();
        }
        // Both markers in, one line starting a frame and the other not: the
        // other belongs to the frame before (its camera sent more lines than
        // this one's). Both starting a frame, their stamps more than
        // SKEW_TICKS apart (modulo 2^STAMP_BITS): the older has lost its
        // partner. The line is dropped, and its side loads its next line
        // into the same bank (see "Pairing").
        self.stamp_diff.next = self.r_stamp_reg.q.val() - self.o_stamp_reg.q.val();
        self.r_older.next = self.stamp_diff.val().get_bit(self.stamp_msb.val().index());
        self.far.next = self.r_sof_reg.q.val()
            & self.o_sof_reg.q.val()
            & (self.stamp_diff.val() > self.skew_ticks.val())
            & (self.stamp_diff.val() < self.skew_ticks_neg.val());
        self.mismatch.next = self.r_done.q.val() & self.o_done.q.val() & ((self.r_sof_reg.q.val() ^ self.o_sof_reg.q.val()) | self.far.val());
        self.r_drop.next = self.mismatch.val() & (!self.r_sof_reg.q.val() | (self.far.val() & self.r_older.val()));
        self.o_drop.next = self.mismatch.val() & (!self.o_sof_reg.q.val() | (self.far.val() & !self.r_older.val()));
        self.r_drop_q.d.next = self.r_drop.val();
        self.o_drop_q.d.next = self.o_drop.val();
        if self.o_drop.val() {
            self.o_done.d.next = false;
            self.o_count.d.next = 0.into();
            self.o_flags_full.d.next = false;
        }
        if self.r_drop.val() {
            self.r_done.d.next = false;
            self.r_count.d.next = 0.into();
            self.r_flags_full.d.next = false;
        }
        // Both markers in, both lines starting a frame or neither, and the
        // slot free: the pair waits for the engine.
        self.handoff.next = self.r_done.q.val() & self.o_done.q.val() & !self.pend.q.val() & !self.mismatch.val();
        // d_t,ref + d_t,other, each rounded down to MATCH_DT_FRAC_BITS and
        // saturated at MATCH_DT_BITS.
        self.r_dt_m.next = self.r_dt_reg.q.val().get_bits::<MATCH_DT_BITS>(self.dt_drop.val().index());
        if self.r_dt_reg.q.val().get_bits::<DT_SAT_BITS>(self.dt_sat.val().index()).any() {
            self.r_dt_m.next = self.dt_max.val();
        }
        self.o_dt_m.next = self.o_dt_reg.q.val().get_bits::<MATCH_DT_BITS>(self.dt_drop.val().index());
        if self.o_dt_reg.q.val().get_bits::<DT_SAT_BITS>(self.dt_sat.val().index()).any() {
            self.o_dt_m.next = self.dt_max.val();
        }
        self.dt_sum.next = bit_cast::<DT_SUM_BITS, MATCH_DT_BITS>(self.r_dt_m.val())
            + bit_cast::<DT_SUM_BITS, MATCH_DT_BITS>(self.o_dt_m.val());
        // The sweep of the line loading (`sweep_cycles`), as far as its
        // reference count n decides it, from the count of a clock ago: with
        // two phases (n ≤ 2N) `2n + [n > N]` and the tail; with four, the
        // wrap of its last phase `(k_last - 1)·(2N + 1)`, the later of its
        // last row's node and phase k_last - 1's last row's,
        // `max(4·c_last + 2N + 1, 4·(N - 1))`, and the tail. The other
        // side's part, `2m` or `4m`, is added at the handoff.
        // With four phases the last row n - 1 = c_last + N·k_last, k_last 2
        // or 3: `n_part` is `4·c_last + k_last·(2N + 1)` and the tail when
        // the last row's node is the later (`c_last` from `own_from` on),
        // `4·(N - 1) + (k_last - 1)·(2N + 1)` and the tail otherwise; with
        // two, `2n + [n > N]` and the tail. One adder each.
        self.n_kl.next = bit_cast::<PHASE_BITS, COUNT_BITS>(self.r_count_m1.q.val() >> self.cells_log2.val());
        self.n_c.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.r_count_m1.q.val()) & self.cells_mask.val();
        self.n_p4.d.next = self.r_count.q.val() > self.cells_2c.val();
        self.n_klast.d.next = self.n_kl.val();
        self.n_own.next = (bit_cast::<SWEEP_BITS, INDEX_BITS>(self.n_c.val()) << self.bit2.val()) + self.own_k2.val();
        self.n_before.next = self.before_k2.val();
        if self.n_kl.val().all() {
            self.n_own.next = (bit_cast::<SWEEP_BITS, INDEX_BITS>(self.n_c.val()) << self.bit2.val()) + self.own_k3.val();
            self.n_before.next = self.before_k3.val();
        }
        self.n_part.d.next = self.n_before.val();
        if self.n_c.val() >= self.own_from.val() {
            self.n_part.d.next = self.n_own.val();
        }
        if self.r_count.q.val() <= self.cells_2c.val() {
            self.n_part.d.next = (bit_cast::<SWEEP_BITS, COUNT_BITS>(self.r_count.q.val()) << self.bit1.val()) + self.sweep_tail.val();
            if self.r_count.q.val() > self.cells_c.val() {
                self.n_part.d.next =
                    (bit_cast::<SWEEP_BITS, COUNT_BITS>(self.r_count.q.val()) << self.bit1.val()) + self.sweep_tail1.val();
            }
        }
        self.m_part.next = bit_cast::<SWEEP_BITS, COUNT_BITS>(self.o_count.q.val()) << self.bit1.val();
        if self.n_p4.q.val() {
            self.m_part.next = bit_cast::<SWEEP_BITS, COUNT_BITS>(self.o_count.q.val()) << self.bit2.val();
        }
        if self.handoff.val() {
            self.pend_end_m1.d.next = self.n_part.q.val() + self.m_part.val();
            self.pend_fold.d.next = self.r_count.q.val() > self.cells_c.val();
            self.pend_p4.d.next = self.n_p4.q.val();
            self.pend_klast.d.next = self.n_klast.q.val();
            if !self.n_p4.q.val() {
                self.pend_klast.d.next = 0.into();
                if self.r_count.q.val() > self.cells_c.val() {
                    self.pend_klast.d.next = 1.into();
                }
            }
            self.pend.d.next = true;
            self.pend_bank.d.next = self.lbank.q.val();
            self.pend_pbank.d.next = self.lpbank.q.val();
            self.pend_n.d.next = self.r_count.q.val();
            self.pend_m.d.next = self.o_count.q.val();
            self.pend_dt_sum.d.next = self.dt_sum.val();
            self.pend_wide.d.next = self.r_flags_wide.q.val() | self.o_flags_wide.q.val();
            self.pend_full.d.next = self.r_flags_full.q.val() | self.o_flags_full.q.val();
            self.pend_sof.d.next = self.r_sof_reg.q.val();
            self.pend_lastx.d.next = self.r_lastx.q.val();
            self.lbank.d.next = !self.lbank.q.val();
            self.lpbank.d.next = self.lpbank.q.val() ^ self.lbank.q.val();
            self.r_done.d.next = false;
            self.o_done.d.next = false;
            self.r_count.d.next = 0.into();
            self.o_count.d.next = 0.into();
            self.r_flags_full.d.next = false;
            self.o_flags_full.d.next = false;
        }

        // ---- Engine.
        // The line's constants from the taken pair's d_t sum, every clock
        // (no load enable: the engine's `take` stays near the engine; the
        // constants reach the array a clock after `e_dt_sum`, two after the
        // take, long before the sweep's first column). below2 = ⌈2·gmax⌉ = ⌈(d_t,ref +
        // d_t,other) / 2^DT_FRAC_BITS⌉: the integer part, plus one when a
        // fraction bit is set.
        self.below2_reg.d.next = bit_cast::<DIST_BITS, DT_SUM_INT_BITS>(
            self.e_dt_sum.q.val().get_bits::<DT_SUM_INT_BITS>(self.dt_frac.val().index()),
        );
        if self.e_dt_sum.q.val().get_bits::<MATCH_DT_FRAC_BITS>(0).any() {
            self.below2_reg.d.next = bit_cast::<DIST_BITS, DT_SUM_INT_BITS>(
                self.e_dt_sum.q.val().get_bits::<DT_SUM_INT_BITS>(self.dt_frac.val().index()),
            ) + 1;
        }
        self.f1_reg.d.next = bit_cast::<GAIN_BITS, DT_SUM_BITS>(self.e_dt_sum.q.val());
        self.f3_reg.d.next = bit_cast::<GAIN_BITS, DT_SUM_BITS>(self.e_dt_sum.q.val())
            + bit_cast::<GAIN_BITS, DT_SUM_BITS>(self.e_dt_sum.q.val())
            + bit_cast::<GAIN_BITS, DT_SUM_BITS>(self.e_dt_sum.q.val());
        self.tb_busy.next = self.tb_begun.q.val() ^ self.tb_ended.q.val();
        // The sweep engine takes a waiting pair when it is idle, no swept line
        // waits for the traceback, and the traceback is not on the bank of the
        // choice memory the pair will write (lines alternate between two).
        self.take.next = (self.eng.q.val() == self.eng_idle.val())
            & self.pend.q.val()
            & !self.tq.q.val()
            & !(self.tb_busy.val() & (self.t_bank.q.val() == self.pend_bank.q.val()));
        if self.take.val() {
            self.pend.d.next = false;
            self.eng.d.next = self.eng_sweep.val();
            self.ebank.d.next = self.pend_bank.q.val();
            self.epbank.d.next = self.pend_pbank.q.val();
            self.en.d.next = self.pend_n.q.val();
            self.em.d.next = self.pend_m.q.val();
            self.sc.d.next = 0.into();
            // The sweep's last clock less one; see `sweep_cycles`.
            self.sweep_end_m1.d.next = self.pend_end_m1.q.val();
            self.e_fold.d.next = self.pend_fold.q.val();
            self.e_p4.d.next = self.pend_p4.q.val();
            self.e_klast.d.next = self.pend_klast.q.val();
        }
        // A clock after the take: the handoff refills `pend_*` at the
        // earliest on this clock's edge (`pend` fell on the take's).
        self.take_q.d.next = self.take.val();
        if self.take_q.q.val() {
            self.e_dt_sum.d.next = self.pend_dt_sum.q.val();
            self.e_wide.d.next = self.pend_wide.q.val();
            self.e_full.d.next = self.pend_full.q.val();
            self.e_sof.d.next = self.pend_sof.q.val();
            self.e_lastx.d.next = self.pend_lastx.q.val();
        }
        // Sweep: clock sc reads reference sc, which the next clock
        // broadcasts, and column j of phase k where sc = p·j + (2N + 1)·k
        // (p = 2 with two phases, 4 with four): k = sc mod p, j = ⌊sc/p⌋ -
        // k·2N/p, when the line has that phase and column; the next clock
        // feeds it to the array.
        self.sc_idx.next = bit_cast::<INDEX_BITS, SWEEP_BITS>(self.sc.q.val());
        self.sc_phase.next = bit_cast::<PHASE_BITS, 1>(self.sc.q.val().get_bits::<1>(self.bit0.val().index()));
        // ⌊sc/p⌋ for either p; the line's m at the sweep's width.
        self.base2.next = self.sc.q.val() >> self.bit1.val();
        self.base4.next = self.sc.q.val() >> self.bit2.val();
        self.em_w.next = bit_cast::<SWEEP_BITS, COUNT_BITS>(self.em.q.val());
        self.sc_base.next = self.base2.val();
        self.sc_off.next = bit_cast::<SWEEP_BITS, PHASE_BITS>(self.sc_phase.val()) << self.cells_log2.val();
        if self.e_p4.q.val() {
            self.sc_phase.next = self.sc.q.val().get_bits::<PHASE_BITS>(self.bit0.val().index());
            self.sc_base.next = self.base4.val();
            self.sc_off.next = (bit_cast::<SWEEP_BITS, PHASE_BITS>(self.sc_phase.val()) << self.cells_log2.val()) >> self.bit1.val();
        }
        self.sc_j.next = self.sc_base.val() - self.sc_off.val();
        // j < m as ⌊sc/p⌋ < k·2N/p + m, against the taken line's sums, one
        // per phase, registered (phase k > 0's first column comes at sc ≥
        // 2N + 1, long after they are; phase 0's bound is m itself): no
        // subtraction before the comparison.
        self.lim1.d.next = self.off1.val() + self.em_w.val();
        self.lim2.d.next = self.off2.val() + self.em_w.val();
        self.lim3.d.next = self.off3.val() + self.em_w.val();
        if self.e_p4.q.val() {
            self.lim1.d.next = self.off1_p4.val() + self.em_w.val();
            self.lim2.d.next = self.off2_p4.val() + self.em_w.val();
            self.lim3.d.next = self.off3_p4.val() + self.em_w.val();
        }
        // `sc_off ≤ ⌊sc/p⌋ < lim_k` tested for each phase k and each p on
        // its own, from registers and constants (`sc_off` is k·N with two
        // phases, k·N/2 with four; phase 0's lower bound is 0), and picked
        // by the mode and the phase after the comparisons: no multiplexer
        // before their carry chains into `c_valid_d`.
        self.in2_0.next = self.base2.val() < self.em_w.val();
        self.in2_1.next = (self.base2.val() >= self.off1.val()) & (self.base2.val() < self.lim1.q.val());
        self.in4_0.next = self.base4.val() < self.em_w.val();
        self.in4_1.next = (self.base4.val() >= self.off1_p4.val()) & (self.base4.val() < self.lim1.q.val());
        self.in4_2.next = (self.base4.val() >= self.off2_p4.val()) & (self.base4.val() < self.lim2.q.val());
        self.in4_3.next = (self.base4.val() >= self.off3_p4.val()) & (self.base4.val() < self.lim3.q.val());
        self.in_window.next = self.in2_0.val();
        if self.sc.q.val().get_bit(self.bit0.val().index()) {
            self.in_window.next = self.in2_1.val();
        }
        if self.e_p4.q.val() {
            self.in_window.next = self.in4_0.val();
            if self.sc.q.val().get_bit(self.bit0.val().index()) {
                self.in_window.next = self.in4_1.val();
            }
            if self.sc.q.val().get_bit(self.bit1.val().index()) {
                self.in_window.next = self.in4_2.val();
                if self.sc.q.val().get_bit(self.bit0.val().index()) {
                    self.in_window.next = self.in4_3.val();
                }
            }
        }
        self.col_ok.next = self.in_window.val() & (self.sc_phase.val() <= self.e_klast.q.val());
        self.col_j.next = bit_cast::<INDEX_BITS, SWEEP_BITS>(self.sc_j.val());
        self.rd_bank_base.next = 0.into();
        if self.ebank.q.val() {
            self.rd_bank_base.next = self.bank_size.val();
        }
        self.r_rd.next = bit_cast::<DIAG_BITS, INDEX_BITS>(self.sc_idx.val()) + self.rd_bank_base.val();
        self.o_rd.next = bit_cast::<DIAG_BITS, INDEX_BITS>(self.col_j.val()) + self.rd_bank_base.val();
        self.ld_valid_d.d.next = false;
        self.c_valid_d.d.next = false;
        self.ld_index_d.d.next = self.sc_idx.val();
        self.c_phase_d.d.next = self.sc_phase.val();
        // The choices in the array's word registers now are those of the
        // nodes whose columns were read ENGINE_LAG clocks ago (with four
        // phases, plus the cells' skews): at tw = sc - ENGINE_LAG, with two
        // phases anti-diagonal ⌊tw/2⌋ of phase tw mod 2 (tw = 2s + k), with
        // four ⌊tw/4⌋ + k·N/2 of phase k = tw mod 4 (tw = 4s - (2N - 1)·k).
        // (Computed a clock ahead, from the sweep clock's next value, and
        // registered: the choice memory's write address comes from
        // registers. The first clock of a sweep writes nothing.)
        self.tw.next = self.sc.q.val() - self.engine_lag_m1.val();
        self.tw_phase.next = bit_cast::<PHASE_BITS, 1>(self.tw.val().get_bits::<1>(self.bit0.val().index()));
        self.tw_diag.next = self.tw.val() >> self.bit1.val();
        if self.e_p4.q.val() {
            self.tw_phase.next = self.tw.val().get_bits::<PHASE_BITS>(self.bit0.val().index());
            self.tw_diag.next = (self.tw.val() >> self.bit2.val())
                + ((bit_cast::<SWEEP_BITS, PHASE_BITS>(self.tw_phase.val()) << self.cells_log2.val()) >> self.bit1.val());
        }
        self.array.cw_en.next = (self.eng.q.val() == self.eng_sweep.val()) & (self.sc.q.val() >= self.engine_lag.val());
        self.cw_diag_q.d.next = bit_cast::<DIAG_BITS, SWEEP_BITS>(self.tw_diag.val());
        self.cw_phase_q.d.next = self.tw_phase.val();
        self.array.cw_diag.next = self.cw_diag_q.q.val();
        self.array.cw_phase.next = self.cw_phase_q.q.val();
        // The sweep's last clock is known a clock ahead (a register: the
        // traceback's start goes to its walk registers, far from the engine).
        // The swept line's traceback starts then if the traceback is free,
        // or waits in `tq` until it is; the next sweep goes on meanwhile.
        self.tb_from_q.next = self.tq.q.val() & !self.tb_busy.val();
        self.tb_start.next = self.tb_from_q.val() | (self.sweep_done.q.val() & !self.tb_busy.val() & !self.tq.q.val());
        self.traceback.start.next = self.tb_start.val();
        // (`en`, `em` hold from the clock after a take until the next take,
        // and `sweep_done` is high two clocks after the take at the
        // earliest: the `e_*` walk start is theirs when the sweep ends.)
        self.e_wi0.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.en.q.val() - 1);
        self.e_wj0.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.em.q.val() - 1);
        self.e_diag0.d.next = bit_cast::<DIAG_BITS, COUNT_BITS>(self.en.q.val())
            + bit_cast::<DIAG_BITS, COUNT_BITS>(self.em.q.val())
            - self.diag_two.val();
        self.e_empty.d.next = !self.en.q.val().any() | !self.em.q.val().any();
        self.traceback.wi0.next = self.e_wi0.q.val();
        self.traceback.wj0.next = self.e_wj0.q.val();
        self.traceback.diag0.next = self.e_diag0.q.val();
        self.traceback.empty.next = self.e_empty.q.val();
        if self.tb_from_q.val() {
            self.traceback.wi0.next = self.tq_wi0.q.val();
            self.traceback.wj0.next = self.tq_wj0.q.val();
            self.traceback.diag0.next = self.tq_diag0.q.val();
            self.traceback.empty.next = self.tq_empty.q.val();
        }
        if self.tb_start.val() {
            self.tb_begun.d.next = !self.tb_begun.q.val();
            self.t_n.d.next = self.en.q.val();
            self.t_m.d.next = self.em.q.val();
            self.t_bank.d.next = self.ebank.q.val();
            self.t_pbank.d.next = self.epbank.q.val();
            self.t_wide.d.next = self.e_wide.q.val();
            self.t_full.d.next = self.e_full.q.val();
            self.t_sof.d.next = self.e_sof.q.val();
            self.t_lastx.d.next = self.e_lastx.q.val();
            if self.tb_from_q.val() {
                self.tq.d.next = false;
                self.t_n.d.next = self.tq_n.q.val();
                self.t_m.d.next = self.tq_m.q.val();
                self.t_bank.d.next = self.tq_bank.q.val();
                self.t_pbank.d.next = self.tq_pbank.q.val();
                self.t_wide.d.next = self.tq_wide.q.val();
                self.t_full.d.next = self.tq_full.q.val();
                self.t_sof.d.next = self.tq_sof.q.val();
                self.t_lastx.d.next = self.tq_lastx.q.val();
            }
        }
        if self.traceback.out_last.val() {
            self.tb_ended.d.next = !self.tb_ended.q.val();
        }
        if self.sweep_done.q.val() & (self.tb_busy.val() | self.tq.q.val()) {
            self.tq.d.next = true;
            self.tq_n.d.next = self.en.q.val();
            self.tq_m.d.next = self.em.q.val();
            self.tq_wi0.d.next = self.e_wi0.q.val();
            self.tq_wj0.d.next = self.e_wj0.q.val();
            self.tq_diag0.d.next = self.e_diag0.q.val();
            self.tq_empty.d.next = self.e_empty.q.val();
            self.tq_bank.d.next = self.ebank.q.val();
            self.tq_pbank.d.next = self.epbank.q.val();
            self.tq_wide.d.next = self.e_wide.q.val();
            self.tq_full.d.next = self.e_full.q.val();
            self.tq_sof.d.next = self.e_sof.q.val();
            self.tq_lastx.d.next = self.e_lastx.q.val();
        }
        self.sweep_done.d.next = false;
        if self.eng.q.val() == self.eng_sweep.val() {
            self.sc.d.next = self.sc.q.val() + 1;
            self.ld_valid_d.d.next = self.sc.q.val() < bit_cast::<SWEEP_BITS, COUNT_BITS>(self.en.q.val());
            self.c_valid_d.d.next = self.col_ok.val();
            self.sweep_done.d.next = self.sc.q.val() == self.sweep_end_m1.q.val();
            if self.sweep_done.q.val() {
                self.eng.d.next = self.eng_idle.val();
            }
        }
        // The traceback's pairs read their positions in the copies.
        self.tb_base.next = 0.into();
        if self.t_bank.q.val() {
            self.tb_base.next = self.copy_bank_size.val();
        }
        if self.t_pbank.q.val() {
            self.tb_base.next = self.tb_base.val() + self.copy_bank2_size.val();
        }
        self.p_addr_r.d.next = bit_cast::<COPY_ADDR_BITS, INDEX_BITS>(self.traceback.out_i.val()) + self.tb_base.val();
        self.p_addr_o.d.next = bit_cast::<COPY_ADDR_BITS, INDEX_BITS>(self.traceback.out_j.val()) + self.tb_base.val();
        self.r_mem.p_addr.next = self.p_addr_r.q.val();
        self.o_mem.p_addr.next = self.p_addr_o.q.val();

        // (Registered, so that the route from the engine and the traceback
        // to the record memories has a clock of its own.)
        self.r_addr_q.d.next = self.r_rd.val();
        self.o_addr_q.d.next = self.o_rd.val();
        self.r_mem.r_addr.next = self.r_addr_q.q.val();
        self.o_mem.r_addr.next = self.o_addr_q.q.val();

        // ---- The array.
        // Load tokens: high the clock before references 0, N, 2N and 3N are
        // on the broadcast, with their phase (the array moves them on to the
        // cells).
        self.ld_valid_e.d.next = self.ld_valid_d.q.val();
        self.ld_index_e.d.next = self.ld_index_d.q.val();
        self.ld_first.d.next = self.ld_valid_e.q.val() & !(self.ld_index_e.q.val() & self.cells_mask.val()).any();
        self.ld_phase.d.next =
            bit_cast::<PHASE_BITS, INDEX_BITS>(self.ld_index_e.q.val() >> self.cells_log2.val());
        // The six levels side by side (wiring).
        self.ld_levs.next = bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.r_mem.lev0.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.r_mem.lev1.val()) << self.lev_at1.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.r_mem.lev2.val()) << self.lev_at2.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.r_mem.lev3.val()) << self.lev_at3.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.r_mem.lev4.val()) << self.lev_at4.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.r_mem.lev5.val()) << self.lev_at5.val());
        self.c_levs.next = bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.o_mem.lev0.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.o_mem.lev1.val()) << self.lev_at1.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.o_mem.lev2.val()) << self.lev_at2.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.o_mem.lev3.val()) << self.lev_at3.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.o_mem.lev4.val()) << self.lev_at4.val())
            | (bit_cast::<LEVELS_BITS, LEVEL_BITS>(self.o_mem.lev5.val()) << self.lev_at5.val());
        self.ld_pos_q.d.next = self.r_mem.pos.val();
        self.ld_levs_q.d.next = self.ld_levs.val();
        self.ld_rising_q.d.next = self.r_mem.rising.val();
        self.c_valid_e.d.next = self.c_valid_d.q.val();
        self.c_phase_e.d.next = self.c_phase_d.q.val();
        self.c_valid_e2.d.next = self.c_valid_e.q.val();
        self.c_phase_e2.d.next = self.c_phase_e.q.val();
        self.c_valid_q.d.next = self.c_valid_e2.q.val();
        self.c_phase_q.d.next = self.c_phase_e2.q.val();
        // The column's position moved by dispmin, `X_j + dispmin`, so that
        // the cells' test of `0 < X_i - X_j' < dispmax - dispmin` is eq. 6's
        // `dispmin < X_i - X_j < dispmax` with no adder in the cell. A sum
        // past the format saturates at its largest value, which no `X_i`
        // exceeds: `X_i - X_j' ≤ 0` either way, no node.
        self.c_pos_min.next = bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.o_mem.pos.val())
            + bit_cast::<{ POS_BITS + 1 }, DISPMAX_BITS>(self.dispmin.val());
        self.c_pos_q.d.next = bit_cast::<POS_BITS, { POS_BITS + 1 }>(self.c_pos_min.val());
        if self.c_pos_min.val().get_bit(self.pos_carry.val().index()) {
            self.c_pos_q.d.next = self.pos_max.val();
        }
        self.c_levs_q.d.next = self.c_levs.val();
        self.c_rising_q.d.next = self.o_mem.rising.val();
        self.array.ld_first.next = self.ld_first.q.val();
        self.array.ld_phase.next = self.ld_phase.q.val();
        self.array.ld_pos.next = self.ld_pos_q.q.val();
        self.array.ld_levs.next = self.ld_levs_q.q.val();
        self.array.ld_rising.next = self.ld_rising_q.q.val();
        self.array.c_valid.next = self.c_valid_q.q.val();
        self.array.c_phase.next = self.c_phase_q.q.val();
        self.array.c_pos.next = self.c_pos_q.q.val();
        self.array.c_levs.next = self.c_levs_q.q.val();
        self.array.c_rising.next = self.c_rising_q.q.val();
        // The width of eq. 6's area less one LSB, `dispmax - dispmin - 1`
        // (0 for an empty area: no node then).
        self.band.next = bit_cast::<{ POS_BITS + 1 }, DISPMAX_BITS>(self.dispmax.val())
            - bit_cast::<{ POS_BITS + 1 }, DISPMAX_BITS>(self.dispmin.val());
        self.dm1_reg.d.next = 0.into();
        if self.dispmax.val() > self.dispmin.val() {
            self.dm1_reg.d.next = self.band.val() - 1;
        }
        self.array.dispmax_m1.next = self.dm1_reg.q.val();
        self.array.below2.next = self.below2_reg.q.val();
        self.array.f1.next = self.f1_reg.q.val();
        self.array.f3.next = self.f3_reg.q.val();
        self.array.p4.next = self.e_p4.q.val();
        self.array.same_polarity.next = self.relative.val();
        self.array.one_sided.next = self.one_sided.val();
        self.array.tb_diag.next = self.traceback.tb_diag.val();
        self.array.tb_bank.next = self.t_bank.q.val();
        self.array.cw_bank.next = self.ebank.q.val();
        self.array.tb_group.next = self.traceback.tb_group.val();

        // ---- Traceback.
        self.traceback.tb_word.next = self.array.tb_word.val();
        self.traceback.tb_word_prev.next = self.array.tb_word_prev.val();

        // ---- Output: positions read and registered, then X_i - X_j
        // registered.
        self.q_valid.d.next = self.traceback.out_valid.val();
        self.q_last.d.next = self.traceback.out_last.val();
        self.q_i.d.next = self.traceback.out_i.val();
        self.q_j.d.next = self.traceback.out_j.val();
        self.q_count.d.next = self.traceback.out_count.val();
        self.q2_valid.d.next = self.q_valid.q.val();
        self.q2_last.d.next = self.q_last.q.val();
        self.q2_i.d.next = self.q_i.q.val();
        self.q2_j.d.next = self.q_j.q.val();
        self.q2_count.d.next = self.q_count.q.val();
        self.w_valid.d.next = self.q2_valid.q.val();
        self.w_last.d.next = self.q2_last.q.val();
        if self.q2_valid.q.val() {
            self.w_i.d.next = self.q2_i.q.val();
            self.w_j.d.next = self.q2_j.q.val();
        }
        if self.q2_last.q.val() {
            self.w_count.d.next = self.q2_count.q.val();
        }
        // The line's own counts and flags, kept from the clock after the
        // traceback's marker (the engine may take the next pair on the
        // clock after that).
        if self.q_last.q.val() {
            self.w_n.d.next = self.t_n.q.val();
            self.w_m.d.next = self.t_m.q.val();
            self.w_wide.d.next = self.t_wide.q.val();
            self.w_full.d.next = self.t_full.q.val();
            self.w_sof.d.next = self.t_sof.q.val();
            self.w_lastx.d.next = self.t_lastx.q.val();
        }
        self.out_valid.d.next = self.w_valid.q.val() | self.w_last.q.val();
        self.out_last.d.next = self.w_last.q.val();
        if self.w_valid.q.val() {
            self.out_ref.d.next = self.w_i.q.val();
            self.out_other.d.next = self.w_j.q.val();
            self.out_x_ref.d.next = self.r_mem.p_pos.val();
            self.out_disp.d.next = self.r_mem.p_pos.val() - self.o_mem.p_pos.val();
        }
        if self.w_last.q.val() {
            self.out_count.d.next = self.w_count.q.val();
            self.out_n.d.next = self.w_n.q.val();
            self.out_m.d.next = self.w_m.q.val();
            self.out_wide.d.next = self.w_wide.q.val();
            self.out_full.d.next = self.w_full.q.val();
            self.out_sof.d.next = self.w_sof.q.val();
            self.out_x_ref.d.next = bit_cast::<POS_BITS, X_BITS>(self.w_lastx.q.val());
        }
        self.m_valid.next = self.out_valid.q.val();
        self.m_last.next = self.out_last.q.val();
        self.m_ref.next = self.out_ref.q.val();
        self.m_other.next = self.out_other.q.val();
        self.m_x_ref.next = self.out_x_ref.q.val();
        self.m_disp.next = self.out_disp.q.val();
        self.m_count.next = self.out_count.q.val();
        self.m_n.next = self.out_n.q.val();
        self.m_m.next = self.out_m.q.val();
        self.m_wide.next = self.out_wide.q.val();
        self.m_full.next = self.out_full.q.val();
        self.m_sof.next = self.out_sof.q.val();
        self.r_unpaired.next = self.r_drop_q.q.val();
        self.o_unpaired.next = self.o_drop_q.q.val();
    }
}
