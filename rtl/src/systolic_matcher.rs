//! The systolic array of the matcher (`DESIGN.md` §3): `N` [`GainCell`]s in
//! a line, cell `i` holding reference declivity `i`, the other view's
//! declivities streaming through the chain one cell per clock. Column `j`
//! reaches cell `i` `i` clocks after cell 0, so the `N × M` table of eq. 9
//! is swept in anti-diagonal wavefronts: the cells of anti-diagonal
//! `s = i + j` compute their `P` on the same clock.
//!
//! ## Ports
//! - `ld_*`: the reference-declivity broadcast, to every cell (the cell
//!   whose index is `ld_index` takes it).
//! - `c_*`: the column stream, into the first slot of the column pipeline
//!   (one register slot per cell, slot i read by cell i).
//! - `dispmax`, `below2`, `f1`, `f3`, `same_polarity`, `one_sided`: to every
//!   cell (see [`GainCell`]).
//! - `tb_diag`, `tb_row`, `tb_row_up` in; `tb_choice`, `tb_choice_up` out:
//!   the choices of cells `tb_row` and `tb_row_up` in anti-diagonal
//!   `tb_diag` read one clock earlier, each the OR of the cells' outputs
//!   (the others show zero).
//!
//! ## Timing
//! Column `j` offered on `c_*` at clock `t - 1` sits in slot 0 at `t` and gives `P(i, j)` at the
//! end of clock `t + i +` [`CELL_DEPTH`] `- 1`. Cell 0's `P(i-1, ·)` is the
//! border, 0. Eq. 9 in `N + M - 1` wavefronts plus the cells' depth.

use crate::gain_cell::GainCell;
use crate::params::*;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct SystolicMatcher<const N: usize> {
    pub clock: Signal<In, Clock>,
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
    pub dispmax: Signal<In, Bits<DISPMAX_BITS>>,
    pub below2: Signal<In, Bits<DIST_BITS>>,
    pub f1: Signal<In, Bits<GAIN_BITS>>,
    pub f3: Signal<In, Bits<GAIN_BITS>>,
    pub same_polarity: Signal<In, Bit>,
    pub one_sided: Signal<In, Bit>,
    pub tb_diag: Signal<In, Bits<DIAG_BITS>>,
    pub tb_row: Signal<In, Bits<INDEX_BITS>>,
    pub tb_row_up: Signal<In, Bits<INDEX_BITS>>,
    pub tb_choice: Signal<Out, Bits<2>>,
    pub tb_choice_up: Signal<Out, Bits<2>>,
    pub cells: [GainCell; N],
    // P of each cell.
    p_reg: [DFF<Bits<PATH_BITS>>; N],
    // The column pipeline: slot i is cell i's column.
    col_valid: [DFF<Bit>; N],
    col_first: [DFF<Bit>; N],
    col_j: [DFF<Bits<INDEX_BITS>>; N],
    col_pos: [DFF<Bits<POS_BITS>>; N],
    col_lev0: [DFF<Bits<LEVEL_BITS>>; N],
    col_lev1: [DFF<Bits<LEVEL_BITS>>; N],
    col_lev2: [DFF<Bits<LEVEL_BITS>>; N],
    col_lev3: [DFF<Bits<LEVEL_BITS>>; N],
    col_lev4: [DFF<Bits<LEVEL_BITS>>; N],
    col_lev5: [DFF<Bits<LEVEL_BITS>>; N],
    col_rising: [DFF<Bit>; N],
    choice_or: Signal<Local, Bits<2>>,
    choice_up_or: Signal<Local, Bits<2>>,
}

impl<const N: usize> Default for SystolicMatcher<N> {
    fn default() -> Self {
        assert!((1..=N_MAX).contains(&N), "1 ..= N_MAX cells");
        SystolicMatcher {
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
            cells: core::array::from_fn(GainCell::new),
            p_reg: core::array::from_fn(|_| Default::default()),
            col_valid: core::array::from_fn(|_| Default::default()),
            col_first: core::array::from_fn(|_| Default::default()),
            col_j: core::array::from_fn(|_| Default::default()),
            col_pos: core::array::from_fn(|_| Default::default()),
            col_lev0: core::array::from_fn(|_| Default::default()),
            col_lev1: core::array::from_fn(|_| Default::default()),
            col_lev2: core::array::from_fn(|_| Default::default()),
            col_lev3: core::array::from_fn(|_| Default::default()),
            col_lev4: core::array::from_fn(|_| Default::default()),
            col_lev5: core::array::from_fn(|_| Default::default()),
            col_rising: core::array::from_fn(|_| Default::default()),
            choice_or: Default::default(),
            choice_up_or: Default::default(),
        }
    }
}

impl<const N: usize> Logic for SystolicMatcher<N> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..N {
            self.cells[i].clock.next = self.clock.val();
            self.cells[i].ld_valid.next = self.ld_valid.val();
            self.cells[i].ld_index.next = self.ld_index.val();
            self.cells[i].ld_pos.next = self.ld_pos.val();
            self.cells[i].ld_lev0.next = self.ld_lev0.val();
            self.cells[i].ld_lev1.next = self.ld_lev1.val();
            self.cells[i].ld_lev2.next = self.ld_lev2.val();
            self.cells[i].ld_lev3.next = self.ld_lev3.val();
            self.cells[i].ld_lev4.next = self.ld_lev4.val();
            self.cells[i].ld_lev5.next = self.ld_lev5.val();
            self.cells[i].ld_rising.next = self.ld_rising.val();
            self.cells[i].dispmax.next = self.dispmax.val();
            self.cells[i].below2.next = self.below2.val();
            self.cells[i].f1.next = self.f1.val();
            self.cells[i].f3.next = self.f3.val();
            self.cells[i].same_polarity.next = self.same_polarity.val();
            self.cells[i].one_sided.next = self.one_sided.val();
            self.cells[i].tb_diag.next = self.tb_diag.val();
            self.cells[i].tb_row.next = self.tb_row.val();
            self.cells[i].tb_row_up.next = self.tb_row_up.val();
        }
        // The column pipeline: slot 0 takes the stream, slot i the column
        // of slot i - 1; a bubble moves as one. Cell i reads slot i.
        for i in 0..N {
            self.p_reg[i].clock.next = self.clock.val();
            self.p_reg[i].d.next = self.p_reg[i].q.val();
            if self.cells[i].p_clear.val() {
                self.p_reg[i].d.next = 0.into();
            }
            if self.cells[i].p_load.val() {
                self.p_reg[i].d.next = self.cells[i].p_next.val();
            }
            self.cells[i].own_p.next = self.p_reg[i].q.val();
            self.col_valid[i].clock.next = self.clock.val();
            self.col_first[i].clock.next = self.clock.val();
            self.col_j[i].clock.next = self.clock.val();
            self.col_pos[i].clock.next = self.clock.val();
            self.col_lev0[i].clock.next = self.clock.val();
            self.col_lev1[i].clock.next = self.clock.val();
            self.col_lev2[i].clock.next = self.clock.val();
            self.col_lev3[i].clock.next = self.clock.val();
            self.col_lev4[i].clock.next = self.clock.val();
            self.col_lev5[i].clock.next = self.clock.val();
            self.col_rising[i].clock.next = self.clock.val();
            self.col_valid[i].d.next = self.col_valid[i].q.val();
            self.col_first[i].d.next = self.col_first[i].q.val();
            self.col_j[i].d.next = self.col_j[i].q.val();
            self.col_pos[i].d.next = self.col_pos[i].q.val();
            self.col_lev0[i].d.next = self.col_lev0[i].q.val();
            self.col_lev1[i].d.next = self.col_lev1[i].q.val();
            self.col_lev2[i].d.next = self.col_lev2[i].q.val();
            self.col_lev3[i].d.next = self.col_lev3[i].q.val();
            self.col_lev4[i].d.next = self.col_lev4[i].q.val();
            self.col_lev5[i].d.next = self.col_lev5[i].q.val();
            self.col_rising[i].d.next = self.col_rising[i].q.val();
        }
        for i in 0..1 {
            self.col_valid[i].d.next = self.c_valid.val();
            if self.c_valid.val() {
                self.col_first[i].d.next = self.c_first.val();
                self.col_j[i].d.next = self.c_j.val();
                self.col_pos[i].d.next = self.c_pos.val();
                self.col_lev0[i].d.next = self.c_lev0.val();
                self.col_lev1[i].d.next = self.c_lev1.val();
                self.col_lev2[i].d.next = self.c_lev2.val();
                self.col_lev3[i].d.next = self.c_lev3.val();
                self.col_lev4[i].d.next = self.c_lev4.val();
                self.col_lev5[i].d.next = self.c_lev5.val();
                self.col_rising[i].d.next = self.c_rising.val();
            }
            self.cells[i].up_p.next = 0.into();
        }
        for i in 1..N {
            self.col_valid[i].d.next = self.col_valid[i - 1].q.val();
            if self.col_valid[i - 1].q.val() {
                self.col_first[i].d.next = self.col_first[i - 1].q.val();
                self.col_j[i].d.next = self.col_j[i - 1].q.val();
                self.col_pos[i].d.next = self.col_pos[i - 1].q.val();
                self.col_lev0[i].d.next = self.col_lev0[i - 1].q.val();
                self.col_lev1[i].d.next = self.col_lev1[i - 1].q.val();
                self.col_lev2[i].d.next = self.col_lev2[i - 1].q.val();
                self.col_lev3[i].d.next = self.col_lev3[i - 1].q.val();
                self.col_lev4[i].d.next = self.col_lev4[i - 1].q.val();
                self.col_lev5[i].d.next = self.col_lev5[i - 1].q.val();
                self.col_rising[i].d.next = self.col_rising[i - 1].q.val();
            }
            self.cells[i].up_p.next = self.p_reg[i - 1].q.val();
        }
        for i in 0..N {
            self.cells[i].c_valid.next = self.col_valid[i].q.val();
            self.cells[i].c_first.next = self.col_first[i].q.val();
            self.cells[i].c_j.next = self.col_j[i].q.val();
            self.cells[i].c_pos.next = self.col_pos[i].q.val();
            self.cells[i].c_lev0.next = self.col_lev0[i].q.val();
            self.cells[i].c_lev1.next = self.col_lev1[i].q.val();
            self.cells[i].c_lev2.next = self.col_lev2[i].q.val();
            self.cells[i].c_lev3.next = self.col_lev3[i].q.val();
            self.cells[i].c_lev4.next = self.col_lev4[i].q.val();
            self.cells[i].c_lev5.next = self.col_lev5[i].q.val();
            self.cells[i].c_rising.next = self.col_rising[i].q.val();
        }
        self.choice_or.next = 0.into();
        for i in 0..N {
            self.choice_or.next = self.choice_or.val() | self.cells[i].tb_choice.val();
        }
        self.tb_choice.next = self.choice_or.val();
        self.choice_up_or.next = 0.into();
        for i in 0..N {
            self.choice_up_or.next = self.choice_up_or.val() | self.cells[i].tb_choice_up.val();
        }
        self.tb_choice_up.next = self.choice_up_or.val();

    }
}
