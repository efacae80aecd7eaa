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
//!
//! ## Configurations
//! The budget is computed from the constants and formulas of one
//! configuration's crate: [`sd`] from `rtl`, [`hd`] from `rtl-hd` (the
//! same code, `budget/model.rs`, built once for each). The types are
//! shared, and [`budget`] computes a request in the configuration it names.

use serde::Serialize;

use crate::config::{Config, Sizes as HardwareSizes};
use crate::formats::DispmaxError;

/// The budget of the `sd` configuration (`rtl`).
pub mod sd {
    /// The configuration this module computes.
    pub const CONFIG: crate::config::Config = crate::config::Config::Sd;
    include!("model.rs");
}

/// The budget of the `hd` configuration (`rtl-hd`).
pub mod hd {
    use ::rtl_hd as rtl;
    /// The configuration this module computes.
    pub const CONFIG: crate::config::Config = crate::config::Config::Hd;
    include!("model.rs");
}

/// The budget of `r` in its configuration, every row the worst for
/// `N = r.n_max` (see the module's doc).
pub fn budget(r: &BudgetRequest) -> Result<Budget, BudgetError> {
    match r.config {
        Config::Sd => sd::budget(r),
        Config::Hd => hd::budget(r),
    }
}

/// The budget of `r` in its configuration with every row costing `load`.
pub fn budget_with_load(r: &BudgetRequest, load: &RowLoad) -> Result<Budget, BudgetError> {
    match r.config {
        Config::Sd => sd::budget_with_load(r, load),
        Config::Hd => hd::budget_with_load(r, load),
    }
}

/// The fewest rows of a frame the budget models (the same in every
/// configuration, [`sd::MIN_HEIGHT`]).
pub const MIN_HEIGHT: usize = sd::MIN_HEIGHT;
const _: () = assert!(sd::MIN_HEIGHT == hd::MIN_HEIGHT);

/// The most rows of a frame in `config` (its `height` port).
pub fn max_height(config: Config) -> usize {
    match config {
        Config::Sd => sd::MAX_HEIGHT,
        Config::Hd => hd::MAX_HEIGHT,
    }
}

/// What the budget is asked for (the options of `declivity budget`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BudgetRequest {
    /// The configuration budgeted.
    pub config: Config,
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
    /// A request for the `sd` sensor's matcher (its `N_CELLS` cells)
    /// without horizontal blanking.
    pub fn new(width: usize, height: usize, n_max: usize, dispmax: f64, clock_mhz: f64) -> Self {
        BudgetRequest { config: Config::Sd, width, height, n_max, dispmax, clock_mhz, hblank: 0, cells: Config::Sd.sizes().cells }
    }

    /// The request in `config`, with its sensor's matcher.
    pub fn in_config(self, config: Config) -> Self {
        BudgetRequest { config, cells: config.sizes().cells, ..self }
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
    #[error("--height {height}: the {config} line processor's row count has {height_bits} bits, at most {max} rows a frame")]
    TooManyRows {
        /// The rows asked for.
        height: usize,
        config: Config,
        height_bits: usize,
        /// The configuration's `MAX_HEIGHT`.
        max: usize,
    },
    /// `W > W_MAX`.
    #[error(
        "--width {width}: wider than the {config} line processor's W_MAX = {w_max} pixels (it would process the first {w_max} of each line and flag it wide); {}",
        Config::fitting_hint(*width)
    )]
    TooWide {
        /// The width asked for.
        width: usize,
        config: Config,
        /// The configuration's `W_MAX`.
        w_max: usize,
        /// The smallest configuration that takes the width, if any.
        fits: Option<Config>,
    },
    /// `N = 0`.
    #[error("--n-max 0: budget the matcher for at least one declivity per line (a line without one costs it a clock)")]
    NoDeclivities,
    /// `N > N_MAX`.
    #[error(
        "--n-max {n}: more than the {config} configuration's N_MAX = {n_max} declivities per line; the detector keeps the first {n_max} of a line, drops the rest and flags it full"
    )]
    TooManyDeclivities {
        /// The count asked for.
        n: usize,
        config: Config,
        /// The configuration's `N_MAX`.
        n_max: usize,
    },
    /// A cell count the matcher is not generated with.
    #[error("--cells {cells}: the {config} matcher is generated with {:?} gain cells", config.matcher_cells())]
    UnsupportedCells {
        /// The count asked for.
        cells: usize,
        config: Config,
    },
    /// More declivities than the array's rows.
    #[error(
        "--n-max {n} with --cells {cells}: the array holds {rows} reference declivities ({} per cell) and drops the rest; {n} need at least {need} cells", rows / cells
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
    /// Bits of one reference row.
    pub reference_row_word_bits: usize,
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


/// The budget of a request.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Budget {
    /// The configuration budgeted, and its sizes (`W_MAX`, `N_MAX`, the
    /// sensor's cells).
    pub config: Config,
    pub hardware: HardwareSizes,
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
    let _ = writeln!(
        o,
        "configuration {}: lines up to W_MAX = {} px, N_MAX = {} declivities, {} gain cells of {} rows",
        b.config, b.hardware.w_max, b.hardware.n_max, b.hardware.cells, b.hardware.rows_per_cell
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
        r.reference_row_word_bits,
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

    #[test]
    fn grouped_digits() {
        assert_eq!(grouped(0u64), "0");
        assert_eq!(grouped(999u64), "999");
        assert_eq!(grouped(65_536u64), "65 536");
        assert_eq!(grouped(1_234_567u64), "1 234 567");
    }

    /// A line too wide for `sd` is refused with the configuration that
    /// takes it named, and budgeted in that one; a line too wide for every
    /// configuration is refused in each.
    #[test]
    fn a_line_wider_than_sd_names_hd_and_hd_budgets_it() {
        for (width, height, fps_at_least) in [(1280, 720, 60.0), (1920, 1080, 30.0)] {
            let sd = BudgetRequest::new(width, height, 128, 64.0, 148.5);
            let e = budget(&sd).expect_err("wider than sd's W_MAX");
            assert!(matches!(e, BudgetError::TooWide { fits: Some(Config::Hd), .. }), "{e}");
            assert!(e.to_string().contains("--config hd"), "{e}");
            let b = budget(&sd.in_config(Config::Hd)).expect("hd takes it");
            assert_eq!((b.config, b.hardware.w_max, b.hardware.n_max, b.cells), (Config::Hd, 2048, 256, 64));
            assert!(b.fps >= fps_at_least, "{width}×{height}: {} frames/s", b.fps);
        }
        let wide = BudgetRequest::new(2049, 720, 128, 64.0, 148.5).in_config(Config::Hd);
        let e = budget(&wide).expect_err("wider than every configuration");
        assert!(matches!(e, BudgetError::TooWide { fits: None, .. }) && e.to_string().contains("no configuration"), "{e}");
    }
}
