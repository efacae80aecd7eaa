//! `declivity rtl detect`: every row of an image through the rtl declivity
//! detector, compared with golden, with the records drawn over the image.

use std::ops::Range;
use std::path::{Path, PathBuf};

use golden::GreyImage;

use crate::config::Config;
use crate::drive::detector::{as_features, detect_image, DetectReport, DetectorDut, DetectorSim, HdDetector};
use crate::error::SimError;
use crate::eval::pictures;

/// A waveform to write: the file and the rows it covers.
#[derive(Debug, Clone)]
pub struct Waveform {
    pub path: PathBuf,
    pub rows: Range<usize>,
}

/// Runs `image` through the detector of `config`, writes
/// `declivities_rtl.png` into `out` (created first, so that a bad folder
/// fails before the simulation) and, with `vcd`, the waveform of its rows.
/// `progress` is called with the lines done. Returns the report and the
/// overlay's path.
pub fn rtl_detect(
    config: Config,
    name: &str,
    image: &GreyImage,
    out: &Path,
    vcd: Option<&Waveform>,
    progress: impl FnMut(usize),
) -> Result<(DetectReport, PathBuf), SimError> {
    match config {
        Config::Sd => detect_with(DetectorSim::new(), name, image, out, vcd, progress),
        Config::Hd => detect_with(DetectorSim::<HdDetector>::build(), name, image, out, vcd, progress),
    }
}

fn detect_with<D: DetectorDut>(
    mut sim: DetectorSim<D>,
    name: &str,
    image: &GreyImage,
    out: &Path,
    vcd: Option<&Waveform>,
    progress: impl FnMut(usize),
) -> Result<(DetectReport, PathBuf), SimError> {
    if let Some(v) = vcd {
        if v.rows.is_empty() || v.rows.end > image.height() {
            return Err(SimError::Argument(format!("--lines {}..{}: the image has {} rows", v.rows.start, v.rows.end, image.height())));
        }
    }
    std::fs::create_dir_all(out).map_err(|source| SimError::Io { path: out.to_path_buf(), source })?;
    if let Some(v) = vcd {
        // Lines stream back to back: row y enters at about y·W clocks and its
        // records leave within one marker latency.
        let w = image.width().min(D::CONFIG.sizes().w_max) as u64;
        let range = v.rows.start as u64 * w..v.rows.end as u64 * w + D::marker_latency(image.width()) as u64 + w;
        sim.trace_to(&v.path, range).map_err(|source| SimError::Io { path: v.path.clone(), source })?;
    }
    let (report, lines) = detect_image(&mut sim, name, image, progress).map_err(|e| SimError::Argument(e.to_string()))?;
    sim.finish_trace();
    let features = as_features(&lines);
    let refs: Vec<_> = features.iter().collect();
    let overlay = out.join("declivities_rtl.png");
    pictures::save_png(&pictures::declivity_overlay(image, &refs), &overlay)?;
    Ok((report, overlay))
}
