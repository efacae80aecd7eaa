//! The traceback of eq. 9's optimal path (`golden::dp::traceback`): from
//! `P(N, M)` back along the cells' 2-bit choices, `node` taking the pair and
//! moving to `(i-1, j-1)`, `up` to `(i-1, j)`, `left` to `(i, j-1)`, `start`
//! ending the path; then the pairs in reference order.
//!
//! Every move lowers the anti-diagonal `i + j` by one (up, left) or two
//! (node). So the walk reads the anti-diagonals in falling order, one per
//! clock, whatever the path does: the array's choice memory, one word per
//! anti-diagonal, is read at addresses known in advance (`tb_diag`), and
//! the walker only picks its row's choice of the anti-diagonal read three
//! clocks before (memory, then two registers), and skips the
//! anti-diagonal a node jumps over. The row's choice is a selection out of
//! the whole word, so it is registered: while the walker decides on one
//! anti-diagonal, the array already shows the next one's choices of both
//! rows the decision can leave it on (`tb_row` = its row, `tb_row_up` = the
//! row above), and the next decision takes the right one. The pairs come
//! out last first; a small stack turns them round.
//!
//! ## Ports
//! - `start` (a pulse), `n`, `m`: the line's declivity counts; `start` is
//!   taken in the idle state only.
//! - To the array: `tb_diag`, `tb_row`, `tb_row_up`; from it, `tb_choice`
//!   and `tb_choice_up` (the two rows' choices).
//! - Out: `out_valid`, `out_i`, `out_j` (a matched pair, reference order),
//!   then `out_last` with `out_count` (pairs of the line) for one clock.
//!
//! ## Timing
//! After `start` at clock `t`, the walk reads anti-diagonal `n + m - 2`
//! at `t + 1`, has it at `t + 3`, registers its row's choice at `t + 4` and
//! decides on it at `t + 5`, then one anti-diagonal per clock
//! until the path starts (at most `n + m - 1` decisions); the `K` pairs
//! then leave on consecutive clocks from two clocks after the last
//! decision, and `out_last` one clock after the last pair: in all
//! [`traceback_cycles`] clocks from `start` to `out_last`, at most
//! `n + m + K + 5`.

use crate::gain_cell::{CHOICE_LEFT, CHOICE_NODE, CHOICE_START, CHOICE_UP};
use crate::params::*;
use rust_hdl::prelude::*;

const TB_IDLE: u64 = 0;
const TB_WALK: u64 = 1;
const TB_EMIT: u64 = 2;

/// Clocks from `start` to `out_last` for a line of `n` reference and `m`
/// other declivities whose walk stops on anti-diagonal `stop_diag` (the
/// `i + j` of the cell whose choice is `start`, or of the border cell it
/// left last) with `k` pairs: five to the first decision, one per
/// anti-diagonal from `n + m - 2` down to `stop_diag`, and `k + 2` to
/// empty the stack (the first address, one read per pair, then the marker;
/// just the marker when `k = 0`). An empty line (`n` or `m` zero) takes one.
pub const fn traceback_cycles(n: usize, m: usize, stop_diag: usize, k: usize) -> usize {
    if n == 0 || m == 0 {
        return 1;
    }
    let emit = if k == 0 { 1 } else { k + 2 };
    5 + (n + m - 2 - stop_diag) + emit
}

#[derive(LogicBlock)]
pub struct Traceback {
    pub clock: Signal<In, Clock>,
    pub start: Signal<In, Bit>,
    pub n: Signal<In, Bits<COUNT_BITS>>,
    pub m: Signal<In, Bits<COUNT_BITS>>,
    pub tb_diag: Signal<Out, Bits<DIAG_BITS>>,
    pub tb_row: Signal<Out, Bits<INDEX_BITS>>,
    pub tb_row_up: Signal<Out, Bits<INDEX_BITS>>,
    pub tb_choice: Signal<In, Bits<2>>,
    pub tb_choice_up: Signal<In, Bits<2>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_i: Signal<Out, Bits<INDEX_BITS>>,
    pub out_j: Signal<Out, Bits<INDEX_BITS>>,
    pub out_last: Signal<Out, Bit>,
    pub out_count: Signal<Out, Bits<COUNT_BITS>>,
    stack_i: RAM<Bits<INDEX_BITS>, INDEX_BITS>,
    stack_j: RAM<Bits<INDEX_BITS>, INDEX_BITS>,
    state: DFF<Bits<2>>,
    diag: DFF<Bits<DIAG_BITS>>,
    wi: DFF<Bits<INDEX_BITS>>,
    wj: DFF<Bits<INDEX_BITS>>,
    wi_up: DFF<Bits<INDEX_BITS>>,
    primed: DFF<Bit>,
    primed2: DFF<Bit>,
    primed3: DFF<Bit>,
    primed4: DFF<Bit>,
    moved: DFF<Bit>,
    here: DFF<Bits<2>>,
    above: DFF<Bits<2>>,
    skip: DFF<Bit>,
    count: DFF<Bits<COUNT_BITS>>,
    left: DFF<Bits<COUNT_BITS>>,
    k: DFF<Bits<INDEX_BITS>>,
    pend: DFF<Bit>,
    choice: Signal<Local, Bits<2>>,
    push: Signal<Local, Bit>,
    stop: Signal<Local, Bit>,
    issue: Signal<Local, Bit>,
    st_idle: Constant<Bits<2>>,
    st_walk: Constant<Bits<2>>,
    st_emit: Constant<Bits<2>>,
    c_start: Constant<Bits<2>>,
    c_node: Constant<Bits<2>>,
    c_up: Constant<Bits<2>>,
    c_left: Constant<Bits<2>>,
}

impl Default for Traceback {
    fn default() -> Self {
        let c2 = |v: u64| Constant::new(v.into());
        Traceback {
            clock: Default::default(),
            start: Default::default(),
            n: Default::default(),
            m: Default::default(),
            tb_diag: Default::default(),
            tb_row: Default::default(),
            tb_row_up: Default::default(),
            tb_choice: Default::default(),
            tb_choice_up: Default::default(),
            out_valid: Default::default(),
            out_i: Default::default(),
            out_j: Default::default(),
            out_last: Default::default(),
            out_count: Default::default(),
            stack_i: Default::default(),
            stack_j: Default::default(),
            state: Default::default(),
            diag: Default::default(),
            wi: Default::default(),
            wj: Default::default(),
            wi_up: Default::default(),
            primed: Default::default(),
            primed2: Default::default(),
            primed3: Default::default(),
            primed4: Default::default(),
            moved: Default::default(),
            here: Default::default(),
            above: Default::default(),
            skip: Default::default(),
            count: Default::default(),
            left: Default::default(),
            k: Default::default(),
            pend: Default::default(),
            choice: Default::default(),
            push: Default::default(),
            stop: Default::default(),
            issue: Default::default(),
            st_idle: c2(TB_IDLE),
            st_walk: c2(TB_WALK),
            st_emit: c2(TB_EMIT),
            c_start: c2(CHOICE_START),
            c_node: c2(CHOICE_NODE),
            c_up: c2(CHOICE_UP),
            c_left: c2(CHOICE_LEFT),
        }
    }
}

impl Logic for Traceback {
    #[hdl_gen]
    fn update(&mut self) {
        self.stack_i.read_clock.next = self.clock.val();
        self.stack_i.write_clock.next = self.clock.val();
        self.stack_j.read_clock.next = self.clock.val();
        self.stack_j.write_clock.next = self.clock.val();
        dff_setup!(self, clock, state, diag, wi, wj, wi_up, primed, primed2, primed3, primed4, moved, here, above, skip, count, left, k, pend);

        self.tb_diag.next = self.diag.q.val();
        self.tb_row.next = self.wi.q.val();
        self.tb_row_up.next = self.wi_up.q.val();
        // The array's choices of rows wi and wi - 1, registered: the
        // decision on the next clock takes the one of the row it is then on.
        self.here.d.next = self.tb_choice.val();
        self.above.d.next = self.tb_choice_up.val();
        self.choice.next = self.here.q.val();
        if self.moved.q.val() {
            self.choice.next = self.above.q.val();
        }
        self.moved.d.next = false;
        self.push.next = false;
        self.stop.next = false;
        self.issue.next = false;
        self.stack_i.write_address.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.count.q.val());
        self.stack_j.write_address.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.count.q.val());
        self.stack_i.write_data.next = self.wi.q.val();
        self.stack_j.write_data.next = self.wj.q.val();
        self.stack_i.read_address.next = self.k.q.val();
        self.stack_j.read_address.next = self.k.q.val();
        self.pend.d.next = false;
        self.out_last.next = false;
        self.out_count.next = self.count.q.val();

        if self.state.q.val() == self.st_idle.val() {
            if self.start.val() {
                self.count.d.next = 0.into();
                self.primed.d.next = false;
                self.primed2.d.next = false;
                self.primed3.d.next = false;
                self.primed4.d.next = false;
                self.skip.d.next = false;
                self.wi.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.n.val() - 1);
                self.wi_up.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.n.val() - 2);
                self.wj.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.m.val() - 1);
                self.diag.d.next = bit_cast::<DIAG_BITS, COUNT_BITS>(self.n.val() - 1)
                    + bit_cast::<DIAG_BITS, COUNT_BITS>(self.m.val() - 1);
                self.state.d.next = self.st_walk.val();
                if !self.n.val().any() | !self.m.val().any() {
                    self.left.d.next = 0.into();
                    self.state.d.next = self.st_emit.val();
                }
            }
        }
        if self.state.q.val() == self.st_walk.val() {
            // The anti-diagonal read this clock is decided on the next.
            self.diag.d.next = self.diag.q.val() - 1;
            self.primed.d.next = true;
            self.primed2.d.next = self.primed.q.val();
            self.primed3.d.next = self.primed2.q.val();
            self.primed4.d.next = self.primed3.q.val();
            if self.primed4.q.val() {
                if self.skip.q.val() {
                    self.skip.d.next = false;
                } else {
                    if self.choice.val() == self.c_start.val() {
                        self.stop.next = true;
                    }
                    if self.choice.val() == self.c_node.val() {
                        self.push.next = true;
                        self.skip.d.next = true;
                        self.moved.d.next = true;
                        self.wi.d.next = self.wi.q.val() - 1;
                        self.wi_up.d.next = self.wi_up.q.val() - 1;
                        self.wj.d.next = self.wj.q.val() - 1;
                        self.stop.next = !self.wi.q.val().any() | !self.wj.q.val().any();
                    }
                    if self.choice.val() == self.c_up.val() {
                        self.moved.d.next = true;
                        self.wi.d.next = self.wi.q.val() - 1;
                        self.wi_up.d.next = self.wi_up.q.val() - 1;
                        self.stop.next = !self.wi.q.val().any();
                    }
                    if self.choice.val() == self.c_left.val() {
                        self.wj.d.next = self.wj.q.val() - 1;
                        self.stop.next = !self.wj.q.val().any();
                    }
                }
            }
            if self.push.val() {
                self.count.d.next = self.count.q.val() + 1;
            }
            if self.stop.val() {
                self.state.d.next = self.st_emit.val();
                self.left.d.next = self.count.q.val();
                if self.push.val() {
                    self.left.d.next = self.count.q.val() + 1;
                }
                // The last pair pushed is read first.
                self.k.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.count.q.val() - 1);
                if self.push.val() {
                    self.k.d.next = bit_cast::<INDEX_BITS, COUNT_BITS>(self.count.q.val());
                }
            }
        }
        if self.state.q.val() == self.st_emit.val() {
            self.issue.next = self.left.q.val().any();
            if self.issue.val() {
                self.k.d.next = self.k.q.val() - 1;
                self.left.d.next = self.left.q.val() - 1;
                self.pend.d.next = true;
            }
            if !self.issue.val() & !self.pend.q.val() {
                self.out_last.next = true;
                self.state.d.next = self.st_idle.val();
            }
        }
        self.stack_i.write_enable.next = self.push.val();
        self.stack_j.write_enable.next = self.push.val();
        self.out_valid.next = self.pend.q.val();
        self.out_i.next = self.stack_i.read_data.val();
        self.out_j.next = self.stack_j.read_data.val();
    }
}
