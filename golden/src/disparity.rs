//! From matches to a dense line of disparities (paper §IV, last step).
//!
//! Each matched reference declivity gets `d = x_left - x_right` from the two
//! sub-pixel positions. "For points which do not correspond to declivities,
//! the disparity is assigned by interpolation": linear in `x` between
//! consecutive matched reference declivities; before the first and after the
//! last, the nearest is held ([`EndRule::Hold`]) or the pixels stay empty
//! ([`EndRule::Empty`]). A line without a match stays empty.
//!
//! A dense line stores `0.0` for "no disparity": every disparity the method
//! produces is positive (eq. 6), and so is every interpolation between them.

use crate::params::EndRule;

/// Value of a pixel without disparity.
pub const NO_DISPARITY: f64 = 0.0;

/// A disparity anchored at a sub-pixel position of the reference line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// Position `X_i` (eq. 3) of the matched reference declivity.
    pub x: f64,
    /// Its disparity `d > 0`.
    pub d: f64,
}

/// Linear interpolation of the anchors (sorted by strictly increasing `x`)
/// at every pixel centre `x = 0 … width-1`; see the module doc for the ends.
pub fn interpolate_line(anchors: &[Anchor], width: usize, ends: EndRule) -> Vec<f64> {
    let mut out = vec![NO_DISPARITY; width];
    interpolate_into(anchors, ends, &mut out);
    out
}

/// [`interpolate_line`] into an existing row buffer (its length is the width).
pub fn interpolate_into(anchors: &[Anchor], ends: EndRule, out: &mut [f64]) {
    let (Some(first), Some(last)) = (anchors.first(), anchors.last()) else {
        out.fill(NO_DISPARITY);
        return;
    };
    let width = out.len();
    // The first pixel centre at or after x, as an index of `out` (a ceiling
    // without a call to libm's `ceil`).
    let first_at_or_after = |x: f64| {
        let x = x.max(0.0);
        let t = x as usize;
        (t + ((t as f64) < x) as usize).min(width)
    };
    let (held_first, held_last) = match ends {
        EndRule::Hold => (first.d, last.d),
        EndRule::Empty => (NO_DISPARITY, NO_DISPARITY),
    };
    // Every pixel is written once: before the first anchor, between
    // consecutive anchors a and b (centres in [x_a, x_b)), then from the
    // last anchor on (its own value at x = x_last, held or empty beyond).
    let begin = first_at_or_after(first.x);
    out[..begin].fill(held_first);
    for w in anchors.windows(2) {
        let (a, b) = (w[0], w[1]);
        let slope = (b.d - a.d) / (b.x - a.x);
        let (from, to) = (first_at_or_after(a.x), first_at_or_after(b.x));
        for (x, v) in out[from..to].iter_mut().enumerate() {
            *v = a.d + slope * ((from + x) as f64 - a.x);
        }
    }
    let mut tail = first_at_or_after(last.x);
    if tail < width && tail as f64 == last.x {
        out[tail] = last.d;
        tail += 1;
    }
    out[tail..].fill(held_last);
}
