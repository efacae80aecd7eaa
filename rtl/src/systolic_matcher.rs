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
//! - `c_*`: the column stream into cell 0.
//! - `dispmax`, `below2`, `f1`, `f3`, `same_polarity`, `one_sided`: to every
//!   cell (see [`GainCell`]).
//! - `tb_diag`, `tb_row` in; `tb_choice` out: the choice of cell `tb_row`
//!   in anti-diagonal `tb_diag` read one clock earlier, the OR of the
//!   cells' outputs (the others show zero).
//!
//! ## Timing
//! Column `j` entering cell 0's registers at clock `t` gives `P(i, j)` at the
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
    pub tb_choice: Signal<Out, Bits<2>>,
    pub cells: [GainCell; N],
    choice_or: Signal<Local, Bits<2>>,
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
            tb_choice: Default::default(),
            cells: core::array::from_fn(GainCell::new),
            choice_or: Default::default(),
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
        }
        // Cell 0 takes the stream; its P(i-1, ·) is the border.
        for i in 0..1 {
            self.cells[i].c_valid.next = self.c_valid.val();
            self.cells[i].c_first.next = self.c_first.val();
            self.cells[i].c_j.next = self.c_j.val();
            self.cells[i].c_pos.next = self.c_pos.val();
            self.cells[i].c_lev0.next = self.c_lev0.val();
            self.cells[i].c_lev1.next = self.c_lev1.val();
            self.cells[i].c_lev2.next = self.c_lev2.val();
            self.cells[i].c_lev3.next = self.c_lev3.val();
            self.cells[i].c_lev4.next = self.c_lev4.val();
            self.cells[i].c_lev5.next = self.c_lev5.val();
            self.cells[i].c_rising.next = self.c_rising.val();
            self.cells[i].up_p.next = 0.into();
        }
        for i in 1..N {
            self.cells[i].c_valid.next = self.cells[i - 1].o_valid.val();
            self.cells[i].c_first.next = self.cells[i - 1].o_first.val();
            self.cells[i].c_j.next = self.cells[i - 1].o_j.val();
            self.cells[i].c_pos.next = self.cells[i - 1].o_pos.val();
            self.cells[i].c_lev0.next = self.cells[i - 1].o_lev0.val();
            self.cells[i].c_lev1.next = self.cells[i - 1].o_lev1.val();
            self.cells[i].c_lev2.next = self.cells[i - 1].o_lev2.val();
            self.cells[i].c_lev3.next = self.cells[i - 1].o_lev3.val();
            self.cells[i].c_lev4.next = self.cells[i - 1].o_lev4.val();
            self.cells[i].c_lev5.next = self.cells[i - 1].o_lev5.val();
            self.cells[i].c_rising.next = self.cells[i - 1].o_rising.val();
            self.cells[i].up_p.next = self.cells[i - 1].p.val();
        }
        self.choice_or.next = 0.into();
        for i in 0..N {
            self.choice_or.next = self.choice_or.val() | self.cells[i].tb_choice.val();
        }
        self.tb_choice.next = self.choice_or.val();
    }
}
