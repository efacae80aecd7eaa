//! The systolic array of the matcher (`DESIGN.md` §3): `N` [`GainCell`]s in
//! a line, cell `c` holding reference declivities `c + k·N` for the phases
//! `k = 0 .. ROWS_PER_CELL` ([`ROWS_PER_CELL`] = 4), the other view's
//! declivities streaming through the chain
//! once per phase, one cell every two clocks, the passes interleaved:
//!
//! - a line of at most `2·N` reference declivities (*two phases*): column
//!   `j` enters for phase `k` at `2j + (2N + 1)·k`, so node `(i, j)` of cell
//!   `c` (`i = c + k·N`) is computed at `2·(i + j) + k`: an anti-diagonal
//!   every two clocks, phase 0 on even clocks, phase 1 on odd ones;
//! - a longer line (*four phases*, `p4`): column `j` enters for phase `k` at
//!   `4j + (2N + 1)·k`, so node `(i, j)` is computed at
//!   `2c + 4j + (2N + 1)·k`: each row has four clocks per node, and each
//!   clock of a cell belongs to one phase (`2N + 1` is odd, so the phases
//!   take the four residues mod 4).
//!
//! Every dependency of a node is at least two clocks old: `P(i-1, j)` two
//! (three across a phase, from row `k·N - 1` to row `k·N`, through one
//! register), `P(i, j-1)` two or four, `P(i-1, j-1)` four or six.
//!
//! The cells' choices go to a block-RAM choice memory rather than into the
//! cells. With two phases every cell has, on each clock, a node of one
//! anti-diagonal and one phase; with four, cell `c` is `2c` clocks ahead of
//! cell 0 on an anti-diagonal and holds its choices back as long (the
//! cell's skew), so that again one clock brings one anti-diagonal of one
//! phase: `4s - (2N - 1)·k` clocks after the sweep's origin. Word `s` of
//! RAM `g` holds anti-diagonal `s` of row group `g` (rows `16g .. 16g +
//! 16`, [`CELLS_PER_CHOICE_WORD`] cells: phase `k`'s rows are RAMs
//! `k·N/16` and up; see [`ChoiceWord`] for arrays of fewer than 16 cells).
//!
//! ## Ports
//! - `ld_pos`, `ld_levs`, `ld_rising`: the reference-declivity broadcast,
//!   to every cell, references `0, 1, 2, …` on consecutive clocks;
//!   `ld_first` high (with the phase in `ld_phase`) one clock before
//!   reference `k·N` is on it starts a load token down the cells, so that
//!   cell `c` takes reference `c + k·N` as its row of phase `k`.
//! - `c_*`: the column stream (`c_phase`: the pass), into the column
//!   pipeline: two register slots per cell, b then a; a cell computes on
//!   the column in its slot a and selects its reference by the phase of the
//!   column in its slot b, a clock ahead.
//! - `dispmax_m1`, `below2`, `f1`, `f3`, `p4`: the line's constants, passed
//!   down the cells one per clock; `same_polarity`, `one_sided`: to every
//!   cell (see [`GainCell`]).
//! - `cw_en`, `cw_diag`, `cw_phase`, `cw_bank`: write the choices now in
//!   the array's word registers as anti-diagonal `cw_diag` of phase
//!   `cw_phase` into bank `cw_bank` (two banks: the traceback of one line
//!   reads one while the sweep of the next writes the other). The
//!   engine counts them: the choices of the node whose column entered at
//!   clock `t` are in the word registers at `t +` [`CHOICE_LAG`] (with
//!   four phases, plus the cell's skew).
//! - `tb_diag`, `tb_bank`, `tb_group` in; `tb_word`, `tb_word_prev` out:
//!   the words of anti-diagonal `tb_diag` of bank `tb_bank` (three clocks ago: memory read, its output
//!   register inside the block RAM ([`BlockRam`]), then the register that
//!   feeds the selection) that hold the choices of row groups `tb_group`
//!   and `tb_group - 1` (now; see [`ChoiceWord`]): with the two side by
//!   side, row `r`'s choice is `2·(r - 16·tb_group + 16)` bits up.
//!
//! ## Timing
//! Column `j` offered on `c_*` at clock `t - 1` sits in cell `c`'s slot b
//! at `t + 2c`, in its slot a at `t + 2c + 1`, and gives `P` and the choice
//! of node `(c + N·c_phase, j)` in the cell at `t + 2c + 1 +`
//! [`CELL_DEPTH`], in the word registers one clock later (with `p4`, `2c`
//! clocks later still). Phase `k > 0`'s `P(k·N - 1, ·)` comes from the last
//! cell through one register; phase 0's `P(-1, ·)` is the border, 0.
//! One column enters per clock; `c_valid` low is a bubble that moves down
//! the pipeline as one (and leaves `P = 0` behind it in each cell). No
//! reset: the registers start from their Verilog initial values (zero: no
//! load token, empty slots).
//!
//! The cells compute paper eq. 4–9 ([`GainCell`]); the array is the
//! recurrence of eq. 9 over the whole matching table.

use crate::primitives::block_ram::BlockRam;
use crate::matcher::choice_word::ChoiceWord;
use crate::matcher::gain_cell::{GainCell, CELL_DEPTH};
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from a column offered on `c_*` to its node's choice in the word
/// registers, less the cell's slot offset `2c` (and, with four phases, its
/// skew): two into the cell's slot a, the cell's depth, one into the word
/// register. (The matcher's engine adds its own clocks of record memory.)
pub(crate) const CHOICE_LAG: usize = 2 + CELL_DEPTH + 1;

/// Address bits of the choice memory: the bank above the anti-diagonal.
pub const CHOICE_ADDR_BITS: usize = DIAG_BITS + 1;

/// Words of one phase's choices of an anti-diagonal in the sensor's array.
const PHASE_WORDS: usize = CHOICE_WORDS / ROWS_PER_CELL;
/// Bits of a word's index among a phase's.
const PHASE_WORD_BITS: usize = 2;
const _: () = assert!(PHASE_WORDS <= 1 << PHASE_WORD_BITS);

#[derive(LogicBlock)]
pub struct SystolicMatcher<const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub ld_first: Signal<In, Bit>,
    pub ld_phase: Signal<In, Bits<PHASE_BITS>>,
    pub ld_pos: Signal<In, Bits<POS_BITS>>,
    pub ld_levs: Signal<In, Bits<LEVELS_BITS>>,
    pub ld_rising: Signal<In, Bit>,
    pub c_valid: Signal<In, Bit>,
    pub c_phase: Signal<In, Bits<PHASE_BITS>>,
    pub c_pos: Signal<In, Bits<POS_BITS>>,
    pub c_levs: Signal<In, Bits<LEVELS_BITS>>,
    pub c_rising: Signal<In, Bit>,
    pub dispmax_m1: Signal<In, Bits<{ POS_BITS + 1 }>>,
    pub below2: Signal<In, Bits<DIST_BITS>>,
    pub f1: Signal<In, Bits<GAIN_BITS>>,
    pub f3: Signal<In, Bits<GAIN_BITS>>,
    pub p4: Signal<In, Bit>,
    pub same_polarity: Signal<In, Bit>,
    pub one_sided: Signal<In, Bit>,
    pub cw_en: Signal<In, Bit>,
    pub cw_diag: Signal<In, Bits<DIAG_BITS>>,
    pub cw_phase: Signal<In, Bits<PHASE_BITS>>,
    pub cw_bank: Signal<In, Bit>,
    pub tb_diag: Signal<In, Bits<DIAG_BITS>>,
    pub tb_bank: Signal<In, Bit>,
    pub tb_group: Signal<In, Bits<ROW_GROUP_BITS>>,
    pub tb_word: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    pub tb_word_prev: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    pub cells: [GainCell; N],
    pub row_word: ChoiceWord,
    pub prev_word: ChoiceWord,
    col_a_valid: [ResetDff<Bit>; N],
    col_a_phase: [ResetDff<Bits<PHASE_BITS>>; N],
    col_a_pos: [ResetDff<Bits<POS_BITS>>; N],
    col_a_levs: [ResetDff<Bits<LEVELS_BITS>>; N],
    col_a_rising: [ResetDff<Bit>; N],
    col_b_valid: [ResetDff<Bit>; N],
    col_b_phase: [ResetDff<Bits<PHASE_BITS>>; N],
    col_b_pos: [ResetDff<Bits<POS_BITS>>; N],
    col_b_levs: [ResetDff<Bits<LEVELS_BITS>>; N],
    col_b_rising: [ResetDff<Bit>; N],
    k_dispmax_m1: [ResetDff<Bits<{ POS_BITS + 1 }>>; N],
    k_below2: [ResetDff<Bits<DIST_BITS>>; N],
    k_f1: [ResetDff<Bits<GAIN_BITS>>; N],
    k_f3: [ResetDff<Bits<GAIN_BITS>>; N],
    k_p4: [ResetDff<Bit>; N],
    tok: [ResetDff<Bit>; N],
    tok_phase: [ResetDff<Bits<PHASE_BITS>>; N],
    wrap: ResetDff<Bits<PATH_BITS>>,
    word_q: [ResetDff<Bits<CHOICE_WORD_BITS>>; PHASE_WORDS],
    ram: [BlockRam<CHOICE_WORD_BITS, CHOICE_ADDR_BITS>; CHOICE_WORDS],
    rd2: [ResetDff<Bits<CHOICE_WORD_BITS>>; CHOICE_WORDS],
    // RAM g holds phase `ram_phase[g]`'s word `ram_word[g]` (of
    // `PHASE_WORDS`); RAMs past the phases' (`4·max(1, N/16)`) are never
    // written.
    ram_phase: [Constant<Bits<PHASE_BITS>>; CHOICE_WORDS],
    ram_word: [Constant<Bits<PHASE_WORD_BITS>>; CHOICE_WORDS],
    word_index: [Constant<Bits<PHASE_WORD_BITS>>; PHASE_WORDS],
    ram_used: [Constant<Bit>; CHOICE_WORDS],
    last_p: Signal<Local, Bits<PATH_BITS>>,
    cw_addr: Signal<Local, Bits<CHOICE_ADDR_BITS>>,
    tb_addr: Signal<Local, Bits<CHOICE_ADDR_BITS>>,
    diag_bit: Constant<Bits<8>>,
    group_one: Constant<Bits<ROW_GROUP_BITS>>,
    wacc: [Signal<Local, Bits<CHOICE_WORD_BITS>>; PHASE_WORDS],
}

impl<const N: usize> Default for SystolicMatcher<N> {
    fn default() -> Self {
        assert!((1..=N_CELLS).contains(&N), "1 ..= N_CELLS cells");
        assert_eq!(CELLS_PER_CHOICE_WORD, 16, "the word index below is written i / 16");
        // RAMs per phase: N/16 whole words, or one RAM per phase (packed).
        let per_phase = (N / CELLS_PER_CHOICE_WORD).max(1);
        SystolicMatcher {
            clock: Default::default(),
            reset: Default::default(),
            ld_first: Default::default(),
            ld_phase: Default::default(),
            ld_pos: Default::default(),
            ld_levs: Default::default(),
            ld_rising: Default::default(),
            c_valid: Default::default(),
            c_phase: Default::default(),
            c_pos: Default::default(),
            c_levs: Default::default(),
            c_rising: Default::default(),
            dispmax_m1: Default::default(),
            below2: Default::default(),
            f1: Default::default(),
            f3: Default::default(),
            p4: Default::default(),
            same_polarity: Default::default(),
            one_sided: Default::default(),
            cw_en: Default::default(),
            cw_diag: Default::default(),
            cw_phase: Default::default(),
            cw_bank: Default::default(),
            tb_diag: Default::default(),
            tb_bank: Default::default(),
            tb_group: Default::default(),
            tb_word: Default::default(),
            tb_word_prev: Default::default(),
            cells: core::array::from_fn(|i| GainCell::new(i, N)),
            row_word: ChoiceWord::new(N),
            prev_word: ChoiceWord::new(N),
            col_a_valid: core::array::from_fn(|_| Default::default()),
            col_a_phase: core::array::from_fn(|_| Default::default()),
            col_a_pos: core::array::from_fn(|_| Default::default()),
            col_a_levs: core::array::from_fn(|_| Default::default()),
            col_a_rising: core::array::from_fn(|_| Default::default()),
            col_b_valid: core::array::from_fn(|_| Default::default()),
            col_b_phase: core::array::from_fn(|_| Default::default()),
            col_b_pos: core::array::from_fn(|_| Default::default()),
            col_b_levs: core::array::from_fn(|_| Default::default()),
            col_b_rising: core::array::from_fn(|_| Default::default()),
            k_dispmax_m1: core::array::from_fn(|_| Default::default()),
            k_below2: core::array::from_fn(|_| Default::default()),
            k_f1: core::array::from_fn(|_| Default::default()),
            k_f3: core::array::from_fn(|_| Default::default()),
            k_p4: core::array::from_fn(|_| Default::default()),
            tok: core::array::from_fn(|_| Default::default()),
            tok_phase: core::array::from_fn(|_| Default::default()),
            wrap: Default::default(),
            word_q: Default::default(),
            ram: Default::default(),
            rd2: Default::default(),
            ram_phase: core::array::from_fn(|g| Constant::new((((g / per_phase) % ROWS_PER_CELL) as u64).into())),
            ram_word: core::array::from_fn(|g| Constant::new(((g % per_phase) as u64).into())),
            word_index: core::array::from_fn(|k| Constant::new((k as u64).into())),
            ram_used: core::array::from_fn(|g| Constant::new(g < ROWS_PER_CELL * per_phase)),
            last_p: Default::default(),
            cw_addr: Default::default(),
            tb_addr: Default::default(),
            diag_bit: Constant::new((DIAG_BITS as u64).into()),
            group_one: Constant::new(1u64.into()),
            wacc: Default::default(),
        }
    }
}

impl<const N: usize> Logic for SystolicMatcher<N> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..N {
            self.cells[i].clock.next = self.clock.val();
            self.cells[i].reset.next = self.reset.val();
            self.cells[i].ld_pos.next = self.ld_pos.val();
            self.cells[i].ld_levs.next = self.ld_levs.val();
            self.cells[i].ld_rising.next = self.ld_rising.val();
            self.cells[i].same_polarity.next = self.same_polarity.val();
            self.cells[i].one_sided.next = self.one_sided.val();
        }
        // The load tokens: reference `c + k·N` is on the broadcast when a
        // token of phase k is in cell c; a token enters cell 0 with
        // references 0, N, 2N and 3N and moves one cell per clock as the
        // references follow one another (one token in the array at a time).
        for i in 0..N {
            self.tok[i].clock.next = self.clock.val();
            self.tok[i].reset.next = self.reset.val();
            self.tok_phase[i].clock.next = self.clock.val();
            self.tok_phase[i].reset.next = self.reset.val();
            self.cells[i].ld_en.next = self.tok[i].q.val();
            self.cells[i].ld_phase.next = self.tok_phase[i].q.val();
        }
        for i in 0..1 {
            self.tok[i].d.next = self.ld_first.val();
            self.tok_phase[i].d.next = self.ld_phase.val();
        }
        for i in 1..N {
            self.tok[i].d.next = self.tok[i - 1].q.val();
            self.tok_phase[i].d.next = self.tok_phase[i - 1].q.val();
        }
        // The line's constants travel down the array one cell per clock (a
        // register in every cell: no wire crosses the array; a cell's first
        // node of a line comes more than i clocks after the engine sets them).
        for i in 0..N {
            self.k_dispmax_m1[i].clock.next = self.clock.val();
            self.k_dispmax_m1[i].reset.next = self.reset.val();
            self.cells[i].dispmax_m1.next = self.k_dispmax_m1[i].q.val();
            self.k_below2[i].clock.next = self.clock.val();
            self.k_below2[i].reset.next = self.reset.val();
            self.cells[i].below2.next = self.k_below2[i].q.val();
            self.k_f1[i].clock.next = self.clock.val();
            self.k_f1[i].reset.next = self.reset.val();
            self.cells[i].f1.next = self.k_f1[i].q.val();
            self.k_f3[i].clock.next = self.clock.val();
            self.k_f3[i].reset.next = self.reset.val();
            self.cells[i].f3.next = self.k_f3[i].q.val();
            self.k_p4[i].clock.next = self.clock.val();
            self.k_p4[i].reset.next = self.reset.val();
            self.cells[i].p4.next = self.k_p4[i].q.val();
        }
        for i in 0..1 {
            self.k_dispmax_m1[i].d.next = self.dispmax_m1.val();
            self.k_below2[i].d.next = self.below2.val();
            self.k_f1[i].d.next = self.f1.val();
            self.k_f3[i].d.next = self.f3.val();
            self.k_p4[i].d.next = self.p4.val();
        }
        for i in 1..N {
            self.k_dispmax_m1[i].d.next = self.k_dispmax_m1[i - 1].q.val();
            self.k_below2[i].d.next = self.k_below2[i - 1].q.val();
            self.k_f1[i].d.next = self.k_f1[i - 1].q.val();
            self.k_f3[i].d.next = self.k_f3[i - 1].q.val();
            self.k_p4[i].d.next = self.k_p4[i - 1].q.val();
        }
        // The column pipeline: two slots per cell, `col_b[i]` then
        // `col_a[i]` (cell i's); slot b of cell 0 takes the stream. A column
        // moves one slot per clock; a bubble moves as one. The cell selects
        // its reference by the phase of the column in its slot b.
        for i in 0..N {
            self.col_a_valid[i].clock.next = self.clock.val();
            self.col_a_valid[i].reset.next = self.reset.val();
            self.col_b_valid[i].clock.next = self.clock.val();
            self.col_b_valid[i].reset.next = self.reset.val();
            self.col_a_phase[i].clock.next = self.clock.val();
            self.col_a_phase[i].reset.next = self.reset.val();
            self.col_b_phase[i].clock.next = self.clock.val();
            self.col_b_phase[i].reset.next = self.reset.val();
            self.col_a_pos[i].clock.next = self.clock.val();
            self.col_a_pos[i].reset.next = self.reset.val();
            self.col_b_pos[i].clock.next = self.clock.val();
            self.col_b_pos[i].reset.next = self.reset.val();
            self.col_a_levs[i].clock.next = self.clock.val();
            self.col_a_levs[i].reset.next = self.reset.val();
            self.col_b_levs[i].clock.next = self.clock.val();
            self.col_b_levs[i].reset.next = self.reset.val();
            self.col_a_rising[i].clock.next = self.clock.val();
            self.col_a_rising[i].reset.next = self.reset.val();
            self.col_b_rising[i].clock.next = self.clock.val();
            self.col_b_rising[i].reset.next = self.reset.val();
            self.col_a_phase[i].d.next = self.col_a_phase[i].q.val();
            self.col_b_phase[i].d.next = self.col_b_phase[i].q.val();
            self.col_a_pos[i].d.next = self.col_a_pos[i].q.val();
            self.col_b_pos[i].d.next = self.col_b_pos[i].q.val();
            self.col_a_levs[i].d.next = self.col_a_levs[i].q.val();
            self.col_b_levs[i].d.next = self.col_b_levs[i].q.val();
            self.col_a_rising[i].d.next = self.col_a_rising[i].q.val();
            self.col_b_rising[i].d.next = self.col_b_rising[i].q.val();
            self.col_a_valid[i].d.next = self.col_b_valid[i].q.val();
            if self.col_b_valid[i].q.val() {
                self.col_a_phase[i].d.next = self.col_b_phase[i].q.val();
                self.col_a_pos[i].d.next = self.col_b_pos[i].q.val();
                self.col_a_levs[i].d.next = self.col_b_levs[i].q.val();
                self.col_a_rising[i].d.next = self.col_b_rising[i].q.val();
            }
            self.cells[i].c_valid.next = self.col_a_valid[i].q.val();
            self.cells[i].c_phase.next = self.col_a_phase[i].q.val();
            self.cells[i].c_pos.next = self.col_a_pos[i].q.val();
            self.cells[i].c_levs.next = self.col_a_levs[i].q.val();
            self.cells[i].c_rising.next = self.col_a_rising[i].q.val();
            self.cells[i].c_phase_next.next = self.col_b_phase[i].q.val();
        }
        for i in 0..1 {
            self.col_b_valid[i].d.next = self.c_valid.val();
            if self.c_valid.val() {
                self.col_b_phase[i].d.next = self.c_phase.val();
                self.col_b_pos[i].d.next = self.c_pos.val();
                self.col_b_levs[i].d.next = self.c_levs.val();
                self.col_b_rising[i].d.next = self.c_rising.val();
            }
        }
        for i in 1..N {
            self.col_b_valid[i].d.next = self.col_a_valid[i - 1].q.val();
            if self.col_a_valid[i - 1].q.val() {
                self.col_b_phase[i].d.next = self.col_a_phase[i - 1].q.val();
                self.col_b_pos[i].d.next = self.col_a_pos[i - 1].q.val();
                self.col_b_levs[i].d.next = self.col_a_levs[i - 1].q.val();
                self.col_b_rising[i].d.next = self.col_a_rising[i - 1].q.val();
            }
        }
        // The recurrence: the cell above's P; for cell 0, the last cell's,
        // one clock later (row k·N - 1 is three clocks ahead of row k·N).
        for i in 0..N {
            self.last_p.next = self.cells[i].p.val();
        }
        self.wrap.clock.next = self.clock.val();
        self.wrap.reset.next = self.reset.val();
        self.wrap.d.next = self.last_p.val();
        for i in 0..1 {
            self.cells[i].up_p.next = self.wrap.q.val();
        }
        for i in 1..N {
            self.cells[i].up_p.next = self.cells[i - 1].p.val();
        }

        // The choice memory: each cell's choice in its bits of its word
        // (the other cells show zeros there), registered, written as one
        // anti-diagonal of one phase.
        for k in 0..PHASE_WORDS {
            self.wacc[k].next = 0.into();
        }
        // (`i / 16` is `i / CELLS_PER_CHOICE_WORD`: rust-hdl evaluates an
        // index with literals only.)
        for i in 0..N {
            self.wacc[i / 16].next = self.wacc[i / 16].val() | self.cells[i].choice_word.val();
        }
        for k in 0..PHASE_WORDS {
            self.word_q[k].clock.next = self.clock.val();
            self.word_q[k].reset.next = self.reset.val();
            self.word_q[k].d.next = self.wacc[k].val();
        }
        // Two banks: a line's traceback reads one while the next line's
        // sweep writes the other.
        self.cw_addr.next = bit_cast::<CHOICE_ADDR_BITS, DIAG_BITS>(self.cw_diag.val())
            .replace_bit(self.diag_bit.val().index(), self.cw_bank.val());
        self.tb_addr.next = bit_cast::<CHOICE_ADDR_BITS, DIAG_BITS>(self.tb_diag.val())
            .replace_bit(self.diag_bit.val().index(), self.tb_bank.val());
        for g in 0..CHOICE_WORDS {
            self.ram[g].clock.next = self.clock.val();
            self.ram[g].write_address.next = self.cw_addr.val();
            self.ram[g].write_data.next = self.word_q[0].q.val();
            for k in 1..PHASE_WORDS {
                if self.ram_word[g].val() == self.word_index[k].val() {
                    self.ram[g].write_data.next = self.word_q[k].q.val();
                }
            }
            self.ram[g].write_enable.next =
                self.cw_en.val() & self.ram_used[g].val() & (self.cw_phase.val() == self.ram_phase[g].val());
            self.ram[g].read_address.next = self.tb_addr.val();
            self.rd2[g].clock.next = self.clock.val();
            self.rd2[g].reset.next = self.reset.val();
            self.rd2[g].d.next = self.ram[g].read_data.val();
        }

        // ---- Traceback reads: the words of groups tb_group and tb_group - 1.
        for g in 0..CHOICE_WORDS {
            self.row_word.w[g].next = self.rd2[g].q.val();
            self.prev_word.w[g].next = self.rd2[g].q.val();
        }
        self.row_word.group.next = self.tb_group.val();
        self.prev_word.group.next = self.tb_group.val() - self.group_one.val();
        self.tb_word.next = self.row_word.word.val();
        self.tb_word_prev.next = self.prev_word.word.val();
    }
}
