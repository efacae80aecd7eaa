//! Nodes of the matching graph and their local gains (paper §III–IV,
//! eq. 4–8).
//!
//! Rows of the graph are the reference view's characteristic declivities,
//! columns the other view's. A node `(i, j)` exists when the disparity the
//! pair implies lies inside the search area (eq. 6) and the photometric test
//! of eq. 7 does not reject it.

use crate::declivity::Declivity;
use crate::params::{Mode, RefView};

/// The disparity `d = x_left - x_right` implied by matching a reference
/// declivity at `x_ref` with the other view's declivity at `x_other`.
pub fn pair_disparity(x_ref: f64, x_other: f64, ref_view: RefView) -> f64 {
    match ref_view {
        RefView::Left => x_ref - x_other,
        RefView::Right => x_other - x_ref,
    }
}

/// Eq. 6, the limitation of the search area: `0 < d < dispmax`.
pub fn in_search_area(d: f64, dispmax: f64) -> bool {
    0.0 < d && d < dispmax
}

/// Eq. 4, the left photometric distance
/// `lpd = Σ_{k=0..2} |I_ref(x_i - k) - I_other(x_j - k)|`.
pub fn lpd(reference: &Declivity, other: &Declivity) -> u32 {
    sum_abs_diff(&reference.left, &other.left)
}

/// Eq. 5, the right photometric distance
/// `rpd = Σ_{k=0..2} |I_ref(x_{i+1} + k) - I_other(x_{j+1} + k)|`.
pub fn rpd(reference: &Declivity, other: &Declivity) -> u32 {
    sum_abs_diff(&reference.right, &other.right)
}

fn sum_abs_diff(a: &[u8; 3], b: &[u8; 3]) -> u32 {
    a.iter().zip(b).map(|(&p, &q)| p.abs_diff(q) as u32).sum()
}

/// Eq. 8: `gmax = 0.5 (d_t,ref + d_t,other)`, the self-adaptive gain scale
/// from the two lines' thresholds.
pub fn gmax(dt_ref: f64, dt_other: f64) -> f64 {
    0.5 * (dt_ref + dt_other)
}

/// `f(gmax)` of eq. 7 in the given mode; `None` rejects the node.
///
/// `Paper`: `3·gmax` when `lpd < gmax` and `rpd < gmax`; `gmax` when exactly
/// one of them is below `gmax`; rejected when neither is. Read literally, the
/// one-sided case gives `gain = gmax - lpd - rpd ≤ 0`, so such a node never
/// improves a path: the paper's "partially masked" case never fires.
pub fn f_gmax(lpd: f64, rpd: f64, gmax: f64, mode: Mode) -> Option<f64> {
    let f = f_gmax_or_reject(lpd, rpd, gmax, mode);
    (f != REJECTED).then_some(f)
}

/// The value standing for a rejected node: `-∞`, which no gain beats and
/// which stays `-∞` whatever is added to it (the DP's "no node").
pub const REJECTED: f64 = f64::NEG_INFINITY;

/// [`f_gmax`] as a plain number, [`REJECTED`] for a rejected node, computed
/// with selects rather than branches (the frame pipeline's hot path).
#[inline]
pub fn f_gmax_or_reject(lpd: f64, rpd: f64, gmax: f64, mode: Mode) -> f64 {
    match mode {
        Mode::Paper => {
            let (l, r) = (lpd < gmax, rpd < gmax);
            let f = if l & r { 3.0 * gmax } else { gmax };
            if l | r {
                f
            } else {
                REJECTED
            }
        }
    }
}

/// Eq. 7: `gain = f(gmax) - lpd - rpd`, or `None` when the node is rejected.
pub fn local_gain(lpd: f64, rpd: f64, gmax: f64, mode: Mode) -> Option<f64> {
    f_gmax(lpd, rpd, gmax, mode).map(|f| f - lpd - rpd)
}

/// The node `(i, j)` for a reference and an other-view declivity: its gain
/// (eq. 4–8) when it lies in the search area (eq. 6) and is not rejected.
pub fn node_gain(
    reference: &Declivity,
    other: &Declivity,
    gmax: f64,
    dispmax: f64,
    ref_view: RefView,
    mode: Mode,
) -> Option<f64> {
    let g = node_gain_or_reject(reference, other, gmax, dispmax, ref_view, mode);
    (g != REJECTED).then_some(g)
}

/// [`node_gain`] as a plain number, [`REJECTED`] where there is no node.
#[inline]
pub fn node_gain_or_reject(
    reference: &Declivity,
    other: &Declivity,
    gmax: f64,
    dispmax: f64,
    ref_view: RefView,
    mode: Mode,
) -> f64 {
    let d = pair_disparity(reference.position, other.position, ref_view);
    let (l, r) = (lpd(reference, other) as f64, rpd(reference, other) as f64);
    let g = f_gmax_or_reject(l, r, gmax, mode) - l - r;
    if in_search_area(d, dispmax) {
        g
    } else {
        REJECTED
    }
}
