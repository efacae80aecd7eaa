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
    out.fill(NO_DISPARITY);
    let (Some(first), Some(last)) = (anchors.first(), anchors.last()) else {
        return;
    };
    let mut k = 0usize; // anchors[k].x <= x < anchors[k+1].x
    for (x, v) in out.iter_mut().enumerate() {
        let xf = x as f64;
        *v = if xf < first.x {
            match ends {
                EndRule::Hold => first.d,
                EndRule::Empty => NO_DISPARITY,
            }
        } else if xf > last.x {
            match ends {
                EndRule::Hold => last.d,
                EndRule::Empty => NO_DISPARITY,
            }
        } else {
            while k + 1 < anchors.len() && anchors[k + 1].x <= xf {
                k += 1;
            }
            if k + 1 == anchors.len() {
                last.d
            } else {
                let (a, b) = (anchors[k], anchors[k + 1]);
                a.d + (b.d - a.d) * (xf - a.x) / (b.x - a.x)
            }
        };
    }
}
