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
const NO_DISPARITY: f64 = 0.0;

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
    interpolate_into(anchors, ends, None, &mut out);
    out
}

/// [`interpolate_line`] into an existing row buffer (its length is the
/// width). With `jump = Some(j)`, the interpolation does not bridge depth
/// discontinuities ([`crate::Features::edge_jump`]): between consecutive
/// anchors whose disparities differ by more than `j`, the pixels take the
/// smaller disparity instead of the linear ramp. A jump is a depth edge, and
/// declivities lie on edges: the pixels between a background and a
/// foreground match belong to the background (the nearer object's edge is at
/// its own match), whichever side it is on.
pub fn interpolate_into(anchors: &[Anchor], ends: EndRule, jump: Option<f64>, out: &mut [f64]) {
    let (Some(first), Some(last)) = (anchors.first(), anchors.last()) else {
        out.fill(NO_DISPARITY);
        return;
    };
    let width = out.len();
    let first_at_or_after = |x: f64| first_at_or_after(x, width);
    let (held_first, held_last) = match ends {
        EndRule::Hold => (first.d, last.d),
        EndRule::Empty => (NO_DISPARITY, NO_DISPARITY),
    };
    // Every pixel is written once: before the first anchor, between
    // consecutive anchors a and b (centres in [x_a, x_b)), then from the
    // last anchor on (its own value at x = x_last, held or empty beyond).
    let begin = first_at_or_after(first.x);
    out[..begin].fill(held_first);
    let mut from = begin;
    for w in anchors.windows(2) {
        let (a, b) = (w[0], w[1]);
        let to = first_at_or_after(b.x);
        let segment = &mut out[from..to];
        if jump.is_some_and(|j| (a.d - b.d).abs() > j) {
            segment.fill(a.d.min(b.d));
        } else {
            let slope = (b.d - a.d) / (b.x - a.x);
            for (x, v) in (from..).zip(segment) {
                *v = a.d + slope * (pixel_centre(x) - a.x);
            }
        }
        from = to;
    }
    // `from` is now the first centre at or after the last anchor.
    let mut tail = from;
    if tail < width && pixel_centre(tail) == last.x {
        out[tail] = last.d;
        tail += 1;
    }
    out[tail..].fill(held_last);
}

/// [`interpolate_into`], the same values, with fewer branches on the data
/// (the frame pipeline's path): a segment between two anchors is written
/// [`CHUNK`] pixels at a time, the last chunk running past the segment's end
/// into pixels that the next segments or the held end overwrite (segments
/// are written left to right and each starts where the previous one ends),
/// and a jump is the ramp of slope 0 from the smaller disparity
/// (`d + 0·(x - x_a) = d`: every disparity is positive), so that neither the
/// length of a segment nor its kind is a branch per pixel or per segment.
pub(crate) fn interpolate_chunked(anchors: &[Anchor], ends: EndRule, jump: Option<f64>, out: &mut [f64]) {
    let (Some(first), Some(last)) = (anchors.first(), anchors.last()) else {
        out.fill(NO_DISPARITY);
        return;
    };
    let width = out.len();
    // Pixel indices converted through i32 (two at a time on x86-64): rows of
    // fewer than 2^31 pixels.
    if i32::try_from(width).is_err() {
        return interpolate_into(anchors, ends, jump, out);
    }
    let first_at_or_after = |x: f64| first_at_or_after(x, width);
    let (held_first, held_last) = match ends {
        EndRule::Hold => (first.d, last.d),
        EndRule::Empty => (NO_DISPARITY, NO_DISPARITY),
    };
    let begin = first_at_or_after(first.x);
    out[..begin].fill(held_first);
    let jump = jump.unwrap_or(f64::INFINITY);
    let mut from = begin;
    for w in anchors.windows(2) {
        let (a, b) = (w[0], w[1]);
        let to = first_at_or_after(b.x);
        let is_jump = (a.d - b.d).abs() > jump;
        let (base, slope) = (if is_jump { a.d.min(b.d) } else { a.d }, if is_jump { 0.0 } else { (b.d - a.d) / (b.x - a.x) });
        let mut x = from;
        while x < to {
            match out.get_mut(x..x + CHUNK) {
                Some(chunk) => {
                    for (k, v) in chunk.iter_mut().enumerate() {
                        *v = base + slope * ((x + k) as i32 as f64 - a.x);
                    }
                }
                // The row's last pixels: one at a time, to the segment's end.
                None => {
                    for (k, v) in out[x..to].iter_mut().enumerate() {
                        *v = base + slope * (pixel_centre(x + k) - a.x);
                    }
                }
            }
            x += CHUNK;
        }
        from = to;
    }
    let mut tail = from;
    if tail < width && pixel_centre(tail) == last.x {
        out[tail] = last.d;
        tail += 1;
    }
    out[tail..].fill(held_last);
}

/// Pixels written at once by [`interpolate_chunked`].
const CHUNK: usize = 8;

/// The first pixel centre at or after `x`, as an index of a row of `width`
/// pixels (a ceiling without a call to libm's `ceil`). Through `i64`, whose
/// conversions to and from `f64` are single instructions on x86-64 (those of
/// `usize` are not); a row is far shorter than `2^63` pixels.
fn first_at_or_after(x: f64, width: usize) -> usize {
    let x = x.max(0.0);
    let t = x as i64;
    (t as usize + ((t as f64) < x) as usize).min(width)
}

/// The coordinate of pixel centre `x`, exact (through `i64`, as in
/// [`first_at_or_after`]).
#[inline]
fn pixel_centre(x: usize) -> f64 {
    x as i64 as f64
}

/// The vertical median of a dense map over `rows` rows (1, 3, 5 or 9)
/// centred on row `y`, written into `out_row`; rows beyond the image repeat
/// its top or bottom row. Pixels without disparity take part as `0`.
///
/// Branch-free min/max networks, so that the loop over a row vectorizes: the
/// median of three is `max(min(a, b), min(max(a, b), c))`; for five, the two
/// middle values of four (`max(min(a,b), min(c,d))` and
/// `min(max(a,b), max(c,d))`, in either order) bracket the median with the
/// fifth value; for nine, [`MEDIAN9_NETWORK`].
pub fn vertical_median(disparity: &[f64], width: usize, rows: usize, out_row: &mut [f64], y: usize) {
    assert!(matches!(rows, 1 | 3 | 5 | 9), "vertical median over {rows} rows: 1, 3, 5 or 9 are supported");
    let height = disparity.len() / width;
    let half = (rows / 2) as isize;
    let row = |dy: isize| {
        let yy = (y as isize + dy).clamp(0, height as isize - 1) as usize;
        &disparity[yy * width..(yy + 1) * width]
    };
    let rows: Vec<&[f64]> = (-half..=half).map(row).collect();
    median_of_rows(&rows, out_row);
}

/// The compare-exchanges of the median of nine values (Paeth's network, as
/// in N. Devillard's `opt_med9`): `(a, b)` leaves `min` at `a` and `max` at
/// `b`; after the 19 of them, in this order, value 4 is the median. Each
/// line is one step of the hardware's pipeline (`rtl::post::vertical_median`): its
/// exchanges touch distinct values.
const MEDIAN9_NETWORK: [&[(usize, usize)]; 9] = [
    &[(1, 2), (4, 5), (7, 8)],
    &[(0, 1), (3, 4), (6, 7)],
    &[(1, 2), (4, 5), (7, 8)],
    &[(0, 3), (5, 8), (4, 7)],
    &[(3, 6), (1, 4), (2, 5)],
    &[(4, 7)],
    &[(4, 2)],
    &[(6, 4)],
    &[(4, 2)],
];

/// [`MEDIAN9_NETWORK`] on nine values: their median.
#[inline(always)]
fn median9(mut p: [f64; 9]) -> f64 {
    let min = |a: f64, b: f64| if a < b { a } else { b };
    let max = |a: f64, b: f64| if a > b { a } else { b };
    for step in MEDIAN9_NETWORK {
        for &(a, b) in step {
            (p[a], p[b]) = (min(p[a], p[b]), max(p[a], p[b]));
        }
    }
    p[4]
}

/// The medians of nine rows for two output rows at once, column by column:
/// `rows` are the ten rows `y − 4 ..= y + 5` top to bottom, `out_a` gets
/// row `y`'s median (of `rows[0..9]`) and `out_b` row `y + 1`'s (of
/// `rows[1..10]`): the same values as [`median_of_rows`] on each, for about
/// two thirds of the work.
///
/// The two windows share the eight rows `y − 3 ..= y + 4`. Of those, only
/// the 4th and 5th smallest `c3 ≤ c4` matter: adding a ninth value `v`,
/// the median (the 5th smallest of nine) is `v` clamped to `[c3, c4]`. `c3`
/// and `c4` come from sorting the eight as two sorted quadruples `a`, `b`
/// (pairs, then Batcher's merge of two pairs), whose bitonic split
/// `min(a_k, b_{3−k})` holds the four smallest and `max(a_k, b_{3−k})` the
/// four largest: `c3` is the largest of the first, `c4` the smallest of the
/// second.
pub(crate) fn median9_of_two_rows(rows: &[&[f64]; 10], out_a: &mut [f64], out_b: &mut [f64]) {
    let min = |a: f64, b: f64| if a < b { a } else { b };
    let max = |a: f64, b: f64| if a > b { a } else { b };
    let n = out_a.len();
    let r: [&[f64]; 10] = rows.map(|row| &row[..n]);
    let out_b = &mut out_b[..n];
    for x in 0..n {
        let p = [r[1][x], r[2][x], r[3][x], r[4][x], r[5][x], r[6][x], r[7][x], r[8][x]];
        // Two sorted quadruples: sorted pairs, then the merge of two pairs.
        let quad = |w: f64, x: f64, y: f64, z: f64| {
            let (a0, a1, b0, b1) = (min(w, x), max(w, x), min(y, z), max(y, z));
            let (lo, hi, m0, m1) = (min(a0, b0), max(a1, b1), max(a0, b0), min(a1, b1));
            [lo, min(m0, m1), max(m0, m1), hi]
        };
        let (a, b) = (quad(p[0], p[1], p[2], p[3]), quad(p[4], p[5], p[6], p[7]));
        let c3 = max(max(min(a[0], b[3]), min(a[1], b[2])), max(min(a[2], b[1]), min(a[3], b[0])));
        let c4 = min(min(max(a[0], b[3]), max(a[1], b[2])), min(max(a[2], b[1]), max(a[3], b[0])));
        out_a[x] = min(max(r[0][x], c3), c4);
        out_b[x] = min(max(r[9][x], c3), c4);
    }
}

/// The median of 1, 3, 5 or 9 rows, column by column, into `out_row`: the
/// networks of [`vertical_median`], on the rows top to bottom.
///
/// Disparities are `+0` or positive, never NaN or `-0`: two values that
/// compare equal are the same bits, so either may be taken on a tie, and
/// `min`/`max` are written as the single instructions of x86-64 take them
/// (`a < b ? a : b`, `a > b ? a : b`).
fn median_of_rows(rows: &[&[f64]], out_row: &mut [f64]) {
    let min = |a: f64, b: f64| if a < b { a } else { b };
    let max = |a: f64, b: f64| if a > b { a } else { b };
    let median3 = |a: f64, b: f64, c: f64| max(min(a, b), min(max(a, b), c));
    match *rows {
        [row] => out_row.copy_from_slice(row),
        // Zipped rows rather than indices: no bounds checks, so the loops
        // vectorize.
        [above, centre, below] => {
            let rows = above.iter().zip(centre).zip(below);
            for (v, ((&a, &b), &c)) in out_row.iter_mut().zip(rows) {
                *v = median3(a, b, c);
            }
        }
        [r0, r1, centre, r3, r4] => {
            let rows = r0.iter().zip(r1).zip(centre).zip(r3).zip(r4);
            for (v, ((((&a, &b), &e), &c), &d)) in out_row.iter_mut().zip(rows) {
                let (lo, hi) = (max(min(a, b), min(c, d)), min(max(a, b), max(c, d)));
                *v = median3(lo, hi, e);
            }
        }
        [r0, r1, r2, r3, centre, r5, r6, r7, r8] => {
            let n = out_row.len();
            let rows = [r0, r1, r2, r3, centre, r5, r6, r7, r8].map(|r| &r[..n]);
            for (x, v) in out_row.iter_mut().enumerate() {
                *v = median9(rows.map(|r| r[x]));
            }
        }
        _ => panic!("vertical median over {} rows: 1, 3, 5 or 9 are supported", rows.len()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The median by sorting, with the same edge rule.
    fn median_by_sorting(map: &[f64], width: usize, rows: usize, x: usize, y: usize) -> f64 {
        let height = map.len() / width;
        let half = (rows / 2) as isize;
        let mut v: Vec<f64> = (-half..=half).map(|dy| map[(y as isize + dy).clamp(0, height as isize - 1) as usize * width + x]).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    }

    #[test]
    fn vertical_median_networks_equal_sorting() {
        let mut rng = crate::test_rng::TestRng::new(0xfeed_beef_0000_0001);
        for _ in 0..300 {
            let (w, h) = (1 + (rng.next() % 9) as usize, 1 + (rng.next() % 12) as usize);
            // Few distinct values: ties everywhere; 0 = no disparity.
            let map: Vec<f64> = (0..w * h).map(|_| (rng.next() % 5) as f64 * 1.5).collect();
            for rows in [1, 3, 5, 9] {
                for y in 0..h {
                    let mut out = vec![-1.0; w];
                    vertical_median(&map, w, rows, &mut out, y);
                    for (x, &got) in out.iter().enumerate() {
                        assert_eq!(got, median_by_sorting(&map, w, rows, x, y), "rows {rows}, ({x}, {y}) of {map:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn two_rows_of_nine_row_medians_at_once_equal_the_network() {
        let mut rng = crate::test_rng::TestRng::new(0x9a11_0b5e_0000_0010);
        for case in 0..3000 {
            let w = 1 + (rng.next() % 12) as usize;
            // Few distinct values (ties everywhere), or many.
            let values = if case % 2 == 0 { 4 } else { 1000 };
            let rows: Vec<Vec<f64>> = (0..10).map(|_| (0..w).map(|_| (rng.next() % values) as f64 * 0.75).collect()).collect();
            let refs: [&[f64]; 10] = std::array::from_fn(|k| rows[k].as_slice());
            let (mut a, mut b) = (vec![-1.0; w], vec![-1.0; w]);
            median9_of_two_rows(&refs, &mut a, &mut b);
            let (mut want_a, mut want_b) = (vec![-2.0; w], vec![-2.0; w]);
            median_of_rows(&refs[..9], &mut want_a);
            median_of_rows(&refs[1..], &mut want_b);
            assert_eq!((a, b), (want_a, want_b), "case {case}: {rows:?}");
        }
    }

    #[test]
    fn chunked_interpolation_equals_the_reference() {
        let mut rng = crate::test_rng::TestRng::new(0x1e7e_c4a5_0b0e_0001);
        for case in 0..3000 {
            let width = 1 + (rng.next() % 80) as usize;
            // Anchors at strictly increasing positions, some closer than a
            // pixel, some outside the row; positive disparities with jumps.
            let mut x = (rng.next() % 40) as f64 / 4.0 - 5.0;
            let anchors: Vec<Anchor> = (0..rng.next() % 12)
                .map(|_| {
                    x += (1 + rng.next() % 40) as f64 / 8.0;
                    Anchor { x, d: 0.5 + (rng.next() % 200) as f64 / 7.0 }
                })
                .collect();
            for ends in [EndRule::Hold, EndRule::Empty] {
                for jump in [None, Some(2.0), Some(6.0)] {
                    let (mut want, mut got) = (vec![-1.0; width], vec![-2.0; width]);
                    interpolate_into(&anchors, ends, jump, &mut want);
                    interpolate_chunked(&anchors, ends, jump, &mut got);
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&got), bits(&want), "case {case}, {ends:?}, {jump:?}, {anchors:?}");
                }
            }
        }
    }

    #[test]
    fn jumps_hold_the_background_and_small_steps_stay_linear() {
        // Anchors at x = 2 (d 10), 6 (d 20: a jump of 10), 8 (d 21: a step of 1).
        let a = [Anchor { x: 2.0, d: 10.0 }, Anchor { x: 6.0, d: 20.0 }, Anchor { x: 8.0, d: 21.0 }];
        let mut out = vec![0.0; 10];
        interpolate_into(&a, EndRule::Hold, Some(4.0), &mut out);
        // x = 2..5 between the jump's anchors: the smaller disparity, 10.
        assert_eq!(&out[2..6], &[10.0; 4]);
        // x = 6, 7: linear from 20 to 21 (20, 20.5); 8, 9: 21 (held).
        assert_eq!(&out[6..], &[20.0, 20.5, 21.0, 21.0]);
        assert_eq!(&out[..2], &[10.0, 10.0]);
    }
}
