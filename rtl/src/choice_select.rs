//! One row's choice out of a word of the systolic matcher's choice memory
//! (the traceback's read, `crate::systolic_matcher`): row `r` is the low row
//! of cell `r` or, from `N` on, the high row of cell `r - N`; cell `c`'s
//! choice is bits `2·(c mod 16)` and up of word `c / 16` of its half.
//!
//! ## Ports
//! - `lo0..3`, `hi0..3`: one anti-diagonal's words of the low and high
//!   rows, [`CELLS_PER_CHOICE_WORD`] cells each.
//! - `row`: the row; out `choice`, its 2-bit choice.
//!
//! ## Timing
//! Combinational (multiplexers over the eight words, then over the word's
//! 16 choices).

use crate::params::*;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ChoiceSelect {
    pub lo0: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub lo1: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub lo2: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub lo3: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi0: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi1: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi2: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub hi3: Signal<In, Bits<CHOICE_WORD_BITS>>,
    pub row: Signal<In, Bits<INDEX_BITS>>,
    pub choice: Signal<Out, Bits<2>>,
    hi: Signal<Local, Bit>,
    cell_index: Signal<Local, Bits<CELL_BITS>>,
    widx: Signal<Local, Bits<2>>,
    pair: Signal<Local, Bits<PAIR_BITS>>,
    word: Signal<Local, Bits<CHOICE_WORD_BITS>>,
    cells_c: Constant<Bits<INDEX_BITS>>,
    word_shift: Constant<Bits<8>>,
    bit0: Constant<Bits<8>>,
    w1: Constant<Bits<2>>,
    w2: Constant<Bits<2>>,
    w3: Constant<Bits<2>>,
}

impl ChoiceSelect {
    /// The selection for an array of `cells` cells.
    pub fn new(cells: usize) -> Self {
        assert!(cells <= N_CELLS && CHOICE_WORDS == 4, "four words per half");
        ChoiceSelect {
            lo0: Default::default(),
            lo1: Default::default(),
            lo2: Default::default(),
            lo3: Default::default(),
            hi0: Default::default(),
            hi1: Default::default(),
            hi2: Default::default(),
            hi3: Default::default(),
            row: Default::default(),
            choice: Default::default(),
            hi: Default::default(),
            cell_index: Default::default(),
            widx: Default::default(),
            pair: Default::default(),
            word: Default::default(),
            cells_c: Constant::new((cells as u64).into()),
            word_shift: Constant::new((CELLS_PER_CHOICE_WORD.trailing_zeros() as u64).into()),
            bit0: Constant::new(0u64.into()),
            w1: Constant::new(1u64.into()),
            w2: Constant::new(2u64.into()),
            w3: Constant::new(3u64.into()),
        }
    }
}

impl Default for ChoiceSelect {
    fn default() -> Self {
        ChoiceSelect::new(N_CELLS)
    }
}

impl Logic for ChoiceSelect {
    #[hdl_gen]
    fn update(&mut self) {
        self.hi.next = self.row.val() >= self.cells_c.val();
        self.cell_index.next = bit_cast::<CELL_BITS, INDEX_BITS>(self.row.val());
        if self.hi.val() {
            self.cell_index.next = bit_cast::<CELL_BITS, INDEX_BITS>(self.row.val() - self.cells_c.val());
        }
        self.widx.next = self.cell_index.val().get_bits::<2>(self.word_shift.val().index());
        self.pair.next = bit_cast::<PAIR_BITS, 4>(self.cell_index.val().get_bits::<4>(self.bit0.val().index()))
            + bit_cast::<PAIR_BITS, 4>(self.cell_index.val().get_bits::<4>(self.bit0.val().index()));
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
        self.choice.next = self.word.val().get_bits::<2>(self.pair.val().index());
    }
}
