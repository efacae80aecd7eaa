//! One processing element of the systolic matcher: the nodes `(i, j)` of the
//! matching graph for its [`ROWS_PER_CELL`] (four) reference declivities,
//! `i = index + k·cells` for the phases `k = 0 .. ROWS_PER_CELL`, and each
//! other-view declivity `j` that
//! streams past (paper §III–IV). The column stream passes the array once per
//! phase, the passes interleaved clock by clock, so the cell takes one node
//! a clock, of whichever row the column in its slot belongs to: one datapath
//! serves four rows. A line of at most `2·cells` reference declivities uses
//! two phases, and each row's recurrence has two clocks per node; a longer
//! line uses up to four, and each row has four clocks per node (`p4`).
//!
//! Per node the cell computes, in fixed point:
//! - eq. 6, the search area: `0 < X_i - X_j' < dispmax - dispmin`, where
//!   the column's position comes moved by the lower bound, `X_j' = X_j +
//!   dispmin` (the matcher's engine adds it): `dispmin < X_i - X_j <
//!   dispmax` (left reference);
//! - eq. 4–5, the doubled photometric distances `2·lpd`, `2·rpd` over the
//!   three neighbour levels on each side, in the [`LEVEL_BITS`] format (the
//!   loader has made the levels offset-compensated or not, per the gain
//!   rule);
//! - eq. 7–8, `gain = f(gmax) - (lpd + rpd)`, with `f = 3·gmax` when both
//!   distances are below `gmax`, `gmax` when one is (and, with `one_sided`,
//!   only the similar side's distance subtracted), rejection when neither is
//!   or, with `same_polarity`, when the polarities differ. Gains are integers
//!   in units of `2^-GAIN_FRAC_BITS` grey levels, so they equal golden's f64
//!   gains for the same `d_t` values exactly;
//! - eq. 9 as the prefix-max recurrence of `golden::dp`:
//!   `G = g + P(i-1, j-1)`, `P(i, j) = max(0, G, P(i-1, j), P(i, j-1))`, with
//!   golden's tie order (start, node, up, left; a later candidate wins only
//!   when strictly greater) as a chain of strict comparisons, and its 2-bit
//!   choice, which leaves on `choice_word` for the array's choice memory.
//!
//! ## Ports
//! - `ld_en`, `ld_phase`, `ld_pos`, `ld_levs`, `ld_rising`: the
//!   reference-declivity broadcast (position `X_i`, the six levels side by
//!   side ([`LEVELS_BITS`]), polarity), taken as the cell's row of phase
//!   `ld_phase` when `ld_en` (the array's load token) is high: no index
//!   comparison in the cell.
//! - `c_valid`, `c_phase`, `c_pos`, `c_levs`, `c_rising`: the column in this
//!   cell's slot of the array's column pipeline (registers of the
//!   [`crate::matcher::systolic_matcher::SystolicMatcher`], which moves a column on
//!   by two slots, one cell, every two clocks) and the phase it passes in;
//!   `c_phase_next`: the phase of the column that will be in the slot next
//!   clock (the cell selects its reference one clock ahead).
//! - `up_p`: the `P` register of the cell above (cell `index - 1`; for cell
//!   0, the last cell's, one clock later, and read as 0 in phase 0, the
//!   table's first rows); out `p`, this cell's.
//! - Per line: `dispmax_m1` (the area's width `dispmax - dispmin` less one
//!   LSB; 0 for an empty area), `below2` (`⌈2·gmax⌉`, compared with doubled
//!   distances), `f1` (`gmax`) and `f3` (`3·gmax`) in gain units, `p4` (the
//!   line's rows have four clocks per node); per design: `same_polarity`,
//!   `one_sided`.
//! - Out `choice_word`: the choice in its two bits of the array's
//!   [`CHOICE_WORD_BITS`]-bit memory word, zero elsewhere; with `p4`,
//!   [`skew`]`(index)` clocks later than without.
//!
//! ## Timing
//! A node whose column is in the cell's slot at clock `t` has its `P` in
//! `p` from clock `t +` [`CELL_DEPTH`], and its choice on `choice_word`
//! then (two phases) or `2·index` clocks later (`p4`): stage A
//! (`X_i - X_j`, level differences), B (distances, search area), C (tests
//! of eq. 7), S (the sum of the distances kept), D
//! (the gain), E (`G = g + P(i-1, j-1)` and, beside it, whether `G > 0`), F (start or node), G (up), H (left).
//! The node below, `(i+1, j)`, is two clocks behind in the next cell, so its
//! stage G reads this `P` on `up_p` as soon as it is out; the node to the
//! right, `(i, j+1)`, is two (four with `p4`) clocks behind in this cell,
//! and its stage H reads `P(i, j)` one (three) clocks after it was out (a
//! delay register); the diagonal node `(i+1, j+1)` is in stage E when
//! `(i+1, j)` is in stage G (two phases) or two clocks before that (`p4`),
//! so it reads `P(i, j)` on `up_p`, or on `up_p` two clocks late. A bubble
//! (`c_valid` low) leaves `P = 0` behind it, which is `P(i, -1)` and
//! `P(i-1, -1)` for the column that follows: a line's first column needs no
//! flag. The other stages load only on a valid column. The registers
//! start from their Verilog initial values (zero, so `P = 0`); `reset` (synchronous, active high) returns them there.
//!
//! Why the skew: a column moves a cell every two clocks, so with four phases
//! node `(i, j)` of cell `c` (row `i = c + k·cells`) is reached at
//! `2c + 4j + (2·cells + 1)·k`, which is `4·(i + j) - (2·cells - 1)·k - 2c`:
//! cell `c` is `2c` clocks ahead of cell 0 on the same anti-diagonal, and
//! waits that long to write with it.

use crate::primitives::lut_ram::LutRam;
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

// `-g - P` (stage E's test of `G > 0`) lies between `-2^(GAIN_BITS-1) -
// 2^PATH_BITS` and `2^GAIN_BITS`: inside `SCORE_BITS + 1` bits.
const _: () = assert!(GAIN_BITS <= SCORE_BITS);

/// Clocks from a column in a cell's slot to its node's `P` on `p` and its
/// choice on `choice_word` (stages A–H, S between C and D), without the
/// four-phase skew.
pub(crate) const CELL_DEPTH: usize = 9;

/// The 2-bit choices, as `golden::dp::Choice` numbers them.
pub(crate) const CHOICE_START: u64 = 0;
/// `P = G`: the node is taken.
pub(crate) const CHOICE_NODE: u64 = 1;
/// `P = P(i-1, j)`.
pub(crate) const CHOICE_UP: u64 = 2;
/// `P = P(i, j-1)`.
pub(crate) const CHOICE_LEFT: u64 = 3;

/// Clocks cell `index` holds its choices back in a four-phase line, so that
/// the whole array's choices of one anti-diagonal and phase come out on one
/// clock: `2·index`.
const fn skew(index: usize) -> usize {
    2 * index
}

#[derive(LogicBlock)]
pub struct GainCell {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub ld_en: Signal<In, Bit>,
    pub ld_phase: Signal<In, Bits<PHASE_BITS>>,
    pub ld_pos: Signal<In, Bits<POS_BITS>>,
    pub ld_levs: Signal<In, Bits<LEVELS_BITS>>,
    pub ld_rising: Signal<In, Bit>,
    pub c_valid: Signal<In, Bit>,
    pub c_phase: Signal<In, Bits<PHASE_BITS>>,
    pub c_phase_next: Signal<In, Bits<PHASE_BITS>>,
    pub c_pos: Signal<In, Bits<POS_BITS>>,
    pub c_levs: Signal<In, Bits<LEVELS_BITS>>,
    pub c_rising: Signal<In, Bit>,
    pub up_p: Signal<In, Bits<PATH_BITS>>,
    pub p: Signal<Out, Bits<PATH_BITS>>,
    pub dispmax_m1: Signal<In, Bits<{ POS_BITS + 1 }>>,
    pub below2: Signal<In, Bits<DIST_BITS>>,
    pub f1: Signal<In, Bits<GAIN_BITS>>,
    pub f3: Signal<In, Bits<GAIN_BITS>>,
    pub p4: Signal<In, Bit>,
    pub same_polarity: Signal<In, Bit>,
    pub one_sided: Signal<In, Bit>,
    pub choice_word: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    top_cell: Constant<Bit>,
    skewed: Constant<Bit>,
    skew_sel: Constant<Bits<SKEW_WORDS>>,
    skew_bit: Constant<Bits<8>>,
    zero_word: Constant<Bits<CHOICE_WORD_BITS>>,
    bit_lo: Constant<Bits<8>>,
    bit_hi: Constant<Bits<8>>,
    bit0: Constant<Bits<8>>,
    bit1: Constant<Bits<8>>,
    lev_at1: Constant<Bits<8>>,
    lev_at2: Constant<Bits<8>>,
    lev_at3: Constant<Bits<8>>,
    lev_at4: Constant<Bits<8>>,
    lev_at5: Constant<Bits<8>>,
    skew_top: Constant<Bits<8>>,
    rise_bit: Constant<Bits<8>>,
    two: Constant<Bits<8>>,
    gain_unit_per_dist: Constant<Bits<16>>,
    gain_msb: Constant<Bits<8>>,
    level_sign: Constant<Bits<8>>,
    sign_fill: Constant<Bits<SCORE_BITS>>,
    neg_score_msb: Constant<Bits<8>>,
    path_sign: Constant<Bits<8>>,
    choice_start: Constant<Bits<2>>,
    choice_node: Constant<Bits<2>>,
    choice_up: Constant<Bits<2>>,
    choice_left: Constant<Bits<2>>,
    // The reference declivities of rows `index + k·cells` at address k
    // (phase k): the position with the polarity above it, and the levels.
    rows_pos: LutRam<{ POS_BITS + 1 }>,
    rows_levs: LutRam<LEVELS_BITS>,
    // The reference of the column arriving next clock (registered: the
    // read address, the column's phase, is a register of the array).
    sel_pos: ResetDff<Bits<POS_BITS>>,
    sel_levs: ResetDff<Bits<LEVELS_BITS>>,
    sel_rising: ResetDff<Bit>,
    // Stage A: search area, polarity, level differences.
    a_valid: ResetDff<Bit>,
    a_ph0: ResetDff<Bit>,
    a_diff: ResetDff<Bits<{ POS_BITS + 1 }>>,
    a_same: ResetDff<Bit>,
    a_e0: ResetDff<Bits<LEVEL_BITS>>,
    a_e1: ResetDff<Bits<LEVEL_BITS>>,
    a_e2: ResetDff<Bits<LEVEL_BITS>>,
    a_e3: ResetDff<Bits<LEVEL_BITS>>,
    a_e4: ResetDff<Bits<LEVEL_BITS>>,
    a_e5: ResetDff<Bits<LEVEL_BITS>>,
    a_s0: ResetDff<Bits<1>>,
    a_s1: ResetDff<Bits<1>>,
    a_s3: ResetDff<Bits<1>>,
    a_s4: ResetDff<Bits<1>>,
    // Stage B: doubled distances.
    b_valid: ResetDff<Bit>,
    b_ph0: ResetDff<Bit>,
    b_ok: ResetDff<Bit>,
    b_l2: ResetDff<Bits<DIST_BITS>>,
    b_r2: ResetDff<Bits<DIST_BITS>>,
    // Stage C: eq. 7's tests.
    c2_valid: ResetDff<Bit>,
    c2_ph0: ResetDff<Bit>,
    c2_node: ResetDff<Bit>,
    c2_both: ResetDff<Bit>,
    c2_keep_l: ResetDff<Bit>,
    c2_keep_r: ResetDff<Bit>,
    c2_l: ResetDff<Bits<DIST_BITS>>,
    c2_r: ResetDff<Bits<DIST_BITS>>,
    // Stage S: the sum of the distances the gain subtracts.
    s_valid: ResetDff<Bit>,
    s_ph0: ResetDff<Bit>,
    s_node: ResetDff<Bit>,
    s_both: ResetDff<Bit>,
    s_sum: ResetDff<Bits<DIST_SUM_BITS>>,
    // Stage D: the local gain.
    d_valid: ResetDff<Bit>,
    d_ph0: ResetDff<Bit>,
    d_node: ResetDff<Bit>,
    d_g: ResetDff<Bits<GAIN_BITS>>,
    // `-g`, one bit wider than a score (so that `-g - P` cannot overflow).
    d_neg_g: ResetDff<Bits<{ SCORE_BITS + 1 }>>,
    // Stage E: G = g + P(i-1, j-1).
    e_valid: ResetDff<Bit>,
    e_ph0: ResetDff<Bit>,
    e_node: ResetDff<Bit>,
    e_score: ResetDff<Bits<SCORE_BITS>>,
    // `G > 0`, decided beside the sum (the sign of `-g - P(i-1, j-1)`).
    e_pos: ResetDff<Bit>,
    // Stage F: start or node.
    f_valid: ResetDff<Bit>,
    f_ph0: ResetDff<Bit>,
    f_node: ResetDff<Bit>,
    f_best: ResetDff<Bits<PATH_BITS>>,
    // Stage G: the node above.
    g_valid: ResetDff<Bit>,
    g_best: ResetDff<Bits<PATH_BITS>>,
    g_node: ResetDff<Bit>,
    g_up: ResetDff<Bit>,
    // Stage H: the node to the left; P and the choice.
    p_reg: ResetDff<Bits<PATH_BITS>>,
    p_d1: ResetDff<Bits<PATH_BITS>>,
    p_d2: ResetDff<Bits<PATH_BITS>>,
    p_d3: ResetDff<Bits<PATH_BITS>>,
    up_d1: ResetDff<Bits<PATH_BITS>>,
    up_d2: ResetDff<Bits<PATH_BITS>>,
    choice_reg: ResetDff<Bits<2>>,
    // The four-phase skew: the choices of the last `2·index` clocks, the
    // newest in the low bits of word 0.
    skew_q: [ResetDff<Bits<CHOICE_WORD_BITS>>; SKEW_WORDS],
    // Combinational.
    diff_pos: Signal<Local, Bits<{ POS_BITS + 1 }>>,
    dr0: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dr1: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dr2: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dc2: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dr3: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dr4: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dr5: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    dc5: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    rl0: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    rl1: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    rl2: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    rl3: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    rl4: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    rl5: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    cl0: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    cl1: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    cl2: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    cl3: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    cl4: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    cl5: Signal<Local, Bits<{ LEVEL_BITS + 1 }>>,
    l_x: Signal<Local, Bits<DIST_BITS>>,
    l_y: Signal<Local, Bits<DIST_BITS>>,
    r_x: Signal<Local, Bits<DIST_BITS>>,
    r_y: Signal<Local, Bits<DIST_BITS>>,
    l_sum: Signal<Local, Bits<DIST_BITS>>,
    r_sum: Signal<Local, Bits<DIST_BITS>>,
    lb: Signal<Local, Bit>,
    rb: Signal<Local, Bit>,
    kept_l: Signal<Local, Bits<DIST_SUM_BITS>>,
    kept_r: Signal<Local, Bits<DIST_SUM_BITS>>,
    dist_sum: Signal<Local, Bits<DIST_SUM_BITS>>,
    dist16: Signal<Local, Bits<16>>,
    dist_gain: Signal<Local, Bits<32>>,
    f_sel: Signal<Local, Bits<GAIN_BITS>>,
    g_ext: Signal<Local, Bits<SCORE_BITS>>,
    up: Signal<Local, Bits<PATH_BITS>>,
    up_diag: Signal<Local, Bits<PATH_BITS>>,
    left: Signal<Local, Bits<PATH_BITS>>,
    take_node: Signal<Local, Bit>,
    neg_score: Signal<Local, Bits<{ SCORE_BITS + 1 }>>,
    up_diff: Signal<Local, Bits<{ PATH_BITS + 1 }>>,
    left_diff: Signal<Local, Bits<{ PATH_BITS + 1 }>>,
    up_wins: Signal<Local, Bit>,
    left_wins: Signal<Local, Bit>,
    best: Signal<Local, Bits<PATH_BITS>>,
    best_choice: Signal<Local, Bits<2>>,
    choice_out: Signal<Local, Bits<2>>,
}

/// A constant of `B` bits.
fn k<const B: usize>(v: u64) -> Constant<Bits<B>> {
    Constant::new(v.into())
}

impl GainCell {
    /// The cell of an array of `cells` that holds reference declivities
    /// `index + k·cells`.
    pub(crate) fn new(index: usize, cells: usize) -> Self {
        assert!(index < cells && cells <= N_CELLS, "cell index inside an array of at most N_CELLS");
        assert_eq!(ROWS_PER_CELL, crate::primitives::lut_ram::LUT_RAM_WORDS, "a row per word of the LUT RAM");
        // The skew's last entry, `skew(index) - 1` (entry e is e + 1 clocks
        // old): its word and its bit in the word.
        let entry = skew(index).max(1) - 1;
        GainCell {
            clock: Default::default(),
            reset: Default::default(),
            ld_en: Default::default(),
            ld_phase: Default::default(),
            ld_pos: Default::default(),
            ld_levs: Default::default(),
            ld_rising: Default::default(),
            c_valid: Default::default(),
            c_phase: Default::default(),
            c_phase_next: Default::default(),
            c_pos: Default::default(),
            c_levs: Default::default(),
            c_rising: Default::default(),
            up_p: Default::default(),
            p: Default::default(),
            dispmax_m1: Default::default(),
            below2: Default::default(),
            f1: Default::default(),
            f3: Default::default(),
            p4: Default::default(),
            same_polarity: Default::default(),
            one_sided: Default::default(),
            choice_word: Default::default(),
            top_cell: Constant::new(index == 0),
            skewed: Constant::new(skew(index) > 0),
            skew_sel: k(1 << (entry / CELLS_PER_CHOICE_WORD)),
            skew_bit: k((2 * (entry % CELLS_PER_CHOICE_WORD)) as u64),
            zero_word: k(0),
            bit_lo: k((2 * (index % CELLS_PER_CHOICE_WORD)) as u64),
            bit_hi: k((2 * (index % CELLS_PER_CHOICE_WORD) + 1) as u64),
            bit0: k(0),
            bit1: k(1),
            lev_at1: k(LEVEL_BITS as u64),
            lev_at2: k(2 * LEVEL_BITS as u64),
            lev_at3: k(3 * LEVEL_BITS as u64),
            lev_at4: k(4 * LEVEL_BITS as u64),
            lev_at5: k(5 * LEVEL_BITS as u64),
            skew_top: k(CHOICE_WORD_BITS as u64 - 2),
            rise_bit: k(POS_BITS as u64),
            two: k(2),
            gain_unit_per_dist: k(1u64 << (GAIN_FRAC_BITS - 1)),
            gain_msb: k((GAIN_BITS - 1) as u64),
            level_sign: k(LEVEL_BITS as u64),
            sign_fill: k(((1u64 << SCORE_BITS) - 1) ^ ((1u64 << GAIN_BITS) - 1)),
            neg_score_msb: k(SCORE_BITS as u64),
            path_sign: k(PATH_BITS as u64),
            choice_start: k(CHOICE_START),
            choice_node: k(CHOICE_NODE),
            choice_up: k(CHOICE_UP),
            choice_left: k(CHOICE_LEFT),
            rows_pos: Default::default(),
            rows_levs: Default::default(),
            sel_pos: Default::default(),
            sel_levs: Default::default(),
            sel_rising: Default::default(),
            a_valid: Default::default(),
            a_ph0: Default::default(),
            a_diff: Default::default(),
            a_same: Default::default(),
            a_e0: Default::default(),
            a_e1: Default::default(),
            a_e2: Default::default(),
            a_e3: Default::default(),
            a_e4: Default::default(),
            a_e5: Default::default(),
            a_s0: Default::default(),
            a_s1: Default::default(),
            a_s3: Default::default(),
            a_s4: Default::default(),
            b_valid: Default::default(),
            b_ph0: Default::default(),
            b_ok: Default::default(),
            b_l2: Default::default(),
            b_r2: Default::default(),
            c2_valid: Default::default(),
            c2_ph0: Default::default(),
            c2_node: Default::default(),
            c2_both: Default::default(),
            c2_keep_l: Default::default(),
            c2_keep_r: Default::default(),
            c2_l: Default::default(),
            c2_r: Default::default(),
            s_valid: Default::default(),
            s_ph0: Default::default(),
            s_node: Default::default(),
            s_both: Default::default(),
            s_sum: Default::default(),
            d_valid: Default::default(),
            d_ph0: Default::default(),
            d_node: Default::default(),
            d_g: Default::default(),
            d_neg_g: Default::default(),
            e_valid: Default::default(),
            e_ph0: Default::default(),
            e_node: Default::default(),
            e_score: Default::default(),
            e_pos: Default::default(),
            f_valid: Default::default(),
            f_ph0: Default::default(),
            f_node: Default::default(),
            f_best: Default::default(),
            g_valid: Default::default(),
            g_best: Default::default(),
            g_node: Default::default(),
            g_up: Default::default(),
            p_reg: Default::default(),
            p_d1: Default::default(),
            p_d2: Default::default(),
            p_d3: Default::default(),
            up_d1: Default::default(),
            up_d2: Default::default(),
            choice_reg: Default::default(),
            skew_q: Default::default(),
            diff_pos: Default::default(),
            dr0: Default::default(),
            dr1: Default::default(),
            dr2: Default::default(),
            dc2: Default::default(),
            dr3: Default::default(),
            dr4: Default::default(),
            dr5: Default::default(),
            dc5: Default::default(),
            rl0: Default::default(),
            rl1: Default::default(),
            rl2: Default::default(),
            rl3: Default::default(),
            rl4: Default::default(),
            rl5: Default::default(),
            cl0: Default::default(),
            cl1: Default::default(),
            cl2: Default::default(),
            cl3: Default::default(),
            cl4: Default::default(),
            cl5: Default::default(),
            l_x: Default::default(),
            l_y: Default::default(),
            r_x: Default::default(),
            r_y: Default::default(),
            l_sum: Default::default(),
            r_sum: Default::default(),
            lb: Default::default(),
            rb: Default::default(),
            kept_l: Default::default(),
            kept_r: Default::default(),
            dist_sum: Default::default(),
            dist16: Default::default(),
            dist_gain: Default::default(),
            f_sel: Default::default(),
            g_ext: Default::default(),
            up: Default::default(),
            up_diag: Default::default(),
            left: Default::default(),
            take_node: Default::default(),
            neg_score: Default::default(),
            up_diff: Default::default(),
            left_diff: Default::default(),
            up_wins: Default::default(),
            left_wins: Default::default(),
            best: Default::default(),
            best_choice: Default::default(),
            choice_out: Default::default(),
        }
    }
}

impl Default for GainCell {
    fn default() -> Self {
        GainCell::new(0, 1)
    }
}

impl Logic for GainCell {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, sel_pos, sel_levs, sel_rising, a_valid, a_ph0, a_diff, a_same, a_e0, a_e1, a_e2, a_e3, a_e4, a_e5, a_s0, a_s1, a_s3, a_s4, b_valid, b_ph0, b_ok, b_l2, b_r2, c2_valid, c2_ph0, c2_node, c2_both, c2_keep_l, c2_keep_r, c2_l, c2_r, s_valid, s_ph0, s_node, s_both, s_sum, d_valid, d_ph0, d_node, d_g, d_neg_g, e_valid, e_ph0, e_node, e_score, e_pos, f_valid, f_ph0, f_node, f_best, g_valid, g_best, g_node, g_up, p_reg, p_d1, p_d2, p_d3, up_d1, up_d2, choice_reg
        );
        self.sel_pos.reset.next = self.reset.val();
        self.sel_levs.reset.next = self.reset.val();
        self.sel_rising.reset.next = self.reset.val();
        self.a_valid.reset.next = self.reset.val();
        self.a_ph0.reset.next = self.reset.val();
        self.a_diff.reset.next = self.reset.val();
        self.a_same.reset.next = self.reset.val();
        self.a_e0.reset.next = self.reset.val();
        self.a_e1.reset.next = self.reset.val();
        self.a_e2.reset.next = self.reset.val();
        self.a_e3.reset.next = self.reset.val();
        self.a_e4.reset.next = self.reset.val();
        self.a_e5.reset.next = self.reset.val();
        self.a_s0.reset.next = self.reset.val();
        self.a_s1.reset.next = self.reset.val();
        self.a_s3.reset.next = self.reset.val();
        self.a_s4.reset.next = self.reset.val();
        self.b_valid.reset.next = self.reset.val();
        self.b_ph0.reset.next = self.reset.val();
        self.b_ok.reset.next = self.reset.val();
        self.b_l2.reset.next = self.reset.val();
        self.b_r2.reset.next = self.reset.val();
        self.c2_valid.reset.next = self.reset.val();
        self.c2_ph0.reset.next = self.reset.val();
        self.c2_node.reset.next = self.reset.val();
        self.c2_both.reset.next = self.reset.val();
        self.c2_keep_l.reset.next = self.reset.val();
        self.c2_keep_r.reset.next = self.reset.val();
        self.c2_l.reset.next = self.reset.val();
        self.c2_r.reset.next = self.reset.val();
        self.s_valid.reset.next = self.reset.val();
        self.s_ph0.reset.next = self.reset.val();
        self.s_node.reset.next = self.reset.val();
        self.s_both.reset.next = self.reset.val();
        self.s_sum.reset.next = self.reset.val();
        self.d_valid.reset.next = self.reset.val();
        self.d_ph0.reset.next = self.reset.val();
        self.d_node.reset.next = self.reset.val();
        self.d_g.reset.next = self.reset.val();
        self.d_neg_g.reset.next = self.reset.val();
        self.e_valid.reset.next = self.reset.val();
        self.e_ph0.reset.next = self.reset.val();
        self.e_node.reset.next = self.reset.val();
        self.e_score.reset.next = self.reset.val();
        self.e_pos.reset.next = self.reset.val();
        self.f_valid.reset.next = self.reset.val();
        self.f_ph0.reset.next = self.reset.val();
        self.f_node.reset.next = self.reset.val();
        self.g_valid.reset.next = self.reset.val();
        self.g_best.reset.next = self.reset.val();
        self.g_node.reset.next = self.reset.val();
        self.g_up.reset.next = self.reset.val();
        self.p_d1.reset.next = self.reset.val();
        self.p_d2.reset.next = self.reset.val();
        self.p_d3.reset.next = self.reset.val();
        self.up_d1.reset.next = self.reset.val();
        self.up_d2.reset.next = self.reset.val();
        self.choice_reg.reset.next = self.reset.val();
        for w in 0..SKEW_WORDS {
            self.skew_q[w].clock.next = self.clock.val();
            self.skew_q[w].reset.next = self.reset.val();
        }

        // ---- The reference declivities, from the broadcast: the row of the
        // phase the token brings. The row of the column in the slot next
        // clock (now in the slot before): its phase's.
        self.rows_pos.clock.next = self.clock.val();
        self.rows_levs.clock.next = self.clock.val();
        self.rows_pos.write_enable.next = self.ld_en.val();
        self.rows_levs.write_enable.next = self.ld_en.val();
        self.rows_pos.write_address.next = self.ld_phase.val();
        self.rows_levs.write_address.next = self.ld_phase.val();
        self.rows_pos.write_data.next =
            bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.ld_pos.val()).replace_bit(self.rise_bit.val().index(), self.ld_rising.val());
        self.rows_levs.write_data.next = self.ld_levs.val();
        self.rows_pos.read_address.next = self.c_phase_next.val();
        self.rows_levs.read_address.next = self.c_phase_next.val();
        self.sel_pos.d.next = self.rows_pos.read_data.val().get_bits::<POS_BITS>(0);
        self.sel_rising.d.next = self.rows_pos.read_data.val().get_bit(self.rise_bit.val().index());
        self.sel_levs.d.next = self.rows_levs.read_data.val();

        // ---- A: eq. 6 (left reference: d = X_i - X_j, 0 < d < dispmax), as
        // d - 1 = X_i + !X_j, and
        // |level differences|. One subtraction gives d and its sign. Of each
        // side's three |a - b|, two are kept as a - b or its ones' complement
        // `!(a - b) = |a - b| - 1` with the sign bit beside it, the +1 being
        // the carry-in of stage B's adders; the third, with no carry-in left
        // for it, is a - b or b - a by the sign of a - b.
        self.diff_pos.next = bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.sel_pos.q.val())
            + !bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.c_pos.val());
        // The six levels out of their words (wiring).
        self.rl0.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.sel_levs.q.val().get_bits::<LEVEL_BITS>(0));
        self.rl1.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(
            self.sel_levs.q.val().get_bits::<LEVEL_BITS>(self.lev_at1.val().index()),
        );
        self.rl2.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(
            self.sel_levs.q.val().get_bits::<LEVEL_BITS>(self.lev_at2.val().index()),
        );
        self.rl3.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(
            self.sel_levs.q.val().get_bits::<LEVEL_BITS>(self.lev_at3.val().index()),
        );
        self.rl4.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(
            self.sel_levs.q.val().get_bits::<LEVEL_BITS>(self.lev_at4.val().index()),
        );
        self.rl5.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(
            self.sel_levs.q.val().get_bits::<LEVEL_BITS>(self.lev_at5.val().index()),
        );
        self.cl0.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_levs.val().get_bits::<LEVEL_BITS>(0));
        self.cl1.next =
            bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_levs.val().get_bits::<LEVEL_BITS>(self.lev_at1.val().index()));
        self.cl2.next =
            bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_levs.val().get_bits::<LEVEL_BITS>(self.lev_at2.val().index()));
        self.cl3.next =
            bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_levs.val().get_bits::<LEVEL_BITS>(self.lev_at3.val().index()));
        self.cl4.next =
            bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_levs.val().get_bits::<LEVEL_BITS>(self.lev_at4.val().index()));
        self.cl5.next =
            bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_levs.val().get_bits::<LEVEL_BITS>(self.lev_at5.val().index()));
        self.dr0.next = self.rl0.val() - self.cl0.val();
        self.dr1.next = self.rl1.val() - self.cl1.val();
        self.dr2.next = self.rl2.val() - self.cl2.val();
        self.dc2.next = self.cl2.val() - self.rl2.val();
        self.dr3.next = self.rl3.val() - self.cl3.val();
        self.dr4.next = self.rl4.val() - self.cl4.val();
        self.dr5.next = self.rl5.val() - self.cl5.val();
        self.dc5.next = self.cl5.val() - self.rl5.val();
        self.a_valid.d.next = self.c_valid.val();
        if self.c_valid.val() {
            self.a_ph0.d.next = !self.c_phase.val().any();
            self.a_diff.d.next = self.diff_pos.val();
            self.a_same.d.next = !self.same_polarity.val() | (self.sel_rising.q.val() == self.c_rising.val());
            self.a_e0.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr0.val());
            self.a_s0.d.next = 0.into();
            if self.dr0.val().get_bit(self.level_sign.val().index()) {
                self.a_e0.d.next = !bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr0.val());
                self.a_s0.d.next = 1.into();
            }
            self.a_e1.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr1.val());
            self.a_s1.d.next = 0.into();
            if self.dr1.val().get_bit(self.level_sign.val().index()) {
                self.a_e1.d.next = !bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr1.val());
                self.a_s1.d.next = 1.into();
            }
            self.a_e2.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr2.val());
            if self.dr2.val().get_bit(self.level_sign.val().index()) {
                self.a_e2.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dc2.val());
            }
            self.a_e3.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr3.val());
            self.a_s3.d.next = 0.into();
            if self.dr3.val().get_bit(self.level_sign.val().index()) {
                self.a_e3.d.next = !bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr3.val());
                self.a_s3.d.next = 1.into();
            }
            self.a_e4.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr4.val());
            self.a_s4.d.next = 0.into();
            if self.dr4.val().get_bit(self.level_sign.val().index()) {
                self.a_e4.d.next = !bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr4.val());
                self.a_s4.d.next = 1.into();
            }
            self.a_e5.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dr5.val());
            if self.dr5.val().get_bit(self.level_sign.val().index()) {
                self.a_e5.d.next = bit_cast::<LEVEL_BITS, { LEVEL_BITS + 1 }>(self.dc5.val());
            }
        }

        // ---- B: 2·lpd and 2·rpd (eq. 4–5), `e0 + e1 + e2 + s0 + s1`, as one
        // adder: the three levels reduced to a sum `x` and carries `y`
        // bit by bit (carry-save: one LUT each), `s0` in the carries'
        // empty bit 0, `s1` the adder's carry-in after synthesis: one carry
        // chain, not two adders in series.
        self.l_x.next = bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e0.q.val() ^ self.a_e1.q.val() ^ self.a_e2.q.val());
        self.l_y.next = (bit_cast::<DIST_BITS, LEVEL_BITS>(
            (self.a_e0.q.val() & self.a_e1.q.val()) | (self.a_e0.q.val() & self.a_e2.q.val()) | (self.a_e1.q.val() & self.a_e2.q.val()),
        ) << 1)
            | bit_cast::<DIST_BITS, 1>(self.a_s0.q.val());
        self.l_sum.next = self.l_x.val() + self.l_y.val() + bit_cast::<DIST_BITS, 1>(self.a_s1.q.val());
        self.r_x.next = bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e3.q.val() ^ self.a_e4.q.val() ^ self.a_e5.q.val());
        self.r_y.next = (bit_cast::<DIST_BITS, LEVEL_BITS>(
            (self.a_e3.q.val() & self.a_e4.q.val()) | (self.a_e3.q.val() & self.a_e5.q.val()) | (self.a_e4.q.val() & self.a_e5.q.val()),
        ) << 1)
            | bit_cast::<DIST_BITS, 1>(self.a_s3.q.val());
        self.r_sum.next = self.r_x.val() + self.r_y.val() + bit_cast::<DIST_BITS, 1>(self.a_s4.q.val());
        self.b_valid.d.next = self.a_valid.q.val();
        if self.a_valid.q.val() {
            self.b_ph0.d.next = self.a_ph0.q.val();
            // 0 < d < dispmax ⇔ d - 1 < dispmax - 1 unsigned: d ≤ 0 wraps
            // d - 1 above every bound.
            self.b_ok.d.next = (self.a_diff.q.val() < self.dispmax_m1.val()) & self.a_same.q.val();
            self.b_l2.d.next = self.l_sum.val();
            self.b_r2.d.next = self.r_sum.val();
        }

        // ---- C: eq. 7's tests, `d < gmax ⇔ 2d < ⌈2·gmax⌉`, and whether the
        // gain subtracts each distance (registered: stage S clears a
        // distance it does not subtract by a registered flag).
        self.lb.next = self.b_l2.q.val() < self.below2.val();
        self.rb.next = self.b_r2.q.val() < self.below2.val();
        self.c2_valid.d.next = self.b_valid.q.val();
        if self.b_valid.q.val() {
            self.c2_ph0.d.next = self.b_ph0.q.val();
            self.c2_node.d.next = self.b_ok.q.val() & (self.lb.val() | self.rb.val());
            self.c2_both.d.next = self.lb.val() & self.rb.val();
            self.c2_keep_l.d.next = self.lb.val() | !self.one_sided.val();
            self.c2_keep_r.d.next = self.rb.val() | !self.one_sided.val();
            self.c2_l.d.next = self.b_l2.q.val();
            self.c2_r.d.next = self.b_r2.q.val();
        }

        // ---- S: the sum of the distances the gain subtracts, each kept or
        // cleared (by registered flags), so that stage D holds one adder,
        // not the sum and the gain's subtraction in series (two carry
        // chains into `d_neg_g`).
        self.kept_l.next = 0.into();
        if self.c2_keep_l.q.val() {
            self.kept_l.next = bit_cast::<DIST_SUM_BITS, DIST_BITS>(self.c2_l.q.val());
        }
        self.kept_r.next = 0.into();
        if self.c2_keep_r.q.val() {
            self.kept_r.next = bit_cast::<DIST_SUM_BITS, DIST_BITS>(self.c2_r.q.val());
        }
        self.s_valid.d.next = self.c2_valid.q.val();
        if self.c2_valid.q.val() {
            self.s_ph0.d.next = self.c2_ph0.q.val();
            self.s_node.d.next = self.c2_node.q.val();
            self.s_both.d.next = self.c2_both.q.val();
            self.s_sum.d.next = self.kept_l.val() + self.kept_r.val();
        }

        // ---- D: g = f(gmax) - (lpd + rpd) in gain units (a product by a
        // power of two: a shift in hardware, cheap in rust-hdl's simulation).
        self.dist_sum.next = self.s_sum.q.val();
        self.dist16.next = bit_cast::<16, DIST_SUM_BITS>(self.dist_sum.val());
        self.dist_gain.next = self.dist16.val() * self.gain_unit_per_dist.val();
        self.f_sel.next = self.f1.val();
        if self.s_both.q.val() {
            self.f_sel.next = self.f3.val();
        }
        self.d_valid.d.next = self.s_valid.q.val();
        if self.s_valid.q.val() {
            self.d_ph0.d.next = self.s_ph0.q.val();
            self.d_node.d.next = self.s_node.q.val();
            self.d_g.d.next = self.f_sel.val() - bit_cast::<GAIN_BITS, 32>(self.dist_gain.val());
            // (The same subtraction the other way round, both operands
            // non-negative: exact in a score and a bit.)
            self.d_neg_g.d.next = bit_cast::<{ SCORE_BITS + 1 }, GAIN_BITS>(bit_cast::<GAIN_BITS, 32>(self.dist_gain.val()))
                - bit_cast::<{ SCORE_BITS + 1 }, GAIN_BITS>(self.f_sel.val());
        }

        // ---- E: G = g + P(i-1, j-1). `up_p` holds the cell above's P of
        // column j - 1 now with two phases (two clocks before it shows column
        // j's), two clocks ago with four (four clocks before). Cell 0's
        // phase 0 is the table's first row: nothing above it.
        self.up_d1.d.next = self.up_p.val();
        self.up_d2.d.next = self.up_d1.q.val();
        self.up_diag.next = self.up_p.val();
        if self.p4.val() {
            self.up_diag.next = self.up_d2.q.val();
        }
        if self.top_cell.val() & self.d_ph0.q.val() {
            self.up_diag.next = 0.into();
        }
        self.g_ext.next = bit_cast::<SCORE_BITS, GAIN_BITS>(self.d_g.q.val());
        self.neg_score.next = self.d_neg_g.q.val() - bit_cast::<{ SCORE_BITS + 1 }, PATH_BITS>(self.up_diag.val());
        if self.d_g.q.val().get_bit(self.gain_msb.val().index()) {
            // Sign extension: wiring in hardware.
            self.g_ext.next = bit_cast::<SCORE_BITS, GAIN_BITS>(self.d_g.q.val()) | self.sign_fill.val();
        }
        self.e_valid.d.next = self.d_valid.q.val();
        if self.d_valid.q.val() {
            self.e_ph0.d.next = self.d_ph0.q.val();
            self.e_node.d.next = self.d_node.q.val();
            self.e_score.d.next = self.g_ext.val() + bit_cast::<SCORE_BITS, PATH_BITS>(self.up_diag.val());
            // G > 0 ⇔ -g - P(i-1, j-1) < 0: a second adder beside the sum,
            // so that stage F tests a register, not the sum's sign and
            // every bit of it (six LUT levels into f_best's clear).
            self.e_pos.d.next = self.neg_score.val().get_bit(self.neg_score_msb.val().index());
        }

        // ---- F: the node beats start only when G > 0.
        self.take_node.next = self.e_node.q.val() & self.e_pos.q.val();
        self.f_valid.d.next = self.e_valid.q.val();
        if self.e_valid.q.val() {
            self.f_ph0.d.next = self.e_ph0.q.val();
            self.f_node.d.next = self.take_node.val();
            self.f_best.d.next = bit_cast::<PATH_BITS, SCORE_BITS>(self.e_score.q.val());
        }
        // A beat that is not a node clears `f_best`: through the register's
        // synchronous reset, beside the block's (one LUT for the cell, on
        // the flip-flops' LSR, where a clear inside the enable would cost a
        // LUT a bit once the reset holds the LSR).
        self.f_best.reset.next = self.reset.val() | (self.e_valid.q.val() & !self.take_node.val());

        // ---- G: P(i-1, j) only when strictly greater: the cell above's P
        // as soon as it is out (the node above is two clocks ahead, in the
        // next slot up). (`a > b` as the borrow of `b - a`: one carry chain,
        // where Yosys maps `>` on these widths to a chain and as many LUTs
        // again.)
        self.up.next = self.up_p.val();
        if self.top_cell.val() & self.f_ph0.q.val() {
            self.up.next = 0.into();
        }
        self.up_diff.next = bit_cast::<{ PATH_BITS + 1 }, PATH_BITS>(self.f_best.q.val())
            - bit_cast::<{ PATH_BITS + 1 }, PATH_BITS>(self.up.val());
        self.up_wins.next = self.up_diff.val().get_bit(self.path_sign.val().index());
        self.g_valid.d.next = self.f_valid.q.val();
        if self.f_valid.q.val() {
            self.g_best.d.next = self.f_best.q.val();
            if self.up_wins.val() {
                self.g_best.d.next = self.up.val();
            }
            // (The choice's two flags as they are; stage H encodes them,
            // so that `up_wins` drives registers' data, not the clear of
            // an encoded choice.)
            self.g_node.d.next = self.f_node.q.val();
            self.g_up.d.next = self.up_wins.val();
        }

        // ---- H: P(i, j-1), out two (four) clocks ago, only when strictly
        // greater.
        self.left.next = self.p_d1.q.val();
        if self.p4.val() {
            self.left.next = self.p_d3.q.val();
        }
        self.left_diff.next = bit_cast::<{ PATH_BITS + 1 }, PATH_BITS>(self.g_best.q.val())
            - bit_cast::<{ PATH_BITS + 1 }, PATH_BITS>(self.left.val());
        self.left_wins.next = self.left_diff.val().get_bit(self.path_sign.val().index());
        self.best.next = self.g_best.q.val();
        self.best_choice.next = self.choice_start.val();
        if self.g_node.q.val() {
            self.best_choice.next = self.choice_node.val();
        }
        if self.g_up.q.val() {
            self.best_choice.next = self.choice_up.val();
        }
        if self.left_wins.val() {
            self.best.next = self.left.val();
            self.best_choice.next = self.choice_left.val();
        }
        // A bubble leaves P = 0: the register's synchronous reset, beside
        // the block's (on the flip-flops' LSR, as `f_best`'s clear).
        self.p_reg.d.next = self.best.val();
        self.p_reg.reset.next = self.reset.val() | !self.g_valid.q.val();
        self.p_d1.d.next = self.p_reg.q.val();
        self.p_d2.d.next = self.p_d1.q.val();
        self.p_d3.d.next = self.p_d2.q.val();
        self.choice_reg.d.next = self.best_choice.val();
        self.p.next = self.p_reg.q.val();

        // ---- The choice out, with four phases `2·index` clocks late: a
        // shift register of 2-bit choices in words of 16.
        self.skew_q[0].d.next =
            (self.skew_q[0].q.val() << self.two.val()) | bit_cast::<CHOICE_WORD_BITS, 2>(self.choice_reg.q.val());
        for w in 1..SKEW_WORDS {
            self.skew_q[w].d.next =
                (self.skew_q[w].q.val() << self.two.val()) | (self.skew_q[w - 1].q.val() >> self.skew_top.val());
        }
        self.choice_out.next = self.choice_reg.q.val();
        if self.p4.val() & self.skewed.val() {
            for w in 0..SKEW_WORDS {
                if self.skew_sel.val().get_bit(w) {
                    self.choice_out.next = self.skew_q[w].q.val().get_bits::<2>(self.skew_bit.val().index());
                }
            }
        }
        // The choice in its two bits of the word: wiring in hardware.
        self.choice_word.next = self
            .zero_word
            .val()
            .replace_bit(self.bit_lo.val().index(), self.choice_out.val().get_bit(self.bit0.val().index()))
            .replace_bit(self.bit_hi.val().index(), self.choice_out.val().get_bit(self.bit1.val().index()));
    }
}
