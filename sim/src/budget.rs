//! The latency budget of the hardware line processor (`DESIGN.md` §3,
//! "Latency budget"): for each stage that exists in rtl, its clocks per line
//! as a formula of the line width `W`, the declivity counts `n`, `m` and
//! the σ scan, the line period, the latency of a scanline, frame time and
//! frames per second at a given clock, and the memories and processing
//! elements the blocks are generated with.
//!
//! Every number comes from rtl's own formulas (`marker_latency`,
//! `line_starts`, `sweep_cycles`, `traceback_cycles`, `line_cycles`, their
//! constants) and from the widths in `rtl::params`; nothing here re-derives
//! a clock count that rtl exports. `sim/tests/budget.rs` checks the numbers
//! against clocks measured by simulating the rtl blocks and the memory
//! sizes against the generated Verilog.
//!
//! The stages are a list ([`STAGES`]) in pipeline order: each gives its
//! clocks per line (how long it is busy with one line, the throughput
//! bound) and its latency (from the event that hands it a line to the
//! event that hands the line on). The stages that are in the line processor
//! (`rtl::stereo_line_processor`) but not in this budget yet
//! ([`NOT_YET_INCLUDED`]: the default mode's row check and vertical median,
//! the depth stage) become more entries of the list.
//!
//! ## The matcher's worst line
//! `line_cycles(n, m, s, k, K)` is `sweep_cycles(n, m, K)` =
//! `2·(n + m) + [n > K] + ENGINE_LAG − 3`, plus `traceback_cycles(n, m, s, k)`
//! = `WALK_LEAD + 1 + (n + m − 2 − s) + (k + 2)` (1 for `k = 0`), plus 3:
//! every term grows with `n`, `m` and the matches `k` and falls with the
//! anti-diagonal `s` on which the path stops. With `n, m ≤ N`, `k ≤ min(n, m)`
//! and `s ≥ 0`, all bounds are reached at once by one path, the one that
//! takes every diagonal pair `(i, i)` from `(N−1, N−1)` down to `(0, 0)`
//! (and stops there, `s = 0`): so the worst line is
//! `line_cycles(N, N, 0, N, K)`. (In general the stop and the pairs trade
//! off — a node moves the walk down two anti-diagonals, so `k` pairs need
//! `s ≤ n + m − 2k` — but `s = 0` with `k = N = n = m` meets that bound, so
//! the trade-off does not bind at the worst; the unit tests search every
//! feasible `(n, m, s, k)` of small lines to confirm it.)

use rtl::adaptive_threshold::THRESHOLD_LATENCY;
use rtl::declivity_detector::{line_starts, MIN_LINE_PERIOD};
use rtl::declivity_matcher::{line_cycles, sweep_cycles, ENGINE_LAG, OUTPUT_LAG, TAKE_AFTER_MARKER};
use rtl::params::{
    CELLS_PER_CHOICE_WORD, CHOICE_WORDS, CHOICE_WORD_BITS, DIAG_BITS, DISPMAX_BITS, HIST_ADDR_BITS, HIST_COUNT_BITS,
    INDEX_BITS, LEVEL_BITS, LINE_BUF_ADDR_BITS, N_CELLS, N_MAX, PIXEL_BITS, POS_BITS, POS_FRAC_BITS, RECIP_BITS, RECIP_INDEX_BITS,
    ROWS_PER_CELL, SEG_ADDR_BITS, W_MAX,
};
use rtl::interpolator::{LINE_BITS, LINE_QUEUE, PIXEL_LAG, SEGMENT_BITS, SEGMENT_LAG};
use rtl::traceback::{traceback_cycles, WALK_LEAD};
use serde::Serialize;

use crate::detector::marker_latency_estimate;
use crate::verilog::MATCHER_CELLS;

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
    #[error("--dispmax {dispmax}: {why}")]
    Dispmax {
        /// The bound asked for, px.
        dispmax: f64,
        /// What is wrong with it.
        why: String,
    },
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
    pub fn new(text: impl Into<String>, value: usize) -> Self {
        Term { text: text.into(), value: value as i64 }
    }

    /// A subtrahend.
    pub fn minus(text: impl Into<String>, value: usize) -> Self {
        Term { text: text.into(), value: -(value as i64) }
    }
}

/// The sum of `terms` and its formula, `a + b − c = 1 + 2 − 3`.
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
    let text = if terms.len() == 1 {
        terms[0].text.clone()
    } else {
        format!("{} = {}", join(&|t| t.text.clone()), join(&|t| t.value.unsigned_abs().to_string()))
    };
    (sum.max(0) as u64, text)
}

/// The detector's ping-pong line buffer.
pub const LINE_BUFFER: &str = "line buffer";
/// The detector's |ΔI| histogram.
pub const HISTOGRAM: &str = "|ΔI| histogram";
/// The matcher's record memories.
pub const RECORD_MEMORY: &str = "record memory";
/// The matcher's choice memory.
pub const CHOICE_MEMORY: &str = "choice memory";

/// One memory of a block, as rtl declares it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Memory {
    /// The stage it belongs to.
    pub stage: &'static str,
    /// What it holds.
    pub name: &'static str,
    /// Copies in the whole design (one per camera, one per view, ...).
    pub copies: usize,
    /// Banks per copy (ping-pong halves, low and high rows).
    pub banks: usize,
    /// Words per bank.
    pub words_per_bank: usize,
    /// Bits per word.
    pub word_bits: usize,
    /// `copies × banks × words_per_bank × word_bits`.
    pub bits: usize,
    /// Where rtl declares it and how its word is made up.
    pub rtl: &'static str,
}

impl Memory {
    fn new(
        stage: &'static str,
        name: &'static str,
        copies: usize,
        banks: usize,
        words_per_bank: usize,
        word_bits: usize,
        rtl: &'static str,
    ) -> Self {
        Memory { stage, name, copies, banks, words_per_bank, word_bits, bits: copies * banks * words_per_bank * word_bits, rtl }
    }
}

/// One stage's budget.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageBudget {
    /// The stage.
    pub name: &'static str,
    /// Copies of the block working side by side (the two cameras'
    /// detectors); the budget is per copy.
    pub instances: usize,
    /// Clocks the stage is busy with one line (worst case): the line
    /// period it can sustain.
    pub cycles_per_line: u64,
    /// `cycles_per_line` as a formula with its values.
    pub formula: String,
    /// Clocks from the event that hands the stage a line to the event that
    /// hands it on (see `latency_span`), the stage otherwise idle.
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
    /// the input; negative when the stage holds the input (it stalls by
    /// that much per worst line).
    pub spare_cycles: i64,
    /// Processing elements (gain cells) of the stage, if it has an array.
    pub pe_count: Option<usize>,
    /// Reference rows per processing element.
    pub rows_per_pe: Option<usize>,
    /// The stage's memories, generation-time sizes.
    pub memories: Vec<Memory>,
}

/// The sizes a budget is made for, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sizes {
    /// Pixels offered per line (`W`).
    pub width: usize,
    /// Pixels stored per line, `W' = min(W, W_MAX)`.
    pub stored_width: usize,
    /// Declivities per line on each side (`N`).
    pub n: usize,
    /// Gain cells (`K`).
    pub cells: usize,
}

/// A stage of the pipeline: its budget for the given sizes.
pub type Stage = fn(&Sizes) -> StageBudget;

/// The stages in rtl today, in pipeline order (a line passes them one
/// after the other; the scanline's latency is the sum of theirs).
pub const STAGES: [Stage; 3] = [detector_stage, matcher_stage, interpolator_stage];

/// Stages of the line processor whose cycles are not in the budget yet.
pub const NOT_YET_INCLUDED: [&str; 2] = [
    "row check (rtl::row_check: one line of delay) and vertical median (rtl::vertical_median: two lines of delay, MEDIAN_LAG): in the line processor, not yet included here",
    "depth stage (rtl::depth_stage, Z = f·b/(D·p) per pixel, DEPTH_LAG clocks): in the line processor, not yet included here",
];

/// Lines of one width run through [`line_starts`] to see the detector's
/// steady state (it settles after two lines and alternates with period two
/// at most).
const STEADY_LINES: usize = 12;

/// Line starts of the warm-up that [`detector_cycles_per_line`] skips.
const WARM_UP_LINES: usize = 4;

/// The most clocks between consecutive line starts of back-to-back lines of
/// `width` pixels, in the detector's steady state
/// (`rtl::declivity_detector::line_starts`): `W` from
/// [`MIN_LINE_PERIOD`] on, more for shorter lines (the σ scan,
/// `THRESHOLD_LATENCY + 1` clocks per line, and the ping-pong banks).
pub fn detector_cycles_per_line(width: usize) -> u64 {
    let starts = line_starts(&[width; STEADY_LINES]);
    starts.windows(2).skip(WARM_UP_LINES).map(|w| w[1] - w[0]).max().unwrap_or(width as u64)
}

/// The clock on which the engine can take the next pair, counted back from
/// its marker: the engine takes it the clock after the traceback ends, and
/// the marker leaves OUTPUT_LAG output registers after that end
/// (`rtl::declivity_matcher`, "Timing"; `sim::matcher::match_lines` takes
/// the same).
pub const MARKER_AFTER_NEXT_TAKE: usize = OUTPUT_LAG - 1;

/// Clocks the matcher's engine is busy with a line pair of `n` reference
/// and `m` other declivities whose path stops on anti-diagonal `stop_diag`
/// with `k` pairs, on `cells` cells: from taking it to taking the next
/// (back to back, the next pair loaded meanwhile), `line_cycles − 2`.
pub const fn matcher_cycles_per_line(n: usize, m: usize, stop_diag: usize, k: usize, cells: usize) -> usize {
    line_cycles(n, m, stop_diag, k, cells) - MARKER_AFTER_NEXT_TAKE
}

/// The matcher's worst line for `n` declivities per side on `cells` cells:
/// `(n, m, stop_diag, k)` = `(N, N, 0, N)` (see the module's doc).
pub const fn worst_matcher_line(n: usize) -> (usize, usize, usize, usize) {
    (n, n, 0, n)
}

/// `rtl::declivity_matcher::sweep_cycles` as text.
pub const SWEEP_FORMULA: &str = "sweep_cycles(n, m, K) = 2·(n + m) + [n > K] + ENGINE_LAG − 3";
/// `rtl::traceback::traceback_cycles` as text (`k > 0`).
pub const TRACEBACK_FORMULA: &str = "traceback_cycles(n, m, s, k) = WALK_LEAD + 1 + (n + m − 2 − s) + (k + 2)";

/// The two declivity detectors (one per camera, identical, side by side).
pub fn detector_stage(s: &Sizes) -> StageBudget {
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
        Term::new("(W − 1)", s.width - 1),
        Term::new("marker_latency(W')", marker_latency_estimate(s.width) as usize),
    ];
    let (latency_cycles, latency_formula) = render(&latency_terms);
    StageBudget {
        name: NAME,
        instances: 2,
        cycles_per_line: cycles,
        formula,
        latency_cycles,
        latency_formula,
        latency_terms,
        latency_span: "a line's first pixel accepted → its marker out",
        spare_cycles: 0,
        pe_count: None,
        rows_per_pe: None,
        memories: vec![
            Memory::new(
                NAME,
                LINE_BUFFER,
                2,
                2,
                (1 << LINE_BUF_ADDR_BITS) / 2,
                PIXEL_BITS,
                "DeclivityDetector::line_buf (ping-pong), one per camera",
            ),
            Memory::new(
                NAME,
                HISTOGRAM,
                2,
                2,
                1 << HIST_ADDR_BITS,
                HIST_COUNT_BITS,
                "AdaptiveThreshold::hist0, hist1, one pair per camera",
            ),
        ],
    }
}

/// The matcher: systolic array, traceback, record and choice memories.
pub fn matcher_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "matcher";
    let (n, m, stop, k) = worst_matcher_line(s.n);
    let (cycles, formula) = render(&[
        Term::new("sweep_cycles(N, N, K)", sweep_cycles(n, m, s.cells)),
        Term::new("traceback_cycles(N, N, 0, N)", traceback_cycles(n, m, stop, k)),
        Term::new("OUTPUT_LAG output registers", line_cycles(n, m, stop, k, s.cells) - sweep_cycles(n, m, s.cells) - traceback_cycles(n, m, stop, k)),
        Term::minus("(OUTPUT_LAG − 1) (the next pair is taken the clock after the traceback ends)", MARKER_AFTER_NEXT_TAKE),
    ]);
    debug_assert_eq!(cycles, matcher_cycles_per_line(n, m, stop, k, s.cells) as u64);
    let latency_terms = vec![
        Term::new("TAKE_AFTER_MARKER", TAKE_AFTER_MARKER as usize),
        Term::new("line_cycles(N, N, 0, N, K)", line_cycles(n, m, stop, k, s.cells)),
        Term::minus("1 (the last match leaves the clock before the marker)", 1),
    ];
    let (latency_cycles, latency_formula) = render(&latency_terms);
    let record_bits = (POS_BITS + 1) + 6 * LEVEL_BITS;
    StageBudget {
        name: NAME,
        instances: 1,
        cycles_per_line: cycles,
        formula,
        latency_cycles,
        latency_formula,
        latency_terms,
        latency_span: "the pair's second marker taken → its last match out",
        spare_cycles: 0,
        pe_count: Some(s.cells),
        rows_per_pe: Some(ROWS_PER_CELL),
        memories: vec![
            Memory::new(
                NAME,
                RECORD_MEMORY,
                2,
                2,
                (1 << DIAG_BITS) / 2,
                record_bits,
                "RecordMemory::pos_mem, lev0_mem..lev5_mem (position and polarity, six levels), one per view",
            ),
            Memory::new(
                NAME,
                CHOICE_MEMORY,
                1,
                2,
                1 << DIAG_BITS,
                CHOICE_WORDS * CHOICE_WORD_BITS,
                "SystolicMatcher::lo_ram, hi_ram (low, high rows), one word of 2-bit choices per anti-diagonal",
            ),
            Memory::new(
                NAME,
                "traceback stack",
                1,
                1,
                1 << INDEX_BITS,
                2 * INDEX_BITS,
                "Traceback::stack_i, stack_j",
            ),
        ],
    }
}

/// The interpolator: one disparity per reference pixel per clock
/// (`rtl::interpolator`).
pub fn interpolator_stage(s: &Sizes) -> StageBudget {
    const NAME: &str = "interpolator";
    let latency_terms = vec![
        Term::new("1 (the matcher's marker, the clock after its last match)", 1),
        Term::new("SEGMENT_LAG", SEGMENT_LAG),
        Term::new("PIXEL_LAG", PIXEL_LAG),
        Term::new("(W' − 1) (the line's pixels)", s.stored_width - 1),
    ];
    let (latency_cycles, latency_formula) = render(&latency_terms);
    StageBudget {
        name: NAME,
        instances: 1,
        cycles_per_line: s.stored_width as u64,
        formula: "W' (one pixel per clock, lines back to back)".to_string(),
        latency_cycles,
        latency_formula,
        latency_terms,
        latency_span: "the matcher's last match out → the line's last disparity out",
        spare_cycles: 0,
        pe_count: None,
        rows_per_pe: None,
        memories: vec![
            Memory::new(NAME, "segment memory", 1, 1, 1 << SEG_ADDR_BITS, SEGMENT_BITS, "Interpolator::seg_* (one block RAM per field)"),
            Memory::new(NAME, "reciprocal table", 1, 1, 1 << RECIP_INDEX_BITS, RECIP_BITS, "Interpolator::recip (ROM)"),
            Memory::new(NAME, "line queue", 1, 1, LINE_QUEUE, LINE_BITS, "Interpolator::q_* (LUT RAM)"),
        ],
    }
}

/// Memories and processing elements of the stages, summed.
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
    pub choice_memory_bits: usize,
    pub record_memory_bits: usize,
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
            rows_per_cell: stages.iter().filter_map(|s| s.rows_per_pe).max().unwrap_or(0),
            choice_memory_bits: sum(CHOICE_MEMORY, |m| m.bits),
            record_memory_bits: sum(RECORD_MEMORY, |m| m.bits),
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
    /// Pixels stored and processed per line, `min(W, W_MAX)`.
    pub stored_width: usize,
    /// `W > W_MAX`: every line is processed on its first `W_MAX` pixels and
    /// flagged wide.
    pub wide: bool,
    pub n_max: usize,
    pub dispmax: f64,
    pub clock_mhz: f64,
    pub hblank: usize,
    pub cells: usize,
    /// The stages in pipeline order.
    pub stages: Vec<StageBudget>,
    /// Stages not in the budget yet.
    pub not_included: Vec<&'static str>,
    /// Clocks per line the input offers, `W + hblank`.
    pub input_cycles_per_line: u64,
    /// The stage with the most clocks per line.
    pub slowest_stage: &'static str,
    /// Its clocks per line.
    pub slowest_stage_cycles: u64,
    /// `max(W + hblank, slowest stage)`.
    pub line_period_cycles: u64,
    /// Clocks per line the input is held (`s_tready` low) when every line
    /// is the worst: `line_period − (W + hblank)`.
    pub stall_cycles_per_line: u64,
    /// The least hblank with which the input never stalls.
    pub min_hblank_cycles: u64,
    /// A scanline's first pixel accepted → its last disparity out: the sum of
    /// the stages' latencies.
    pub latency_cycles: u64,
    pub latency_formula: String,
    pub latency_us: f64,
    /// `H × line period`.
    pub frame_cycles: u64,
    pub frame_time_ms: f64,
    pub fps: f64,
    pub resources: Resources,
    /// What the numbers assume, and anything the request changed.
    pub notes: Vec<String>,
}

/// `--dispmax` in the matcher's unit, `1/2^POS_FRAC_BITS` px: a finite
/// value greater than 1 (eq. 6 searches `0 < d < dispmax`), at most
/// `W_MAX`, on that grid. A bound of `W_MAX` is clamped to the largest the
/// matcher's port holds, which no disparity inside a line reaches.
pub fn dispmax_lsb(dispmax: f64) -> Result<u32, BudgetError> {
    let unit = (1u32 << POS_FRAC_BITS) as f64;
    let err = |why: String| BudgetError::Dispmax { dispmax, why };
    if !dispmax.is_finite() || dispmax <= 1.0 {
        return Err(err("dispmax must be greater than 1 (eq. 6 searches 0 < d < dispmax)".into()));
    }
    if dispmax > W_MAX as f64 {
        return Err(err(format!("dispmax must be at most W_MAX = {W_MAX} px (the widest line the hardware stores)")));
    }
    let lsb = dispmax * unit;
    if lsb.fract() != 0.0 {
        return Err(err(format!(
            "the matcher takes dispmax in 1/{unit} px; give a multiple of 1/{unit}, e.g. {}",
            (lsb.round() / unit).max(1.0 + 1.0 / unit)
        )));
    }
    Ok((lsb as u32).min((1u32 << DISPMAX_BITS) - 1))
}

/// Checks a request and gives the sizes its budget is made for.
pub fn validate(r: &BudgetRequest) -> Result<Sizes, BudgetError> {
    if r.width == 0 {
        return Err(BudgetError::ZeroWidth);
    }
    if r.height == 0 {
        return Err(BudgetError::ZeroHeight);
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
    Ok(Sizes { width: r.width, stored_width: r.width.min(W_MAX), n: r.n_max, cells: r.cells })
}

/// The budget of `r` (see the module's doc).
pub fn budget(r: &BudgetRequest) -> Result<Budget, BudgetError> {
    let sizes = validate(r)?;
    let input = (r.width + r.hblank) as u64;
    let mut stages: Vec<StageBudget> = STAGES.iter().map(|stage| stage(&sizes)).collect();
    for s in &mut stages {
        s.spare_cycles = input as i64 - s.cycles_per_line as i64;
    }
    let slowest = stages.iter().max_by_key(|s| s.cycles_per_line).expect("at least one stage");
    let line_period = input.max(slowest.cycles_per_line);
    let latency_terms: Vec<Term> = stages.iter().flat_map(|s| s.latency_terms.iter().cloned()).collect();
    let (latency_cycles, latency_formula) = render(&latency_terms);
    let frame_cycles = r.height as u64 * line_period;
    let frame_time_ms = frame_cycles as f64 / (r.clock_mhz * 1e3);
    let mut notes = Vec::new();
    if r.width > W_MAX {
        notes.push(format!(
            "W = {} > W_MAX = {W_MAX}: the detector processes the first {W_MAX} pixels of each line, accepts and drops the rest, and flags the line wide; the budget uses W' = {W_MAX} stored pixels, the input still takes W clocks per line",
            r.width
        ));
    }
    if r.n_max >= r.width {
        notes.push(format!(
            "N = {} ≥ W = {}: a line of W pixels has at most W − 1 declivities, so the matcher's worst line is pessimistic here",
            r.n_max, r.width
        ));
    }
    let marker_latency = marker_latency_estimate(r.width) as usize;
    notes.push(format!(
        "marker_latency(W') = W' + {} clocks, of which THRESHOLD_LATENCY = {THRESHOLD_LATENCY} are the σ scan (the |ΔI| histogram's median and d_t)",
        marker_latency - sizes.stored_width
    ));
    let (n, _, stop, k) = worst_matcher_line(r.n_max);
    notes.push(format!(
        "the matcher's worst line: n = m = N = {n} declivities, a path of k = {k} pairs stopping on anti-diagonal {stop} (line_cycles grows with n, m and k and falls with the stop diagonal; the path of every diagonal pair reaches all bounds at once)"
    ));
    notes.push(format!("{SWEEP_FORMULA} with ENGINE_LAG = {ENGINE_LAG}; {TRACEBACK_FORMULA} with WALK_LEAD = {WALK_LEAD}"));
    notes.push(format!(
        "dispmax = {} px changes no clock count: eq. 6 only removes nodes, the sweep covers the whole table",
        r.dispmax
    ));
    notes.push(format!(
        "latency with the engines idle (as they are when the line period holds), each stage's output wired to the next; memory sizes are those the blocks are generated with (W_MAX = {W_MAX}, N_MAX = {N_MAX}, choice words of {CELLS_PER_CHOICE_WORD} cells for N_CELLS = {N_CELLS}), whatever W, N and --cells"
    ));
    Ok(Budget {
        width: r.width,
        height: r.height,
        stored_width: sizes.stored_width,
        wide: r.width > W_MAX,
        n_max: r.n_max,
        dispmax: r.dispmax,
        clock_mhz: r.clock_mhz,
        hblank: r.hblank,
        cells: r.cells,
        not_included: NOT_YET_INCLUDED.to_vec(),
        input_cycles_per_line: input,
        slowest_stage: slowest.name,
        slowest_stage_cycles: slowest.cycles_per_line,
        line_period_cycles: line_period,
        stall_cycles_per_line: line_period - input,
        min_hblank_cycles: slowest.cycles_per_line.saturating_sub(r.width as u64),
        latency_cycles,
        latency_formula,
        latency_us: latency_cycles as f64 / r.clock_mhz,
        frame_cycles,
        frame_time_ms,
        fps: 1e3 / frame_time_ms,
        resources: Resources::of(&stages),
        stages,
        notes,
    })
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
            format!("STALLS the input {} per line", -s.spare_cycles)
        };
        let _ = writeln!(o, "  {:<22} {:>6}   [{fits}]   {}", format!("{}{copies}", s.name), s.cycles_per_line, s.formula);
    }
    for s in &b.not_included {
        let _ = writeln!(o, "  {s}");
    }
    let _ = writeln!(
        o,
        "\nline period        {} clocks = max(input W + hblank = {}, slowest stage: {} {})",
        b.line_period_cycles, b.input_cycles_per_line, b.slowest_stage, b.slowest_stage_cycles
    );
    if b.stall_cycles_per_line > 0 {
        let _ = writeln!(
            o,
            "  the {} takes longer than W + hblank: the input stalls {} clocks per worst line; hblank ≥ {} avoids it",
            b.slowest_stage, b.stall_cycles_per_line, b.min_hblank_cycles
        );
    } else {
        let _ = writeln!(o, "  no stage is slower than the input's W + hblank: the input never stalls");
    }
    let _ = writeln!(o, "latency            {} clocks = {:.2} µs per scanline (first pixel in → last disparity out)", b.latency_cycles, b.latency_us);
    for s in &b.stages {
        let _ = writeln!(o, "  {:<22} {:>6}   {}: {}", s.name, s.latency_cycles, s.latency_span, s.latency_formula);
    }
    let _ = writeln!(
        o,
        "frame              {} lines × {} clocks = {} clocks = {:.3} ms at {} MHz, {:.1} frames/s",
        b.height,
        b.line_period_cycles,
        grouped(b.frame_cycles),
        b.frame_time_ms,
        b.clock_mhz,
        b.fps
    );
    let r = &b.resources;
    let _ = writeln!(o, "resources (as generated; memories: copies × banks × words × bits)");
    let _ = writeln!(o, "  gain cells (PEs)   {}, {} reference rows each ({} rows)", r.pe_count, r.rows_per_cell, r.pe_count * r.rows_per_cell);
    for m in &r.memories {
        let _ = writeln!(
            o,
            "  {:<18} {} × {} × {} words × {} bit = {} bit ({})",
            m.name,
            m.copies,
            m.banks,
            m.words_per_bank,
            m.word_bits,
            grouped(m.bits as u64),
            m.rtl
        );
    }
    let _ = writeln!(o, "  all memories       {} bit", grouped(r.memory_bits as u64));
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

    /// Over every feasible `(n, m, stop, k)` of small lines, and over every
    /// `(n, m, k)` with the stop on anti-diagonal 0 at the sensor's size, no
    /// line costs the matcher more than the budget's worst.
    #[test]
    fn the_worst_matcher_line_is_the_largest_line_cycles() {
        for (big, cells) in [(12, 8), (16, 8), (6, 4), (N_MAX, N_CELLS)] {
            let (wn, wm, ws, wk) = worst_matcher_line(big);
            let worst = matcher_cycles_per_line(wn, wm, ws, wk, cells);
            for n in 0..=big {
                for m in 0..=big {
                    let stops = if big <= 16 { n + m } else { 1 };
                    for stop in 0..stops.max(1) {
                        for k in 0..=n.min(m) {
                            // k pairs take 2k anti-diagonals of the n + m - 1 above the stop.
                            if n > 0 && m > 0 && stop + 2 * k > n + m {
                                continue;
                            }
                            let c = matcher_cycles_per_line(n, m, stop, k, cells);
                            assert!(c <= worst, "n {n} m {m} stop {stop} k {k} cells {cells}: {c} > {worst}");
                        }
                    }
                }
            }
        }
    }

    /// The formulas printed as text are rtl's (a guard against the text
    /// going stale when rtl's change).
    #[test]
    fn the_printed_formulas_are_rtls() {
        for n in 1..=N_MAX {
            for m in 1..=N_MAX {
                for cells in [8, N_CELLS] {
                    assert_eq!(sweep_cycles(n, m, cells), 2 * (n + m) + (n > cells) as usize + ENGINE_LAG - 3, "{SWEEP_FORMULA}");
                }
                for (s, k) in [(0, 1), (0, n.min(m)), (n + m - 2, 1), (1, 0)] {
                    if k > 0 {
                        assert_eq!(traceback_cycles(n, m, s, k), WALK_LEAD + 1 + (n + m - 2 - s) + (k + 2), "{TRACEBACK_FORMULA}");
                    }
                }
            }
        }
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

    #[test]
    fn formulas_add_up_to_their_values() {
        let b = budget(&request(512, N_MAX, N_CELLS)).unwrap();
        let sum_of = |f: &str| -> u64 {
            let values = f.rsplit(" = ").next().unwrap();
            let mut total = 0i64;
            let mut sign = 1;
            for tok in values.split_whitespace() {
                match tok {
                    "+" => sign = 1,
                    "−" => sign = -1,
                    v => total += sign * v.parse::<i64>().unwrap(),
                }
            }
            total as u64
        };
        let m = &b.stages[1];
        assert_eq!(sum_of(&m.formula), m.cycles_per_line);
        assert_eq!(sum_of(&m.latency_formula), m.latency_cycles);
        assert_eq!(sum_of(&b.stages[0].latency_formula), b.stages[0].latency_cycles);
        assert_eq!(b.latency_cycles, b.stages.iter().map(|s| s.latency_cycles).sum::<u64>());
    }

    #[test]
    fn bad_requests_are_refused_with_their_reason() {
        let ok = request(512, 64, 32);
        assert!(budget(&ok).is_ok());
        let cases: [(BudgetRequest, fn(&BudgetError) -> bool); 9] = [
            (BudgetRequest { width: 0, ..ok }, |e| matches!(e, BudgetError::ZeroWidth)),
            (BudgetRequest { height: 0, ..ok }, |e| matches!(e, BudgetError::ZeroHeight)),
            (BudgetRequest { n_max: 0, ..ok }, |e| matches!(e, BudgetError::NoDeclivities)),
            (BudgetRequest { n_max: N_MAX + 1, cells: 64, ..ok }, |e| matches!(e, BudgetError::TooManyDeclivities { .. })),
            (BudgetRequest { cells: 5, ..ok }, |e| matches!(e, BudgetError::UnsupportedCells { cells: 5 })),
            (BudgetRequest { n_max: 65, ..ok }, |e| matches!(e, BudgetError::TooFewCells { need: 33, .. })),
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

    #[test]
    fn a_line_wider_than_w_max_is_budgeted_on_w_max_pixels_and_says_so() {
        let b = budget(&request(W_MAX + 476, N_MAX, N_CELLS)).unwrap();
        assert!(b.wide && b.stored_width == W_MAX);
        assert_eq!(b.input_cycles_per_line, W_MAX as u64 + 476);
        assert!(b.notes.iter().any(|n| n.contains("wide") && n.contains("W_MAX")), "{:?}", b.notes);
        assert_eq!(b.stages[0].latency_cycles, (W_MAX + 476 - 1) as u64 + marker_latency_estimate(W_MAX));
    }

    #[test]
    fn grouped_digits() {
        assert_eq!(grouped(0u64), "0");
        assert_eq!(grouped(999u64), "999");
        assert_eq!(grouped(65_536u64), "65 536");
        assert_eq!(grouped(1_234_567u64), "1 234 567");
    }
}
