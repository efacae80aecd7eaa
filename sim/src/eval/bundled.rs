//! The stereo pair bundled in the binary for the main job: Middlebury's
//! Tsukuba (2001), grey, with its ground truth and non-occluded mask. The
//! files are those of `data/stereo/tsukuba/`, whose README gives the citation.

use std::path::{Path, PathBuf};

use crate::error::SimError;
use crate::eval::io::{decode_grey, decode_gt, PairData};

const LEFT: &[u8] = include_bytes!("../../../data/stereo/tsukuba/left_gray.png");
const RIGHT: &[u8] = include_bytes!("../../../data/stereo/tsukuba/right_gray.png");
const GT: &[u8] = include_bytes!("../../../data/stereo/tsukuba/disp_gt.pgm");
const NONOCC: &[u8] = include_bytes!("../../../data/stereo/tsukuba/nonocc.png");

/// Largest ground-truth disparity of the pair (`meta.txt`).
const DISPMAX: f64 = 14.0;
/// Ground-truth scale: disparity = value / 16.
const GT_SCALE: f64 = 16.0;
/// What to print beside results computed on the pair.
pub const CITATION: &str = "Tsukuba pair from the Middlebury stereo datasets: D. Scharstein, R. Szeliski, \
\"A taxonomy and evaluation of dense two-frame stereo correspondence algorithms\", IJCV 47(1/2/3):7-42, 2002 \
(scene: University of Tsukuba, Nakamura et al., CVPR 1996).";

/// The bundled pair, decoded.
pub(crate) fn tsukuba() -> Result<PairData, SimError> {
    let here = PathBuf::from("<bundled tsukuba>");
    let left = decode_grey(LEFT, &here.join("left_gray.png"))?.image;
    let right = decode_grey(RIGHT, &here.join("right_gray.png"))?.image;
    let (w, h) = (left.width(), left.height());
    let gt_left = decode_gt(GT, &here.join("disp_gt.pgm"), GT_SCALE, w, h)?;
    let mask = decode_grey(NONOCC, Path::new("<bundled tsukuba>/nonocc.png"))?.image;
    let nonocc = Some(mask.pixels().iter().map(|&v| v > 127).collect());
    Ok(PairData {
        name: "tsukuba".into(),
        dir: here,
        left,
        right,
        dispmax: DISPMAX,
        gt_left,
        gt_right: None,
        nonocc,
        notes: vec![],
    })
}
