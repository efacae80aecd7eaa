//! The systolic array of the matcher (`DESIGN.md` §3): `N` [`GainCell`]s in
//! a line, cell `c` holding reference declivities `c` and `c + N`, the
//! other view's declivities streaming through the chain twice, one cell
//! every two clocks: the first pass on even clocks meets the low rows
//! `0 .. N`, the second, `2·N + 1` clocks behind on odd clocks, the high
//! rows `N .. 2·N`. Node `(i, j)` is computed `2·(i + j) + [i ≥ N]` clocks
//! after the sweep starts, so the `2N × M` table of eq. 9 is swept in
//! anti-diagonal wavefronts, one every two clocks, and every dependency of
//! a node is at least two clocks old: `P(i-1, j)` and `P(i, j-1)` two (three
//! across the fold from row `N - 1` to row `N`), `P(i-1, j-1)` four.
//!
//! The cells' choices go to a block-RAM choice memory rather than into the
//! cells: on each clock every cell has one node's choice (all of the low
//! rows or all of the high rows, of one anti-diagonal), so word `d` of the
//! low (high) half holds anti-diagonal `d` of the low (high) rows, two bits
//! per cell, [`CELLS_PER_CHOICE_WORD`] cells per word.
//!
//! ## Ports
//! - `ld_pos`, `ld_lev0..5`, `ld_rising`: the reference-declivity
//!   broadcast, to every cell, references `0, 1, 2, …` on consecutive
//!   clocks; `ld_first` (`ld_first_hi`) high one clock before reference 0
//!   (`N`) is on it starts a load token down the cells, so that cell `c`
//!   takes reference `c` (`c + N`).
//! - `c_*`: the column stream (`c_hi`: second pass), into the column
//!   pipeline: two register slots per cell, b then a; a cell computes on
//!   the column in its slot a and selects its reference (low or high row)
//!   by the pass of the column in its slot b, a clock ahead.
//! - `dispmax_m1`, `below2`, `f1`, `f3`: the line's constants, passed down
//!   the cells one per clock; `same_polarity`, `one_sided`: to every cell
//!   (see [`GainCell`]).
//! - `cw_en`, `cw_diag`, `cw_hi`: write the choices now in the array's word
//!   registers as anti-diagonal `cw_diag` of the low (`cw_hi` low) or high
//!   rows. The engine counts them: the choices of the node whose column
//!   entered at clock `t` are in the word registers at `t +` [`CHOICE_LAG`].
//! - `tb_diag`, `tb_group` in; `tb_word`, `tb_word_prev` out: the words of
//!   anti-diagonal `tb_diag` (three clocks ago: memory read, its output
//!   register inside the block RAM ([`BlockRam`]), then the register that
//!   feeds the selection) that hold the choices of row groups `tb_group`
//!   and `tb_group - 1` (now; see [`ChoiceWord`]): with the two side by
//!   side, row `r`'s choice is `2·(r - 16·tb_group + 16)` bits up.
//!
//! ## Timing
//! Column `j` offered on `c_*` at clock `t - 1` sits in cell `c`'s slot b
//! at `t + 2c`, in its slot a at `t + 2c + 1`, and gives `P` and the choice
//! of node `(c + N·c_hi, j)` in the cell at `t + 2c + 1 +`
//! [`CELL_DEPTH`], in the word registers one clock later. The high rows' `P(N-1, ·)` comes from the last cell through one
//! register; the low rows' `P(-1, ·)` is the border, 0.

use crate::block_ram::BlockRam;
use crate::choice_word::ChoiceWord;
use crate::gain_cell::{GainCell, CELL_DEPTH};
use crate::params::*;
use rust_hdl::prelude::*;

/// Clocks from a column offered on `c_*` to its node's choice in the word
/// registers, less the cell's slot offset `2c`: two into the cell's slot a,
/// the cell's depth, one into the word register. (The matcher's engine adds
/// its own two clocks of record memory.)
pub const CHOICE_LAG: usize = 2 + CELL_DEPTH + 1;


#[derive(LogicBlock)]
pub struct SystolicMatcher<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub ld_first: Signal<In, Bit>,
    pub ld_first_hi: Signal<In, Bit>,
    pub ld_pos: Signal<In, Bits<POS_BITS>>,
    pub ld_lev0: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev1: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev2: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev3: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev4: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_lev5: Signal<In, Bits<LEVEL_BITS>>,
    pub ld_rising: Signal<In, Bit>,
    pub c_valid: Signal<In, Bit>,
    pub c_hi: Signal<In, Bit>,
    pub c_pos: Signal<In, Bits<POS_BITS>>,
    pub c_lev0: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev1: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev2: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev3: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev4: Signal<In, Bits<LEVEL_BITS>>,
    pub c_lev5: Signal<In, Bits<LEVEL_BITS>>,
    pub c_rising: Signal<In, Bit>,
    pub dispmax_m1: Signal<In, Bits<{ POS_BITS + 1 }>>,
    pub below2: Signal<In, Bits<DIST_BITS>>,
    pub f1: Signal<In, Bits<GAIN_BITS>>,
    pub f3: Signal<In, Bits<GAIN_BITS>>,
    pub same_polarity: Signal<In, Bit>,
    pub one_sided: Signal<In, Bit>,
    pub cw_en: Signal<In, Bit>,
    pub cw_diag: Signal<In, Bits<DIAG_BITS>>,
    pub cw_hi: Signal<In, Bit>,
    pub tb_diag: Signal<In, Bits<DIAG_BITS>>,
    pub tb_group: Signal<In, Bits<ROW_GROUP_BITS>>,
    pub tb_word: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    pub tb_word_prev: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    pub cells: [GainCell; N],
    pub row_word: ChoiceWord,
    pub prev_word: ChoiceWord,
    col_a_valid: [DFF<Bit>; N],
    col_a_hi: [DFF<Bit>; N],
    col_a_pos: [DFF<Bits<POS_BITS>>; N],
    col_a_lev0: [DFF<Bits<LEVEL_BITS>>; N],
    col_a_lev1: [DFF<Bits<LEVEL_BITS>>; N],
    col_a_lev2: [DFF<Bits<LEVEL_BITS>>; N],
    col_a_lev3: [DFF<Bits<LEVEL_BITS>>; N],
    col_a_lev4: [DFF<Bits<LEVEL_BITS>>; N],
    col_a_lev5: [DFF<Bits<LEVEL_BITS>>; N],
    col_a_rising: [DFF<Bit>; N],
    col_b_valid: [DFF<Bit>; N],
    col_b_hi: [DFF<Bit>; N],
    col_b_pos: [DFF<Bits<POS_BITS>>; N],
    col_b_lev0: [DFF<Bits<LEVEL_BITS>>; N],
    col_b_lev1: [DFF<Bits<LEVEL_BITS>>; N],
    col_b_lev2: [DFF<Bits<LEVEL_BITS>>; N],
    col_b_lev3: [DFF<Bits<LEVEL_BITS>>; N],
    col_b_lev4: [DFF<Bits<LEVEL_BITS>>; N],
    col_b_lev5: [DFF<Bits<LEVEL_BITS>>; N],
    col_b_rising: [DFF<Bit>; N],
    k_dispmax_m1: [DFF<Bits<{ POS_BITS + 1 }>>; N],
    k_below2: [DFF<Bits<DIST_BITS>>; N],
    k_f1: [DFF<Bits<GAIN_BITS>>; N],
    k_f3: [DFF<Bits<GAIN_BITS>>; N],
    tok_lo: [DFF<Bit>; N],
    tok_hi: [DFF<Bit>; N],
    wrap: DFF<Bits<PATH_BITS>>,
    word_q: [DFF<Bits<CHOICE_WORD_BITS>>; CHOICE_WORDS],
    lo_ram: [BlockRam<CHOICE_WORD_BITS, DIAG_BITS>; CHOICE_WORDS],
    hi_ram: [BlockRam<CHOICE_WORD_BITS, DIAG_BITS>; CHOICE_WORDS],
    rd2_lo: [DFF<Bits<CHOICE_WORD_BITS>>; CHOICE_WORDS],
    rd2_hi: [DFF<Bits<CHOICE_WORD_BITS>>; CHOICE_WORDS],
    last_p: Signal<Local, Bits<PATH_BITS>>,
    group_one: Constant<Bits<ROW_GROUP_BITS>>,
    wacc: [Signal<Local, Bits<CHOICE_WORD_BITS>>; CHOICE_WORDS],
}

impl<const N: usize> Default for SystolicMatcher<N> {
    fn default() -> Self {
        assert!((1..=N_CELLS).contains(&N), "1 ..= N_CELLS cells");
        assert_eq!(CHOICE_WORDS, 4, "the choice words below are named four per half");
        assert_eq!(CELLS_PER_CHOICE_WORD, 16, "the word index below is written i / 16");
        SystolicMatcher {
            clock: Default::default(),
            ld_first: Default::default(),
            ld_first_hi: Default::default(),
            ld_pos: Default::default(),
            ld_lev0: Default::default(),
            ld_lev1: Default::default(),
            ld_lev2: Default::default(),
            ld_lev3: Default::default(),
            ld_lev4: Default::default(),
            ld_lev5: Default::default(),
            ld_rising: Default::default(),
            c_valid: Default::default(),
            c_hi: Default::default(),
            c_pos: Default::default(),
            c_lev0: Default::default(),
            c_lev1: Default::default(),
            c_lev2: Default::default(),
            c_lev3: Default::default(),
            c_lev4: Default::default(),
            c_lev5: Default::default(),
            c_rising: Default::default(),
            dispmax_m1: Default::default(),
            below2: Default::default(),
            f1: Default::default(),
            f3: Default::default(),
            same_polarity: Default::default(),
            one_sided: Default::default(),
            cw_en: Default::default(),
            cw_diag: Default::default(),
            cw_hi: Default::default(),
            tb_diag: Default::default(),
            tb_group: Default::default(),
            tb_word: Default::default(),
            tb_word_prev: Default::default(),
            cells: core::array::from_fn(|i| GainCell::new(i, N)),
            row_word: ChoiceWord::new(N),
            prev_word: ChoiceWord::new(N),
            col_a_valid: core::array::from_fn(|_| Default::default()),
            col_a_hi: core::array::from_fn(|_| Default::default()),
            col_a_pos: core::array::from_fn(|_| Default::default()),
            col_a_lev0: core::array::from_fn(|_| Default::default()),
            col_a_lev1: core::array::from_fn(|_| Default::default()),
            col_a_lev2: core::array::from_fn(|_| Default::default()),
            col_a_lev3: core::array::from_fn(|_| Default::default()),
            col_a_lev4: core::array::from_fn(|_| Default::default()),
            col_a_lev5: core::array::from_fn(|_| Default::default()),
            col_a_rising: core::array::from_fn(|_| Default::default()),
            col_b_valid: core::array::from_fn(|_| Default::default()),
            col_b_hi: core::array::from_fn(|_| Default::default()),
            col_b_pos: core::array::from_fn(|_| Default::default()),
            col_b_lev0: core::array::from_fn(|_| Default::default()),
            col_b_lev1: core::array::from_fn(|_| Default::default()),
            col_b_lev2: core::array::from_fn(|_| Default::default()),
            col_b_lev3: core::array::from_fn(|_| Default::default()),
            col_b_lev4: core::array::from_fn(|_| Default::default()),
            col_b_lev5: core::array::from_fn(|_| Default::default()),
            col_b_rising: core::array::from_fn(|_| Default::default()),
            k_dispmax_m1: core::array::from_fn(|_| Default::default()),
            k_below2: core::array::from_fn(|_| Default::default()),
            k_f1: core::array::from_fn(|_| Default::default()),
            k_f3: core::array::from_fn(|_| Default::default()),
            tok_lo: core::array::from_fn(|_| Default::default()),
            tok_hi: core::array::from_fn(|_| Default::default()),
            wrap: Default::default(),
            word_q: core::array::from_fn(|_| Default::default()),
            lo_ram: core::array::from_fn(|_| Default::default()),
            hi_ram: core::array::from_fn(|_| Default::default()),
            rd2_lo: core::array::from_fn(|_| Default::default()),
            rd2_hi: core::array::from_fn(|_| Default::default()),
            last_p: Default::default(),
            group_one: Constant::new(1u64.into()),
            wacc: core::array::from_fn(|_| Default::default()),
        }
    }
}

impl<const N: usize> Logic for SystolicMatcher<N> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..N {
            self.cells[i].clock.next = self.clock.val();
            self.cells[i].ld_pos.next = self.ld_pos.val();
            self.cells[i].ld_lev0.next = self.ld_lev0.val();
            self.cells[i].ld_lev1.next = self.ld_lev1.val();
            self.cells[i].ld_lev2.next = self.ld_lev2.val();
            self.cells[i].ld_lev3.next = self.ld_lev3.val();
            self.cells[i].ld_lev4.next = self.ld_lev4.val();
            self.cells[i].ld_lev5.next = self.ld_lev5.val();
            self.cells[i].ld_rising.next = self.ld_rising.val();
            self.cells[i].same_polarity.next = self.same_polarity.val();
            self.cells[i].one_sided.next = self.one_sided.val();
        }
        // The load tokens: reference r is on the broadcast when the low
        // token is in cell r (r < N) or the high token in cell r - N; they
        // enter cell 0 with references 0 and N and move one cell per clock
        // as the references follow one another.
        for i in 0..N {
            self.tok_lo[i].clock.next = self.clock.val();
            self.tok_hi[i].clock.next = self.clock.val();
            self.cells[i].ld_lo.next = self.tok_lo[i].q.val();
            self.cells[i].ld_hi.next = self.tok_hi[i].q.val();
        }
        for i in 0..1 {
            self.tok_lo[i].d.next = self.ld_first.val();
            self.tok_hi[i].d.next = self.ld_first_hi.val();
        }
        for i in 1..N {
            self.tok_lo[i].d.next = self.tok_lo[i - 1].q.val();
            self.tok_hi[i].d.next = self.tok_hi[i - 1].q.val();
        }
        // The line's constants travel down the array one cell per clock (a
        // register in every cell: no wire crosses the array; a cell's first
        // node of a line comes more than i clocks after the engine sets them).
        for i in 0..N {
            self.k_dispmax_m1[i].clock.next = self.clock.val();
            self.cells[i].dispmax_m1.next = self.k_dispmax_m1[i].q.val();
            self.k_below2[i].clock.next = self.clock.val();
            self.cells[i].below2.next = self.k_below2[i].q.val();
            self.k_f1[i].clock.next = self.clock.val();
            self.cells[i].f1.next = self.k_f1[i].q.val();
            self.k_f3[i].clock.next = self.clock.val();
            self.cells[i].f3.next = self.k_f3[i].q.val();
        }
        for i in 0..1 {
            self.k_dispmax_m1[i].d.next = self.dispmax_m1.val();
            self.k_below2[i].d.next = self.below2.val();
            self.k_f1[i].d.next = self.f1.val();
            self.k_f3[i].d.next = self.f3.val();
        }
        for i in 1..N {
            self.k_dispmax_m1[i].d.next = self.k_dispmax_m1[i - 1].q.val();
            self.k_below2[i].d.next = self.k_below2[i - 1].q.val();
            self.k_f1[i].d.next = self.k_f1[i - 1].q.val();
            self.k_f3[i].d.next = self.k_f3[i - 1].q.val();
        }
        // The column pipeline: two slots per cell, `col_b[i]` then
        // `col_a[i]` (cell i's); slot b of cell 0 takes the stream. A column
        // moves one slot per clock; a bubble moves as one. The cell selects
        // its reference by the pass of the column in its slot b.
        for i in 0..N {
            self.col_a_valid[i].clock.next = self.clock.val();
            self.col_b_valid[i].clock.next = self.clock.val();
            self.col_a_hi[i].clock.next = self.clock.val();
            self.col_b_hi[i].clock.next = self.clock.val();
            self.col_a_pos[i].clock.next = self.clock.val();
            self.col_b_pos[i].clock.next = self.clock.val();
            self.col_a_lev0[i].clock.next = self.clock.val();
            self.col_b_lev0[i].clock.next = self.clock.val();
            self.col_a_lev1[i].clock.next = self.clock.val();
            self.col_b_lev1[i].clock.next = self.clock.val();
            self.col_a_lev2[i].clock.next = self.clock.val();
            self.col_b_lev2[i].clock.next = self.clock.val();
            self.col_a_lev3[i].clock.next = self.clock.val();
            self.col_b_lev3[i].clock.next = self.clock.val();
            self.col_a_lev4[i].clock.next = self.clock.val();
            self.col_b_lev4[i].clock.next = self.clock.val();
            self.col_a_lev5[i].clock.next = self.clock.val();
            self.col_b_lev5[i].clock.next = self.clock.val();
            self.col_a_rising[i].clock.next = self.clock.val();
            self.col_b_rising[i].clock.next = self.clock.val();
            self.col_a_hi[i].d.next = self.col_a_hi[i].q.val();
            self.col_b_hi[i].d.next = self.col_b_hi[i].q.val();
            self.col_a_pos[i].d.next = self.col_a_pos[i].q.val();
            self.col_b_pos[i].d.next = self.col_b_pos[i].q.val();
            self.col_a_lev0[i].d.next = self.col_a_lev0[i].q.val();
            self.col_b_lev0[i].d.next = self.col_b_lev0[i].q.val();
            self.col_a_lev1[i].d.next = self.col_a_lev1[i].q.val();
            self.col_b_lev1[i].d.next = self.col_b_lev1[i].q.val();
            self.col_a_lev2[i].d.next = self.col_a_lev2[i].q.val();
            self.col_b_lev2[i].d.next = self.col_b_lev2[i].q.val();
            self.col_a_lev3[i].d.next = self.col_a_lev3[i].q.val();
            self.col_b_lev3[i].d.next = self.col_b_lev3[i].q.val();
            self.col_a_lev4[i].d.next = self.col_a_lev4[i].q.val();
            self.col_b_lev4[i].d.next = self.col_b_lev4[i].q.val();
            self.col_a_lev5[i].d.next = self.col_a_lev5[i].q.val();
            self.col_b_lev5[i].d.next = self.col_b_lev5[i].q.val();
            self.col_a_rising[i].d.next = self.col_a_rising[i].q.val();
            self.col_b_rising[i].d.next = self.col_b_rising[i].q.val();
            self.col_a_valid[i].d.next = self.col_b_valid[i].q.val();
            if self.col_b_valid[i].q.val() {
                self.col_a_hi[i].d.next = self.col_b_hi[i].q.val();
                self.col_a_pos[i].d.next = self.col_b_pos[i].q.val();
                self.col_a_lev0[i].d.next = self.col_b_lev0[i].q.val();
                self.col_a_lev1[i].d.next = self.col_b_lev1[i].q.val();
                self.col_a_lev2[i].d.next = self.col_b_lev2[i].q.val();
                self.col_a_lev3[i].d.next = self.col_b_lev3[i].q.val();
                self.col_a_lev4[i].d.next = self.col_b_lev4[i].q.val();
                self.col_a_lev5[i].d.next = self.col_b_lev5[i].q.val();
                self.col_a_rising[i].d.next = self.col_b_rising[i].q.val();
            }
            self.cells[i].c_valid.next = self.col_a_valid[i].q.val();
            self.cells[i].c_hi.next = self.col_a_hi[i].q.val();
            self.cells[i].c_pos.next = self.col_a_pos[i].q.val();
            self.cells[i].c_lev0.next = self.col_a_lev0[i].q.val();
            self.cells[i].c_lev1.next = self.col_a_lev1[i].q.val();
            self.cells[i].c_lev2.next = self.col_a_lev2[i].q.val();
            self.cells[i].c_lev3.next = self.col_a_lev3[i].q.val();
            self.cells[i].c_lev4.next = self.col_a_lev4[i].q.val();
            self.cells[i].c_lev5.next = self.col_a_lev5[i].q.val();
            self.cells[i].c_rising.next = self.col_a_rising[i].q.val();
            self.cells[i].c_hi_next.next = self.col_b_hi[i].q.val();
        }
        for i in 0..1 {
            self.col_b_valid[i].d.next = self.c_valid.val();
            if self.c_valid.val() {
                self.col_b_hi[i].d.next = self.c_hi.val();
                self.col_b_pos[i].d.next = self.c_pos.val();
                self.col_b_lev0[i].d.next = self.c_lev0.val();
                self.col_b_lev1[i].d.next = self.c_lev1.val();
                self.col_b_lev2[i].d.next = self.c_lev2.val();
                self.col_b_lev3[i].d.next = self.c_lev3.val();
                self.col_b_lev4[i].d.next = self.c_lev4.val();
                self.col_b_lev5[i].d.next = self.c_lev5.val();
                self.col_b_rising[i].d.next = self.c_rising.val();
            }
        }
        for i in 1..N {
            self.col_b_valid[i].d.next = self.col_a_valid[i - 1].q.val();
            if self.col_a_valid[i - 1].q.val() {
                self.col_b_hi[i].d.next = self.col_a_hi[i - 1].q.val();
                self.col_b_pos[i].d.next = self.col_a_pos[i - 1].q.val();
                self.col_b_lev0[i].d.next = self.col_a_lev0[i - 1].q.val();
                self.col_b_lev1[i].d.next = self.col_a_lev1[i - 1].q.val();
                self.col_b_lev2[i].d.next = self.col_a_lev2[i - 1].q.val();
                self.col_b_lev3[i].d.next = self.col_a_lev3[i - 1].q.val();
                self.col_b_lev4[i].d.next = self.col_a_lev4[i - 1].q.val();
                self.col_b_lev5[i].d.next = self.col_a_lev5[i - 1].q.val();
                self.col_b_rising[i].d.next = self.col_a_rising[i - 1].q.val();
            }
        }
        // The recurrence: the cell above's P; for cell 0, the last cell's,
        // one clock later (row N - 1 is three clocks ahead of row N).
        for i in 0..N {
            self.last_p.next = self.cells[i].p.val();
        }
        self.wrap.clock.next = self.clock.val();
        self.wrap.d.next = self.last_p.val();
        for i in 0..1 {
            self.cells[i].up_p.next = self.wrap.q.val();
        }
        for i in 1..N {
            self.cells[i].up_p.next = self.cells[i - 1].p.val();
        }

        // The choice memory: each cell's choice in its bits of its word
        // (the other cells show zeros there), registered, written as one
        // anti-diagonal of the low or high rows.
        for k in 0..CHOICE_WORDS {
            self.wacc[k].next = 0.into();
        }
        // (`i / 16` is `i / CELLS_PER_CHOICE_WORD`: rust-hdl evaluates an
        // index with literals only.)
        for i in 0..N {
            self.wacc[i / 16].next = self.wacc[i / 16].val() | self.cells[i].choice_word.val();
        }
        for k in 0..CHOICE_WORDS {
            self.word_q[k].clock.next = self.clock.val();
            self.word_q[k].d.next = self.wacc[k].val();
            self.lo_ram[k].clock.next = self.clock.val();
            self.hi_ram[k].clock.next = self.clock.val();
            self.lo_ram[k].write_address.next = self.cw_diag.val();
            self.hi_ram[k].write_address.next = self.cw_diag.val();
            self.lo_ram[k].write_data.next = self.word_q[k].q.val();
            self.hi_ram[k].write_data.next = self.word_q[k].q.val();
            self.lo_ram[k].write_enable.next = self.cw_en.val() & !self.cw_hi.val();
            self.hi_ram[k].write_enable.next = self.cw_en.val() & self.cw_hi.val();
            self.lo_ram[k].read_address.next = self.tb_diag.val();
            self.hi_ram[k].read_address.next = self.tb_diag.val();
            self.rd2_lo[k].clock.next = self.clock.val();
            self.rd2_hi[k].clock.next = self.clock.val();
            self.rd2_lo[k].d.next = self.lo_ram[k].read_data.val();
            self.rd2_hi[k].d.next = self.hi_ram[k].read_data.val();
        }

        // ---- Traceback reads: the words of groups tb_group and tb_group - 1.
        self.row_word.lo0.next = self.rd2_lo[0].q.val();
        self.row_word.hi0.next = self.rd2_hi[0].q.val();
        self.row_word.lo1.next = self.rd2_lo[1].q.val();
        self.row_word.hi1.next = self.rd2_hi[1].q.val();
        self.row_word.lo2.next = self.rd2_lo[2].q.val();
        self.row_word.hi2.next = self.rd2_hi[2].q.val();
        self.row_word.lo3.next = self.rd2_lo[3].q.val();
        self.row_word.hi3.next = self.rd2_hi[3].q.val();
        self.row_word.group.next = self.tb_group.val();
        self.prev_word.lo0.next = self.rd2_lo[0].q.val();
        self.prev_word.hi0.next = self.rd2_hi[0].q.val();
        self.prev_word.lo1.next = self.rd2_lo[1].q.val();
        self.prev_word.hi1.next = self.rd2_hi[1].q.val();
        self.prev_word.lo2.next = self.rd2_lo[2].q.val();
        self.prev_word.hi2.next = self.rd2_hi[2].q.val();
        self.prev_word.lo3.next = self.rd2_lo[3].q.val();
        self.prev_word.hi3.next = self.rd2_hi[3].q.val();
        self.prev_word.group.next = self.tb_group.val() - self.group_one.val();
        self.tb_word.next = self.row_word.word.val();
        self.tb_word_prev.next = self.prev_word.word.val();
    }
}
