//! One pair of epipolar lines through the whole method: thresholds (eq. 2),
//! characteristic declivities (eq. 3), nodes and gains (eq. 4–8), the optimal
//! path (eq. 9), the matches and their disparities.

use crate::declivity::{characteristic_declivities, Declivity};
use crate::disparity::Anchor;
use crate::dp::{banded_dp, BandRow, BandedGains, GainTable};
use crate::gain::{gmax, node_gain, pair_disparity};
use crate::noise::{noise_sigma, threshold};
use crate::params::{Params, RefView};

/// What the segmentation gives for one line of one view.
#[derive(Debug, Clone, PartialEq)]
pub struct LineFeatures {
    /// Noise estimate σ of the line (DESIGN §2.1).
    pub sigma: f64,
    /// Threshold `d_t = 5.6σ` (eq. 2).
    pub dt: f64,
    /// Characteristic declivities, left to right.
    pub declivities: Vec<Declivity>,
}

/// Segments one line: σ, `d_t` (eq. 2) and the characteristic declivities.
pub fn line_features(line: &[u8]) -> LineFeatures {
    let sigma = noise_sigma(line);
    let dt = threshold(sigma);
    LineFeatures { sigma, dt, declivities: characteristic_declivities(line, dt) }
}

/// A matched pair of declivities on the optimal path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Match {
    /// Index of the reference declivity in its line.
    pub ref_index: usize,
    /// Index of the other view's declivity in its line.
    pub other_index: usize,
    /// Position `X` (eq. 3) of the reference declivity.
    pub x_ref: f64,
    /// Position `X` (eq. 3) of the other declivity.
    pub x_other: f64,
    /// `d = x_left - x_right > 0`.
    pub disparity: f64,
    /// Local gain of the node (eq. 7).
    pub gain: f64,
}

impl Match {
    /// The disparity anchored at the reference position, for interpolation.
    pub fn anchor(&self) -> Anchor {
        Anchor { x: self.x_ref, d: self.disparity }
    }
}

/// The result for one pair of lines.
#[derive(Debug, Clone, PartialEq)]
pub struct LineResult {
    /// Segmentation of the reference view's line.
    pub reference: LineFeatures,
    /// Segmentation of the other view's line.
    pub other: LineFeatures,
    /// Matches along the optimal path, in reference order.
    pub matches: Vec<Match>,
    /// Gain of the optimal path (sum of its nodes' gains).
    pub path_gain: f64,
}

/// The columns of the other view that eq. 6 allows for a reference declivity
/// at `x_ref`: `lo .. hi` (0-based, possibly empty) in the sorted positions
/// `others`. Both bounds are non-decreasing in `x_ref`.
pub fn search_band(x_ref: f64, others: &[f64], params: &Params) -> (usize, usize) {
    let d = |x_other: f64| pair_disparity(x_ref, x_other, params.ref_view);
    let (lo, hi) = match params.ref_view {
        // d falls as x_other grows.
        RefView::Left => (
            others.partition_point(|&o| d(o) >= params.dispmax),
            others.partition_point(|&o| d(o) > 0.0),
        ),
        // d grows with x_other.
        RefView::Right => (
            others.partition_point(|&o| d(o) <= 0.0),
            others.partition_point(|&o| d(o) < params.dispmax),
        ),
    };
    (lo, hi.max(lo))
}

/// The graph of two lines as bands of nodes with their gains (eq. 4–8); the
/// columns outside each band are outside the search area (eq. 6).
pub fn banded_gains(reference: &LineFeatures, other: &LineFeatures, params: &Params) -> BandedGains {
    let others: Vec<f64> = other.declivities.iter().map(|d| d.position).collect();
    let g = gmax(reference.dt, other.dt);
    let rows = reference
        .declivities
        .iter()
        .map(|r| {
            let (lo, hi) = search_band(r.position, &others, params);
            let gains = other.declivities[lo..hi]
                .iter()
                .map(|o| node_gain(r, o, g, params.dispmax, params.ref_view, params.mode))
                .collect();
            BandRow { lo, gains }
        })
        .collect();
    BandedGains { m: others.len(), rows }
}

/// The dense gain table of two lines (for pictures of the graph and tests).
pub fn gain_table(reference: &LineFeatures, other: &LineFeatures, params: &Params) -> GainTable {
    let g = gmax(reference.dt, other.dt);
    GainTable::from_fn(reference.declivities.len(), other.declivities.len(), |i, j| {
        node_gain(
            &reference.declivities[i],
            &other.declivities[j],
            g,
            params.dispmax,
            params.ref_view,
            params.mode,
        )
    })
}

/// Matches two segmented lines: the optimal path (eq. 9) and the disparity of
/// each matched reference declivity. Returns the matches in reference order
/// and the path's gain.
pub fn match_lines(reference: &LineFeatures, other: &LineFeatures, params: &Params) -> (Vec<Match>, f64) {
    let bands = banded_gains(reference, other, params);
    let path = banded_dp(&bands);
    let matches = path
        .nodes
        .iter()
        .map(|&(i, j)| {
            let (r, o) = (&reference.declivities[i], &other.declivities[j]);
            let row = &bands.rows[i];
            Match {
                ref_index: i,
                other_index: j,
                x_ref: r.position,
                x_other: o.position,
                disparity: pair_disparity(r.position, o.position, params.ref_view),
                gain: row.gains[j - row.lo].expect("a path node is a node"),
            }
        })
        .collect();
    (matches, path.gain)
}

/// One pair of epipolar lines (same row of the left and right image) through
/// segmentation and matching, with the reference view of `params`.
pub fn process_line(left: &[u8], right: &[u8], params: &Params) -> LineResult {
    let (l, r) = (line_features(left), line_features(right));
    let (reference, other) = match params.ref_view {
        RefView::Left => (l, r),
        RefView::Right => (r, l),
    };
    let (matches, path_gain) = match_lines(&reference, &other, params);
    LineResult { reference, other, matches, path_gain }
}
