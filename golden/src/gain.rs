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

/// Eq. 6, the limitation of the search area: `dispmin < d < dispmax` (the
/// paper's `0 < d < dispmax` with `dispmin = 0`).
pub fn in_search_area(d: f64, dispmin: f64, dispmax: f64) -> bool {
    dispmin < d && d < dispmax
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

/// The mean of a declivity's two end levels, `(I(x_i) + I(x_{i+1})) / 2`.
fn mid_level(d: &Declivity) -> f64 {
    0.5 * (d.left[0] as f64 + d.right[0] as f64)
}

/// Eq. 4 offset-compensated ([`crate::Features::relative`]): the other
/// declivity's levels shifted by `δ = m_ref - m_other` (the difference of the
/// end-level means) before comparing,
/// `Σ_{k=0..2} |I_ref(x_i - k) - I_other(x_j - k) - δ|`.
fn lpd_relative(reference: &Declivity, other: &Declivity) -> f64 {
    shifted_distance(&reference.left, &other.left, mid_level(reference) - mid_level(other))
}

/// Eq. 5 offset-compensated, as [`lpd_relative`] on the right neighbours.
fn rpd_relative(reference: &Declivity, other: &Declivity) -> f64 {
    shifted_distance(&reference.right, &other.right, mid_level(reference) - mid_level(other))
}

/// `Σ_k |a_k - b_k - δ|`.
fn shifted_distance(a: &[u8; 3], b: &[u8; 3], delta: f64) -> f64 {
    a.iter().zip(b).map(|(&p, &q)| (p as f64 - q as f64 - delta).abs()).sum()
}

/// The photometric distances `(lpd, rpd)` of a node in `mode`: eq. 4–5, or
/// their offset-compensated form; `None` when the mode compares only
/// declivities of one polarity and these differ.
pub fn photometric_distances(reference: &Declivity, other: &Declivity, mode: Mode) -> Option<(f64, f64)> {
    if mode.features().relative {
        (reference.polarity() == other.polarity()).then(|| (lpd_relative(reference, other), rpd_relative(reference, other)))
    } else {
        Some((lpd(reference, other) as f64, rpd(reference, other) as f64))
    }
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
/// improves a path: the paper's "partially masked" case never fires. With
/// [`crate::Features::one_sided`], a one-sided node gets `gmax` plus its
/// dissimilar side's distance, so that `gain = gmax - d_similar > 0`.
pub fn f_gmax(lpd: f64, rpd: f64, gmax: f64, mode: Mode) -> Option<f64> {
    let one_sided = mode.features().one_sided;
    match (lpd < gmax, rpd < gmax) {
        (true, true) => Some(3.0 * gmax),
        (true, false) => Some(if one_sided { gmax + rpd } else { gmax }),
        (false, true) => Some(if one_sided { gmax + lpd } else { gmax }),
        (false, false) => None,
    }
}

/// Eq. 7: `gain = f(gmax) - (lpd + rpd)`, or `None` when the node is
/// rejected.
pub fn local_gain(lpd: f64, rpd: f64, gmax: f64, mode: Mode) -> Option<f64> {
    let one_sided = mode.features().one_sided;
    match (lpd < gmax, rpd < gmax) {
        (true, true) => Some(3.0 * gmax - (lpd + rpd)),
        (true, false) if one_sided => Some(gmax - lpd),
        (false, true) if one_sided => Some(gmax - rpd),
        (false, false) => None,
        _ => Some(gmax - (lpd + rpd)),
    }
}

/// Inter-scanline support ([`crate::Features::contour`], after Ohta and
/// Kanade's inter-scanline search): the term added to the gain of eq. 7 of
/// a node of disparity `d` whose reference declivity continues an edge
/// contour matched at disparity `d_contour` in the row above, `bonus`
/// (`weight · gmax`) when `|d - d_contour| ≤ dd` and 0 otherwise. A
/// declivity on no contour has `d_contour = NaN`, which is within no
/// distance of any disparity. A rejected node (`-∞`) stays rejected.
#[inline(always)]
pub fn contour_term(d: f64, d_contour: f64, dd: f64, bonus: f64) -> f64 {
    if (d - d_contour).abs() <= dd {
        bonus
    } else {
        0.0
    }
}

/// The value standing for a rejected node in the hot path ([`LineGain`]):
/// `-∞`, which no gain beats and which stays `-∞` whatever is added to it
/// (the DP's "no node").
pub const REJECTED: f64 = f64::NEG_INFINITY;

/// The node `(i, j)` for a reference and an other-view declivity: its gain
/// (eq. 4–8) when it lies in the search area (eq. 6) and is not rejected.
pub fn node_gain(
    reference: &Declivity,
    other: &Declivity,
    gmax: f64,
    (dispmin, dispmax): (f64, f64),
    ref_view: RefView,
    mode: Mode,
) -> Option<f64> {
    let d = pair_disparity(reference.position, other.position, ref_view);
    if !in_search_area(d, dispmin, dispmax) {
        return None;
    }
    let (l, r) = photometric_distances(reference, other, mode)?;
    local_gain(l, r, gmax, mode)
}

/// A declivity's attributes for eq. 4–5 laid out for speed: the three left
/// and three right neighbour levels, each padded with zeros to 8 bytes (the
/// padding adds `|0 - 0| = 0` to the distances), the same levels relative to
/// the end-level mean and doubled (integers: `2·I - (I(x_i) + I(x_{i+1}))`),
/// and the polarity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Neighbours {
    left: [u8; 8],
    right: [u8; 8],
    /// Left levels in lanes 0–2, right levels in lanes 4–6, lanes 3 and 7 zero.
    relative: [i16; 8],
    rising: bool,
}

impl From<&Declivity> for Neighbours {
    fn from(d: &Declivity) -> Self {
        let mut n = Neighbours { rising: d.amplitude > 0, ..Neighbours::default() };
        n.set_levels(d);
        n.set_relative(d);
        n
    }
}

impl Neighbours {
    /// The raw levels (eq. 4–5).
    #[inline]
    fn set_levels(&mut self, d: &Declivity) {
        self.left[..3].copy_from_slice(&d.left);
        self.right[..3].copy_from_slice(&d.right);
    }

    /// The levels relative to the end-level mean, doubled.
    #[inline]
    fn set_relative(&mut self, d: &Declivity) {
        let ends = d.left[0] as i16 + d.right[0] as i16;
        for k in 0..3 {
            self.relative[k] = 2 * d.left[k] as i16 - ends;
            self.relative[4 + k] = 2 * d.right[k] as i16 - ends;
        }
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
/// Distances are kept doubled, as integers (the offset-compensated ones are
/// half-integers), so `d < gmax ⇔ 2d < ⌈2·gmax⌉` (for every real
/// `gmax ≥ 0`): the tests of eq. 7 run on integers. The search area (eq. 6)
/// is not tested here: the caller passes only pairs inside it (the bands of
/// [`crate::line::search_bands`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineGain {
    /// `⌈2·gmax⌉`: a doubled distance is "below gmax" when it is below this.
    below2: u32,
    /// `f(gmax)` by the number of distances below `gmax`: none (rejected:
    /// [`REJECTED`]), one, both. A table rather than a choice, so that the
    /// data-dependent outcome costs no branch.
    f: [f64; 3],
    relative: bool,
    one_sided: bool,
}

impl LineGain {
    /// The gain rule of `mode` for two lines with thresholds `dt_ref`,
    /// `dt_other` (eq. 8).
    pub fn new(dt_ref: f64, dt_other: f64, mode: Mode) -> Self {
        let g = gmax(dt_ref, dt_other);
        let features = mode.features();
        LineGain {
            below2: (2.0 * g).ceil() as u32,
            f: [REJECTED, g, 3.0 * g],
            relative: features.relative,
            one_sided: features.one_sided,
        }
    }

    /// The attributes of `d` that [`LineGain::gain`] reads in this rule's
    /// mode (raw or relative levels, and the polarity), the others left
    /// zero: the same gains as with [`Neighbours::from`], for half the work.
    #[inline]
    pub fn neighbours(&self, d: &Declivity) -> Neighbours {
        let mut n = Neighbours { rising: d.amplitude > 0, ..Neighbours::default() };
        if self.relative {
            n.set_relative(d);
        } else {
            n.set_levels(d);
        }
        n
    }

    /// Eq. 7 for a node inside the search area: `f(gmax) - (lpd + rpd)` (or
    /// the similar side's distance alone for a one-sided node when the mode
    /// scores them), or [`REJECTED`]; equal to [`node_gain`] there.
    // Always inlined: called out of line, the DP's loop (which calls it per
    // band cell) keeps its running values in memory across the call.
    #[inline(always)]
    pub fn gain(&self, reference: &Neighbours, other: &Neighbours) -> f64 {
        let (l2, r2, same) = if self.relative {
            // Eight lanes at once (the padding lanes are 0 on both sides).
            let mut d = [0u16; 8];
            for (dk, (a, b)) in d.iter_mut().zip(reference.relative.iter().zip(&other.relative)) {
                *dk = a.abs_diff(*b);
            }
            let side = |k: usize| d[k] as u32 + d[k + 1] as u32 + d[k + 2] as u32 + d[k + 3] as u32;
            (side(0), side(4), reference.rising == other.rising)
        } else {
            (2 * sum_abs_diff8(&reference.left, &other.left), 2 * sum_abs_diff8(&reference.right, &other.right), true)
        };
        let (lb, rb) = (l2 < self.below2, r2 < self.below2);
        let similar = (lb as usize + rb as usize) * same as usize;
        // A dissimilar side counts unless one-sided nodes are scored on
        // their similar side alone.
        let (lw, rw) = ((lb | !self.one_sided) as u32, (rb | !self.one_sided) as u32);
        self.f[similar] - (l2 * lw + r2 * rw) as f64 / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decl(position: f64, amplitude: i32, left: [u8; 3], right: [u8; 3]) -> Declivity {
        Declivity { start: 0, end: 1, amplitude, position, left, right }
    }

    #[test]
    fn line_gain_equals_node_gain_inside_the_search_area() {
        let mut rng = crate::test_rng::TestRng::new(0x2545_f491_4f6c_dd1du64);
        let mut next = move || rng.next();
        let mut rejected = 0;
        for _ in 0..20_000 {
            let (pr, po) = (next() % 4 == 0, next() % 4 == 0);
            let mut px = || [0, 1, 2].map(|_| (next() % 64) as u8 + 100);
            // Mostly rising, sometimes falling: polarities agree and differ.
            let r = decl(50.0, if pr { -10 } else { 10 }, px(), px());
            let o = decl(45.5, if po { -10 } else { 10 }, px(), px());
            // Thresholds on and off integers, small and large.
            let dt = |v: u64| if v.is_multiple_of(3) { (v % 40) as f64 } else { (v % 4000) as f64 / 37.0 };
            let (dr, dl) = (dt(next()), dt(next()));
            for mode in Mode::ALL {
                let want = node_gain(&r, &o, gmax(dr, dl), (0.0, 10.0), RefView::Left, mode);
                let rule = LineGain::new(dr, dl, mode);
                let got = rule.gain(&(&r).into(), &(&o).into());
                assert_eq!(want.unwrap_or(REJECTED), got, "{mode:?}: dt {dr} {dl}, {r:?} {o:?}");
                assert_eq!(rule.gain(&rule.neighbours(&r), &rule.neighbours(&o)), got, "{mode:?}: the mode's attributes only");
                rejected += want.is_none() as usize;
            }
        }
        assert!(rejected > 7 * 1000 && rejected < 7 * 19_000, "both outcomes drawn: {rejected} rejected");
    }
}
