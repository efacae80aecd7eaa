//! `declivity eval`: scores on pair folders with ground truth.

use std::path::PathBuf;

use clap::Args;
use sim::eval::io::{expand_pair_dirs, load_pair_dir};
use sim::eval::scores::{diagnosis_table, markdown_table};
use sim::jobs::eval::{evaluate_dir, EvalJob};
use sim::jobs::rtl_depth::{evaluate_pair_rtl, rtl_markdown_table, Engine};
use sim::{Config, SimError};

use crate::args::{engine, CliEngine, MethodArgs};
use crate::progress::Progress;

/// Score the method on pair folders with ground truth (Middlebury style).
#[derive(Args, Debug)]
#[command(long_about = "Score the method on pair folders laid out like data/stereo/<pair>/ \
(left_gray.png, right_gray.png, disp_gt.png|pgm for the left view, meta.txt with `scale` and \
`dispmax`, optional nonocc.png). Runs golden with the search bound dispmax + 1 and prints a table \
or, with --json, one JSON object per pair per line. Metrics (data/stereo/README.md): \
sparse_acc1 = % of matched reference declivities at valid-GT pixels with |d - gt| <= 1; \
bad1/bad2 = % of GT pixels with no output or |d - gt| > 1/2; bad1v/bad2v = the same over pixels \
with output; density = % of pixels with output; nonocc_bad2 = bad2 on nonocc.png > 127; \
ms = golden time per frame on one thread, loading excluded, median of --runs runs.

With --rtl, each pair runs through the cycle-accurate line processor instead (the default mode in \
hardware, one pixel per clock per camera) on the fastest engine installed, and the table gives its \
agreement with golden's hardware parity (exact_px, exact_depth_px: shares of pixels whose disparity, \
depth, equals it exactly; agree_quarter_px: within 1/4 px), its throughput and latency, and its scores.")]
pub(crate) struct EvalArgs {
    /// Pair folders (with meta.txt), or folders of pair folders (e.g. data/stereo).
    #[arg(required = true)]
    pairs: Vec<PathBuf>,
    /// One JSON object per pair per line instead of a table.
    #[arg(long)]
    json: bool,
    /// Timed single-thread runs per pair (the median is reported as `ms`).
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
    runs: u32,
    /// Also print why matches fail: rows without match, declivities whose true
    /// partner fails the photometric test (eq. 7), interpolation across depth edges.
    #[arg(long, conflicts_with = "rtl")]
    diagnose: bool,
    /// Also write, per pair, PAIR_disparity.png and PAIR_truth.png (near is bright, same
    /// scale) and PAIR_errors.png (green <= 1 px, yellow <= 2, red > 2, blue: no disparity;
    /// declivities: white matched right, magenta matched wrong, orange flagged at a depth edge,
    /// cyan missed with a true partner).
    #[arg(long, value_name = "DIR", conflicts_with = "rtl")]
    out: Option<PathBuf>,
    /// Run each pair through the cycle-accurate line processor instead (the default mode in
    /// hardware) and report its exact_px, exact_depth_px, agree_quarter_px, px_per_clk,
    /// stall_cycles, latency_cycles, bad2, nonocc_bad2 and golden's bad2 with the same stages.
    #[arg(long, conflicts_with_all = ["mode", "ref_view", "ends", "hardware_parity"])]
    rtl: bool,
    /// With --rtl: what simulates the line processor [default: verilator if installed, else rust-hdl].
    #[arg(long, value_enum, requires = "rtl")]
    engine: Option<CliEngine>,
    #[command(flatten)]
    method: MethodArgs,
}

pub(crate) fn run(a: EvalArgs) -> Result<(), SimError> {
    // Each pair's own bound (its dispmax + 1) replaces this one; the pair's
    // evaluation checks the bounds again with it.
    let params = a.method.params(f64::MAX)?;
    let dirs = expand_pair_dirs(&a.pairs)?;
    if a.rtl {
        return eval_rtl(&dirs, a.method.config.0, a.method.dispmin, engine(a.engine), a.json);
    }
    let job = EvalJob { params, runs: a.runs as usize, diagnose: a.diagnose, out: a.out.clone() };
    let bar = Progress::new(dirs.len(), "pairs", "eval", a.json);
    let mut reports = Vec::new();
    let mut diagnoses = Vec::new();
    let mut failed = Vec::new();
    for dir in &dirs {
        let outcome = match evaluate_dir(dir, &job) {
            Ok(o) => o,
            Err(e) => {
                bar.suspend(|| eprintln!("error: {e} (pair skipped)"));
                failed.push(dir.clone());
                bar.inc();
                continue;
            }
        };
        bar.suspend(|| super::print_notes(&outcome.notes));
        if a.json {
            bar.suspend(|| super::print_json(&outcome.report));
        }
        if let Some(d) = outcome.diagnosis {
            diagnoses.push((outcome.report.pair.clone(), d));
        }
        reports.push(outcome.report);
        bar.inc();
    }
    bar.finish();
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
            print!("{}", diagnosis_table(&diagnoses));
        }
    }
    pairs_failed(&failed, dirs.len())
}

/// An error naming the pairs that could not be evaluated (each reported
/// when it failed, the others scored), or `Ok` when there are none.
fn pairs_failed(failed: &[PathBuf], total: usize) -> Result<(), SimError> {
    if failed.is_empty() {
        return Ok(());
    }
    let names: Vec<String> = failed.iter().map(|d| d.display().to_string()).collect();
    Err(SimError::Argument(format!("{} of {total} pairs could not be evaluated: {}", failed.len(), names.join(", "))))
}

/// `eval --rtl`: each pair through the line processor.
fn eval_rtl(dirs: &[PathBuf], config: Config, dispmin: f64, engine: Engine, json: bool) -> Result<(), SimError> {
    if !json {
        eprintln!("engine: {}, configuration {config}", engine.name());
    }
    let mut reports = Vec::new();
    let mut failed = Vec::new();
    for dir in dirs {
        let one = || -> Result<_, SimError> {
            let pair = load_pair_dir(dir)?;
            super::print_notes(&pair.notes);
            let bar = super::rtl::frame_progress(pair.left.height(), format!("{} through the line processor", pair.name), engine, json);
            let report = evaluate_pair_rtl(config, &pair, dispmin, 0, engine, |n| bar.set(n));
            bar.finish();
            report
        };
        match one() {
            Ok(report) => {
                if json {
                    super::print_json(&report);
                }
                reports.push(report);
            }
            Err(e) => {
                eprintln!("error: {e} (pair skipped)");
                failed.push(dir.clone());
            }
        }
    }
    if !json {
        print!("{}", rtl_markdown_table(&reports));
    }
    pairs_failed(&failed, dirs.len())
}
