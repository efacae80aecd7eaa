//! The word of the systolic matcher's choice memory that holds a row's
//! choice (the traceback's read, `crate::matcher::systolic_matcher`): row `r` is cell
//! `r mod N`'s row of phase `⌊r/N⌋` (`N` cells), and its choice is at
//! `2·(r mod 16)` in the word of its group `⌊r/16⌋` (16 =
//! [`CELLS_PER_CHOICE_WORD`]). With `N` a multiple of 16, each block RAM
//! of the memory holds one group (phase `k`'s words are RAMs `k·N/16` and
//! up), and the word is RAM `group`'s. A smaller array writes each phase
//! into a RAM of its own (RAM `k`, its `2·N` low bits); the word of a group
//! is then its phases' RAMs side by side, phase `k` at `2·(k·N mod 16)`.
//!
//! ## Ports
//! - `w[0 .. CHOICE_WORDS]`: one anti-diagonal's words of the memory's
//!   [`CHOICE_WORDS`] RAMs (8 in `sd`, 16 in `hd`).
//! - `group`: the row's group `⌊r / 16⌋`; out `word`, the word holding the
//!   choices of the group's rows.
//!
//! ## Timing
//! Combinational (a `CHOICE_WORDS`-way multiplexer of words, a tree of
//! two-way ones on the group's bits from bit 0 up, or a few ORs): no
//! registers, no latency.
//!
//! No paper equation: addressing of the traceback's choices (eq. 9).

use crate::params::*;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ChoiceWord {
    pub w: [Signal<In, Bits<CHOICE_WORD_BITS>>; CHOICE_WORDS],
    pub group: Signal<In, Bits<ROW_GROUP_BITS>>,
    pub word: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    // A small array's groups: phase k's bits shifted into group 0 or 1.
    small_array: Constant<Bit>,
    in_g1: [Constant<Bit>; ROWS_PER_CELL],
    shift: [Constant<Bits<8>>; ROWS_PER_CELL],
    g0: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    g1: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    phase_word: [Signal<Local, Bits<CHOICE_WORD_BITS>>; ROWS_PER_CELL],
    // The multiplexer's levels: level k selects by the group's bit k - 1
    // between pairs of level k - 1's words (level 0 is `w`); the last level
    // holds one word (arrays past it are empty).
    level1: [Signal<Local, Bits<CHOICE_WORD_BITS>>; LEVEL1_WORDS],
    level2: [Signal<Local, Bits<CHOICE_WORD_BITS>>; LEVEL2_WORDS],
    level3: [Signal<Local, Bits<CHOICE_WORD_BITS>>; LEVEL3_WORDS],
    level4: [Signal<Local, Bits<CHOICE_WORD_BITS>>; LEVEL4_WORDS],
}

/// Words of the multiplexer's levels (see `ChoiceWord::level1`).
const LEVEL1_WORDS: usize = CHOICE_WORDS / 2;
const LEVEL2_WORDS: usize = CHOICE_WORDS / 4;
const LEVEL3_WORDS: usize = CHOICE_WORDS / 8;
const LEVEL4_WORDS: usize = CHOICE_WORDS / 16;
// Three or four levels: 8 or 16 words.
const _: () = assert!(CHOICE_WORDS == 8 || CHOICE_WORDS == 16);
const _: () = assert!(CHOICE_WORDS == 1 << ROW_GROUP_BITS);

impl ChoiceWord {
    /// The selection for an array of `cells` cells.
    pub(crate) fn new(cells: usize) -> Self {
        assert!(cells <= N_CELLS, "at most the sensor's cells");
        let packed = cells < CELLS_PER_CHOICE_WORD;
        assert!(packed || cells % CELLS_PER_CHOICE_WORD == 0, "whole words per phase, or phases packed into words");
        assert!(!packed || CELLS_PER_CHOICE_WORD % cells == 0, "a whole number of phases per word");
        let first_row = |k: usize| k * cells;
        ChoiceWord {
            w: Default::default(),
            group: Default::default(),
            word: Default::default(),
            small_array: Constant::new(packed),
            in_g1: core::array::from_fn(|k| Constant::new(first_row(k) / CELLS_PER_CHOICE_WORD == 1)),
            shift: core::array::from_fn(|k| Constant::new(((2 * (first_row(k) % CELLS_PER_CHOICE_WORD)) as u64).into())),
            g0: Default::default(),
            g1: Default::default(),
            phase_word: Default::default(),
            level1: Default::default(),
            level2: Default::default(),
            level3: Default::default(),
            level4: Default::default(),
        }
    }
}

impl Default for ChoiceWord {
    fn default() -> Self {
        ChoiceWord::new(N_CELLS)
    }
}

impl Logic for ChoiceWord {
    #[hdl_gen]
    fn update(&mut self) {
        // Whole words: RAM `group`, a tree of two-way multiplexers.
        for j in 0..LEVEL1_WORDS {
            self.level1[j].next = self.w[2 * j].val();
            if self.group.val().get_bit(0) {
                self.level1[j].next = self.w[2 * j + 1].val();
            }
        }
        for j in 0..LEVEL2_WORDS {
            self.level2[j].next = self.level1[2 * j].val();
            if self.group.val().get_bit(1) {
                self.level2[j].next = self.level1[2 * j + 1].val();
            }
        }
        for j in 0..LEVEL3_WORDS {
            self.level3[j].next = self.level2[2 * j].val();
            if self.group.val().get_bit(2) {
                self.level3[j].next = self.level2[2 * j + 1].val();
            }
        }
        for j in 0..LEVEL4_WORDS {
            self.level4[j].next = self.level3[2 * j].val();
            if self.group.val().get_bit(3) {
                self.level4[j].next = self.level3[2 * j + 1].val();
            }
        }
        self.word.next = self.level3[0].val();
        for j in 0..LEVEL4_WORDS {
            self.word.next = self.level4[j].val();
        }
        // Packed phases: RAM k is phase k.
        for k in 0..ROWS_PER_CELL {
            self.phase_word[k].next = self.w[k].val() << self.shift[k].val();
        }
        self.g0.next = 0.into();
        self.g1.next = 0.into();
        for k in 0..ROWS_PER_CELL {
            if self.in_g1[k].val() {
                self.g1.next = self.g1.val() | self.phase_word[k].val();
            } else {
                self.g0.next = self.g0.val() | self.phase_word[k].val();
            }
        }
        if self.small_array.val() {
            self.word.next = self.g0.val();
            if self.group.val().get_bit(0) {
                self.word.next = self.g1.val();
            }
        }
    }
}
