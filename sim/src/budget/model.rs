// The budget of one configuration, included by `budget/mod.rs` once per
// configuration crate (`rtl` names that crate here).

use rtl::detector::adaptive_threshold::THRESHOLD_LATENCY;
use rtl::primitives::block_ram::{dp16kd_count, DP16KD_WIDTH};
use rtl::primitives::lut_ram::DPR16X4_WIDTH;
use rtl::detector::declivity_detector::{camera_marker_latency, line_starts, MIN_LINE_PERIOD};
use rtl::matcher::declivity_matcher::{line_cycles, line_period, sweep_cycles, ENGINE_LAG, TAKE_AFTER_MARKER};
use rtl::post::depth_stage::DEPTH_LAG;
use rtl::post::interpolator::{LINE_BITS, LINE_QUEUE, PIXEL_LAG, SEGMENT_BITS, SEGMENT_LAG};
use rtl::params::{
    CELLS_PER_CHOICE_WORD, CHOICE_WORDS, CHOICE_WORD_BITS, DEPTH_INDEX_BITS, DEPTH_WORD_BITS, DIAG_BITS,
    HIST_ADDR_BITS, HIST_COUNT_BITS, INDEX_BITS, LEVELS_BITS, LEVEL_BITS, LINE_BUF_ADDR_BITS, MEDIAN_HALF, MEDIAN_LINE_BUFFERS, MEDIAN_TAPS, N_CELLS,
    N_MAX, PIXEL_BITS, POS_BITS, RECIP_BITS, RECIP_INDEX_BITS, ROWS_PER_CELL, ROW_ADDR_BITS, ROW_BANK_BITS,
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

use super::{lines, render, Budget, BudgetError, BudgetRequest, Memory, Resources, RowLoad, Sizes, StageBudget, Term};
use super::{CHOICE_MEMORY, DEPTH_TABLE, HISTOGRAM, LINE_BUFFER, MEDIAN_LINE_BUFFER, POSITION_COPY, RECORD_MEMORY, RECORD_QUEUE, ROW_MEMORY};
use crate::config::Config;
use crate::formats::dispmax_lsb;

/// The fewest rows of a frame the budget models: row `y`'s output waits for
/// rows `y + 1` (the row check) and `y + MEDIAN_HALF` (the vertical
/// median), and row `y + MEDIAN_HALF`'s check for row `y + MEDIAN_HALF +
/// 1`; the first output row leaves on that path only if that row exists.
pub const MIN_HEIGHT: usize = MEDIAN_HALF + 2;
/// The most rows a frame can have: the largest `height` the line
/// processor's `HEIGHT_BITS`-bit input takes.
pub const MAX_HEIGHT: usize = (1 << HEIGHT_BITS) - 1;

/// `DP16KD`s of one `rtl::primitives::block_ram::BlockRam` of `words` words of
/// `word_bits` bits (`rtl::primitives::block_ram::dp16kd_count`: the
/// widest mode that holds the words, one per that many bits).
const fn dp16kd_of(word_bits: usize, words: usize) -> usize {
    dp16kd_count(word_bits, words.next_power_of_two().trailing_zeros() as usize)
}

/// Bits of a reference row in a gain cell's LUT RAM: the position and its
/// polarity, and the six levels (`rtl::matcher::gain_cell`).
const REFERENCE_ROW_BITS: usize = POS_BITS + 1 + LEVELS_BITS;
/// `TRELLIS_DPR16X4`s of one gain cell's rows: one per four bits of each of
/// its two LUT RAMs (`rtl::primitives::lut_ram`).
const REFERENCE_ROW_DPR16X4: usize = (POS_BITS + 1).div_ceil(DPR16X4_WIDTH) + LEVELS_BITS.div_ceil(DPR16X4_WIDTH);

/// Every row the worst for `n` declivities per side: the matcher's
/// worst line ([`worst_matcher_line`]) and its `n` matches checked
/// against rows of `n` matches, at the bound `row_check_cycles`.
pub const fn worst_load(n: usize) -> RowLoad {
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

/// `line_cycles(n, m, s, k, cells)` of a row's load.
const fn load_line_cycles(l: &RowLoad, cells: usize) -> usize {
    line_cycles(l.n, l.m, l.stop_diag, l.k, cells)
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
        Term::new("marker_latency(W')", camera_marker_latency(s.width)),
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
                "SystolicMatcher::ram[g] (one per row group g of 16 rows, CHOICE_WORDS in all: its 2-bit choices of an anti-diagonal in a word), two banks: the traceback of a line reads one while the next line's sweep writes the other",
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
            Memory::new(NAME, "segment memory", 1, 1, 1 << SEG_ADDR_BITS, SEGMENT_BITS, Some(seg_rams), "Interpolator::seg_* (one block RAM per field)"),
            Memory::new(
                NAME,
                "reciprocal table",
                1,
                1,
                1 << RECIP_INDEX_BITS,
                RECIP_BITS,
                Some(dp16kd_of(RECIP_BITS, 1 << RECIP_INDEX_BITS)),
                "Interpolator::recip (a BlockRam that starts with the table and is never written)",
            ),
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

/// The resources of the stages, summed.
fn resources_of(stages: &[StageBudget]) -> Resources {
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
        reference_row_word_bits: REFERENCE_ROW_BITS,
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

/// Checks a request and gives the sizes its budget is made for (every row
/// the worst).
///
/// # Panics
/// If `r` names another configuration than this module's (the budget
/// entry points of `super` choose the module by it).
fn validate(r: &BudgetRequest) -> Result<Sizes, BudgetError> {
    assert_eq!(r.config, CONFIG, "a request of one configuration budgeted in another");
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
        return Err(BudgetError::TooManyRows { height: r.height, config: CONFIG, height_bits: HEIGHT_BITS, max: MAX_HEIGHT });
    }
    if r.width > W_MAX {
        return Err(BudgetError::TooWide { width: r.width, config: CONFIG, w_max: W_MAX, fits: Config::fitting(r.width) });
    }
    if r.n_max == 0 {
        return Err(BudgetError::NoDeclivities);
    }
    if r.n_max > N_MAX {
        return Err(BudgetError::TooManyDeclivities { n: r.n_max, config: CONFIG, n_max: N_MAX });
    }
    if !CONFIG.matcher_cells().contains(&r.cells) {
        return Err(BudgetError::UnsupportedCells { cells: r.cells, config: CONFIG });
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
    dispmax_lsb(r.dispmax, CONFIG)?;
    Ok(Sizes {
        width: r.width,
        stored_width: r.width.min(W_MAX),
        n: r.n_max,
        cells: r.cells,
        load: worst_load(r.n_max),
        worst: true,
        line_period: 0,
    })
}

/// The budget of `r` with every row the worst for `N = r.n_max` (see the
/// module's doc).
pub fn budget(r: &BudgetRequest) -> Result<Budget, BudgetError> {
    budget_with_load(r, &worst_load(r.n_max))
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
    sizes.worst = *load == worst_load(r.n_max);
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
    any.push(Term::new(format!("line_cycles({}, K)", sizes.line_args()), load_line_cycles(load, r.cells)));
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
    let marker_latency = camera_marker_latency(r.width);
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
        config: CONFIG,
        hardware: CONFIG.sizes(),
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
        resources: resources_of(&stages),
        stages,
        notes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(width: usize, n: usize, cells: usize) -> BudgetRequest {
        BudgetRequest { cells, ..BudgetRequest::new(width, 100, n, 64.0, 125.0).in_config(CONFIG) }
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
        for &cells in CONFIG.matcher_cells() {
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
        for &cells in CONFIG.matcher_cells() {
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
        let w = worst_load(N_MAX);
        assert_eq!((w.n, w.m, w.stop_diag, w.k), worst_matcher_line(N_MAX));
        assert_eq!(w.check + ROW_RESTART_LAG, row_check_period());
        let b = budget(&request(1024, N_MAX, N_CELLS)).unwrap();
        let rc = b.stages.iter().find(|s| s.name == "row check").unwrap();
        assert_eq!(rc.cycles_per_line, row_check_period() as u64);
        for big in [1, 5, 16] {
            let w = worst_load(big);
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
            let r = BudgetRequest { hblank, ..request(w, n, N_CELLS) };
            let worst = worst_load(n);
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
            (BudgetRequest { cells: 5, ..ok }, |e| matches!(e, BudgetError::UnsupportedCells { cells: 5, config: CONFIG })),
            (BudgetRequest { cells: 2 * N_CELLS, ..ok }, |e| matches!(e, BudgetError::UnsupportedCells { cells, .. } if *cells == 2 * N_CELLS)),
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
            assert_eq!(budget(&request(w, N_MAX, N_CELLS)), Err(BudgetError::TooWide { width: w, config: CONFIG, w_max: W_MAX, fits: Config::fitting(w) }));
        }
        let tall = |height| BudgetRequest { height, ..request(640, N_MAX, N_CELLS) };
        assert!(budget(&tall(MAX_HEIGHT)).is_ok());
        for h in [MAX_HEIGHT + 1, 300_000_000, usize::MAX] {
            assert_eq!(budget(&tall(h)), Err(BudgetError::TooManyRows { height: h, config: CONFIG, height_bits: HEIGHT_BITS, max: MAX_HEIGHT }));
        }
    }
}

