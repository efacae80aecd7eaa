//! `declivity rtl detect|match|depth|faults`: the hardware, clock by clock, on
//! your images, compared with golden.

use std::ops::Range;
use std::path::PathBuf;

use clap::{Args, Subcommand};
use rtl::params::{DT_FRAC_BITS, MATCH_DT_FRAC_BITS, MEDIAN_HALF, POS_FRAC_BITS, ROWS_PER_CELL};
use sim::eval::io::{load_grey, load_pair_images};
use sim::jobs::rtl_depth::{rtl_depth, Engine, RtlDepthJob};
use sim::jobs::rtl_detect::{rtl_detect, Waveform};
use sim::jobs::rtl_match::{check_rows, rtl_match, MatchJob};
use sim::{Config, SimError};

use crate::args::{config_help, engine, parse_range, CameraArgs, CliConfig, CliEngine, CliRule};
use crate::progress::Progress;

#[derive(Subcommand, Debug)]
/// Run the cycle-accurate hardware (rtl) on images and compare it with golden.
pub(crate) enum RtlCommand {
    #[command(about = "Stream every row of an image through the rtl declivity detector.", long_about = detect_about())]
    Detect(DetectArgs),
    #[command(about = "Run the rows of a stereo pair through the rtl matcher and compare with golden.", long_about = match_about())]
    Match(MatchArgs),
    #[command(about = "Run a stereo pair through the whole rtl line processor, clock by clock.", long_about = depth_about())]
    Depth(DepthArgs),
    #[command(about = "Inject camera faults into the line processor's Verilog under Verilator and check its behaviour.", long_about = super::faults::faults_about())]
    Faults(super::faults::FaultsArgs),
}

fn detect_about() -> String {
    format!(
        "Stream every row of an 8-bit grey image (colour is converted with ITU-R 601 luma) through the \
cycle-accurate declivity detector (rtl::detector::declivity_detector; W_MAX, N_MAX of --config: {w}; {n}), \
back to back at one pixel per clock, and compare each line's records with golden's detector in \
hardware-parity mode, which computes the detector's fixed-point values exactly. Prints config, lines, pixels, \
cycles, px_per_clk, declivities_rtl, declivities_golden, mismatches (every difference in a record or a \
line's d_t, flags or count; 0 when they agree), borderline (of the mismatches, declivities one side \
only keeps whose |a| is floor(d_t) or floor(d_t) + 1), max_pos_err_lsb (position error in 1/{} px), \
max_dt_err_lsb (d_t error in 1/{} grey level) and sim_cycles_per_s, or one JSON object with --json. Writes declivities_rtl.png (the rtl \
records over the image) into --out, and with --vcd a waveform of the clocks during which --lines \
stream through.",
        1u32 << POS_FRAC_BITS,
        1u32 << DT_FRAC_BITS,
        w = crate::args::per_config(|s| s.w_max),
        n = crate::args::per_config(|s| s.n_max)
    )
}

fn match_about() -> String {
    format!(
        "Run the rows of a rectified stereo pair (8-bit grey; colour is converted with ITU-R 601 luma) \
through the cycle-accurate matcher (rtl::matcher::declivity_matcher: a systolic array of N_CELLS gain \
cells ({cells} by --config), each holding up to {ROWS_PER_CELL} of the N_MAX reference declivities ({n}), \
and its traceback; left view as reference) and compare every line with golden's matcher (eq. 4-9).

Both matchers get the same inputs: golden's declivities of each row (hardware-parity detector), \
brought to the detector's fixed-point formats (positions in 1/{pos} px rounded down, d_t in 1/{dt} \
grey level). On those values golden's f64 arithmetic is exact and the tolerance is zero, so every line \
is expected to come out identical, node for node. The rows are cut into runs simulated on parallel \
matchers, one per core, with a progress bar; --rows runs a few.

Prints, or with --json as one JSON object: config, cells, image, rule, dispmin and dispmax (px), lines, declivities_ref / \
declivities_other, matches_rtl / matches_golden, identical_lines, equal_gain_lines (other pairs with \
golden's optimal gain: a tie broken otherwise), mismatch_lines (neither: a bug), malformed_lines \
(outputs inconsistent with the inputs or with golden), off_schedule_lines (a marker on another clock \
than rtl::matcher::declivity_matcher::schedule gives: a bug), max_cycles_per_line and \
max_cycles_line, max_engine_period, cycles, sim_cycles_per_s, rows, seconds and graph. Writes into \
--out graph_rtl_line_Y.png: the matching graph of row Y (fig. 4) with golden's gains, golden's optimal \
path as green rings and the rtl path as orange boxes.",
        pos = 1u32 << POS_FRAC_BITS,
        dt = 1u32 << MATCH_DT_FRAC_BITS,
        cells = crate::args::per_config(|s| s.cells),
        n = crate::args::per_config(|s| s.n_max)
    )
}

fn depth_about() -> String {
    let camera = rtl::post::depth_stage::DepthCamera::default();
    format!(
        "Run a rectified stereo pair (8-bit grey; colour is converted with ITU-R 601 luma) through the \
cycle-accurate line processor (rtl::stereo_line_processor: two declivity detectors, a record queue per \
side, the matcher of N_CELLS cells ({cells} by --config) in the default gain rule, the row check, the \
interpolator with the default mode's edge jump, the vertical median of {rows} rows, and the depth \
stage generated for the camera of --focal-px and --baseline-m, by default focal length {f} px, baseline \
{b} mm, the motorcycle pair's), the two cameras \
streaming one pixel per clock with --hblank idle clocks after each line, and compare the disparity map \
with golden's default mode in hardware parity.

--engine verilator runs the processor's generated Verilog under Verilator (the default when \
`verilator` is installed; its build is kept in the temporary directory, keyed by the design, for later \
runs), rust-hdl the model itself (the default with --vcd or without Verilator; slow, thousands of \
clocks per second), icarus the Verilog under Icarus Verilog (slowest). --rows runs a band (as a frame of its own).

Prints, or with --json as one JSON object: image, config, hardware (w_max, n_max, cells), width, height, \
dispmin, dispmax, hblank, camera (focal_px, baseline_mm), pixels, cycles, \
px_per_clk, stall_cycles, latency_cycles (first pixel in to first disparity out), exact_px (share \
of pixels whose disparity equals golden's hardware parity exactly), exact_depth_px (the same for \
the depth), agree_quarter_px (share of pixels within 1/4 px of golden), sim_cycles_per_s, seconds, engine, build_seconds, \
lines_out, and the status counters records_dropped, lines_dropped, pixels_dropped, lines_full, \
lines_wide, lines_unpaired. Writes into --out disparity_rtl.png and disparity_golden.png (near is bright, one scale), \
disparity16_rtl.png (the output word's disparity: 16-bit, value = d x {unit}, 0 = none) and \
depth_mm_rtl.png (its depth in millimetres, 0 = none).",
        rows = 2 * MEDIAN_HALF + 1,
        f = camera.focal_px,
        b = camera.baseline_mm,
        unit = 1u32 << POS_FRAC_BITS,
        cells = crate::args::per_config(|s| s.cells)
    )
}

#[derive(Args, Debug)]
pub(crate) struct DetectArgs {
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
    #[arg(long, value_parser = parse_range, requires = "vcd")]
    lines: Option<Range<usize>>,
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the detector"))]
    config: CliConfig,
}

/// What `rtl match` and `rtl depth` both take: a rectified pair, eq. 6's
/// bound, the output form.
#[derive(Args, Debug)]
struct PairArgs {
    /// Left image of the rectified pair (the reference view).
    left: PathBuf,
    /// Right image of the rectified pair.
    right: PathBuf,
    #[arg(long, help = dispmax_help())]
    dispmax: f64,
    #[arg(long, default_value_t = 0.0, help = dispmin_help())]
    dispmin: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn dispmax_help() -> String {
    format!(
        "Search bound of eq. 6 in pixels: DISPMIN < d < DISPMAX (greater than 1, at most the configuration's \
         W_MAX: {w}; a multiple of 1/{unit} px: the matcher takes it in 1/{unit} px)",
        unit = 1u32 << POS_FRAC_BITS,
        w = crate::args::per_config(|s| s.w_max)
    )
}

fn dispmin_help() -> String {
    format!(
        "Lower search bound of eq. 6 in pixels (the paper's 0), the line processor's `dispmin` input: for a \
         verged or offset rig, or a scene with a known nearest range (0 or more, below DISPMAX - 1, a \
         multiple of 1/{} px)",
        1u32 << POS_FRAC_BITS
    )
}

#[derive(Args, Debug)]
pub(crate) struct MatchArgs {
    #[command(flatten)]
    pair: PairArgs,
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
    rows: Option<Range<usize>>,
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the matcher (its N_CELLS gain cells)"))]
    config: CliConfig,
}

#[derive(Args, Debug)]
pub(crate) struct DepthArgs {
    #[command(flatten)]
    pair: PairArgs,
    /// Folder for the pictures [default: ./declivity-out/rtl-depth-LEFT_STEM].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Idle clocks (tvalid low) after each line of the cameras: horizontal blanking.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(..=1 << 20))]
    hblank: u32,
    /// Rows to run, as A..B (rows A to B-1, a frame of their own) [default: all].
    #[arg(long, value_parser = parse_range)]
    rows: Option<Range<usize>>,
    /// What simulates the line processor clock by clock [default: rust-hdl with --vcd, else
    /// verilator if installed, else rust-hdl].
    #[arg(long, value_enum)]
    engine: Option<CliEngine>,
    /// Write a VCD waveform of every signal of the line processor (a clock of 10 ns) while the
    /// rows given by --lines go through it, from the first pixel of the first row in to the last
    /// disparity of the last row out (rust-hdl engine only; large: keep the rows few).
    #[arg(long, requires = "lines")]
    vcd: Option<PathBuf>,
    /// Rows of the frame (of the band, with --rows) to trace in the VCD, as A..B (rows A to B-1).
    #[arg(long, value_parser = parse_range, requires = "vcd")]
    lines: Option<Range<usize>>,
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the run (hd: on verilator or icarus)"))]
    config: CliConfig,
    #[command(flatten)]
    camera: CameraArgs,
}

pub(crate) fn run(c: RtlCommand) -> Result<(), SimError> {
    match c {
        RtlCommand::Detect(a) => detect(a),
        RtlCommand::Match(a) => match_pair(a),
        RtlCommand::Depth(a) => depth(a),
        RtlCommand::Faults(a) => super::faults::run(a),
    }
}

/// The progress of a frame through the line processor: a bar of its lines
/// on the rust-hdl engine, a spinner while Verilator or Icarus builds and
/// runs it.
pub(crate) fn frame_progress(lines: usize, message: String, engine: Engine, json: bool) -> Progress {
    match engine {
        Engine::RustHdl => Progress::new(lines, "lines", message, json),
        _ => Progress::spinner(format!("{message} ({}: build, then the frame)", engine.name()), json),
    }
}

fn detect(a: DetectArgs) -> Result<(), SimError> {
    let loaded = load_grey(&a.image)?;
    if let Some(note) = &loaded.converted {
        eprintln!("note: {}: {note}", a.image.display());
    }
    let image = loaded.image;
    let out = super::out_dir(&a.out, "rtl", &a.image);
    let vcd = a.vcd.clone().zip(a.lines.clone()).map(|(path, rows)| Waveform { path, rows });
    let config = a.config.0;
    let w_max = config.sizes().w_max;
    if image.width() > w_max {
        eprintln!(
            "note: {}: lines of {} px are wider than the {config} detector's W_MAX = {w_max} px: it keeps the first {w_max} pixels of each \
             and marks the line wide, as golden does; {}",
            a.image.display(),
            image.width(),
            sim::Config::fitting_hint(image.width())
        );
    }
    let bar = Progress::new(image.height(), "lines", format!("rtl detector ({config})"), a.json);
    let (report, overlay) = rtl_detect(config, &a.image.display().to_string(), &image, &out, vcd.as_ref(), |n| bar.set(n))?;
    bar.finish();
    if a.json {
        super::print_json(&report);
        return Ok(());
    }
    let r = &report;
    println!("{}: {} lines of {} px, {} pixels in {} clocks", r.image, r.lines, r.width, r.pixels, r.cycles);
    println!("  px_per_clk          {:.4} ({} stall clocks)", r.px_per_clk, r.stall_cycles);
    println!("  declivities         rtl {}, golden {}", r.declivities_rtl, r.declivities_golden);
    println!("  mismatches          {} (every difference from golden's hardware parity)", r.mismatches);
    println!("  borderline          {} (of those, one side only with |a| at floor(d_t) or floor(d_t) + 1)", r.borderline);
    println!("  max position error  {:.3} LSB (1/{} px)", r.max_pos_err_lsb, 1u32 << POS_FRAC_BITS);
    println!("  max d_t error       {:.3} LSB (1/{} grey level)", r.max_dt_err_lsb, 1u32 << DT_FRAC_BITS);
    println!("  wide / full lines   {} / {}", r.wide_lines, r.full_lines);
    println!("  first line latency  {} clocks (last pixel in to marker out)", r.first_line_latency);
    println!("  simulation          {:.0} clocks/s", r.sim_cycles_per_s);
    println!("  {:<44} rtl records over the image", overlay.display());
    if let Some(p) = &a.vcd {
        println!("  {:<44} waveform", p.display());
    }
    Ok(())
}

fn match_pair(a: MatchArgs) -> Result<(), SimError> {
    let config = a.config.0;
    let area = sim::formats::SearchArea::from_px(a.pair.dispmin, a.pair.dispmax, config)?;
    let (left, right, notes) = load_pair_images(&a.pair.left, &a.pair.right)?;
    super::print_notes(&notes);
    let w_max = config.sizes().w_max;
    if left.width() > w_max {
        eprintln!(
            "note: lines of {} px are wider than the {config} matcher's W_MAX = {w_max} px: it matches the declivities of the first \
             {w_max} pixels of each, as the detector sends them; {}",
            left.width(),
            sim::Config::fitting_hint(left.width())
        );
    }
    let rows = a.rows.clone().unwrap_or(0..left.height());
    let matchers = std::thread::available_parallelism().map_or(2, |n| n.get()).min(rows.len().max(1));
    let job = MatchJob {
        config,
        rule: a.rule.rule(),
        area,
        graph_line: a.graph_line.unwrap_or(rows.start + rows.len() / 2),
        rows,
        out: super::out_dir(&a.out, "rtl-match", &a.pair.left),
        matchers,
    };
    check_rows(&job, left.height(), &a.pair.left)?;
    let bar = Progress::new(job.rows.len(), "lines", format!("rtl matcher ({config}) x{matchers}"), a.pair.json);
    let outcome = rtl_match(&a.pair.left.display().to_string(), &left, &right, &job, &|| bar.inc())?;
    bar.finish();
    let r = &outcome.report;
    if a.pair.json {
        super::print_json(&outcome);
    } else {
        println!(
            "{}: {} line pairs (rows {}..{}), {} rule, {} < d < {} px, {matchers} matchers of {} cells ({})",
            r.image, r.lines, outcome.rows[0], outcome.rows[1], r.rule, r.dispmin, r.dispmax, r.cells, r.config
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
        println!("  simulation          {} clocks in {:.1} s, {:.0} clocks/s", r.cycles, outcome.seconds, r.sim_cycles_per_s);
        use sim::drive::matcher::Agreement;
        let verdict = match outcome.graph_agreement {
            Agreement::Identical => "identical",
            Agreement::EqualGain => "equal gain",
            Agreement::Mismatch => "MISMATCH",
        };
        println!("  {:<44} matching graph of row {} ({verdict}): golden path rings, rtl path boxes", outcome.graph, job.graph_line);
    }
    if r.mismatch_lines + r.malformed_lines > 0 {
        eprintln!("warning: the rtl matcher disagrees with golden ({} mismatch lines, {} malformed lines)", r.mismatch_lines, r.malformed_lines);
    }
    Ok(())
}

fn depth(a: DepthArgs) -> Result<(), SimError> {
    let camera = a.camera.camera();
    sim::hdl::verilog::check_camera(a.config.0, &camera)?;
    let (left, right, notes) = load_pair_images(&a.pair.left, &a.pair.right)?;
    super::print_notes(&notes);
    // A waveform comes from the rust-hdl engine only, so asking for one picks it
    // unless an engine is named.
    let engine = match (a.engine, &a.vcd) {
        (None, Some(_)) => Engine::RustHdl,
        (asked, _) => engine(asked),
    };
    let rows = a.rows.clone().unwrap_or(0..left.height());
    let job = RtlDepthJob {
        config: a.config.0,
        dispmin: a.pair.dispmin,
        dispmax: a.pair.dispmax,
        hblank: a.hblank as usize,
        camera,
        rows: rows.clone(),
        engine,
        vcd: a.vcd.clone().zip(a.lines.clone()).map(|(path, rows)| Waveform { path, rows }),
        out: super::out_dir(&a.out, "rtl-depth", &a.pair.left),
    };
    if !a.pair.json {
        eprintln!("engine: {}, configuration {}", engine.name(), a.config);
    }
    let bar = frame_progress(rows.len(), format!("rtl line processor ({})", a.config), engine, a.pair.json);
    let (report, files) = rtl_depth(&a.pair.left.display().to_string(), &left, &right, &job, |n| bar.set(n))?;
    bar.finish();
    if a.pair.json {
        super::print_json(&report);
        return Ok(());
    }
    let r = &report;
    println!("{}: {}x{} (rows {}..{}), {} < d < {} px, hblank {}", r.image, r.width, r.height, rows.start, rows.end, r.dispmin, r.dispmax, r.hblank);
    println!("  camera              {} (the depth stage's, eq. 1)", r.camera);
    println!("  pixels              {} in {} clocks, {:.4} px/clk, {} stall clocks", r.pixels, r.cycles, r.px_per_clk, r.stall_cycles);
    match r.latency_cycles {
        Some(c) => println!("  latency             {c} clocks (first pixel in to first disparity out)"),
        None => println!("  latency             no disparity came out"),
    }
    println!("  exact_px            {:.4} (share of disparities equal to golden's hardware parity)", r.exact_px);
    println!("  exact_depth_px      {:.4} (share of depths equal to golden's hardware parity)", r.exact_depth_px);
    println!("  agree_quarter_px    {:.4} (share within 1/4 px of golden)", r.agree_quarter_px);
    println!(
        "  status              {} lines out, {} records dropped, {} lines dropped, {} pixels dropped, {} lines full, {} lines wide, {} lines unpaired",
        r.lines_out, r.records_dropped, r.lines_dropped, r.pixels_dropped, r.lines_full, r.lines_wide, r.lines_unpaired
    );
    println!("  simulation          {} clocks in {:.1} s, {:.0} clocks/s ({}; build {:.1} s)", r.cycles, r.seconds, r.sim_cycles_per_s, r.engine, r.build_seconds);
    for (p, what) in &files {
        println!("  {:<44} {what}", p.display());
    }
    if let (Some(p), Some(lines)) = (&a.vcd, &a.lines) {
        println!("  {:<44} waveform of rows {}..{}", p.display(), lines.start, lines.end);
    }
    Ok(())
}
