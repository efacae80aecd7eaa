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
