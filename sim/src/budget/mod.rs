//! The latency budget of the hardware line processor (`DESIGN.md` §3,
//! "Latency budget"; `rtl::stereo_line_processor`): for each of its
//! stages, its clocks per line as a formula of the line width `W`, the
//! declivity counts `n`, `m` and the σ scan, the line period, the latency
//! of a scanline, the frame's flush and vertical blanking, frame time and
//! frames per second at a given clock, and the memories, DSP blocks and
//! processing elements the blocks are generated with.
//!
//! Every number comes from rtl's own formulas and named constants
//! (`marker_latency`, `line_starts`, `RECORD_FIFO_LAG`, `sweep_cycles`,
//! `traceback_cycles`, `line_cycles`, `line_period`, `row_check_cycles`, `ROW_START_LAG`,
//! `SEGMENT_LAG`, `PIXEL_LAG`, `MEDIAN_LAG`, `DEPTH_LAG`) and from the
//! widths in `rtl::params`; nothing here re-derives a clock count that rtl
//! exports. `sim/tests/budget.rs` checks the numbers against clocks
//! measured by simulating the rtl blocks and the whole line processor, and
//! the memory sizes against the generated Verilog.
//!
//! The stages are a list ([`STAGES`]) in pipeline order: detectors → record
//! queues → matcher → row check → interpolator → vertical median → depth
//! stage. Each gives its clocks per line (how long it is busy with one
//! line, the throughput bound) and its latency (from the event that hands
//! it a row to the event that hands the row on).
//!
//! ## A scanline's latency
//! Output row `y` is the median of rows `y − 4 … y + 4` (`MEDIAN_HALF` = 4
//! rows on each side), and row `y + 4` leaves the row check only once row
//! `y + 5`'s marker has left the matcher: row `y`'s first disparity waits
//! for row `y + 5`'s pixels, five line periods `P` after its own. From row `y`'s first pixel in
//! (rows every `P` clocks, every row the same work):
//!
//! - detector: `SKID_LAG` (the camera's register slice) `+ (W − 1) +
//!   marker_latency(W')` to the row's marker;
//! - record queue: `RECORD_FIFO_LAG` to the matcher's ports;
//! - matcher: `TAKE_AFTER_MARKER + line_cycles(n, m, s, k, K)` to the
//!   pair's marker (see "The matcher's schedule": no traceback waits);
//! - row check: `P` (it waits for row `y + 1`'s marker) `+ ROW_START_LAG +
//!   c + 1` to the row's marker out, `c ≤ row_check_cycles(n_above, n,
//!   n_below)` the engine's clocks for the row;
//! - interpolator: `CHECK_REGISTER_LAG` (the register from the row check)
//!   `+ SEGMENT_LAG + PIXEL_LAG` to the row's first pixel (the
//!   pixels start from the row's marker, not its first match, so
//!   `ROW_FIRST_LAG` is in no path);
//! - vertical median: `INTERP_REGISTER_LAG` (the register from the
//!   interpolator) `+ 4·P` (it waits for row `y + 4`) `+ MEDIAN_LAG`;
//! - depth stage: `MEDIAN_REGISTER_LAG` (the register from the median) + `DEPTH_LAG` +
//!   `OUTPUT_REGISTER_LAG` (the register to the output port).
//!
//! The sum is the latency from a row's first pixel in to its first
//! disparity out; its last disparity leaves `W' − 1` clocks later. On the
//! simulated line processor it is exact for the frame's first row
//! (`StereoRun::latency_cycles`, `sim/tests/budget.rs`): the detector's markers follow its σ scans
//! back to back from the first row on even when lines shorter than
//! `MIN_LINE_PERIOD` are taken early. With the worst line everywhere
//! ([`RowLoad::worst`]) it bounds every row's latency as long as no stage
//! is slower than `P` (each term grows with the row's work; a lighter row
//! never delays a later one by more than a line period).
//!
//! ## The frame's end: flush and vertical blanking
//! The frame's last row `H − 1` is checked right after row `H − 2` (the
//! row check does not wait for a row below it) and reaches the interpolator
//! `max(c_last + ROW_RESTART_LAG, W')` clocks after row `H − 2` (`c_last`
//! its check's clocks, started `ROW_RESTART_LAG` after row `H − 2`'s finish; the interpolator is still busy with row `H − 2` for `W'`). The
//! median then sends output row `H − 5` in the last row's slot and flushes
//! rows `H − 4 … H − 1`, one pixel per clock, back to back. So the
//! frame's output rows `0 … H − 6` leave one per line period from the
//! first disparity on, and the last disparity leaves `(H − 6)·P +
//! max(c_last + ROW_RESTART_LAG, W') + 5·W' − 1` clocks after the first.
//!
//! The median takes the next frame's pixels only after its flush (the
//! pixels that come during it are dropped, `pixels_dropped`). The next
//! frame's row 0 reaches the interpolator once its row 1's marker has left
//! the matcher, `(V + 2)·P` after this frame's row `H − 1`'s (`V` lines of
//! vertical blanking), so with the same work per row it needs
//! `(V + 2)·P + c_first − c ≥ max(c_last + ROW_RESTART_LAG, W') + 5·W'`: `c_first` the
//! first row's check clocks (no row above), `c` a row's inside the frame
//! (row `H − 2`'s). The least such `V` is the budget's vertical blanking,
//! and a frame takes `(H + V)·P` clocks. A next frame whose first rows are
//! lighter than this frame's last (an empty row checked in 1 clock,
//! matched in `line_cycles(0, 0, 0, 0, K)`) reaches the median earlier by
//! the difference: the blanking that covers any rows of at most `N`
//! declivities is given too.
//!
//! ## The matcher's schedule
//! The traceback of a line overlaps the sweep of the next
//! (`rtl::matcher::declivity_matcher::schedule`): the engine takes pair `L` at
//! `take_L = max(input_done_L + TAKE_AFTER_MARKER, start_{L−1} + 1)`, its
//! traceback starts at `start_L = max(take_L + sweep_L, start_{L−1} +
//! traceback_{L−1} + 1)` and its marker leaves `traceback_L + OUTPUT_LAG`
//! later. Back to back, pairs of the same work leave a marker every
//! `line_period(n, m, s, k, K) = max(sweep_cycles(n, m, K),
//! traceback_cycles(n, m, s, k)) + 1` clocks: the matcher's clocks per line.
//! A pair taken by an idle engine leaves its marker `TAKE_AFTER_MARKER +
//! line_cycles(n, m, s, k, K)` after its second marker: the matcher's
//! latency. With rows every `P ≥ line_period` of the worst line (`S`, `T`
//! its sweep and traceback), every row's marker is within that latency of
//! the worst line: if `start_{L−1} ≤ input_done_{L−1} + TAKE_AFTER_MARKER +
//! S`, then `take_L = input_done_L + TAKE_AFTER_MARKER` (as `P ≥ S + 1`) and
//! `start_L ≤ input_done_L + TAKE_AFTER_MARKER + S` (as `P ≥ T + 1`), so no
//! traceback waits beyond the worst line's sweep; rows of the same work
//! take the pair exactly `TAKE_AFTER_MARKER` after its second marker and
//! start its traceback at the end of its own sweep.
//!
//! ## The matcher's worst line
//! `line_cycles(n, m, s, k, K)` is `sweep_cycles(n, m, K)`, plus
//! `traceback_cycles(n, m, s, k)` = `WALK_LEAD + 1 + (n + m − 2 − s) + (k +
//! 2)` (1 for `k = 0`), plus `OUTPUT_LAG`. The sweep has two cases
//! ([`SWEEP_FORMULA`]): a line of `n ≤ 2·K` reference declivities takes two
//! phases, an anti-diagonal every 2 clocks, `2·(n + m) + [n > K] +
//! ENGINE_LAG − 3`; a longer one four, an anti-diagonal every 4 clocks,
//! `4·m + (p − 1)·(2·K + 1) + max(4·c + 2·K + 1, 4·(K − 1)) + ENGINE_LAG −
//! 3` with the last row `n − 1 = c + p·K` (cell `c`, phase `p`). Both
//! `sweep_cycles` (across the two cases too: the unit tests check every `n,
//! m ≤ 4·K` for every array size) and `traceback_cycles` are non-decreasing
//! in `n`, `m` and the matches `k` and non-increasing in the anti-diagonal
//! `s` on which the path stops, so `line_cycles` and `line_period` are too.
//! With `n, m ≤ N`, `k ≤ min(n, m)` and `s ≥ 0`, all bounds are reached at
//! once by one path, the one that takes every diagonal pair `(i, i)` from
//! `(N−1, N−1)` down to `(0, 0)` (and stops there, `s = 0`): so the worst
//! line is `(N, N, 0, N)`, for the latency (`line_cycles`) and the clocks
//! per line (`line_period`) alike. (In general the stop and the pairs trade
//! off — a node moves the walk down two anti-diagonals, so `k` pairs need
//! `s ≤ n + m − 2k` — but `s = 0` with `k = N = n = m` meets that bound, so
//! the trade-off does not bind at the worst; the unit tests search every
//! feasible `(n, m, s, k)` of small lines to confirm it.) Its `k = N`
//! matches are the row check's rows: `row_check_cycles` grows with each of
//! its three counts, so the worst row inside the frame is
//! `row_check_cycles(N, N, N)`, the first `row_check_cycles(0, N, N)`, the
//! last `row_check_cycles(N, N, 0)` — bounds, loose on real rows (the row
//! check's doc: real rows take about `n + 7`).

use rtl::detector::adaptive_threshold::THRESHOLD_LATENCY;
use rtl::primitives::block_ram::{DP16KD_ADDR_BITS, DP16KD_WIDTH};
use rtl::primitives::lut_ram::DPR16X4_WIDTH;
use rtl::detector::declivity_detector::{line_starts, MIN_LINE_PERIOD};
use rtl::matcher::declivity_matcher::{line_cycles, line_period, sweep_cycles, ENGINE_LAG, TAKE_AFTER_MARKER};
use rtl::post::depth_stage::DEPTH_LAG;
use rtl::post::interpolator::{LINE_BITS, LINE_QUEUE, PIXEL_LAG, SEGMENT_BITS, SEGMENT_LAG};
use rtl::params::{
    CELLS_PER_CHOICE_WORD, CHOICE_WORDS, CHOICE_WORD_BITS, DEPTH_INDEX_BITS, DEPTH_WORD_BITS, DIAG_BITS,
    HIST_ADDR_BITS, HIST_COUNT_BITS, INDEX_BITS, LEVELS_BITS, LEVEL_BITS, LINE_BUF_ADDR_BITS, MEDIAN_HALF, MEDIAN_LINE_BUFFERS, MEDIAN_TAPS, N_CELLS,
    N_MAX, PIXEL_BITS, POS_BITS, RECIP_BITS, ROWS_PER_CELL, ROW_ADDR_BITS, ROW_BANK_BITS,
    ROW_ENTRY_BITS, SEG_ADDR_BITS, WIDTH_BITS, W_MAX,
};
use rtl::stream::record_fifo::{RECORD_FIFO_DEPTH, RECORD_FIFO_LAG, RECORD_FIFO_LANES};
use rtl::post::row_check::{row_check_cycles, row_check_period, ROW_RESTART_LAG, ROW_START_LAG};
use rtl::stream::skid_buffer::SKID_LAG;
use rtl::stereo_line_processor::{CHECK_REGISTER_LAG, HEIGHT_BITS, INTERP_REGISTER_LAG, MEDIAN_REGISTER_LAG, OUTPUT_REGISTER_LAG};
use rtl::matcher::record_memory::COPY_ADDR_BITS;
use rtl::matcher::systolic_matcher::CHOICE_ADDR_BITS;
use rtl::matcher::traceback::{traceback_cycles, WALK_LEAD};
use rtl::post::vertical_median::MEDIAN_LAG;
use serde::Serialize;

use crate::drive::detector::marker_latency_estimate;
use crate::blocks::MATCHER_CELLS;
use crate::formats::{dispmax_lsb, DispmaxError};

/// What the budget is asked for (the options of `declivity budget`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BudgetRequest {
    /// Pixels per line offered on each camera's input (`W`).
    pub width: usize,
    /// Lines per frame (`H`).
    pub height: usize,
    /// Characteristic declivities per line to budget the matcher for, on
    /// both sides (`N`, at most `N_MAX`).
    pub n_max: usize,
    /// Eq. 6's search bound, px.
    pub dispmax: f64,
    /// Clock frequency, MHz.
    pub clock_mhz: f64,
    /// Clocks of horizontal blanking after each line (`tvalid` low).
    pub hblank: usize,
    /// Gain cells of the matcher's systolic array (`K`).
    pub cells: usize,
}

impl BudgetRequest {
    /// A request for the sensor's matcher ([`N_CELLS`] cells) without
    /// horizontal blanking.
    pub fn new(width: usize, height: usize, n_max: usize, dispmax: f64, clock_mhz: f64) -> Self {
        BudgetRequest { width, height, n_max, dispmax, clock_mhz, hblank: 0, cells: N_CELLS }
    }
}

/// A request the hardware cannot be budgeted for.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BudgetError {
    /// `W = 0`.
    #[error("--width 0: a line needs at least one pixel")]
    ZeroWidth,
    /// `H = 0`.
    #[error("--height 0: a frame needs at least one line")]
    ZeroHeight,
    /// `0 < H < MIN_HEIGHT`.
    #[error(
        "--height {height}: the budget models frames of at least {MIN_HEIGHT} rows (a row's output waits for the {} rows below it; the rows of shorter frames all leave through the vertical median's flush)", MIN_HEIGHT - 1
    )]
    TooFewRows {
        /// The rows asked for.
        height: usize,
    },
    /// `H > MAX_HEIGHT`.
    #[error("--height {height}: the line processor's row count has HEIGHT_BITS = {HEIGHT_BITS} bits, at most {MAX_HEIGHT} rows a frame")]
    TooManyRows {
        /// The rows asked for.
        height: usize,
    },
    /// `W > W_MAX`.
    #[error(
        "--width {width}: wider than the line processor's W_MAX = {W_MAX} pixels (it would process the first {W_MAX} of each line and flag it wide); this build has no configuration for wider lines"
    )]
    TooWide {
        /// The width asked for.
        width: usize,
    },
    /// `N = 0`.
    #[error("--n-max 0: budget the matcher for at least one declivity per line (a line without one costs it a clock)")]
    NoDeclivities,
    /// `N > N_MAX`.
    #[error(
        "--n-max {n}: more than N_MAX = {N_MAX} declivities per line; the detector keeps the first {N_MAX} of a line, drops the rest and flags it full"
    )]
    TooManyDeclivities {
        /// The count asked for.
        n: usize,
    },
    /// A cell count the matcher is not generated with.
    #[error("--cells {cells}: the matcher is generated with {MATCHER_CELLS:?} gain cells")]
    UnsupportedCells {
        /// The count asked for.
        cells: usize,
    },
    /// More declivities than the array's rows.
    #[error(
        "--n-max {n} with --cells {cells}: the array holds {rows} reference declivities ({ROWS_PER_CELL} per cell) and drops the rest; {n} need at least {need} cells"
    )]
    TooFewCells {
        /// The declivities asked for.
        n: usize,
        /// The cells asked for.
        cells: usize,
        /// Rows of that array.
        rows: usize,
        /// Cells that `n` rows need.
        need: usize,
    },
    /// A clock that is not a positive frequency.
    #[error("--clock-mhz {mhz}: the clock must be a finite frequency above 0 MHz")]
    Clock {
        /// The frequency asked for.
        mhz: f64,
    },
    /// A search bound the matcher does not take.
    #[error(transparent)]
    Dispmax(#[from] DispmaxError),
}

/// One addend of a formula: its text and its value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Term {
    /// The addend as text (`line_cycles(N, N, 0, N, K)`).
    pub text: String,
    /// Its value, negative for a subtrahend.
    pub value: i64,
}

impl Term {
    /// An addend.
    fn new(text: impl Into<String>, value: usize) -> Self {
        Term { text: text.into(), value: value as i64 }
    }

    /// A subtrahend.
    fn minus(text: impl Into<String>, value: usize) -> Self {
        Term { text: text.into(), value: -(value as i64) }
    }
}

/// The sum of `terms` and its formula, `a + b − c = 1 + 2 − 3` (a single
/// named term `a = 1`).
fn render(terms: &[Term]) -> (u64, String) {
    let join = |f: &dyn Fn(&Term) -> String| {
        let mut s = String::new();
        for (i, t) in terms.iter().enumerate() {
            match (i, t.value < 0) {
                (0, false) => {}
                (0, true) => s.push('−'),
                (_, false) => s.push_str(" + "),
                (_, true) => s.push_str(" − "),
            }
            s.push_str(&f(t));
        }
        s
    };
    let sum: i64 = terms.iter().map(|t| t.value).sum();
    let text = if terms.len() == 1 && terms[0].text.parse::<i64>().is_err() {
        format!("{} = {}", terms[0].text, terms[0].value)
    } else if terms.len() == 1 {
        terms[0].text.clone()
    } else {
        format!("{} = {}", join(&|t| t.text.clone()), join(&|t| t.value.unsigned_abs().to_string()))
    };
    (sum.max(0) as u64, text)
}

/// The detector's ping-pong line buffer.
const LINE_BUFFER: &str = "line buffer";
/// The detector's |ΔI| histogram.
const HISTOGRAM: &str = "|ΔI| histogram";
/// The record queues between the detectors and the matcher.
const RECORD_QUEUE: &str = "record queue";
/// The matcher's record memories.
const RECORD_MEMORY: &str = "record memory";
/// The copy of the record memories' positions the traceback reads.
const POSITION_COPY: &str = "position copy";
/// The matcher's choice memory.
const CHOICE_MEMORY: &str = "choice memory";
/// The row check's memories of matches.
const ROW_MEMORY: &str = "row memory";
/// The vertical median's line buffers.
const MEDIAN_LINE_BUFFER: &str = "median line buffer";
/// The depth stage's table.
const DEPTH_TABLE: &str = "depth table";

/// The fewest rows of a frame the budget models: row `y`'s output waits for
/// rows `y + 1` (the row check) and `y + MEDIAN_HALF` (the vertical
/// median), and row `y + MEDIAN_HALF`'s check for row `y + MEDIAN_HALF +
/// 1`; the first output row leaves on that path only if that row exists.
pub const MIN_HEIGHT: usize = MEDIAN_HALF + 2;
/// The most rows a frame can have: the largest `height` the line
/// processor's `HEIGHT_BITS`-bit input takes.
pub const MAX_HEIGHT: usize = (1 << HEIGHT_BITS) - 1;

/// `DP16KD`s of one `rtl::primitives::block_ram::BlockRam` of `words` words of
/// `word_bits` bits: one per [`DP16KD_WIDTH`] bits of width and
/// `2^DP16KD_ADDR_BITS` words (`rtl::primitives::block_ram`).
const fn dp16kd_of(word_bits: usize, words: usize) -> usize {
    word_bits.div_ceil(DP16KD_WIDTH) * words.div_ceil(1 << DP16KD_ADDR_BITS)
}

/// Bits of a reference row in a gain cell's LUT RAM: the position and its
/// polarity, and the six levels (`rtl::matcher::gain_cell`).
const REFERENCE_ROW_BITS: usize = POS_BITS + 1 + LEVELS_BITS;
/// `TRELLIS_DPR16X4`s of one gain cell's rows: one per four bits of each of
/// its two LUT RAMs (`rtl::primitives::lut_ram`).
const REFERENCE_ROW_DPR16X4: usize = (POS_BITS + 1).div_ceil(DPR16X4_WIDTH) + LEVELS_BITS.div_ceil(DPR16X4_WIDTH);

/// One memory of a block, as rtl declares it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Memory {
    /// The stage it belongs to.
    pub stage: &'static str,
    /// What it holds.
    pub name: &'static str,
    /// Copies in the whole design (one per camera, one per view, ...).
    pub copies: usize,
    /// Banks per copy (ping-pong halves, low and high rows, lanes, line
    /// buffers).
    pub banks: usize,
    /// Words per bank.
    pub words_per_bank: usize,
    /// Bits per word.
    pub word_bits: usize,
    /// `copies × banks × words_per_bank × word_bits`.
    pub bits: usize,
    /// `DP16KD` block RAMs the block instantiates for it (all copies;
    /// `rtl::primitives::block_ram::BlockRam`), `None` where Yosys infers the memory
    /// from a rust-hdl `RAM` or `SyncROM` (and chooses block or LUT RAM).
    pub dp16kd: Option<usize>,
    /// Where rtl declares it and how its word is made up.
    pub rtl: &'static str,
}

impl Memory {
    #[allow(clippy::too_many_arguments)]
    fn new(
        stage: &'static str,
        name: &'static str,
        copies: usize,
        banks: usize,
        words_per_bank: usize,
        word_bits: usize,
        dp16kd: Option<usize>,
        rtl: &'static str,
    ) -> Self {
        Memory { stage, name, copies, banks, words_per_bank, word_bits, bits: copies * banks * words_per_bank * word_bits, dp16kd, rtl }
    }
}

/// One stage's budget.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageBudget {
    /// The stage.
    pub name: &'static str,
    /// Copies of the block working side by side (the two cameras'
    /// detectors and record queues); the budget is per copy.
    pub instances: usize,
    /// Clocks the stage is busy with one line (worst case): the line
    /// period it can sustain.
    pub cycles_per_line: u64,
    /// `cycles_per_line` as a formula with its values.
    pub formula: String,
    /// Clocks from the event that hands the stage a row to the event that
    /// hands it on (see `latency_span`), the stage otherwise idle, rows
    /// every line period.
    pub latency_cycles: u64,
    /// `latency_cycles` as a formula with its values.
    pub latency_formula: String,
    /// The addends of `latency_cycles` (the scanline's latency adds up the
    /// stages' addends).
    #[serde(skip)]
    pub latency_terms: Vec<Term>,
    /// The two events `latency_cycles` lies between.
    pub latency_span: &'static str,
    /// `W + hblank − cycles_per_line`: clocks to spare per line against
    /// the input; negative when the stage is slower than the input (by
    /// that much per worst line).
    pub spare_cycles: i64,
    /// Processing elements (gain cells) of the stage, if it has an array.
    pub pe_count: Option<usize>,
    /// Reference rows per processing element.
    pub rows_per_pe: Option<usize>,
    /// DSP blocks (`MULT18X18D`) of the stage, all copies, as its doc or
    /// `declivity synth` gives them.
    pub dsp_blocks: Option<usize>,
    /// The stage's memories, generation-time sizes.
    pub memories: Vec<Memory>,
}

impl StageBudget {
    /// A stage of `instances` copies, busy `cycles_per_line` clocks a line
    /// (`formula`), its latency the sum of `latency_terms` between the
    /// events `latency_span` names; no DSP block, memory or array until
    /// given (`spare_cycles` is the budget's to set).
    fn new(name: &'static str, instances: usize, cycles_per_line: u64, formula: String, latency_terms: Vec<Term>, latency_span: &'static str) -> Self {
        let (latency_cycles, latency_formula) = render(&latency_terms);
        StageBudget {
            name,
            instances,
            cycles_per_line,
            formula,
            latency_cycles,
            latency_formula,
            latency_terms,
            latency_span,
            spare_cycles: 0,
            pe_count: None,
            rows_per_pe: None,
            dsp_blocks: Some(0),
            memories: Vec::new(),
        }
    }

    fn dsp_blocks(self, dsp_blocks: usize) -> Self {
        StageBudget { dsp_blocks: Some(dsp_blocks), ..self }
    }

    fn array(self, pe_count: usize, rows_per_pe: usize) -> Self {
        StageBudget { pe_count: Some(pe_count), rows_per_pe: Some(rows_per_pe), ..self }
    }

    fn memories(self, memories: Vec<Memory>) -> Self {
        StageBudget { memories, ..self }
    }
}

/// What the rows of a frame cost the two stages whose clocks depend on the
/// data, the matcher and the row check: every row's line pair, and the row
/// check's clocks (start → finish) of a row inside the frame, of its first
/// row and of its last.
///
/// In the latency, `(n, m, stop_diag, k)` is row `y + 5`'s line and `check`
/// row `y + 4`'s clocks; in the frame's end, the last row's line, row
/// `H − 2`'s `check` and row `H − 1`'s `last_check`; in the vertical
/// blanking, the next frame's row 0's `first_check`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct RowLoad {
    /// Reference declivities of a row (`n`).
    pub n: usize,
    /// Declivities of the other view's row (`m`).
    pub m: usize,
    /// The anti-diagonal the matcher's path stops on (`s`).
    pub stop_diag: usize,
    /// Matches of the row (`k`).
    pub k: usize,
    /// Row-check clocks of a row with rows above and below (`c`).
    pub check: usize,
    /// Of the frame's first row, checked against the row below only
    /// (`c_first`).
    pub first_check: usize,
    /// Of the frame's last row, checked against the row above only
    /// (`c_last`).
    pub last_check: usize,
}

impl RowLoad {
    /// Every row the worst for `n` declivities per side: the matcher's
    /// worst line ([`worst_matcher_line`]) and its `n` matches checked
    /// against rows of `n` matches, at the bound `row_check_cycles`.
    const fn worst(n: usize) -> Self {
        let (n, m, stop_diag, k) = worst_matcher_line(n);
        RowLoad {
            n,
            m,
            stop_diag,
            k,
            check: row_check_cycles(k, k, k),
            first_check: row_check_cycles(0, k, k),
            last_check: row_check_cycles(k, k, 0),
        }
    }

    /// `line_cycles(n, m, s, k, cells)`.
    const fn line_cycles(&self, cells: usize) -> usize {
        line_cycles(self.n, self.m, self.stop_diag, self.k, cells)
    }
}

/// The sizes a budget is made for, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sizes {
    /// Pixels offered per line (`W`).
    pub width: usize,
    /// Pixels stored per line, `W' = min(W, W_MAX)`.
    pub stored_width: usize,
    /// Declivities per line on each side budgeted for (`N`).
    pub n: usize,
    /// Gain cells (`K`).
    pub cells: usize,
    /// The rows' work.
    pub load: RowLoad,
    /// `load` is [`RowLoad::worst`]`(n)` (the formulas then name `N`).
    pub worst: bool,
    /// The line period `P` (0 until the stages' clocks per line give it:
    /// only the latencies use it).
    pub line_period: u64,
}

impl Sizes {
    /// The matcher's line as formula arguments: `N, N, 0, N` for the
    /// worst, else the numbers.
    fn line_args(&self) -> String {
        let l = &self.load;
        if self.worst {
            "N, N, 0, N".to_string()
        } else {
            format!("{}, {}, {}, {}", l.n, l.m, l.stop_diag, l.k)
        }
    }

    /// A row-check count as text: `row_check_cycles(N, N, N)` for the
    /// worst, else `c`.
    fn check_text(&self, worst: &str, measured: &str) -> String {
        if self.worst {
            worst.to_string()
        } else {
            measured.to_string()
        }
    }
}

/// A stage of the pipeline: its budget for the given sizes.
type Stage = fn(&Sizes) -> StageBudget;

/// The line processor's stages in pipeline order (a row passes them one
/// after the other; the scanline's latency is the sum of theirs).
const STAGES: [Stage; 7] =
    [detector_stage, record_queue_stage, matcher_stage, row_check_stage, interpolator_stage, vertical_median_stage, depth_stage];

/// Lines of one width run through [`line_starts`] to see the detector's
/// steady state (it settles after two lines and alternates with period two
/// at most).
const STEADY_LINES: usize = 12;

/// Line starts of the warm-up that [`detector_cycles_per_line`] skips.
const WARM_UP_LINES: usize = 4;

/// The most clocks between consecutive line starts of back-to-back lines of
/// `width` pixels, in the detector's steady state
/// (`rtl::detector::declivity_detector::line_starts`): `W` from
/// [`MIN_LINE_PERIOD`] on, more for shorter lines (the σ scan,
/// `THRESHOLD_LATENCY + 1` clocks per line, and the ping-pong banks).
fn detector_cycles_per_line(width: usize) -> u64 {
    let starts = line_starts(&[width; STEADY_LINES]);
    starts.windows(2).skip(WARM_UP_LINES).map(|w| w[1] - w[0]).max().unwrap_or(width as u64)
}

/// The matcher's worst line for `n` declivities per side on `cells` cells:
/// `(n, m, stop_diag, k)` = `(N, N, 0, N)` (see the module's doc).
const fn worst_matcher_line(n: usize) -> (usize, usize, usize, usize) {
    (n, n, 0, n)
}

/// `rtl::matcher::declivity_matcher::sweep_cycles` as text: two phases for `n ≤
/// 2·K`, four for longer lines.
const SWEEP_FORMULA: &str = "sweep_cycles(n, m, K) = 2·(n + m) + [n > K] + ENGINE_LAG − 3 for n ≤ 2·K (two phases, an anti-diagonal every 2 clocks); 4·m + (p − 1)·(2·K + 1) + max(4·c + 2·K + 1, 4·(K − 1)) + ENGINE_LAG − 3 for n > 2·K (four phases, every 4 clocks; the last row n − 1 = c + p·K is cell c's of phase p)";
/// `rtl::matcher::declivity_matcher::line_period` as text: the matcher's clocks per
/// line, back to back.
const LINE_PERIOD_FORMULA: &str = "line_period(n, m, s, k, K) = max(sweep_cycles(n, m, K), traceback_cycles(n, m, s, k)) + 1";
/// `rtl::matcher::traceback::traceback_cycles` as text (`k > 0`).
const TRACEBACK_FORMULA: &str = "traceback_cycles(n, m, s, k) = WALK_LEAD + 1 + (n + m − 2 − s) + (k + 2)";

/// The two declivity detectors (one per camera, identical, side by side).
fn detector_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "declivity detector";
    let cycles = detector_cycles_per_line(s.width);
    let formula = if cycles == s.width as u64 {
        format!("W (one pixel per clock, sustained for W ≥ MIN_LINE_PERIOD = {MIN_LINE_PERIOD})")
    } else {
        format!(
            "line_starts steady state for W < MIN_LINE_PERIOD = {MIN_LINE_PERIOD}: the σ scan (THRESHOLD_LATENCY + 1 = {} clocks per line) and the ping-pong banks hold the input",
            THRESHOLD_LATENCY + 1
        )
    };
    let latency_terms = vec![
        Term::new("SKID_LAG", SKID_LAG),
        Term::new("(W − 1)", s.width - 1),
        Term::new("marker_latency(W')", marker_latency_estimate(s.width) as usize),
    ];
    StageBudget::new(NAME, 2, cycles, formula, latency_terms, "a row's first pixel accepted → its marker out")
        .dsp_blocks(2 * 3)
        .memories(vec![
            Memory::new(
                NAME,
                LINE_BUFFER,
                2,
                2,
                (1 << LINE_BUF_ADDR_BITS) / 2,
                PIXEL_BITS,
                Some(2 * 2 * dp16kd_of(PIXEL_BITS, (1 << LINE_BUF_ADDR_BITS) / 2)),
                "DeclivityDetector::line_buf0, line_buf1 (ping-pong, a BlockRam per bank), one pair per camera",
            ),
            Memory::new(
                NAME,
                HISTOGRAM,
                2,
                2,
                1 << HIST_ADDR_BITS,
                HIST_COUNT_BITS,
                Some(2 * 2 * dp16kd_of(HIST_COUNT_BITS, 1 << HIST_ADDR_BITS)),
                "AdaptiveThreshold::hist0, hist1 (BlockRam: the DP16KD's output register), one pair per camera",
            ),
        ])
}

/// The record queues, one per camera (`rtl::stream::record_fifo`): a line's
/// records wait there while the matcher is busy with a heavier line.
fn record_queue_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "record queues";
    let beats = s.load.n.max(s.load.m) + 1;
    let formula = if s.worst {
        format!("N + 1 (one beat a clock: a line's N records and its marker) = {beats}")
    } else {
        format!("max(n, m) + 1 (one beat a clock: a line's records and its marker) = {beats}")
    };
    let latency_terms = vec![Term::new("RECORD_FIFO_LAG", RECORD_FIFO_LAG)];
    StageBudget::new(NAME, 2, beats as u64, formula, latency_terms, "the row's marker out of the detectors → on the matcher's ports (the queue empty)")
        .memories(vec![Memory::new(
            NAME,
            RECORD_QUEUE,
            2,
            RECORD_FIFO_LANES,
            RECORD_FIFO_DEPTH,
            DP16KD_WIDTH,
            Some(2 * RECORD_FIFO_LANES * dp16kd_of(DP16KD_WIDTH, RECORD_FIFO_DEPTH)),
            "RecordFifo::mem0..mem4 (a record's fields and a marker's flags in five DP16KD lanes), one queue per camera",
        )])
}

/// The matcher: systolic array, traceback, record and choice memories.
fn matcher_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "matcher";
    let l = &s.load;
    let (n, m, stop, k) = (l.n, l.m, l.stop_diag, l.k);
    let args = s.line_args();
    let nm_args = if s.worst { "N, N".to_string() } else { format!("{n}, {m}") };
    // Back to back, the traceback of a line overlaps the sweep of the next
    // (module doc, "The matcher's schedule").
    let (sweep, walk) = (sweep_cycles(n, m, s.cells), traceback_cycles(n, m, stop, k));
    let cycles = line_period(n, m, stop, k, s.cells) as u64;
    let formula = format!(
        "max(sweep_cycles({nm_args}, K), traceback_cycles({args})) + 1 (line_period: the engine takes the next pair the clock after this one's traceback starts, and starts the next traceback once that pair's sweep and this traceback are over) = max({sweep}, {walk}) + 1"
    );
    let latency_terms = vec![
        Term::new("TAKE_AFTER_MARKER", TAKE_AFTER_MARKER as usize),
        Term::new(format!("line_cycles({args}, K)"), line_cycles(n, m, stop, k, s.cells)),
    ];
    let record_bits = (POS_BITS + 1) + 6 * LEVEL_BITS;
    let record_rams = dp16kd_of(POS_BITS + 1, 1 << DIAG_BITS) + 6 * dp16kd_of(LEVEL_BITS, 1 << DIAG_BITS);
    StageBudget::new(NAME, 1, cycles, formula, latency_terms, "the pair's second marker on the matcher's ports → the pair's marker out")
        .array(s.cells, ROWS_PER_CELL)
        .memories(vec![
            Memory::new(
                NAME,
                RECORD_MEMORY,
                2,
                2,
                (1 << DIAG_BITS) / 2,
                record_bits,
                Some(2 * record_rams),
                "RecordMemory::pos_mem, lev_mem[0..5] (position and polarity, six levels; two lines: the one loading, the one sweeping), one per view",
            ),
            Memory::new(
                NAME,
                POSITION_COPY,
                2,
                1 << (COPY_ADDR_BITS - INDEX_BITS),
                1 << INDEX_BITS,
                POS_BITS,
                Some(2 * dp16kd_of(POS_BITS, 1 << COPY_ADDR_BITS)),
                "RecordMemory::pos_copy (the positions of four lines: the traceback reads a line's while the next sweeps and the one after loads), one per view",
            ),
            Memory::new(
                NAME,
                CHOICE_MEMORY,
                1,
                1 << (CHOICE_ADDR_BITS - DIAG_BITS),
                1 << DIAG_BITS,
                CHOICE_WORDS * CHOICE_WORD_BITS,
                Some(CHOICE_WORDS * dp16kd_of(CHOICE_WORD_BITS, 1 << CHOICE_ADDR_BITS)),
                "SystolicMatcher::ram[0..8] (one per row group of 16 rows: its 2-bit choices of an anti-diagonal in a word), two banks: the traceback of a line reads one while the next line's sweep writes the other",
            ),
            Memory::new(NAME, "traceback stack", 1, 1, 1 << INDEX_BITS, 2 * INDEX_BITS, None, "Traceback::stack_i, stack_j"),
        ])
}

/// The row check (`rtl::post::row_check`, the default mode's consistency check
/// against the rows above and below): one line of delay.
/// The row check stage's name.
const ROW_CHECK_NAME: &str = "row check";

fn row_check_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = ROW_CHECK_NAME;
    let c = s.load.check;
    let check = s.check_text("row_check_cycles(N, N, N)", "c (the row's measured clocks)");
    let (cycles, formula) = render(&[
        Term::new(check.clone(), c),
        Term::new("ROW_RESTART_LAG (the engine takes the next row this long after it finished)", ROW_RESTART_LAG),
    ]);
    let formula = if s.worst {
        format!("{formula} (a bound; row_check_period() = {} for N = N_MAX)", row_check_period())
    } else {
        formula
    };
    let latency_terms = vec![
        Term::new("P (it waits for row y + 1's marker, a line period later)", s.line_period as usize),
        Term::new("ROW_START_LAG", ROW_START_LAG),
        Term::new(check, c),
        Term::new("1 (the marker leaves the clock after the finish)", 1),
    ];
    StageBudget::new(NAME, 1, cycles, formula, latency_terms, "row y's marker out of the matcher → row y's marker out of the row check")
        .memories(vec![Memory::new(
            NAME,
            ROW_MEMORY,
            3,
            1 << ROW_BANK_BITS,
            1 << INDEX_BITS,
            ROW_ENTRY_BITS,
            Some(3 * dp16kd_of(ROW_ENTRY_BITS, 1 << ROW_ADDR_BITS)),
            "RowCheck::cur_mem, above.mem, below.mem (the checked row, the rows above and below: three read ports; NeighbourWindow::mem), four banks of N_MAX matches (X, d)",
        )])
}

/// The interpolator: one disparity per reference pixel per clock
/// (`rtl::post::interpolator`).
fn interpolator_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "interpolator";
    let latency_terms = vec![
        Term::new("CHECK_REGISTER_LAG", CHECK_REGISTER_LAG),
        Term::new("SEGMENT_LAG", SEGMENT_LAG),
        Term::new("PIXEL_LAG", PIXEL_LAG),
    ];
    // The segment memory's fields (`Interpolator::seg_*`), one BlockRam each.
    let shape_bits = SEGMENT_BITS - WIDTH_BITS - 3 * POS_BITS - RECIP_BITS;
    let seg_rams = [WIDTH_BITS, POS_BITS, POS_BITS, POS_BITS, shape_bits, RECIP_BITS].iter().map(|&b| dp16kd_of(b, 1 << SEG_ADDR_BITS)).sum();
    StageBudget::new(NAME, 1, s.stored_width as u64, "W' (one pixel per clock, lines back to back)".to_string(), latency_terms, "the row check's marker out → the row's first disparity out (its pixels start from the marker)")
        .dsp_blocks(2)
        .memories(vec![
            // (The reciprocal table, 2^RECIP_INDEX_BITS × RECIP_BITS, is no
            // memory: `Interpolator::recip` is a `LogicRom`, LUTs behind a
            // registered address.)
            Memory::new(NAME, "segment memory", 1, 1, 1 << SEG_ADDR_BITS, SEGMENT_BITS, Some(seg_rams), "Interpolator::seg_* (one block RAM per field; the reciprocal from a table in LUTs, LogicRom)"),
            Memory::new(NAME, "line queue", 1, 2, LINE_QUEUE, LINE_BITS, None, "Interpolator::q_line and q_line_n (LUT RAM, one word a line, kept twice: read at the read pointer and at its successor)"),
        ])
}

/// The vertical median of nine rows (`rtl::post::vertical_median`):
/// `MEDIAN_HALF` = 4 lines of delay.
fn vertical_median_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "vertical median";
    let latency_terms = vec![
        Term::new("INTERP_REGISTER_LAG", INTERP_REGISTER_LAG),
        Term::new(
            format!("{MEDIAN_HALF}·P (the median of rows y − {MEDIAN_HALF} … y + {MEDIAN_HALF} waits for row y + {MEDIAN_HALF}, {MEDIAN_HALF} line periods later)"),
            MEDIAN_HALF * s.line_period as usize,
        ),
        Term::new("MEDIAN_LAG", MEDIAN_LAG),
    ];
    StageBudget::new(NAME, 1, s.stored_width as u64, "W' (one pixel per clock)".to_string(), latency_terms, "row y's first disparity out of the interpolator → output row y's first median out")
        .memories(vec![Memory::new(
            NAME,
            MEDIAN_LINE_BUFFER,
            1,
            MEDIAN_LINE_BUFFERS,
            W_MAX,
            POS_BITS,
            Some(MEDIAN_LINE_BUFFERS * dp16kd_of(POS_BITS, W_MAX)),
            "VerticalMedian::line (rows k − 8 … k − 1 of the MEDIAN_TAPS = 9 taps, one DP16KD each)",
        )])
}

/// The depth stage (`rtl::post::depth_stage`, eq. 1): one depth per disparity per
/// clock.
fn depth_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "depth stage";
    let latency_terms = vec![
        Term::new("MEDIAN_REGISTER_LAG", MEDIAN_REGISTER_LAG),
        Term::new("DEPTH_LAG", DEPTH_LAG),
        Term::new("OUTPUT_REGISTER_LAG", OUTPUT_REGISTER_LAG),
    ];
    StageBudget::new(NAME, 1, s.stored_width as u64, "W' (one pixel per clock)".to_string(), latency_terms, "a median out → its depth on the output")
        .dsp_blocks(1)
        .memories(vec![Memory::new(
            NAME,
            DEPTH_TABLE,
            1,
            1,
            1 << DEPTH_INDEX_BITS,
            DEPTH_WORD_BITS,
            None,
            "DepthStage::depth_rom (SyncROM: each entry K/m_i above its slope)",
        )])
}

/// Memories, DSP blocks and processing elements of the stages, summed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Resources {
    /// Every memory of every stage.
    pub memories: Vec<Memory>,
    /// Line buffers (one per camera) and their bits, all banks.
    pub line_buffers: usize,
    pub line_buffer_bits: usize,
    /// Histogram banks (two per camera) and their bits.
    pub histogram_banks: usize,
    pub histogram_bits: usize,
    /// Gain cells of the matcher's array.
    pub pe_count: usize,
    /// Reference declivities per cell.
    pub rows_per_cell: usize,
    /// The cells' reference rows in LUT RAM (`rtl::primitives::lut_ram`: a cell's four
    /// rows of position, polarity and six levels), their bits and the
    /// `TRELLIS_DPR16X4` primitives that hold them (four bits each). Not in
    /// `memories`: the primitives are instantiated, not inferred.
    pub reference_row_bits: usize,
    pub reference_row_dpr16x4: usize,
    pub choice_memory_bits: usize,
    /// The record memories' bits, their position copies' included (all of
    /// `rtl::matcher::record_memory::RecordMemory`'s RAMs).
    pub record_memory_bits: usize,
    /// The record queues' bits (both cameras).
    pub record_queue_bits: usize,
    /// The row check's memories' bits.
    pub row_memory_bits: usize,
    /// The vertical median's line buffers and their bits.
    pub median_line_buffers: usize,
    pub median_line_buffer_bits: usize,
    /// The depth stage's table bits.
    pub depth_table_bits: usize,
    /// `DP16KD`s the blocks instantiate (`rtl::primitives::block_ram::BlockRam`); Yosys
    /// adds what it infers for the other memories.
    pub dp16kd_instances: usize,
    /// DSP blocks (`MULT18X18D`) of all stages.
    pub dsp_blocks: usize,
    /// All memories.
    pub memory_bits: usize,
}

impl Resources {
    fn of(stages: &[StageBudget]) -> Self {
        let memories: Vec<Memory> = stages.iter().flat_map(|s| s.memories.iter().cloned()).collect();
        let sum = |name: &str, f: fn(&Memory) -> usize| memories.iter().filter(|m| m.name == name).map(f).sum::<usize>();
        Resources {
            line_buffers: sum(LINE_BUFFER, |m| m.copies),
            line_buffer_bits: sum(LINE_BUFFER, |m| m.bits),
            histogram_banks: sum(HISTOGRAM, |m| m.copies * m.banks),
            histogram_bits: sum(HISTOGRAM, |m| m.bits),
            pe_count: stages.iter().filter_map(|s| s.pe_count).sum(),
            reference_row_bits: stages.iter().filter_map(|s| s.pe_count).sum::<usize>() * ROWS_PER_CELL * REFERENCE_ROW_BITS,
            reference_row_dpr16x4: stages.iter().filter_map(|s| s.pe_count).sum::<usize>() * REFERENCE_ROW_DPR16X4,
            rows_per_cell: stages.iter().filter_map(|s| s.rows_per_pe).max().unwrap_or(0),
            choice_memory_bits: sum(CHOICE_MEMORY, |m| m.bits),
            record_memory_bits: sum(RECORD_MEMORY, |m| m.bits) + sum(POSITION_COPY, |m| m.bits),
            record_queue_bits: sum(RECORD_QUEUE, |m| m.bits),
            row_memory_bits: sum(ROW_MEMORY, |m| m.bits),
            median_line_buffers: sum(MEDIAN_LINE_BUFFER, |m| m.copies * m.banks),
            median_line_buffer_bits: sum(MEDIAN_LINE_BUFFER, |m| m.bits),
            depth_table_bits: sum(DEPTH_TABLE, |m| m.bits),
            dp16kd_instances: memories.iter().filter_map(|m| m.dp16kd).sum(),
            dsp_blocks: stages.iter().filter_map(|s| s.dsp_blocks).sum(),
            memory_bits: memories.iter().map(|m| m.bits).sum(),
            memories,
        }
    }
}

/// The budget of a request.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Budget {
    pub width: usize,
    pub height: usize,
    /// Pixels stored and processed per line, `W' = min(W, W_MAX)` (`W`:
    /// wider lines are refused).
    pub stored_width: usize,
    pub n_max: usize,
    pub dispmax: f64,
    pub clock_mhz: f64,
    pub hblank: usize,
    pub cells: usize,
    /// The rows' work the numbers are for ([`RowLoad::worst`] unless
    /// [`budget_with_load`] was given another).
    pub load: RowLoad,
    /// The stages in pipeline order.
    pub stages: Vec<StageBudget>,
    /// Clocks per line the input offers, `W + hblank`.
    pub input_cycles_per_line: u64,
    /// The stage with the most clocks per line.
    pub slowest_stage: &'static str,
    /// Its clocks per line.
    pub slowest_stage_cycles: u64,
    /// `P = max(W + hblank, slowest stage)`.
    pub line_period_cycles: u64,
    /// Clocks per worst line by which the slowest stage exceeds `W + hblank`,
    /// `P − (W + hblank)`: the detector holds the input (`tready` low) that
    /// long; a slower matcher falls behind by that much, which the record
    /// queues absorb for a while before records are dropped; a slower row
    /// check drops rows. The numbers below assume the input paced to `P`.
    pub stall_cycles_per_line: u64,
    /// The least hblank with which no stage is slower than the input.
    pub min_hblank_cycles: u64,
    /// A scanline's latency: a row's first pixel accepted → its first
    /// disparity out, the sum of the stages' latencies.
    pub latency_cycles: u64,
    pub latency_formula: String,
    pub latency_us: f64,
    /// A row's first pixel accepted → its last disparity out,
    /// `latency + (W' − 1)`.
    pub latency_last_pixel_cycles: u64,
    /// The frame's first disparity out → its last,
    /// `(H − 6)·P + max(c_last + ROW_RESTART_LAG, W') + 5·W' − 1`.
    pub output_span_cycles: u64,
    pub output_span_formula: String,
    /// The frame's first pixel accepted → its last disparity out,
    /// `latency + output span`.
    pub last_out_cycles: u64,
    /// The clock of the frame's last pixel accepted, from its first: rows
    /// every `P` (`line_starts` for back-to-back lines the detector holds).
    pub last_in_cycle: u64,
    /// The frame's last pixel accepted → its last disparity out (the
    /// pipeline's and the median's flush).
    pub flush_cycles: u64,
    /// The least vertical blanking, in lines of `P`, before the next frame
    /// of rows of the same work (see the module's doc).
    pub vblank_lines: u64,
    pub vblank_formula: String,
    /// The least vertical blanking whatever the next frame's rows (its
    /// first rows empty).
    pub vblank_lines_any_rows: u64,
    /// `(H + vblank_lines) × P`.
    pub frame_cycles: u64,
    pub frame_time_ms: f64,
    pub fps: f64,
    pub resources: Resources,
    /// What the numbers assume, and anything the request changed.
    pub notes: Vec<String>,
}

/// Checks a request and gives the sizes its budget is made for (every row
/// the worst).
fn validate(r: &BudgetRequest) -> Result<Sizes, BudgetError> {
    if r.width == 0 {
        return Err(BudgetError::ZeroWidth);
    }
    if r.height == 0 {
        return Err(BudgetError::ZeroHeight);
    }
    if r.height < MIN_HEIGHT {
        return Err(BudgetError::TooFewRows { height: r.height });
    }
    if r.height > MAX_HEIGHT {
        return Err(BudgetError::TooManyRows { height: r.height });
    }
    if r.width > W_MAX {
        return Err(BudgetError::TooWide { width: r.width });
    }
    if r.n_max == 0 {
        return Err(BudgetError::NoDeclivities);
    }
    if r.n_max > N_MAX {
        return Err(BudgetError::TooManyDeclivities { n: r.n_max });
    }
    if !MATCHER_CELLS.contains(&r.cells) {
        return Err(BudgetError::UnsupportedCells { cells: r.cells });
    }
    if r.n_max > ROWS_PER_CELL * r.cells {
        return Err(BudgetError::TooFewCells {
            n: r.n_max,
            cells: r.cells,
            rows: ROWS_PER_CELL * r.cells,
            need: r.n_max.div_ceil(ROWS_PER_CELL),
        });
    }
    if !(r.clock_mhz.is_finite() && r.clock_mhz > 0.0) {
        return Err(BudgetError::Clock { mhz: r.clock_mhz });
    }
    dispmax_lsb(r.dispmax)?;
    Ok(Sizes {
        width: r.width,
        stored_width: r.width.min(W_MAX),
        n: r.n_max,
        cells: r.cells,
        load: RowLoad::worst(r.n_max),
        worst: true,
        line_period: 0,
    })
}

/// The budget of `r` with every row the worst for `N = r.n_max` (see the
/// module's doc).
pub fn budget(r: &BudgetRequest) -> Result<Budget, BudgetError> {
    budget_with_load(r, &RowLoad::worst(r.n_max))
}

/// The budget of `r` for a frame whose rows take `load` (each row's line
/// pair at most `r.n_max` declivities a side): the numbers a simulation of
/// such a frame measures.
pub fn budget_with_load(r: &BudgetRequest, load: &RowLoad) -> Result<Budget, BudgetError> {
    let mut sizes = validate(r)?;
    assert!(
        load.n <= r.n_max && load.m <= r.n_max && load.k <= load.n.min(load.m),
        "a row load of {load:?} for N = {}",
        r.n_max
    );
    sizes.worst = *load == RowLoad::worst(r.n_max);
    sizes.load = *load;
    let input = (r.width + r.hblank) as u64;
    // The clocks per line do not depend on the line period; the latencies
    // do: a first pass gives the period, the second the latencies.
    let period_of = |stages: &[StageBudget]| stages.iter().map(|s| s.cycles_per_line).max().unwrap_or(0).max(input);
    let first: Vec<StageBudget> = STAGES.iter().map(|stage| stage(&sizes)).collect();
    sizes.line_period = period_of(&first);
    let mut stages: Vec<StageBudget> = STAGES.iter().map(|stage| stage(&sizes)).collect();
    for s in &mut stages {
        s.spare_cycles = input as i64 - s.cycles_per_line as i64;
    }
    // The first of the slowest (the detector when it ties with the stages
    // that also take a pixel a clock).
    let slowest = stages.iter().rev().max_by_key(|s| s.cycles_per_line).expect("at least one stage");
    let line_period = sizes.line_period;
    debug_assert_eq!(line_period, period_of(&stages));
    let (w, wp, h, p) = (r.width, sizes.stored_width, r.height, line_period as usize);

    // A scanline: its first pixel in → its first disparity out.
    let latency_terms: Vec<Term> = stages.iter().flat_map(|s| s.latency_terms.iter().cloned()).collect();
    let (latency_cycles, latency_formula) = render(&latency_terms);

    // The frame's end (module doc, "The frame's end").
    let last_check = if sizes.worst { "max(row_check_cycles(N, N, 0) + ROW_RESTART_LAG, W')" } else { "max(c_last + ROW_RESTART_LAG, W')" };
    let last_check_cycles = (load.last_check + ROW_RESTART_LAG).max(wp);
    let (output_span_cycles, output_span_formula) = render(&[
        Term::new(format!("(H − {MIN_HEIGHT})·P (output rows 0 … H − {MIN_HEIGHT}, one a line period)"), (h - MIN_HEIGHT) * p),
        Term::new(format!("{last_check} (the last row, checked right after row H − 2, follows it into the interpolator)"), last_check_cycles),
        Term::new(
            format!("{}·W' (output row H − {} in the last row's slot, then the median's flush of rows H − {MEDIAN_HALF} … H − 1, back to back)", MEDIAN_HALF + 1, MEDIAN_HALF + 1),
            (MEDIAN_HALF + 1) * wp,
        ),
        Term::minus("1", 1),
    ]);
    let last_out_cycles = latency_cycles + output_span_cycles;
    let det_cycles = stages[0].cycles_per_line;
    let last_in_cycle = if r.hblank == 0 && line_period == det_cycles {
        line_starts(&vec![w; h])[h - 1] + w as u64 - 1
    } else {
        ((h - 1) * p + w - 1) as u64
    };
    let flush_cycles = last_out_cycles - last_in_cycle;

    // Vertical blanking.
    let need = |terms: &[Term]| -> (u64, String) {
        let (sum, text) = render(terms);
        let lines = (sum.div_ceil(line_period)).saturating_sub(2);
        (lines, format!("⌈({text}) / P⌉ − 2, at least 0"))
    };
    let end = |first: Term| -> Vec<Term> {
        vec![
            Term::new(last_check, last_check_cycles),
            Term::new(format!("{}·W' (the last row and the median's flush)", MEDIAN_HALF + 1), (MEDIAN_HALF + 1) * wp),
            Term::new(if sizes.worst { "row_check_cycles(N, N, N)" } else { "c" }, load.check),
            first,
        ]
    };
    let (vblank_lines, vblank_formula) =
        need(&end(Term::minus(if sizes.worst { "row_check_cycles(0, N, N)" } else { "c_first" }, load.first_check)));
    let empty_line = line_cycles(0, 0, 0, 0, r.cells);
    let mut any = end(Term::minus("1 (an empty first row)", 1));
    any.push(Term::new(format!("line_cycles({}, K)", sizes.line_args()), load.line_cycles(r.cells)));
    any.push(Term::minus("line_cycles(0, 0, 0, 0, K) (an empty line)", empty_line));
    let (vblank_lines_any_rows, _) = need(&any);
    let frame_cycles = (r.height as u64 + vblank_lines) * line_period;
    let frame_time_ms = frame_cycles as f64 / (r.clock_mhz * 1e3);

    let mut notes = Vec::new();
    if r.n_max >= r.width {
        notes.push(format!(
            "N = {} ≥ W = {}: a line of W pixels has at most W − 1 declivities, so the matcher's worst line is pessimistic here",
            r.n_max, r.width
        ));
    }
    if slowest.name != stages[0].name && line_period > input {
        let queue_lines = RECORD_FIFO_DEPTH / (r.n_max + 1);
        let behind = if slowest.name == ROW_CHECK_NAME {
            "the row check falls behind and drops a row (lines_dropped) that arrives before it has finished the row two before it (its clocks are a bound, loose on real rows: about n + 7)".to_string()
        } else {
            format!("the matcher falls behind and the record queues ({RECORD_FIFO_DEPTH} beats a camera, {queue_lines} lines of N records) absorb a run of such lines before records are dropped (records_dropped), and a row check behind drops rows (lines_dropped)")
        };
        notes.push(format!(
            "the {} is slower than W + hblank: the numbers assume the input paced to P = {line_period} (hblank ≥ {}); with a faster input {behind}",
            slowest.name,
            slowest.cycles_per_line.saturating_sub(r.width as u64)
        ));
    }
    if r.width < MIN_LINE_PERIOD && r.hblank == 0 {
        let starts = line_starts(&[r.width; STEADY_LINES]);
        let y = STEADY_LINES - 1;
        let late = (y as u64 * line_period).saturating_sub(starts[y]);
        notes.push(format!(
            "W < MIN_LINE_PERIOD: the detector takes rows 0 and 1 back to back and then holds the input, so a row inside the frame was accepted y·P − line_starts[y] = {late} clocks earlier than the first row's latency assumes: its latency is {} clocks (from line_starts; not measured on the whole line processor)",
            latency_cycles + late
        ));
    } else if r.width < MIN_LINE_PERIOD {
        notes.push("W < MIN_LINE_PERIOD with hblank: the line starts are not modelled (line_starts takes back-to-back lines); the frame's end assumes rows every P".to_string());
    }
    let marker_latency = marker_latency_estimate(r.width) as usize;
    notes.push(format!(
        "marker_latency(W') = W' + {} clocks, of which THRESHOLD_LATENCY = {THRESHOLD_LATENCY} are the σ scan (the |ΔI| histogram's median and d_t)",
        marker_latency - sizes.stored_width
    ));
    if sizes.worst {
        let (n, _, stop, k) = worst_matcher_line(r.n_max);
        notes.push(format!(
            "the matcher's worst line: n = m = N = {n} declivities, a path of k = {k} pairs stopping on anti-diagonal {stop} (line_cycles and line_period grow with n, m and k and fall with the stop diagonal; the path of every diagonal pair reaches all bounds at once); its k = N matches checked against rows of N: row_check_cycles(N, N, N) = {} inside the frame, row_check_cycles(0, N, N) = {} for the first row, row_check_cycles(N, N, 0) = {} for the last — bounds, loose on real rows (about n + 7 clocks, rtl::post::row_check)",
            load.check, load.first_check, load.last_check
        ));
    } else {
        notes.push(format!(
            "the rows' work as given: the matcher's line (n, m, s, k) = ({}, {}, {}, {}), the row check's c = {} inside the frame, c_first = {}, c_last = {}",
            load.n, load.m, load.stop_diag, load.k, load.check, load.first_check, load.last_check
        ));
    }
    notes.push(format!("{SWEEP_FORMULA}, with ENGINE_LAG = {ENGINE_LAG}; {TRACEBACK_FORMULA}, with WALK_LEAD = {WALK_LEAD}; {LINE_PERIOD_FORMULA} (the matcher's clocks per line: the traceback of a line overlaps the sweep of the next), its latency TAKE_AFTER_MARKER + line_cycles"));
    notes.push(format!(
        "dispmax = {} px changes no clock count: eq. 6 only removes nodes, the sweep covers the whole table",
        r.dispmax
    ));
    notes.push(format!(
        "vertical blanking: the median (MEDIAN_TAPS = {MEDIAN_TAPS} rows) flushes the frame's last MEDIAN_HALF = {MEDIAN_HALF} rows after it and drops the pixels that come meanwhile (pixels_dropped); {} of P with rows of the same work, {} whatever the next frame's rows",
        lines(vblank_lines),
        lines(vblank_lines_any_rows)
    ));
    notes.push(format!(
        "latencies with the stages idle, as they are when the line period holds, each stage's output wired to the next; memory sizes are those the blocks are generated with (W_MAX = {W_MAX}, N_MAX = {N_MAX}, N_CELLS = {N_CELLS} gain cells of ROWS_PER_CELL = {ROWS_PER_CELL} rows, choice words of {CELLS_PER_CHOICE_WORD} rows' choices), whatever W, N and --cells"
    ));
    Ok(Budget {
        width: r.width,
        height: r.height,
        stored_width: sizes.stored_width,
        n_max: r.n_max,
        dispmax: r.dispmax,
        clock_mhz: r.clock_mhz,
        hblank: r.hblank,
        cells: r.cells,
        load: *load,
        input_cycles_per_line: input,
        slowest_stage: slowest.name,
        slowest_stage_cycles: slowest.cycles_per_line,
        line_period_cycles: line_period,
        stall_cycles_per_line: line_period - input,
        min_hblank_cycles: slowest.cycles_per_line.saturating_sub(r.width as u64),
        latency_cycles,
        latency_formula,
        latency_us: latency_cycles as f64 / r.clock_mhz,
        latency_last_pixel_cycles: latency_cycles + wp as u64 - 1,
        output_span_cycles,
        output_span_formula,
        last_out_cycles,
        last_in_cycle,
        flush_cycles,
        vblank_lines,
        vblank_formula,
        vblank_lines_any_rows,
        frame_cycles,
        frame_time_ms,
        fps: 1e3 / frame_time_ms,
        resources: Resources::of(&stages),
        stages,
        notes,
    })
}

/// `n lines` (`1 line`).
fn lines(n: u64) -> String {
    if n == 1 {
        "1 line".to_string()
    } else {
        format!("{n} lines")
    }
}

/// `n` with thin spaces between groups of three digits (`65 536`).
fn grouped(n: impl Into<u64>) -> String {
    let s = n.into().to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i) % 3 == 0 {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

/// The budget as text, as `declivity budget` prints it.
pub fn report_text(b: &Budget) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    let _ = writeln!(
        o,
        "latency budget: {}×{} px, N = {} declivities per line, dispmax {} px, {} MHz, hblank {}, {} gain cells",
        b.width, b.height, b.n_max, b.dispmax, b.clock_mhz, b.hblank, b.cells
    );
    let _ = writeln!(o, "\nper stage, clocks per line (worst line):");
    for s in &b.stages {
        let copies = if s.instances > 1 { format!(" ×{}", s.instances) } else { String::new() };
        let fits = if s.spare_cycles >= 0 {
            format!("fits W + hblank, {} to spare", s.spare_cycles)
        } else {
            format!("{} OVER W + hblank", -s.spare_cycles)
        };
        let _ = writeln!(o, "  {:<22} {:>6}   [{fits}]   {}", format!("{}{copies}", s.name), s.cycles_per_line, s.formula);
    }
    let _ = writeln!(
        o,
        "\nline period P      {} clocks = max(input W + hblank = {}, slowest stage: {} {})",
        b.line_period_cycles, b.input_cycles_per_line, b.slowest_stage, b.slowest_stage_cycles
    );
    if b.stall_cycles_per_line > 0 {
        if b.slowest_stage == b.stages[0].name {
            let _ = writeln!(
                o,
                "  the {} takes longer than W + hblank: it holds the input (tready low) {} clocks per line",
                b.slowest_stage, b.stall_cycles_per_line
            );
        } else {
            let _ = writeln!(
                o,
                "  the {} takes {} clocks per worst line more than W + hblank: hblank ≥ {} paces the input to it (else the record queues absorb a run of such lines, then records or rows are dropped)",
                b.slowest_stage, b.stall_cycles_per_line, b.min_hblank_cycles
            );
        }
    } else {
        let _ = writeln!(o, "  no stage is slower than the input's W + hblank: nothing holds the input or falls behind");
    }
    let _ = writeln!(
        o,
        "latency            {} clocks = {:.2} µs per scanline (a row's first pixel in → its first disparity out; its last {} clocks after the first pixel in)",
        b.latency_cycles,
        b.latency_us,
        b.latency_last_pixel_cycles
    );
    for s in &b.stages {
        let _ = writeln!(o, "  {:<22} {:>6}   {}: {}", s.name, s.latency_cycles, s.latency_span, s.latency_formula);
    }
    let _ = writeln!(
        o,
        "frame out          {} clocks from the first disparity out to the last: {}",
        b.output_span_cycles, b.output_span_formula
    );
    let _ = writeln!(
        o,
        "flush              {} clocks from the frame's last pixel in (clock {}) to its last disparity out (clock {})",
        b.flush_cycles, b.last_in_cycle, b.last_out_cycles
    );
    let _ = writeln!(
        o,
        "vertical blanking  {} (rows of the same work: {}); {} whatever the next frame's rows",
        lines(b.vblank_lines),
        b.vblank_formula,
        lines(b.vblank_lines_any_rows)
    );
    let _ = writeln!(
        o,
        "frame              ({} lines + {} of vertical blanking) × {} clocks = {} clocks = {:.3} ms at {} MHz, {:.1} frames/s",
        b.height,
        b.vblank_lines,
        b.line_period_cycles,
        grouped(b.frame_cycles),
        b.frame_time_ms,
        b.clock_mhz,
        b.fps
    );
    let r = &b.resources;
    let _ = writeln!(o, "resources (as generated; memories: copies × banks × words × bits)");
    let _ = writeln!(o, "  gain cells (PEs)   {}, {} reference rows each ({} rows)", r.pe_count, r.rows_per_cell, r.pe_count * r.rows_per_cell);
    let _ = writeln!(
        o,
        "  reference rows     {} × {} words × {} bit = {} bit in LUT RAM, {} TRELLIS_DPR16X4 instantiated (GainCell::rows_pos, rows_levs)",
        r.pe_count,
        r.rows_per_cell,
        REFERENCE_ROW_BITS,
        r.reference_row_bits,
        r.reference_row_dpr16x4
    );
    for m in &b.resources.memories {
        let rams = m.dp16kd.map_or("inferred".to_string(), |n| format!("{n} DP16KD"));
        let _ = writeln!(
            o,
            "  {:<18} {} × {} × {} words × {} bit = {} bit, {rams} ({})",
            m.name,
            m.copies,
            m.banks,
            m.words_per_bank,
            m.word_bits,
            grouped(m.bits as u64),
            m.rtl
        );
    }
    let _ = writeln!(o, "  all memories       {} bit; {} DP16KD instantiated (Yosys adds what it infers)", grouped(r.memory_bits as u64), r.dp16kd_instances);
    let dsp: Vec<String> = b.stages.iter().filter_map(|s| s.dsp_blocks.filter(|&d| d > 0).map(|d| format!("{} {d}", s.name))).collect();
    let _ = writeln!(o, "  DSP (MULT18X18D)   {} ({})", r.dsp_blocks, dsp.join(", "));
    for n in &b.notes {
        let _ = writeln!(o, "note: {n}");
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(width: usize, n: usize, cells: usize) -> BudgetRequest {
        BudgetRequest { cells, ..BudgetRequest::new(width, 100, n, 64.0, 125.0) }
    }

    /// Over every feasible `(n, m, stop, k)` of small lines (two phases and
    /// four), and over every `(n, m, k)` with the stop on anti-diagonal 0 at
    /// the sensor's size, no line costs the matcher more than the budget's
    /// worst: neither alone (`line_cycles`, the latency) nor back to back
    /// (`line_period`, the clocks per line).
    #[test]
    fn the_worst_matcher_line_is_the_largest_line_cycles_and_line_period() {
        for (big, cells) in [(12, 4), (16, 4), (8, 2), (6, 2), (32, 8), (24, 8), (N_MAX, N_CELLS)] {
            let (wn, wm, ws, wk) = worst_matcher_line(big);
            let worst = (line_cycles(wn, wm, ws, wk, cells), line_period(wn, wm, ws, wk, cells));
            for n in 0..=big {
                for m in 0..=big {
                    // The walk stops on an anti-diagonal of the grid, 0 ..= n + m - 2.
                    let stops = if big <= 32 { (n + m).saturating_sub(1) } else { 1 };
                    for stop in 0..stops.max(1) {
                        for k in 0..=n.min(m) {
                            // k pairs take 2k anti-diagonals of the n + m - 1 above the stop.
                            if n > 0 && m > 0 && stop + 2 * k > n + m {
                                continue;
                            }
                            let c = (line_cycles(n, m, stop, k, cells), line_period(n, m, stop, k, cells));
                            assert!(c.0 <= worst.0 && c.1 <= worst.1, "n {n} m {m} stop {stop} k {k} cells {cells}: {c:?} > {worst:?}");
                        }
                    }
                }
            }
        }
    }

    /// `sweep_cycles` never falls as a line grows, on either side, across
    /// the switch from two phases to four included, for every array the
    /// matcher is generated with and every line it holds.
    #[test]
    fn sweep_cycles_is_non_decreasing_in_n_and_m() {
        for cells in MATCHER_CELLS {
            let rows = ROWS_PER_CELL * cells;
            for n in 0..=rows {
                for m in 0..=rows {
                    let c = sweep_cycles(n, m, cells);
                    if n < rows {
                        assert!(sweep_cycles(n + 1, m, cells) >= c, "cells {cells}: n {n} → {} at m {m}", n + 1);
                    }
                    if m < rows {
                        assert!(sweep_cycles(n, m + 1, cells) >= c, "cells {cells}: m {m} → {} at n {n}", m + 1);
                    }
                }
            }
        }
    }

    /// `SWEEP_FORMULA` as its text reads, for `n ≤ 4·K`.
    fn sweep_as_printed(n: usize, m: usize, k: usize) -> usize {
        if n <= 2 * k {
            2 * (n + m) + (n > k) as usize + ENGINE_LAG - 3
        } else {
            let (p, c) = ((n - 1) / k, (n - 1) % k);
            4 * m + (p - 1) * (2 * k + 1) + (4 * c + 2 * k + 1).max(4 * (k - 1)) + ENGINE_LAG - 3
        }
    }

    /// The formulas printed as text are rtl's (a guard against the text
    /// going stale when rtl's change).
    #[test]
    fn the_printed_formulas_are_rtls() {
        for cells in MATCHER_CELLS {
            let rows = ROWS_PER_CELL * cells;
            for n in 1..=rows {
                for m in 1..=rows {
                    assert_eq!(sweep_cycles(n, m, cells), sweep_as_printed(n, m, cells), "n {n} m {m} K {cells}: {SWEEP_FORMULA}");
                    for (s, k) in [(0, 1), (0, n.min(m)), (n + m - 2, 1), ((n + m - 2).min(1), 0)] {
                        let walk = traceback_cycles(n, m, s, k);
                        if k > 0 {
                            assert_eq!(walk, WALK_LEAD + 1 + (n + m - 2 - s) + (k + 2), "{TRACEBACK_FORMULA}");
                        }
                        assert_eq!(line_period(n, m, s, k, cells), sweep_cycles(n, m, cells).max(walk) + 1, "{LINE_PERIOD_FORMULA}");
                        assert_eq!(line_cycles(n, m, s, k, cells), sweep_cycles(n, m, cells) + walk + rtl::matcher::declivity_matcher::OUTPUT_LAG);
                    }
                }
            }
        }
        // The sensor's worst line sweeps with four phases, the switch at
        // 2·K rows as the text says.
        assert_eq!(sweep_cycles(2 * N_CELLS, 1, N_CELLS), 2 * (2 * N_CELLS + 1) + 1 + ENGINE_LAG - 3);
        assert!(sweep_cycles(N_MAX, N_MAX, N_CELLS) > 4 * N_MAX);
    }

    #[test]
    fn detector_period_is_the_width_from_min_line_period_on() {
        for w in [MIN_LINE_PERIOD, MIN_LINE_PERIOD + 1, 512, W_MAX, W_MAX + 300] {
            assert_eq!(detector_cycles_per_line(w), w as u64);
        }
        // Shorter lines wait for the σ scan of the threshold engine.
        for w in [1, 64, THRESHOLD_LATENCY - 1] {
            assert_eq!(detector_cycles_per_line(w), THRESHOLD_LATENCY as u64 + 1);
        }
        // Just below MIN_LINE_PERIOD, line starts alternate between two
        // spacings; the budget takes the longer.
        for w in THRESHOLD_LATENCY..MIN_LINE_PERIOD {
            let c = detector_cycles_per_line(w);
            assert!(c > w as u64 && c <= MIN_LINE_PERIOD as u64, "W {w}: {c}");
        }
    }

    /// The value part of a rendered formula (`a + b − c = 1 + 2 − 3`, a
    /// `max(1, 2)` among the values taken as its larger).
    fn sum_of(f: &str) -> i64 {
        let mut values = f.rsplit(" = ").next().unwrap().to_string();
        while let Some(at) = values.find("max(") {
            let end = at + values[at..].find(')').unwrap();
            let larger = values[at + 4..end].split(", ").map(|v| v.parse::<i64>().unwrap()).max().unwrap();
            values.replace_range(at..=end, &larger.to_string());
        }
        let mut total = 0i64;
        let mut sign = 1;
        for tok in values.split_whitespace() {
            match tok {
                "+" => sign = 1,
                "−" => sign = -1,
                v => total += sign * v.parse::<i64>().unwrap(),
            }
        }
        total
    }

    #[test]
    fn formulas_add_up_to_their_values() {
        for (w, hblank) in [(512, 0), (1024, 320), (64, 0)] {
            let b = budget(&BudgetRequest { hblank, ..request(w, N_MAX, N_CELLS) }).unwrap();
            for s in &b.stages {
                assert_eq!(sum_of(&s.latency_formula), s.latency_cycles as i64, "{}: {}", s.name, s.latency_formula);
            }
            for name in ["matcher", "row check"] {
                let s = b.stages.iter().find(|s| s.name == name).unwrap();
                assert_eq!(sum_of(s.formula.split(" (a bound").next().unwrap()), s.cycles_per_line as i64, "{}", s.formula);
            }
            assert_eq!(sum_of(&b.latency_formula), b.latency_cycles as i64);
            assert_eq!(b.latency_cycles, b.stages.iter().map(|s| s.latency_cycles).sum::<u64>());
            assert_eq!(sum_of(&b.output_span_formula), b.output_span_cycles as i64);
            assert_eq!(b.last_out_cycles, b.latency_cycles + b.output_span_cycles);
            assert_eq!(b.latency_last_pixel_cycles, b.latency_cycles + b.stored_width as u64 - 1);
            // Five line periods: one in the row check, four in the median.
            let p = b.line_period_cycles;
            let lines: u64 = b.stages.iter().flat_map(|s| &s.latency_terms).filter(|t| t.text.starts_with("P ") || t.text.starts_with("4·P ")).map(|t| t.value as u64).sum();
            assert_eq!(lines, 5 * p);
        }
    }

    /// The worst row load takes rtl's bounds by name: the matcher's worst
    /// line and `row_check_cycles` of `N` matches with rows of `N` around,
    /// which no smaller row exceeds; at `N = N_MAX` the row check's clocks
    /// per line are `row_check_period()`.
    #[test]
    fn the_worst_row_load_is_rtls_bounds() {
        let w = RowLoad::worst(N_MAX);
        assert_eq!((w.n, w.m, w.stop_diag, w.k), worst_matcher_line(N_MAX));
        assert_eq!(w.check + ROW_RESTART_LAG, row_check_period());
        let b = budget(&request(1024, N_MAX, N_CELLS)).unwrap();
        let rc = b.stages.iter().find(|s| s.name == "row check").unwrap();
        assert_eq!(rc.cycles_per_line, row_check_period() as u64);
        for big in [1, 5, 16] {
            let w = RowLoad::worst(big);
            for a in 0..=big {
                for n in 0..=big {
                    for c in 0..=big {
                        assert!(row_check_cycles(a, n, c) <= w.check, "{a} {n} {c}");
                        assert!(row_check_cycles(0, n, c) <= w.first_check);
                        assert!(row_check_cycles(a, n, 0) <= w.last_check);
                    }
                }
            }
        }
    }

    /// Rows of the same work everywhere (the first row no lighter than the
    /// others) need at most the `MEDIAN_HALF` = 4 lines of vertical blanking
    /// the median's doc asks for (its flush of four rows, back to back),
    /// whatever the line period; lighter first rows need more.
    #[test]
    fn vertical_blanking_is_the_medians_four_lines_at_most_for_rows_of_equal_work() {
        for (w, hblank, n) in [(512, 0, 16), (1024, 0, 16), (300, 37, 8), (64, 0, 4), (1024, 0, N_MAX)] {
            let r = BudgetRequest { hblank, cells: N_CELLS, ..BudgetRequest::new(w, 100, n, 64.0, 125.0) };
            let worst = RowLoad::worst(n);
            let even = RowLoad { first_check: worst.check, last_check: worst.check, ..worst };
            let b = budget_with_load(&r, &even).unwrap();
            assert!(b.vblank_lines <= MEDIAN_HALF as u64, "W {w} N {n}: {} ({})", b.vblank_lines, b.vblank_formula);
            assert!(b.vblank_lines_any_rows >= b.vblank_lines);
            let bw = budget(&r).unwrap();
            assert!(bw.vblank_lines >= b.vblank_lines && bw.vblank_lines_any_rows >= bw.vblank_lines);
            assert_eq!(bw.frame_cycles, (100 + bw.vblank_lines) * bw.line_period_cycles);
        }
    }

    #[test]
    fn bad_requests_are_refused_with_their_reason() {
        let ok = request(512, 64, N_CELLS);
        assert!(budget(&ok).is_ok());
        let cases: [(BudgetRequest, fn(&BudgetError) -> bool); 11] = [
            (BudgetRequest { width: 0, ..ok }, |e| matches!(e, BudgetError::ZeroWidth)),
            (BudgetRequest { height: 0, ..ok }, |e| matches!(e, BudgetError::ZeroHeight)),
            (BudgetRequest { height: MIN_HEIGHT - 1, ..ok }, |e| matches!(e, BudgetError::TooFewRows { height: 5 })),
            (BudgetRequest { n_max: 0, ..ok }, |e| matches!(e, BudgetError::NoDeclivities)),
            (BudgetRequest { n_max: N_MAX + 1, ..ok }, |e| matches!(e, BudgetError::TooManyDeclivities { .. })),
            (BudgetRequest { cells: 5, ..ok }, |e| matches!(e, BudgetError::UnsupportedCells { cells: 5 })),
            (BudgetRequest { cells: 2 * N_CELLS, ..ok }, |e| matches!(e, BudgetError::UnsupportedCells { cells: 64 })),
            (BudgetRequest { n_max: 65, cells: 16, ..ok }, |e| matches!(e, BudgetError::TooFewCells { rows: 64, need: 17, .. })),
            (BudgetRequest { clock_mhz: 0.0, ..ok }, |e| matches!(e, BudgetError::Clock { .. })),
            (BudgetRequest { clock_mhz: f64::NAN, ..ok }, |e| matches!(e, BudgetError::Clock { .. })),
            (BudgetRequest { dispmax: 1.0, ..ok }, |e| matches!(e, BudgetError::Dispmax { .. })),
        ];
        for (r, want) in cases {
            let e = budget(&r).expect_err("refused");
            assert!(want(&e), "{r:?}: {e}");
        }
        for d in [W_MAX as f64 + 1.0, 10.01, f64::INFINITY] {
            assert!(matches!(budget(&BudgetRequest { dispmax: d, ..ok }), Err(BudgetError::Dispmax { .. })), "dispmax {d}");
        }
    }

    /// A frame rate is never given for pixels the hardware does not
    /// process, and sizes beyond the hardware's are refused before anything
    /// is allocated for them.
    #[test]
    fn lines_wider_than_w_max_and_frames_taller_than_the_row_count_are_refused() {
        assert!(budget(&request(W_MAX, N_MAX, N_CELLS)).is_ok());
        for w in [W_MAX + 1, W_MAX + 476, usize::MAX] {
            assert_eq!(budget(&request(w, N_MAX, N_CELLS)), Err(BudgetError::TooWide { width: w }));
        }
        let tall = |height| BudgetRequest { height, ..request(640, N_MAX, N_CELLS) };
        assert!(budget(&tall(MAX_HEIGHT)).is_ok());
        for h in [MAX_HEIGHT + 1, 300_000_000, usize::MAX] {
            assert_eq!(budget(&tall(h)), Err(BudgetError::TooManyRows { height: h }));
        }
    }

    #[test]
    fn grouped_digits() {
        assert_eq!(grouped(0u64), "0");
        assert_eq!(grouped(999u64), "999");
        assert_eq!(grouped(65_536u64), "65 536");
        assert_eq!(grouped(1_234_567u64), "1 234 567");
    }
}
