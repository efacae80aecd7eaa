//! `declivity eval`: golden on pair folders with ground truth, scored, with
//! the diagnosis of its failures and the pictures on request.

use std::path::{Path, PathBuf};

use golden::{FrameResult, Params};

use crate::error::SimError;
use crate::eval::io::load_pair_dir;
use crate::eval::pictures;
use crate::eval::scores::{self, Diagnosis, EvalReport};

/// What `eval` was asked for besides the pairs.
#[derive(Debug, Clone)]
pub struct EvalJob {
    /// The method's parameters (the search bound is each pair's
    /// `dispmax + 1`).
    pub params: Params,
    /// Timed single-thread runs per pair.
    pub runs: usize,
    /// Whether to diagnose the failures.
    pub diagnose: bool,
    /// Folder for the pictures of each pair, if any.
    pub out: Option<PathBuf>,
}

/// One pair's evaluation.
#[derive(Debug, Clone)]
pub struct PairOutcome {
    pub report: EvalReport,
    pub diagnosis: Option<Diagnosis>,
    /// Notes on the pair's files (conversions, missing optional files).
    pub notes: Vec<String>,
}

/// Evaluates the pair in `dir`.
pub fn evaluate_dir(dir: &Path, job: &EvalJob) -> Result<PairOutcome, SimError> {
    let pair = load_pair_dir(dir)?;
    let (report, frame) = scores::evaluate_pair(&pair, &job.params, job.runs)?;
    let gt = scores::reference_gt(&pair, job.params.ref_view)?;
    let diagnosis = job.diagnose.then(|| scores::diagnose(&frame, gt));
    if let Some(out) = &job.out {
        write_pictures(out, &report.pair, &frame, gt)?;
    }
    Ok(PairOutcome { report, diagnosis, notes: pair.notes })
}

/// The pictures of `eval --out`: disparity and ground truth on one scale, and
/// the error map with the declivities' fates.
fn write_pictures(out: &Path, pair: &str, frame: &FrameResult, gt: &[f64]) -> Result<(), SimError> {
    std::fs::create_dir_all(out).map_err(|source| SimError::Io { path: out.to_path_buf(), source })?;
    let scale = frame.params.dispmax;
    pictures::save_png(&pictures::disparity_visual(frame, scale), &out.join(format!("{pair}_disparity.png")))?;
    pictures::save_png(&pictures::disparity_visual_of(gt, frame.width, frame.height, scale), &out.join(format!("{pair}_truth.png")))?;
    pictures::save_png(&scores::error_picture(frame, gt), &out.join(format!("{pair}_errors.png")))?;
    Ok(())
}
