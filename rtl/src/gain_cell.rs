//! One processing element of the systolic matcher: the node `(i, j)` of the
//! matching graph for its reference declivity `i` and each other-view
//! declivity `j` that streams past (paper §III–IV).
//!
//! Per column the cell computes, in fixed point:
//! - eq. 6, the search area: `0 < X_i - X_j < dispmax` (left reference);
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
//!   when strictly greater) and its 2-bit choice, which the cell keeps in its
//!   column memory at address `j`.
//!
//! ## Ports
//! - `ld_valid`, `ld_index`, `ld_pos`, `ld_lev0..5`, `ld_rising`: the
//!   reference-declivity broadcast; the cell whose index is `ld_index` takes
//!   the declivity (position `X_i`, levels left 0–2 then right 0–2,
//!   polarity).
//! - `c_valid`, `c_first` (column 0 of a line), `c_j`, `c_pos`, `c_lev0..5`,
//!   `c_rising`: the column in this cell's slot of the array's column
//!   pipeline (registers of the [`crate::systolic_matcher::SystolicMatcher`],
//!   which moves the column to the next cell's slot on the next clock).
//! - `up_p`: the previous cell's `P` (0 for the first cell); `own_p`: this
//!   cell's; out `p_next`, loaded into `own_p` when `p_load` is high, and
//!   `p_clear`, which zeroes `own_p` before a line's first column reaches
//!   stage F (the `P` registers belong to the array, so that the last
//!   cell's leads nowhere unused).
//! - Per line: `dispmax`, `below2` (`⌈2·gmax⌉`, compared with doubled
//!   distances), `f1` (`gmax`) and `f3` (`3·gmax`) in gain units; per design:
//!   `same_polarity`, `one_sided`.
//! - Traceback: `tb_diag` (anti-diagonal `i + j`), `tb_row` and `tb_row_up`;
//!   the cell reads its choice of column `tb_diag - index` and shows it one
//!   clock later on `tb_choice` when `tb_row` is its index, on
//!   `tb_choice_up` when `tb_row_up` is (zero, i.e. `start`, otherwise, so
//!   the array's outputs can be OR-ed).
//!
//! ## Timing
//! A column moves one cell per clock. The column in the cell's slot at
//! clock `t` has its `P` on `p_next` and its choice written at the
//! end of clock `t +` [`CELL_DEPTH`] `- 1`: stage A (search area,
//! differences), B (distances), C (tests of eq. 7), D (gain), E
//! (`G = g + P(i-1, j-1)`, start or node), F (up, left). Stage E reads
//! `up_p` one clock before stage F, when it still holds the previous cell's
//! `P` of column `j - 1`: the diagonal needs no register of its own. Bubbles
//! (`c_valid` low) pass through; registers of a stage load only on a valid
//! column.

use crate::params::*;
use rust_hdl::prelude::*;

/// Clocks from a column in a cell's slot to its `P` on `p_next` (stages
/// A–F; in the `P` register one clock later).
pub const CELL_DEPTH: usize = 6;

/// The 2-bit choices, as `golden::dp::Choice` numbers them.
pub const CHOICE_START: u64 = 0;
/// `P = G`: the node is taken.
pub const CHOICE_NODE: u64 = 1;
/// `P = P(i-1, j)`.
pub const CHOICE_UP: u64 = 2;
/// `P = P(i, j-1)`.
pub const CHOICE_LEFT: u64 = 3;

#[derive(LogicBlock)]
pub struct GainCell {
    pub clock: Signal<In, Clock>,
    // Reference broadcast.
    pub ld_valid: Signal<In, Bit>,
    pub ld_index: Signal<In, Bits<INDEX_BITS>>,
    pub ld_pos: Signal<In, Bits<POS_BITS>>,
    pub ld_lev0: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev1: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev2: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev3: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev4: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev5: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_rising: Signal<In, Bit>,
    // The column in this cell's slot.
    pub c_valid: Signal<In, Bit>,
    pub c_first: Signal<In, Bit>,
    pub c_j: Signal<In, Bits<INDEX_BITS>>,
    pub c_pos: Signal<In, Bits<POS_BITS>>,
    pub c_lev0: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev1: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev2: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev3: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev4: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev5: Signal<In, Bits<LEVEL_BITS>>,
    pub c_rising: Signal<In, Bit>,
    // The recurrence: P of the previous cell and this one (the array's
    // registers), and the next P of this one.
    pub up_p: Signal<In, Bits<PATH_BITS>>,
    pub own_p: Signal<In, Bits<PATH_BITS>>,
    pub p_next: Signal<Out, Bits<PATH_BITS>>,
    pub p_load: Signal<Out, Bit>,
    pub p_clear: Signal<Out, Bit>,
    // Per line and per design.
    pub dispmax: Signal<In, Bits<DISPMAX_BITS>>,
    pub below2: Signal<In, Bits<DIST_BITS>>,
    pub f1: Signal<In, Bits<GAIN_BITS>>,
    pub f3: Signal<In, Bits<GAIN_BITS>>,
    pub same_polarity: Signal<In, Bit>,
    pub one_sided: Signal<In, Bit>,
    // Traceback.
    pub tb_diag: Signal<In, Bits<DIAG_BITS>>,
    pub tb_row: Signal<In, Bits<INDEX_BITS>>,
    pub tb_row_up: Signal<In, Bits<INDEX_BITS>>,
    pub tb_choice: Signal<Out, Bits<2>>,
    pub tb_choice_up: Signal<Out, Bits<2>>,
    choices: RAM<Bits<2>, INDEX_BITS>,
    index: Constant<Bits<INDEX_BITS>>,
    index8: Constant<Bits<DIAG_BITS>>,
    gain_unit_per_dist: Constant<Bits<16>>,
    choice_start: Constant<Bits<2>>,
    gain_msb: Constant<Bits<8>>,
    pos_sign: Constant<Bits<8>>,
    level_sign: Constant<Bits<8>>,
    sign_fill: Constant<Bits<SCORE_BITS>>,
    score_msb: Constant<Bits<8>>,
    choice_node: Constant<Bits<2>>,
    choice_up: Constant<Bits<2>>,
    choice_left: Constant<Bits<2>>,
    // The reference declivity.
    r_pos: DFF<Bits<POS_BITS>>,
    r_lev0: DFF<Bits<LEVEL_BITS>>,
    r_lev1: DFF<Bits<LEVEL_BITS>>,
    r_lev2: DFF<Bits<LEVEL_BITS>>,
    r_lev3: DFF<Bits<LEVEL_BITS>>,
    r_lev4: DFF<Bits<LEVEL_BITS>>,
    r_lev5: DFF<Bits<LEVEL_BITS>>,
    r_rising: DFF<Bit>,
    // Stage A: search area, polarity, level differences.
    a_valid: DFF<Bit>,
    a_first: DFF<Bit>,
    a_j: DFF<Bits<INDEX_BITS>>,
    a_area: DFF<Bit>,
    a_same: DFF<Bit>,
    a_e0: DFF<Bits<LEVEL_BITS>>,
    a_e1: DFF<Bits<LEVEL_BITS>>,
    a_e2: DFF<Bits<LEVEL_BITS>>,
    a_e3: DFF<Bits<LEVEL_BITS>>,
    a_e4: DFF<Bits<LEVEL_BITS>>,
    a_e5: DFF<Bits<LEVEL_BITS>>,
    a_s0: DFF<Bits<1>>,
    a_s1: DFF<Bits<1>>,
    a_s3: DFF<Bits<1>>,
    a_s4: DFF<Bits<1>>,
    // Stage B: doubled distances.
    b_valid: DFF<Bit>,
    b_first: DFF<Bit>,
    b_j: DFF<Bits<INDEX_BITS>>,
    b_ok: DFF<Bit>,
    b_l2: DFF<Bits<DIST_BITS>>,
    b_r2: DFF<Bits<DIST_BITS>>,
    // Stage C: eq. 7's tests.
    c2_valid: DFF<Bit>,
    c2_first: DFF<Bit>,
    c2_j: DFF<Bits<INDEX_BITS>>,
    c2_node: DFF<Bit>,
    c2_both: DFF<Bit>,
    c2_dist: DFF<Bits<DIST_SUM_BITS>>,
    // Stage D: the local gain.
    d_valid: DFF<Bit>,
    d_first: DFF<Bit>,
    d_j: DFF<Bits<INDEX_BITS>>,
    d_node: DFF<Bit>,
    d_g: DFF<Bits<GAIN_BITS>>,
    // Stage E: start or node.
    e_valid: DFF<Bit>,
    e_j: DFF<Bits<INDEX_BITS>>,
    e_best: DFF<Bits<PATH_BITS>>,
    e_node: DFF<Bit>,
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
    l_part0: Signal<Local, Bits<DIST_BITS>>,
    r_part0: Signal<Local, Bits<DIST_BITS>>,
    l_sum: Signal<Local, Bits<DIST_BITS>>,
    r_sum: Signal<Local, Bits<DIST_BITS>>,
    lb: Signal<Local, Bit>,
    rb: Signal<Local, Bit>,
    l_part: Signal<Local, Bits<DIST_SUM_BITS>>,
    r_part: Signal<Local, Bits<DIST_SUM_BITS>>,
    dist16: Signal<Local, Bits<16>>,
    dist_gain: Signal<Local, Bits<32>>,
    f_sel: Signal<Local, Bits<GAIN_BITS>>,
    g_ext: Signal<Local, Bits<SCORE_BITS>>,
    diag: Signal<Local, Bits<SCORE_BITS>>,
    score: Signal<Local, Bits<SCORE_BITS>>,
    take_node: Signal<Local, Bit>,
    left: Signal<Local, Bits<PATH_BITS>>,
    up_wins: Signal<Local, Bit>,
    left_over_a: Signal<Local, Bit>,
    left_over_up: Signal<Local, Bit>,
    best2: Signal<Local, Bits<PATH_BITS>>,
    choice2: Signal<Local, Bits<2>>,
    read_col: Signal<Local, Bits<DIAG_BITS>>,
}

impl GainCell {
    /// The cell that holds reference declivity `index`.
    pub fn new(index: usize) -> Self {
        assert!(index < N_MAX, "cell index inside the array");
        GainCell {
            clock: Default::default(),
            ld_valid: Default::default(),
            ld_index: Default::default(),
            ld_pos: Default::default(),
            ld_lev0: Default::default(),
            ld_lev1: Default::default(),
            ld_lev2: Default::default(),
            ld_lev3: Default::default(),
            ld_lev4: Default::default(),
            ld_lev5: Default::default(),
            ld_rising: Default::default(),
            c_valid: Default::default(),
            c_first: Default::default(),
            c_j: Default::default(),
            c_pos: Default::default(),
            c_lev0: Default::default(),
            c_lev1: Default::default(),
            c_lev2: Default::default(),
            c_lev3: Default::default(),
            c_lev4: Default::default(),
            c_lev5: Default::default(),
            c_rising: Default::default(),
            up_p: Default::default(),
            own_p: Default::default(),
            p_next: Default::default(),
            p_load: Default::default(),
            p_clear: Default::default(),
            dispmax: Default::default(),
            below2: Default::default(),
            f1: Default::default(),
            f3: Default::default(),
            same_polarity: Default::default(),
            one_sided: Default::default(),
            tb_diag: Default::default(),
            tb_row: Default::default(),
            tb_row_up: Default::default(),
            tb_choice: Default::default(),
            tb_choice_up: Default::default(),
            choices: Default::default(),
            index: Constant::new((index as u64).into()),
            index8: Constant::new((index as u64).into()),
            gain_unit_per_dist: Constant::new((1u64 << (GAIN_FRAC_BITS - 1)).into()),
            choice_start: Constant::new(CHOICE_START.into()),
            gain_msb: Constant::new(((GAIN_BITS - 1) as u64).into()),
            pos_sign: Constant::new((POS_BITS as u64).into()),
            level_sign: Constant::new((LEVEL_BITS as u64).into()),
            sign_fill: Constant::new((((1u64 << SCORE_BITS) - 1) ^ ((1u64 << GAIN_BITS) - 1)).into()),
            score_msb: Constant::new(((SCORE_BITS - 1) as u64).into()),
            choice_node: Constant::new(CHOICE_NODE.into()),
            choice_up: Constant::new(CHOICE_UP.into()),
            choice_left: Constant::new(CHOICE_LEFT.into()),
            r_pos: Default::default(),
            r_lev0: Default::default(),
            r_lev1: Default::default(),
            r_lev2: Default::default(),
            r_lev3: Default::default(),
            r_lev4: Default::default(),
            r_lev5: Default::default(),
            r_rising: Default::default(),
            a_valid: Default::default(),
            a_first: Default::default(),
            a_j: Default::default(),
            a_area: Default::default(),
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
            b_first: Default::default(),
            b_j: Default::default(),
            b_ok: Default::default(),
            b_l2: Default::default(),
            b_r2: Default::default(),
            c2_valid: Default::default(),
            c2_first: Default::default(),
            c2_j: Default::default(),
            c2_node: Default::default(),
            c2_both: Default::default(),
            c2_dist: Default::default(),
            d_valid: Default::default(),
            d_first: Default::default(),
            d_j: Default::default(),
            d_node: Default::default(),
            d_g: Default::default(),
            e_valid: Default::default(),
            e_j: Default::default(),
            e_best: Default::default(),
            e_node: Default::default(),
            diff_pos: Default::default(),
            dr0: Default::default(),
            dr1: Default::default(),
            dr2: Default::default(),
            dc2: Default::default(),
            dr3: Default::default(),
            dr4: Default::default(),
            dr5: Default::default(),
            dc5: Default::default(),
            l_part0: Default::default(),
            r_part0: Default::default(),
            l_sum: Default::default(),
            r_sum: Default::default(),
            lb: Default::default(),
            rb: Default::default(),
            l_part: Default::default(),
            r_part: Default::default(),
            dist16: Default::default(),
            dist_gain: Default::default(),
            f_sel: Default::default(),
            g_ext: Default::default(),
            diag: Default::default(),
            score: Default::default(),
            take_node: Default::default(),
            left: Default::default(),
            up_wins: Default::default(),
            left_over_a: Default::default(),
            left_over_up: Default::default(),
            best2: Default::default(),
            choice2: Default::default(),
            read_col: Default::default(),
        }
    }
}

impl Default for GainCell {
    fn default() -> Self {
        GainCell::new(0)
    }
}

impl Logic for GainCell {
    #[hdl_gen]
    fn update(&mut self) {
        self.choices.read_clock.next = self.clock.val();
        self.choices.write_clock.next = self.clock.val();
        dff_setup!(
            self, clock, r_pos, r_lev0, r_lev1, r_lev2, r_lev3, r_lev4, r_lev5, r_rising, a_valid,
            a_first, a_j, a_area, a_same, a_e0, a_e1, a_e2, a_e3, a_e4, a_e5, a_s0, a_s1, a_s3, a_s4, b_valid, b_first, b_j, b_ok, b_l2,
            b_r2, c2_valid, c2_first, c2_j, c2_node, c2_both, c2_dist, d_valid, d_first, d_j, d_node, d_g,
            e_valid, e_j, e_best, e_node
        );

        // ---- The reference declivity, from the broadcast.
        if self.ld_valid.val() & (self.ld_index.val() == self.index.val()) {
            self.r_pos.d.next = self.ld_pos.val();
            self.r_lev0.d.next = self.ld_lev0.val();
            self.r_lev1.d.next = self.ld_lev1.val();
            self.r_lev2.d.next = self.ld_lev2.val();
            self.r_lev3.d.next = self.ld_lev3.val();
            self.r_lev4.d.next = self.ld_lev4.val();
            self.r_lev5.d.next = self.ld_lev5.val();
            self.r_rising.d.next = self.ld_rising.val();
        }

        // ---- A: eq. 6 (left reference: d = X_i - X_j, 0 < d < dispmax) and
        // |level differences|. One subtraction gives d and its sign. Of each
        // side's three |a - b|, two are kept as a - b or its ones' complement
        // `!(a - b) = |a - b| - 1` with the sign bit beside it, the +1 being
        // the carry-in of stage B's adders; the third, with no carry-in left
        // for it, is a - b or b - a by the sign of a - b.
        self.diff_pos.next = bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.r_pos.q.val())
            - bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.c_pos.val());
        self.dr0.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev0.q.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev0.val());
        self.dr1.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev1.q.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev1.val());
        self.dr2.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev2.q.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev2.val());
        self.dc2.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev2.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev2.q.val());
        self.dr3.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev3.q.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev3.val());
        self.dr4.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev4.q.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev4.val());
        self.dr5.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev5.q.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev5.val());
        self.dc5.next = bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.c_lev5.val())
            - bit_cast::<{ LEVEL_BITS + 1 }, LEVEL_BITS>(self.r_lev5.q.val());
        self.a_valid.d.next = self.c_valid.val();
        if self.c_valid.val() {
            self.a_first.d.next = self.c_first.val();
            self.a_j.d.next = self.c_j.val();
            self.a_area.d.next = !self.diff_pos.val().get_bit(self.pos_sign.val().index())
                & self.diff_pos.val().any()
                & (bit_cast::<POS_BITS, { POS_BITS + 1 }>(self.diff_pos.val()) < self.dispmax.val());
            self.a_same.d.next = !self.same_polarity.val() | (self.r_rising.q.val() == self.c_rising.val());
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

        // ---- B: 2·lpd and 2·rpd (eq. 4–5); each one-bit term is an adder's
        // carry-in after synthesis.
        self.l_part0.next = bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e0.q.val())
            + bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e1.q.val())
            + bit_cast::<DIST_BITS, 1>(self.a_s0.q.val());
        self.l_sum.next = self.l_part0.val()
            + bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e2.q.val())
            + bit_cast::<DIST_BITS, 1>(self.a_s1.q.val());
        self.r_part0.next = bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e3.q.val())
            + bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e4.q.val())
            + bit_cast::<DIST_BITS, 1>(self.a_s3.q.val());
        self.r_sum.next = self.r_part0.val()
            + bit_cast::<DIST_BITS, LEVEL_BITS>(self.a_e5.q.val())
            + bit_cast::<DIST_BITS, 1>(self.a_s4.q.val());
        self.b_valid.d.next = self.a_valid.q.val();
        if self.a_valid.q.val() {
            self.b_first.d.next = self.a_first.q.val();
            self.b_j.d.next = self.a_j.q.val();
            self.b_ok.d.next = self.a_area.q.val() & self.a_same.q.val();
            self.b_l2.d.next = self.l_sum.val();
            self.b_r2.d.next = self.r_sum.val();
        }

        // ---- C: eq. 7's tests, `d < gmax ⇔ 2d < ⌈2·gmax⌉`, and the
        // distances the gain subtracts.
        self.lb.next = self.b_l2.q.val() < self.below2.val();
        self.rb.next = self.b_r2.q.val() < self.below2.val();
        self.l_part.next = 0.into();
        if self.lb.val() | !self.one_sided.val() {
            self.l_part.next = bit_cast::<DIST_SUM_BITS, DIST_BITS>(self.b_l2.q.val());
        }
        self.r_part.next = 0.into();
        if self.rb.val() | !self.one_sided.val() {
            self.r_part.next = bit_cast::<DIST_SUM_BITS, DIST_BITS>(self.b_r2.q.val());
        }
        self.c2_valid.d.next = self.b_valid.q.val();
        if self.b_valid.q.val() {
            self.c2_first.d.next = self.b_first.q.val();
            self.c2_j.d.next = self.b_j.q.val();
            self.c2_node.d.next = self.b_ok.q.val() & (self.lb.val() | self.rb.val());
            self.c2_both.d.next = self.lb.val() & self.rb.val();
            self.c2_dist.d.next = self.l_part.val() + self.r_part.val();
        }

        // ---- D: g = f(gmax) - (lpd + rpd) in gain units (a product by a
        // power of two: a shift in hardware, cheap in rust-hdl's simulation).
        self.dist16.next = bit_cast::<16, DIST_SUM_BITS>(self.c2_dist.q.val());
        self.dist_gain.next = self.dist16.val() * self.gain_unit_per_dist.val();
        self.f_sel.next = self.f1.val();
        if self.c2_both.q.val() {
            self.f_sel.next = self.f3.val();
        }
        self.d_valid.d.next = self.c2_valid.q.val();
        if self.c2_valid.q.val() {
            self.d_first.d.next = self.c2_first.q.val();
            self.d_j.d.next = self.c2_j.q.val();
            self.d_node.d.next = self.c2_node.q.val();
            self.d_g.d.next = self.f_sel.val() - bit_cast::<GAIN_BITS, 32>(self.dist_gain.val());
        }

        // ---- E: G = g + P(i-1, j-1); the node beats start only when G > 0.
        // `up_p` still holds the previous cell's P of column j - 1.
        self.g_ext.next = bit_cast::<SCORE_BITS, GAIN_BITS>(self.d_g.q.val());
        if self.d_g.q.val().get_bit(self.gain_msb.val().index()) {
            // Sign extension: wiring in hardware.
            self.g_ext.next = bit_cast::<SCORE_BITS, GAIN_BITS>(self.d_g.q.val()) | self.sign_fill.val();
        }
        self.diag.next = bit_cast::<SCORE_BITS, PATH_BITS>(self.up_p.val());
        if self.d_first.q.val() {
            self.diag.next = 0.into();
        }
        self.score.next = self.g_ext.val() + self.diag.val();
        self.take_node.next =
            self.d_node.q.val() & !self.score.val().get_bit(self.score_msb.val().index()) & self.score.val().any();
        self.e_valid.d.next = self.d_valid.q.val();
        if self.d_valid.q.val() {
            self.e_j.d.next = self.d_j.q.val();
            self.e_node.d.next = self.take_node.val();
            self.e_best.d.next = 0.into();
            if self.take_node.val() {
                self.e_best.d.next = bit_cast::<PATH_BITS, SCORE_BITS>(self.score.val());
            }
        }

        // ---- F: P(i, j) = max(start/node, up, left), a later candidate only
        // when strictly greater: the three comparisons side by side, then
        // the choice (`left > max(A, up)` is `left > up` when up won, else
        // `left > A`).
        self.left.next = self.own_p.val();
        self.up_wins.next = self.up_p.val() > self.e_best.q.val();
        self.left_over_a.next = self.left.val() > self.e_best.q.val();
        self.left_over_up.next = self.left.val() > self.up_p.val();
        self.best2.next = self.e_best.q.val();
        self.choice2.next = self.choice_start.val();
        if self.e_node.q.val() {
            self.choice2.next = self.choice_node.val();
        }
        if self.up_wins.val() {
            self.best2.next = self.up_p.val();
            self.choice2.next = self.choice_up.val();
            if self.left_over_up.val() {
                self.best2.next = self.left.val();
                self.choice2.next = self.choice_left.val();
            }
        } else {
            if self.left_over_a.val() {
                self.best2.next = self.left.val();
                self.choice2.next = self.choice_left.val();
            }
        }
        self.p_next.next = self.best2.val();
        self.p_load.next = self.e_valid.q.val();
        // P(i, -1) = 0: cleared as column 0 enters stage E, so that stage F
        // reads P(i, j - 1) straight from the register.
        self.p_clear.next = self.d_valid.q.val() & self.d_first.q.val();
        self.choices.write_address.next = self.e_j.q.val();
        self.choices.write_data.next = self.choice2.val();
        self.choices.write_enable.next = self.e_valid.q.val();

        // ---- Traceback: the choice of column tb_diag - index.
        self.read_col.next = self.tb_diag.val() - self.index8.val();
        self.choices.read_address.next = bit_cast::<INDEX_BITS, DIAG_BITS>(self.read_col.val());
        self.tb_choice.next = 0.into();
        if self.tb_row.val() == self.index.val() {
            self.tb_choice.next = self.choices.read_data.val();
        }
        self.tb_choice_up.next = 0.into();
        if self.tb_row_up.val() == self.index.val() {
            self.tb_choice_up.next = self.choices.read_data.val();
        }
    }
}
