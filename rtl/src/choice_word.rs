//! The word of the systolic matcher's choice memory that holds a row's
//! choice (the traceback's read, `crate::systolic_matcher`): row `r` is the
//! low row of cell `r` or, from `N` on, the high row of cell `r - N`; cell
//! `c`'s choice is bits `2·(c mod 16)` and up of word `c / 16` of its half.
//! With `N` a multiple of 16, each word holds 16 consecutive rows, so row
//! `r`'s choice is at `2·(r mod 16)` in it. An array of at most 8 cells has
//! all its rows in the first words of its halves; they are put side by
//! side (`lo0` then `hi0`), so row `r`'s choice is at `2·r` there too.
//!
//! ## Ports
//! - `lo0..3`, `hi0..3`: one anti-diagonal's words of the low and high
//!   rows, [`CELLS_PER_CHOICE_WORD`] cells each.
//! - `group`: the row's group `⌊r / 16⌋`; out `word`, the word holding the
//!   choices of the group's rows.
//!
//! ## Timing
//! Combinational (one eight-way multiplexer of words).

use crate::params::*;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ChoiceWord {
    pub lo0: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub lo1: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub lo2: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub lo3: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi0: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi1: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi2: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi3: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub group: Signal<In, Bits<ROW_GROUP_BITS>>,
    pub word: Signal<Out, Bits<CHOICE_WORD_BITS>>,
    hi: Signal<Local, Bit>,
    widx: Signal<Local, Bits<ROW_GROUP_BITS>>,
    half_groups: Constant<Bits<ROW_GROUP_BITS>>,
    one_word: Constant<Bit>,
    one_word_shift: Constant<Bits<8>>,
    w1: Constant<Bits<ROW_GROUP_BITS>>,
    w2: Constant<Bits<ROW_GROUP_BITS>>,
    w3: Constant<Bits<ROW_GROUP_BITS>>,
}

impl ChoiceWord {
    /// The selection for an array of `cells` cells.
    pub fn new(cells: usize) -> Self {
        assert!(cells <= N_CELLS && CHOICE_WORDS == 4, "four words per half");
        let one_word = 2 * cells <= CELLS_PER_CHOICE_WORD;
        assert!(one_word || cells % CELLS_PER_CHOICE_WORD == 0, "whole words per half, or one word for both");
        ChoiceWord {
            lo0: Default::default(),
            lo1: Default::default(),
            lo2: Default::default(),
            lo3: Default::default(),
            hi0: Default::default(),
            hi1: Default::default(),
            hi2: Default::default(),
            hi3: Default::default(),
            group: Default::default(),
            word: Default::default(),
            hi: Default::default(),
            widx: Default::default(),
            half_groups: Constant::new(((cells / CELLS_PER_CHOICE_WORD) as u64).into()),
            one_word: Constant::new(one_word),
            one_word_shift: Constant::new((2 * cells as u64).into()),
            w1: Constant::new(1u64.into()),
            w2: Constant::new(2u64.into()),
            w3: Constant::new(3u64.into()),
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
        // Groups 0 .. N/16 are the low rows' words, the next the high rows'.
        self.hi.next = self.group.val() >= self.half_groups.val();
        self.widx.next = self.group.val();
        if self.hi.val() {
            self.widx.next = self.group.val() - self.half_groups.val();
        }
        self.word.next = self.lo0.val();
        if self.hi.val() {
            self.word.next = self.hi0.val();
        }
        if self.widx.val() == self.w1.val() {
            self.word.next = self.lo1.val();
            if self.hi.val() {
                self.word.next = self.hi1.val();
            }
        }
        if self.widx.val() == self.w2.val() {
            self.word.next = self.lo2.val();
            if self.hi.val() {
                self.word.next = self.hi2.val();
            }
        }
        if self.widx.val() == self.w3.val() {
            self.word.next = self.lo3.val();
            if self.hi.val() {
                self.word.next = self.hi3.val();
            }
        }
        if self.one_word.val() {
            self.word.next = self.lo0.val() | (self.hi0.val() << self.one_word_shift.val());
        }
    }
}
