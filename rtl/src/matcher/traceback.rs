//! The traceback of eq. 9's optimal path (`golden::dp::traceback`): from
//! `P(N, M)` back along the cells' 2-bit choices, `node` taking the pair and
//! moving to `(i-1, j-1)`, `up` to `(i-1, j)`, `left` to `(i, j-1)`, `start`
//! ending the path; then the pairs in reference order.
//!
//! Every move lowers the anti-diagonal `i + j` by one (up, left) or two
//! (node). So the walk reads the anti-diagonals in falling order, one per
//! clock, whatever the path does: the array's choice memory, one word per
//! anti-diagonal, is read at addresses known in advance (`tb_diag`), and
//! the walker picks its row's choice of the anti-diagonal read
//! [`WALK_LEAD`] (six) clocks before, and skips the anti-diagonal a node
//! jumps over.
//!
//! The pick is an [`N_MAX`]-way selection, too slow for one clock beside the
//! decision, so it is spread over three, using that the row falls by at
//! most one per clock. With the word read (memory, then a register in the
//! array) the array selects the two 16-row words that hold the walker's row
//! `r` now and the rows below it (`tb_group` = `⌊r/16⌋`, `tb_word`,
//! `tb_word_prev`);
//! they are registered. Next clock, the choices of rows `r .. r - 3` are
//! picked out of the two (16-way each) and registered. Next clock the
//! walker has moved by 0, 1 or 2 rows (`moved`, `moved2`): the choices of
//! its row and the row above it are taken out of the four and registered,
//! and the decision on the clock after that takes the one of the row it is
//! then on. The pairs come out last first; a small stack turns them round.
//!
//! ## Ports
//! - `start` (a pulse) with the line's walk start, from the caller's
//!   registers: `wi0` = `n - 1`, `wj0` = `m - 1` (the last cell, `n`, `m`
//!   the line's declivity counts), `diag0` = `n + m - 2` (its
//!   anti-diagonal) and `empty` (`n` or `m` is 0: no walk; the others are
//!   then unused). (From registers, so that the caller's choice of line,
//!   the sum and the zero tests are not on `start`'s clock.) `start` is
//!   taken in the idle state only.
//! - To the array: `tb_diag`, `tb_group`; from it, `tb_word` and
//!   `tb_word_prev` (see `crate::matcher::systolic_matcher`).
//! - Out: `out_valid`, `out_i`, `out_j` (a matched pair, reference order),
//!   then `out_last` with `out_count` (pairs of the line) for one clock.
//!
//! ## Timing
//! After `start` at clock `t`, the walk reads anti-diagonal `n + m - 2`
//! at `t + 1`, has its words at `t + 4`, the four rows' choices at `t + 5`,
//! its row's at `t + 6`, and decides on it at `t + 7`
//! ([`WALK_LEAD`] clocks of walk before the first decision), then one
//! anti-diagonal per clock until the path starts (at most `n + m - 1`
//! decisions); the `K` pairs then leave on consecutive clocks from two
//! clocks after the last decision, and `out_last` one clock after the last
//! pair: in all [`traceback_cycles`] clocks from `start` to `out_last`, at
//! most `n + m + K + 7`. The walker starts idle (Verilog initial values);
//! `reset` (synchronous, active high) returns it there.

use crate::matcher::gain_cell::{CHOICE_LEFT, CHOICE_NODE, CHOICE_START, CHOICE_UP};
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

const TB_IDLE: u64 = 0;
const TB_WALK: u64 = 1;
const TB_EMIT: u64 = 2;

/// Clocks of walk from the first read of the choice memory to the first
/// decision: the memory's two, the array's register, the three of the pick.
pub const WALK_LEAD: usize = 6;
/// Bits of the lead's count.
const LEAD_BITS: usize = 3;

/// Clocks from `start` to `out_last` for a line of `n` reference and `m`
/// other declivities whose walk stops on anti-diagonal `stop_diag` (the
/// `i + j` of the cell whose choice is `start`, or of the border cell it
/// left last) with `k` pairs: [`WALK_LEAD`] + 1 to the first decision, one per
/// anti-diagonal from `n + m - 2` down to `stop_diag`, and `k + 2` to
/// empty the stack (the first address, one read per pair, then the marker;
/// just the marker when `k = 0`). An empty line (`n` or `m` zero) takes one.
pub const fn traceback_cycles(n: usize, m: usize, stop_diag: usize, k: usize) -> usize {
    if n == 0 || m == 0 {
        return 1;
    }
    let emit = if k == 0 { 1 } else { k + 2 };
    WALK_LEAD + 1 + (n + m - 2 - stop_diag) + emit
}

#[derive(LogicBlock)]
pub struct Traceback {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub start: Signal<In, Bit>,
    pub wi0: Signal<In, Bits<INDEX_BITS>>,
    pub wj0: Signal<In, Bits<INDEX_BITS>>,
    pub diag0: Signal<In, Bits<DIAG_BITS>>,
    pub empty: Signal<In, Bit>,
    pub tb_diag: Signal<Out, Bits<DIAG_BITS>>,
    pub tb_group: Signal<Out, Bits<ROW_GROUP_BITS>>,
    pub tb_word: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub tb_word_prev: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_i: Signal<Out, Bits<INDEX_BITS>>,
    pub out_j: Signal<Out, Bits<INDEX_BITS>>,
    pub out_last: Signal<Out, Bit>,
    pub out_count: Signal<Out, Bits<COUNT_BITS>>,
    stack_i: RAM<Bits<INDEX_BITS>, INDEX_BITS>,
    stack_j: RAM<Bits<INDEX_BITS>, INDEX_BITS>,
    state: ResetDff<Bits<2>>,
    diag: ResetDff<Bits<DIAG_BITS>>,
    wi: ResetDff<Bits<INDEX_BITS>>,
    wj: ResetDff<Bits<INDEX_BITS>>,
    // `wi == 0`, `wj == 0` as registers, set beside the coordinates, so
    // that the zero tests are not LUT levels in front of `stop`, and so of
    // `left` and `k`.
    wi_zero: ResetDff<Bit>,
    wj_zero: ResetDff<Bit>,
    lead: ResetDff<Bits<LEAD_BITS>>,
    // `lead != 0` as a register, so that the zero test is not a LUT level
    // in front of the walk's decisions into `left`.
    leading: ResetDff<Bit>,
    win_hi: ResetDff<Bits<CHOICE_WORD_BITS>>,
    win_lo: ResetDff<Bits<CHOICE_WORD_BITS>>,
    win_b: ResetDff<Bits<4>>,
    near0: ResetDff<Bits<2>>,
    near1: ResetDff<Bits<2>>,
    near2: ResetDff<Bits<2>>,
    near3: ResetDff<Bits<2>>,
    moved: ResetDff<Bit>,
    moved2: ResetDff<Bit>,
    here: ResetDff<Bits<2>>,
    above: ResetDff<Bits<2>>,
    skip: ResetDff<Bit>,
    count: ResetDff<Bits<COUNT_BITS>>,
    left: ResetDff<Bits<COUNT_BITS>>,
    k: ResetDff<Bits<INDEX_BITS>>,
    pend: ResetDff<Bit>,
    choice: Signal<Local, Bits<2>>,
    pair: Signal<Local, Bits<PAIR_BITS>>,
    slice1: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    slice2: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    slice3: Signal<Local, Bits<CHOICE_WORD_BITS>>,
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
    walk_lead: Constant<Bits<LEAD_BITS>>,
    lead_one: Constant<Bits<LEAD_BITS>>,
    index_one: Constant<Bits<INDEX_BITS>>,
    bit0: Constant<Bits<8>>,
    group_shift: Constant<Bits<8>>,
    up1: Constant<Bits<8>>,
    up2: Constant<Bits<8>>,
    up3: Constant<Bits<8>>,
    down1: Constant<Bits<8>>,
    down2: Constant<Bits<8>>,
    down3: Constant<Bits<8>>,
}

impl Default for Traceback {
    fn default() -> Self {
        let c2 = |v: u64| Constant::new(v.into());
        let c8 = |v: u64| Constant::new(v.into());
        Traceback {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            wi0: Default::default(),
            wj0: Default::default(),
            diag0: Default::default(),
            empty: Default::default(),
            tb_diag: Default::default(),
            tb_group: Default::default(),
            tb_word: Default::default(),
            tb_word_prev: Default::default(),
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
            wi_zero: ResetDff::new(true),
            wj_zero: ResetDff::new(true),
            lead: Default::default(),
            leading: Default::default(),
            win_hi: Default::default(),
            win_lo: Default::default(),
            win_b: Default::default(),
            near0: Default::default(),
            near1: Default::default(),
            near2: Default::default(),
            near3: Default::default(),
            moved: Default::default(),
            moved2: Default::default(),
            here: Default::default(),
            above: Default::default(),
            skip: Default::default(),
            count: Default::default(),
            left: Default::default(),
            k: Default::default(),
            pend: Default::default(),
            choice: Default::default(),
            pair: Default::default(),
            slice1: Default::default(),
            slice2: Default::default(),
            slice3: Default::default(),
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
            walk_lead: Constant::new((WALK_LEAD as u64).into()),
            lead_one: Constant::new(1u64.into()),
            index_one: Constant::new(1u64.into()),
            bit0: c8(0),
            group_shift: c8(CELLS_PER_CHOICE_WORD.trailing_zeros() as u64),
            up1: c8(2),
            up2: c8(4),
            up3: c8(6),
            down1: c8(CHOICE_WORD_BITS as u64 - 2),
            down2: c8(CHOICE_WORD_BITS as u64 - 4),
            down3: c8(CHOICE_WORD_BITS as u64 - 6),
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
        dff_setup!(self, clock, state, diag, wi, wj, wi_zero, wj_zero, lead, leading, win_hi, win_lo, win_b, near0, near1, near2, near3, moved, moved2, here, above, skip, count, left, k, pend);
        self.state.reset.next = self.reset.val();
        self.diag.reset.next = self.reset.val();
        self.wi.reset.next = self.reset.val();
        self.wj.reset.next = self.reset.val();
        self.wi_zero.reset.next = self.reset.val();
        self.wj_zero.reset.next = self.reset.val();
        self.lead.reset.next = self.reset.val();
        self.leading.reset.next = self.reset.val();
        self.win_hi.reset.next = self.reset.val();
        self.win_lo.reset.next = self.reset.val();
        self.win_b.reset.next = self.reset.val();
        self.near0.reset.next = self.reset.val();
        self.near1.reset.next = self.reset.val();
        self.near2.reset.next = self.reset.val();
        self.near3.reset.next = self.reset.val();
        self.moved.reset.next = self.reset.val();
        self.moved2.reset.next = self.reset.val();
        self.here.reset.next = self.reset.val();
        self.above.reset.next = self.reset.val();
        self.skip.reset.next = self.reset.val();
        self.count.reset.next = self.reset.val();
        self.left.reset.next = self.reset.val();
        self.k.reset.next = self.reset.val();
        self.pend.reset.next = self.reset.val();

        self.tb_diag.next = self.diag.q.val();
        self.tb_group.next = self.wi.q.val().get_bits::<ROW_GROUP_BITS>(self.group_shift.val().index());
        // The pick of the walker's choice, over three clocks. First the
        // words of its row `r` and the 16 rows below, and `r mod 16`.
        self.win_hi.d.next = self.tb_word.val();
        self.win_lo.d.next = self.tb_word_prev.val();
        self.win_b.d.next = self.wi.q.val().get_bits::<4>(self.bit0.val().index());
        // Then the choices of rows r, r - 1, r - 2, r - 3: row r - k is at
        // `r mod 16` in the words shifted up by k rows.
        self.pair.next = bit_cast::<PAIR_BITS, 4>(self.win_b.q.val()) + bit_cast::<PAIR_BITS, 4>(self.win_b.q.val());
        self.slice1.next = (self.win_hi.q.val() << self.up1.val()) | (self.win_lo.q.val() >> self.down1.val());
        self.slice2.next = (self.win_hi.q.val() << self.up2.val()) | (self.win_lo.q.val() >> self.down2.val());
        self.slice3.next = (self.win_hi.q.val() << self.up3.val()) | (self.win_lo.q.val() >> self.down3.val());
        self.near0.d.next = self.win_hi.q.val().get_bits::<2>(self.pair.val().index());
        self.near1.d.next = self.slice1.val().get_bits::<2>(self.pair.val().index());
        self.near2.d.next = self.slice2.val().get_bits::<2>(self.pair.val().index());
        self.near3.d.next = self.slice3.val().get_bits::<2>(self.pair.val().index());
        // Then those of the row the walker is on now and the row above,
        // it having moved by `moved + moved2` rows since.
        self.moved2.d.next = self.moved.q.val();
        self.here.d.next = self.near0.q.val();
        self.above.d.next = self.near1.q.val();
        if self.moved.q.val() ^ self.moved2.q.val() {
            self.here.d.next = self.near1.q.val();
            self.above.d.next = self.near2.q.val();
        }
        if self.moved.q.val() & self.moved2.q.val() {
            self.here.d.next = self.near2.q.val();
            self.above.d.next = self.near3.q.val();
        }
        // The decision takes the one of the row it is on.
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
                self.lead.d.next = self.walk_lead.val();
                self.leading.d.next = self.walk_lead.val().any();
                self.skip.d.next = false;
                self.wi.d.next = self.wi0.val();
                self.wj.d.next = self.wj0.val();
                self.wi_zero.d.next = !self.wi0.val().any();
                self.wj_zero.d.next = !self.wj0.val().any();
                self.diag.d.next = self.diag0.val();
                self.state.d.next = self.st_walk.val();
                if self.empty.val() {
                    self.left.d.next = 0.into();
                    self.state.d.next = self.st_emit.val();
                }
            }
        }
        if self.state.q.val() == self.st_walk.val() {
            // The anti-diagonal read this clock is decided on the next.
            self.diag.d.next = self.diag.q.val() - 1;
            if self.leading.q.val() {
                self.lead.d.next = self.lead.q.val() - 1;
                self.leading.d.next = self.lead.q.val() != self.lead_one.val();
            } else {
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
                        self.wj.d.next = self.wj.q.val() - 1;
                        self.wi_zero.d.next = self.wi.q.val() == self.index_one.val();
                        self.wj_zero.d.next = self.wj.q.val() == self.index_one.val();
                        self.stop.next = self.wi_zero.q.val() | self.wj_zero.q.val();
                    }
                    if self.choice.val() == self.c_up.val() {
                        self.moved.d.next = true;
                        self.wi.d.next = self.wi.q.val() - 1;
                        self.wi_zero.d.next = self.wi.q.val() == self.index_one.val();
                        self.stop.next = self.wi_zero.q.val();
                    }
                    if self.choice.val() == self.c_left.val() {
                        self.wj.d.next = self.wj.q.val() - 1;
                        self.wj_zero.d.next = self.wj.q.val() == self.index_one.val();
                        self.stop.next = self.wj_zero.q.val();
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
