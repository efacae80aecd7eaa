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
//! - `w0..7`: one anti-diagonal's words of the memory's eight
//!   ([`CHOICE_WORDS`]) RAMs.
//! - `group`: the row's group `⌊r / 16⌋`; out `word`, the word holding the
//!   choices of the group's rows.
//!
//! ## Timing
//! Combinational (an eight-way multiplexer of words, or a few ORs): no
//! registers, no latency.
//!
//! No paper equation: addressing of the traceback's choices (eq. 9).

use crate::params::*;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ChoiceWord {
    pub w0: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w1: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w2: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w3: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w4: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w5: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w6: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub w7: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub group: Signal<In, Bits<ROW_GROUP_BITS>>,
    pub word: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    // A small array's groups: phase k's bits shifted into group 0 or 1.
    small_array: Constant<Bit>,
    in_g1: [Constant<Bit>; ROWS_PER_CELL],
    shift: [Constant<Bits<8>>; ROWS_PER_CELL],
    g0: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    g1: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    phase_word: [Signal<Local, Bits<CHOICE_WORD_BITS>>; ROWS_PER_CELL],
}

impl ChoiceWord {
    /// The selection for an array of `cells` cells.
    pub(crate) fn new(cells: usize) -> Self {
        assert!(cells <= N_CELLS && CHOICE_WORDS == 8, "eight words");
        let packed = cells < CELLS_PER_CHOICE_WORD;
        assert!(packed || cells % CELLS_PER_CHOICE_WORD == 0, "whole words per phase, or phases packed into words");
        assert!(!packed || CELLS_PER_CHOICE_WORD % cells == 0, "a whole number of phases per word");
        let first_row = |k: usize| k * cells;
        ChoiceWord {
            w0: Default::default(),
            w1: Default::default(),
            w2: Default::default(),
            w3: Default::default(),
            w4: Default::default(),
            w5: Default::default(),
            w6: Default::default(),
            w7: Default::default(),
            group: Default::default(),
            word: Default::default(),
            small_array: Constant::new(packed),
            in_g1: core::array::from_fn(|k| Constant::new(first_row(k) / CELLS_PER_CHOICE_WORD == 1)),
            shift: core::array::from_fn(|k| Constant::new(((2 * (first_row(k) % CELLS_PER_CHOICE_WORD)) as u64).into())),
            g0: Default::default(),
            g1: Default::default(),
            phase_word: Default::default(),
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
        // Whole words: RAM `group`.
        self.word.next = self.w0.val();
        if self.group.val().get_bit(2) {
            if self.group.val().get_bit(1) {
                if self.group.val().get_bit(0) {
                    self.word.next = self.w7.val();
                } else {
                    self.word.next = self.w6.val();
                }
            } else {
                if self.group.val().get_bit(0) {
                    self.word.next = self.w5.val();
                } else {
                    self.word.next = self.w4.val();
                }
            }
        } else {
            if self.group.val().get_bit(1) {
                if self.group.val().get_bit(0) {
                    self.word.next = self.w3.val();
                } else {
                    self.word.next = self.w2.val();
                }
            } else {
                if self.group.val().get_bit(0) {
                    self.word.next = self.w1.val();
                }
            }
        }
        // Packed phases: RAM k is phase k.
        self.phase_word[0].next = self.w0.val() << self.shift[0].val();
        self.phase_word[1].next = self.w1.val() << self.shift[1].val();
        self.phase_word[2].next = self.w2.val() << self.shift[2].val();
        self.phase_word[3].next = self.w3.val() << self.shift[3].val();
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
