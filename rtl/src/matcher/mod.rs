//! The matcher (paper §III–IV, eq. 4–9): the record input registers and memories, the gain cells of the systolic array, the choice memory's word, the traceback and the matcher that joins them.

pub(crate) mod record_input;
pub mod record_memory;
pub mod gain_cell;
pub mod systolic_matcher;
pub mod choice_word;
pub mod traceback;
pub mod declivity_matcher;
