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
    match mode {
        Mode::Paper => match (lpd < gmax, rpd < gmax) {
            (true, true) => Some(3.0 * gmax),
            (true, false) | (false, true) => Some(gmax),
            (false, false) => None,
        },
    }
}

/// The value standing for a rejected node in the hot path ([`LineGain`]):
/// `-∞`, which no gain beats and which stays `-∞` whatever is added to it
/// (the DP's "no node").
pub const REJECTED: f64 = f64::NEG_INFINITY;

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
    let d = pair_disparity(reference.position, other.position, ref_view);
    if !in_search_area(d, dispmax) {
        return None;
    }
    local_gain(lpd(reference, other) as f64, rpd(reference, other) as f64, gmax, mode)
}

/// A declivity's attributes for eq. 4–5 laid out for speed: the three left
/// and three right neighbour levels, each padded with zeros to 8 bytes (the
/// padding adds `|0 - 0| = 0` to the distances).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Neighbours {
    left: [u8; 8],
    right: [u8; 8],
}

impl From<&Declivity> for Neighbours {
    fn from(d: &Declivity) -> Self {
        let mut n = Neighbours::default();
        n.left[..3].copy_from_slice(&d.left);
        n.right[..3].copy_from_slice(&d.right);
        n
    }
}

/// `Σ |a_k - b_k|` over 8 bytes (one `psadbw` on x86-64).
#[inline]
fn sum_abs_diff8(a: &[u8; 8], b: &[u8; 8]) -> u32 {
    let mut s = 0u32;
    for k in 0..8 {
        s += a[k].abs_diff(b[k]) as u32;
    }
    s
}

/// The local gain of eq. 4–8 for the nodes of one pair of lines, with what
/// depends only on the lines computed once: the frame pipeline's hot path.
///
/// The photometric distances are integers, so `lpd < gmax ⇔ lpd < ⌈gmax⌉`
/// (for every real `gmax ≥ 0`): the tests of eq. 7 run on integers. The
/// search area (eq. 6) is not tested here: the caller passes only pairs
/// inside it (the bands of [`crate::line::search_bands`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineGain {
    /// `⌈gmax⌉`: a distance is "below gmax" when it is below this.
    below: u32,
    /// `f(gmax)` by the number of distances below `gmax`: none (rejected:
    /// [`REJECTED`]), one, both. A table rather than a choice, so that the
    /// data-dependent outcome costs no branch.
    f: [f64; 3],
}

impl LineGain {
    /// The gain rule of `mode` for two lines with thresholds `dt_ref`,
    /// `dt_other` (eq. 8).
    pub fn new(dt_ref: f64, dt_other: f64, mode: Mode) -> Self {
        let g = gmax(dt_ref, dt_other);
        match mode {
            Mode::Paper => LineGain { below: g.ceil() as u32, f: [REJECTED, g, 3.0 * g] },
        }
    }

    /// Eq. 7 for a node inside the search area: `f(gmax) - lpd - rpd`, or
    /// [`REJECTED`]; equal to [`node_gain`] there.
    #[inline]
    pub fn gain(&self, reference: &Neighbours, other: &Neighbours) -> f64 {
        let (l, r) = (sum_abs_diff8(&reference.left, &other.left), sum_abs_diff8(&reference.right, &other.right));
        let similar = (l < self.below) as usize + (r < self.below) as usize;
        self.f[similar] - (l + r) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decl(position: f64, left: [u8; 3], right: [u8; 3]) -> Declivity {
        Declivity { start: 0, end: 1, amplitude: 10, position, left, right }
    }

    #[test]
    fn line_gain_equals_node_gain_inside_the_search_area() {
        let mut rng = crate::test_rng::TestRng::new(0x2545_f491_4f6c_dd1du64);
        let mut next = move || rng.next();
        let mut rejected = 0;
        for _ in 0..20_000 {
            let mut px = || [0, 1, 2].map(|_| (next() % 64) as u8 + 100);
            let r = decl(50.0, px(), px());
            let o = decl(45.5, px(), px());
            // Thresholds on and off integers, small and large.
            let dt = |v: u64| if v % 3 == 0 { (v % 40) as f64 } else { (v % 4000) as f64 / 37.0 };
            let (dr, dl) = (dt(next()), dt(next()));
            let want = node_gain(&r, &o, gmax(dr, dl), 10.0, RefView::Left, Mode::Paper);
            let got = LineGain::new(dr, dl, Mode::Paper).gain(&(&r).into(), &(&o).into());
            assert_eq!(want.unwrap_or(REJECTED), got, "dt {dr} {dl}, {r:?} {o:?}");
            rejected += want.is_none() as usize;
        }
        assert!(rejected > 1000 && rejected < 19_000, "both outcomes drawn: {rejected} rejected");
    }
}
