//! `declivity depth`, and the main job (no command).

use std::path::PathBuf;

use clap::Args;
use golden::Threads;
use sim::eval::io::load_pair_images;
use sim::jobs::depth::{bundled_depth, run_depth, DepthJob, DepthSummary};
use sim::SimError;

use crate::args::{parse_positive, MethodArgs};

/// Disparity and depth of a rectified stereo pair, with the paper's pictures.
#[derive(Args, Debug)]
#[command(long_about = "Disparity and depth of a rectified stereo pair (8-bit grey; colour is \
converted with ITU-R 601 luma). Writes into --out: disparity16.png (16-bit, value = d x 16, 0 = no \
disparity), disparity.png (near is bright, the paper's photo 5), declivities_left.png and \
declivities_right.png (photos 3-4: red rising, cyan falling), graph_line_Y.png (the matching graph of \
one line with its optimal path, fig. 4), and with --focal-px and --baseline-m a depth map \
depth_mm.png (16-bit millimetres) and a point cloud points.ply (eq. 1). Disparity is \
d = x_left - x_right.")]
pub(crate) struct DepthArgs {
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
    #[arg(long, requires = "baseline_m", value_parser = parse_positive)]
    focal_px: Option<f64>,
    /// Baseline in metres, for depth and the point cloud (with --focal-px).
    #[arg(long, requires = "focal_px", value_parser = parse_positive)]
    baseline_m: Option<f64>,
    /// Use one thread instead of all cores (same result).
    #[arg(long)]
    single_thread: bool,
    #[command(flatten)]
    method: MethodArgs,
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
pub(crate) fn main_job() -> Result<(), SimError> {
    let out_dir = PathBuf::from("declivity-out").join("tsukuba");
    println!("declivity: depth map of the bundled pair (default mode, search bound = its largest disparity + 1)");
    println!("  {}", sim::eval::bundled::CITATION);
    let run = bundled_depth(&out_dir)?;
    print_summary(&run.summary);
    println!(
        "against the ground truth: sparse_acc1 {:.1} % of {} matched declivities, bad2 {:.1} % (bad2v {:.1} % where there is a disparity)",
        100.0 * run.matched_right as f64 / run.matched.max(1) as f64,
        run.matched,
        run.scores.bad2,
        run.scores.bad2v
    );
    println!("pictures written to {}", out_dir.display());
    println!("(try `declivity depth --help` for your own pair, `declivity eval --help` to score on Middlebury pairs)");
    Ok(())
}

pub(crate) fn run(a: DepthArgs) -> Result<(), SimError> {
    let params = a.method.params(a.dispmax)?;
    let (left, right, notes) = load_pair_images(&a.left, &a.right)?;
    super::print_notes(&notes);
    if let Some(y) = a.graph_line {
        if y >= left.height() {
            return Err(SimError::Argument(format!("--graph-line {y} is outside the image ({} has {} rows)", a.left.display(), left.height())));
        }
    }
    let job = DepthJob {
        out_dir: a.out.clone(),
        graph_line: a.graph_line,
        camera: a.focal_px.zip(a.baseline_m),
        threads: if a.single_thread { Threads::One } else { Threads::All },
    };
    let summary = run_depth(&left, &right, &params, &job)?;
    print_summary(&summary);
    println!("pictures written to {}", a.out.display());
    Ok(())
}
