//! The `depth` job: runs golden on a pair and writes its pictures.

use std::path::{Path, PathBuf};
use std::time::Instant;

use golden::reconstruct::Camera;
use golden::{process_frame, FrameResult, GreyImage, Params, RefView, Threads};

use crate::error::SimError;
use crate::eval::pictures;

/// What the `depth` job was asked for besides the pair and the parameters.
#[derive(Debug, Clone)]
pub struct DepthJob {
    /// Folder the pictures go to (created if missing).
    pub out_dir: PathBuf,
    /// Row whose matching graph is drawn (default: the middle row).
    pub graph_line: Option<usize>,
    /// Camera for depth and the point cloud.
    pub camera: Option<(f64, f64)>,
    /// Threads for the frame.
    pub threads: Threads,
}

/// What the job did.
#[derive(Debug, Clone)]
pub struct DepthSummary {
    /// The frame's result.
    pub frame: FrameResult,
    /// Wall time of the frame (ms), loading and writing excluded.
    pub ms: f64,
    /// Files written, with what each shows.
    pub files: Vec<(PathBuf, &'static str)>,
    /// Points in the PLY cloud, when a camera was given.
    pub points: Option<usize>,
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> SimError + '_ {
    move |source| SimError::Io { path: path.to_path_buf(), source }
}

/// Runs the method on `left`/`right` and writes, into `job.out_dir`:
/// `disparity16.png` (16-bit, value = d × 16, 0 = none), `disparity.png`
/// (near is bright, photo 5), `declivities_left.png` and
/// `declivities_right.png` (photos 3–4), `graph_line_Y.png` (fig. 4), and
/// with a camera `depth_mm.png` (16-bit millimetres) and `points.ply`.
pub fn run_depth(left: &GreyImage, right: &GreyImage, params: &Params, job: &DepthJob) -> Result<DepthSummary, SimError> {
    let t0 = Instant::now();
    let frame = process_frame(left, right, params, job.threads)?;
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    std::fs::create_dir_all(&job.out_dir).map_err(io_err(&job.out_dir))?;
    let mut files = Vec::new();
    let mut put = |name: String, what: &'static str| -> PathBuf {
        let p = job.out_dir.join(name);
        files.push((p.clone(), what));
        p
    };

    pictures::save_png(&pictures::disparity_png16(&frame), &put("disparity16.png".into(), "disparity, 16-bit, value = d x 16, 0 = none"))?;
    pictures::save_png(
        &pictures::disparity_visual(&frame, params.dispmax),
        &put("disparity.png".into(), "disparity, near is bright (paper's photo 5)"),
    )?;
    let (left_feats, right_feats) = match params.ref_view {
        RefView::Left => (pictures::reference_features(&frame), pictures::other_features(&frame)),
        RefView::Right => (pictures::other_features(&frame), pictures::reference_features(&frame)),
    };
    pictures::save_png(
        &pictures::declivity_overlay(left, &left_feats),
        &put("declivities_left.png".into(), "left characteristic declivities (photo 3): red rising, cyan falling"),
    )?;
    pictures::save_png(
        &pictures::declivity_overlay(right, &right_feats),
        &put("declivities_right.png".into(), "right characteristic declivities (photo 4)"),
    )?;
    let y = job.graph_line.unwrap_or(frame.height / 2).min(frame.height - 1);
    pictures::save_png(
        &pictures::line_matching_graph(&frame.lines[y], params),
        &put(format!("graph_line_{y}.png"), "matching graph of that line with its optimal path (fig. 4)"),
    )?;
    let mut points = None;
    if let Some((focal_px, baseline_m)) = job.camera {
        let cam = Camera::centred(focal_px, baseline_m, frame.width, frame.height);
        pictures::save_png(&pictures::depth_png16(&frame, &cam), &put("depth_mm.png".into(), "depth Z (eq. 1), 16-bit millimetres, 0 = none"))?;
        let reference = match params.ref_view {
            RefView::Left => left,
            RefView::Right => right,
        };
        points = Some(pictures::write_ply(&put("points.ply".into(), "3-D points (eq. 1), ASCII PLY"), &frame, &cam, reference)?);
    }
    Ok(DepthSummary { frame, ms, files, points })
}

/// What the main job gave: the bundled pair's depth job and its scores
/// against the bundled ground truth.
#[derive(Debug, Clone)]
pub struct BundledRun {
    pub summary: DepthSummary,
    /// Matched reference declivities at pixels with ground truth, and those
    /// within 1 px of it.
    pub matched: usize,
    pub matched_right: usize,
    /// Dense scores of the map.
    pub scores: crate::eval::scores::DenseScores,
}

/// The main job: the default mode on the bundled pair (search bound
/// `dispmax + 1`), its pictures in `out_dir`, its scores.
pub fn bundled_depth(out_dir: &Path) -> Result<BundledRun, SimError> {
    let pair = crate::eval::bundled::tsukuba()?;
    let params = Params::new(pair.dispmax + 1.0)?;
    let job = DepthJob { out_dir: out_dir.to_path_buf(), graph_line: None, camera: None, threads: Threads::All };
    let summary = run_depth(&pair.left, &pair.right, &params, &job)?;
    let scores = crate::eval::scores::dense_scores(&summary.frame.disparity, &pair.gt_left, None);
    let (matched_right, matched) = crate::eval::scores::sparse_counts(&summary.frame, &pair.gt_left);
    Ok(BundledRun { summary, matched, matched_right, scores })
}
