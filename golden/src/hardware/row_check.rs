//! The row check of the line processor (`rtl::post::row_check`) on the
//! matcher's fixed-point matches: golden's [`crate::frame::confirmed_matches`]
//! as the hardware compares.
//!
//! A match of row `y` is kept iff row `y − 1` or row `y + 1` holds a match
//! `b` with `|X − X_b| ≤ DX` and `|d − d_b| ≤ DD`, both bounds inclusive,
//! in position LSBs (`1/2^pos_frac_bits` px): `DX` = [`CONSISTENT_DX`] px
//! and `DD` = [`CONSISTENT_DD`] px in that unit ([`row_check_bounds`]: 48
//! and 16 LSB for 1/16 px). A frame's first row is checked against the row
//! below only, its last against the row above only; a one-row frame keeps
//! nothing. On the same matches it keeps what
//! [`crate::frame::confirmed_matches`] keeps (the values are multiples of
//! 1/16 px, exact in `f64`); here the comparisons are the hardware's, on
//! integers.

use crate::hardware::HardwareLimits;
use crate::line::Match;
use crate::params::{CONSISTENT_DD, CONSISTENT_DX};

/// A match as the matcher sends it to the row check and the interpolator:
/// the reference position `X` and the disparity `d = X_left − X_right`,
/// both unsigned with `pos_frac_bits` fraction bits (14 bits for the
/// default hardware's 1024-px lines: 10 integer, 4 fraction).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FixedMatch {
    /// `X`, position LSBs.
    pub x: u32,
    /// `d`, position LSBs.
    pub d: u32,
}

impl FixedMatch {
    /// golden's match in the matcher's format: `⌊X · 2^f⌋` and
    /// `⌊d · 2^f⌋`. In hardware parity both are multiples of `2^-f`
    /// ([`crate::hardware::matcher_view`] rounds the positions, and a
    /// disparity is their difference), so this is exact.
    pub fn of(m: &Match, limits: HardwareLimits) -> FixedMatch {
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        FixedMatch { x: (m.x_ref * unit).floor() as u32, d: (m.disparity * unit).floor() as u32 }
    }

    /// The match in px (`X / 2^f`, `d / 2^f`, exact in `f64`).
    pub fn px(self, limits: HardwareLimits) -> (f64, f64) {
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        (self.x as f64 / unit, self.d as f64 / unit)
    }
}

/// The row check's bounds `(DX, DD)` in position LSBs:
/// `CONSISTENT_DX · 2^f`, `CONSISTENT_DD · 2^f` (whole pixels: exact).
pub fn row_check_bounds(limits: HardwareLimits) -> (u32, u32) {
    let unit = (1u64 << limits.pos_frac_bits) as f64;
    ((CONSISTENT_DX * unit) as u32, (CONSISTENT_DD * unit) as u32)
}

/// Which matches of each row a neighbouring row confirms (module doc):
/// one flag per match, rows in frame order, matches by increasing `X`.
/// Each pair of adjacent rows is merged once (the hardware reads each
/// neighbour in order through a window) and marks both.
pub fn row_check(rows: &[Vec<FixedMatch>], limits: HardwareLimits) -> Vec<Vec<bool>> {
    let (dx, dd) = row_check_bounds(limits);
    let mut keep: Vec<Vec<bool>> = rows.iter().map(|r| vec![false; r.len()]).collect();
    for y in 1..rows.len() {
        let (above, below) = keep.split_at_mut(y);
        let (ka, kb) = (&mut above[y - 1], &mut below[0]);
        let (a, b) = (&rows[y - 1], &rows[y]);
        // b[lo..]: the matches of row y not left of the window of a[i]
        // (`X_b ≥ X − DX`, written without a borrow).
        let mut lo = 0usize;
        for (i, m) in a.iter().enumerate() {
            while lo < b.len() && b[lo].x + dx < m.x {
                lo += 1;
            }
            for (j, n) in b.iter().enumerate().skip(lo).take_while(|(_, n)| n.x <= m.x + dx) {
                let close = m.d.abs_diff(n.d) <= dd;
                ka[i] |= close;
                kb[j] |= close;
            }
        }
    }
    keep
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::confirmed_matches;
    use crate::line::{LineFeatures, LineResult};

    fn lines(rows: &[Vec<FixedMatch>], limits: HardwareLimits) -> Vec<LineResult> {
        let empty = LineFeatures { sigma: 1.0, dt: 5.6, declivities: vec![] };
        rows.iter()
            .map(|r| {
                let matches = r
                    .iter()
                    .map(|&f| {
                        let (x, d) = f.px(limits);
                        Match { ref_index: 0, other_index: 0, x_ref: x, x_other: x - d, disparity: d, gain: 1.0, edge: false }
                    })
                    .collect();
                LineResult { reference: empty.clone(), other: empty.clone(), matches, path_gain: 0.0 }
            })
            .collect()
    }

    #[test]
    fn the_row_check_on_lsbs_keeps_what_confirmed_matches_keeps_bounds_included() {
        let limits = HardwareLimits::default();
        assert_eq!(row_check_bounds(limits), (48, 16));
        let mut rng = crate::test_rng::TestRng::new(0x20c4_ec4_0000_0001);
        let mut kept = 0;
        for case in 0..3000 {
            // Positions at least a pixel apart, often within 3 px of the
            // row above; disparities often 1 px apart (the bounds hit).
            let rows: Vec<Vec<FixedMatch>> = (0..(rng.next() % 6))
                .map(|_| {
                    let mut x = (rng.next() % 40) as u32;
                    (0..rng.next() % 14)
                        .map(|_| {
                            x += 16 + (rng.next() % 40) as u32;
                            FixedMatch { x, d: 16 + (rng.next() % 48) as u32 }
                        })
                        .collect()
                })
                .collect();
            let got = row_check(&rows, limits);
            assert_eq!(got, confirmed_matches(&lines(&rows, limits)), "case {case}: {rows:?}");
            kept += got.iter().flatten().filter(|&&k| k).count();
        }
        assert!(kept > 1000, "the cases keep matches: {kept}");
        // The bounds, inclusive: 48 and 16 LSB confirm, 49 and 17 do not.
        let m = |x, d| FixedMatch { x, d };
        let two = |a: FixedMatch, b: FixedMatch| row_check(&[vec![a], vec![b]], limits);
        assert_eq!(two(m(100, 40), m(148, 56)), vec![vec![true], vec![true]]);
        assert_eq!(two(m(100, 40), m(149, 56)), vec![vec![false], vec![false]]);
        assert_eq!(two(m(148, 40), m(100, 57)), vec![vec![false], vec![false]]);
        assert_eq!(row_check(&[vec![m(5, 5)]], limits), vec![vec![false]]);
    }
}
