//! `declivity budget`: the line processor's clocks per line, latency and
//! frame rate at a resolution and clock.

use clap::Args;
use rtl::detector::declivity_detector::MIN_LINE_PERIOD;
use rtl::params::{MEDIAN_HALF, POS_FRAC_BITS, ROWS_PER_CELL};
use sim::budget::{budget, max_height, report_text, BudgetRequest, MIN_HEIGHT};
use sim::{Config, SimError};

use crate::args::{cells_per_config, config_help, per_config, CliConfig};

/// Latency budget of the hardware: clocks per line per stage, line period, latency, frame rate, resources.
#[derive(Args, Debug)]
#[command(allow_negative_numbers = true, long_about = long_about())]
pub(crate) struct BudgetArgs {
    #[arg(long, help = width_help())]
    width: usize,
    #[arg(long, help = height_help())]
    height: usize,
    #[arg(long, help = n_max_help())]
    n_max: usize,
    #[arg(long, help = dispmax_help())]
    dispmax: f64,
    /// Clock frequency in MHz (> 0), for the latency in µs, the frame time and frames per second.
    #[arg(long)]
    clock_mhz: f64,
    /// Horizontal blanking: idle clocks after each line on the inputs. A stage slower than
    /// W + hblank sets the line period: the input must be paced to it.
    #[arg(long, default_value_t = 0)]
    hblank: usize,
    #[arg(long, help = cells_help())]
    cells: Option<usize>,
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the budget"))]
    config: CliConfig,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn long_about() -> String {
    format!(
        "Latency budget of the hardware line processor (rtl::stereo_line_processor), from the rtl \
blocks' own cycle formulas and named constants, which the tests check against clocks measured by \
simulating the blocks and the whole line processor.

Per stage, in pipeline order (the two declivity detectors, the two record queues, the matcher, the row \
check, the interpolator, the vertical median, the depth stage): its clocks per line for the worst line, \
as a formula with its values. The detector takes W clocks per line (one pixel per clock) from \
W >= MIN_LINE_PERIOD = {MIN_LINE_PERIOD} on; the matcher (the configuration's gain cells, {cells}, of up \
to {ROWS_PER_CELL} reference declivities unless --cells says otherwise) takes line_period = max(sweep_cycles, \
traceback_cycles) + 1 clocks per line back to back, for its worst line of n = m = N declivities. Then: \
the line period P = max(W + hblank, slowest stage), and if a stage is slower than the input, by how \
much per line and the least hblank that paces the input to it; the latency of a scanline, from a row's \
first pixel accepted to its first disparity out, stage by stage (the row check waits for the row below, \
the vertical median for the {MEDIAN_HALF} rows below); the frame's end and the vertical blanking the \
median's flush needs; the frame time and frames per second; the resources as the rtl blocks declare \
them (memories in bits and DP16KD block RAMs, DSP blocks, gain cells), at the generation-time sizes \
of --config (W_MAX: {w_max}; N_MAX: {n_max}). --json prints the same as one JSON object (line_period_cycles, \
stall_cycles_per_line, min_hblank_cycles, latency_cycles, latency_us, output_span_cycles, flush_cycles, \
vblank_lines, frame_cycles, frame_time_ms, fps, stages[] with cycles_per_line, formula, latency_cycles, \
latency_formula, resources, notes, and the configuration: config, hardware with w_max, n_max, cells).",
        cells = per_config(|s| s.cells),
        w_max = per_config(|s| s.w_max),
        n_max = per_config(|s| s.n_max),
    )
}

fn width_help() -> String {
    format!(
        "Pixels per line W on each camera's input, at most the configuration's W_MAX ({}): the line \
         processor would process the first W_MAX pixels of a wider line and flag it wide, so a wider W \
         is refused, naming the configuration that takes it",
        per_config(|s| s.w_max)
    )
}

fn height_help() -> String {
    format!(
        "Lines per frame H (at least MIN_HEIGHT = {MIN_HEIGHT}: a row's output waits for the {} rows below it; \
         at most the line processor's row count: {})",
        MIN_HEIGHT - 1,
        Config::ALL.iter().map(|&c| format!("{c} {}", max_height(c))).collect::<Vec<_>>().join(", ")
    )
}

fn n_max_help() -> String {
    format!(
        "Characteristic declivities per line N to budget the matcher for, on both views: 1 to the \
         configuration's N_MAX ({}; the detector keeps at most N_MAX; at most {ROWS_PER_CELL} per gain \
         cell, so N <= {ROWS_PER_CELL}·cells)",
        per_config(|s| s.n_max)
    )
}

fn dispmax_help() -> String {
    format!(
        "Search bound of eq. 6 in px (greater than 1, at most the configuration's W_MAX, a multiple of \
         1/{}). Changes no clock count: it only removes nodes of the table the matcher sweeps",
        1u32 << POS_FRAC_BITS
    )
}

fn cells_help() -> String {
    format!(
        "Gain cells of the matcher's systolic array K ({}; each holds up to {ROWS_PER_CELL} reference \
         declivities, so N <= {ROWS_PER_CELL}·K) [default: the configuration's sensor: {}]",
        cells_per_config(),
        per_config(|s| s.cells)
    )
}

pub(crate) fn run(a: BudgetArgs) -> Result<(), SimError> {
    let config = a.config.0;
    let request = BudgetRequest {
        config,
        width: a.width,
        height: a.height,
        n_max: a.n_max,
        dispmax: a.dispmax,
        clock_mhz: a.clock_mhz,
        hblank: a.hblank,
        cells: a.cells.unwrap_or(config.sizes().cells),
    };
    let budget = budget(&request)?;
    if a.json {
        super::print_json(&budget);
    } else {
        print!("{}", report_text(&budget));
    }
    Ok(())
}
