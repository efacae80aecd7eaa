//! A whole rectified image pair, line by line, on one thread or all cores.

use rayon::prelude::*;

use crate::disparity::{interpolate_chunked, interpolate_into, median9_of_two_rows, vertical_median, Anchor};
use crate::error::GoldenError;
use crate::hardware::interpolate::Interpolator;
use crate::hardware::row_check::{row_check, FixedMatch};
use crate::hardware::HardwareLimits;
use crate::line::{process_line_in, ContourPoint, LineBuffers, LineResult, Match};
use crate::params::{Params, CONSISTENT_DD, CONSISTENT_DX};

/// An 8-bit grey image, row-major.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GreyImage {
    width: usize,
    height: usize,
    data: Vec<u8>,
}

impl GreyImage {
    /// Wraps a row-major buffer of `width × height` bytes.
    pub fn new(width: usize, height: usize, data: Vec<u8>) -> Result<Self, GoldenError> {
        if data.len() != width * height {
            return Err(GoldenError::BufferSize { width, height, len: data.len() });
        }
        if width == 0 || height == 0 {
            return Err(GoldenError::EmptyImage { width, height });
        }
        Ok(GreyImage { width, height, data })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row `y` (an epipolar line).
    pub fn row(&self, y: usize) -> &[u8] {
        &self.data[y * self.width..(y + 1) * self.width]
    }

    /// All pixels, row-major.
    pub fn pixels(&self) -> &[u8] {
        &self.data
    }
}

/// How many threads process the lines. Results are identical either way:
/// lines are independent (a mode with inter-scanline support,
/// [`crate::Features::contour`], matches them in order on one thread).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Threads {
    /// The calling thread only.
    One,
    /// All cores (rayon's global pool).
    #[default]
    All,
}

/// The method's result on a frame.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameResult {
    /// Width of the images.
    pub width: usize,
    /// Height of the images.
    pub height: usize,
    /// The parameters used.
    pub params: Params,
    /// One result per row.
    pub lines: Vec<LineResult>,
    /// Dense disparity of the reference view, row-major, `0.0` = none.
    pub disparity: Vec<f64>,
}

impl FrameResult {
    /// Characteristic declivities of the reference view.
    pub fn reference_declivities(&self) -> usize {
        self.lines.iter().map(|l| l.reference.declivities.len()).sum()
    }

    /// Matched reference declivities (reported matches: those flagged as
    /// depth-edge matches are not counted).
    pub fn matches(&self) -> usize {
        self.lines.iter().map(|l| l.matches.iter().filter(|m| !m.edge).count()).sum()
    }

    /// Matches flagged as lying next to a depth edge.
    pub fn edge_matches(&self) -> usize {
        self.lines.iter().map(|l| l.matches.iter().filter(|m| m.edge).count()).sum()
    }
}

/// Which matches a neighbouring row confirms ([`crate::Features::consistent`]),
/// row by row: a match is confirmed by a match within [`CONSISTENT_DX`] px in
/// the row above or below whose disparity differs by at most
/// [`CONSISTENT_DD`] px. Confirmation is mutual, so each pair of adjacent
/// rows is merged once (matches are sorted by position) and marks both.
pub fn confirmed_matches(lines: &[LineResult]) -> Vec<Vec<bool>> {
    let mut keep: Vec<Vec<bool>> = lines.iter().map(|l| vec![false; l.matches.len()]).collect();
    for y in 1..lines.len() {
        let (above, below) = keep.split_at_mut(y);
        let (ka, kb) = (&mut above[y - 1], &mut below[0]);
        let (a, b) = (&lines[y - 1].matches, &lines[y].matches);
        // b[lo..] are the matches not left of the window of a[i].
        let mut lo = 0usize;
        for (i, m) in a.iter().enumerate() {
            while lo < b.len() && b[lo].x_ref < m.x_ref - CONSISTENT_DX {
                lo += 1;
            }
            let mut j = lo;
            while j < b.len() && b[j].x_ref <= m.x_ref + CONSISTENT_DX {
                let close = (b[j].disparity - m.disparity).abs() <= CONSISTENT_DD;
                ka[i] |= close;
                kb[j] |= close;
                j += 1;
            }
        }
    }
    keep
}

/// Flags the matches of a row whose disparity differs by more than `jump`
/// from that of the previous or the next match ([`crate::Features::edge_flag`]).
fn flag_edge_matches(matches: &mut [Match], jump: f64) {
    // A jump between matches k-1 and k flags both; `prev` carries the flag
    // of the jump before k.
    let mut prev = false;
    for k in 0..matches.len() {
        let next = k + 1 < matches.len() && (matches[k].disparity - matches[k + 1].disparity).abs() > jump;
        matches[k].edge = prev | next;
        prev = next;
    }
}

/// Runs the method on a rectified pair: every row of `left` with the same
/// row of `right` (with inter-scanline support, top to bottom, each row
/// with the matches of the row above), then (as the mode asks) the check
/// of matches against the neighbouring rows, the flag on matches next to a
/// depth edge, interpolation along each reference row, and a vertical
/// median.
pub fn process_frame(left: &GreyImage, right: &GreyImage, params: &Params, threads: Threads) -> Result<FrameResult, GoldenError> {
    params.validate()?;
    if left.width != right.width || left.height != right.height {
        return Err(GoldenError::SizeMismatch {
            left_w: left.width,
            left_h: left.height,
            right_w: right.width,
            right_h: right.height,
        });
    }
    let (w, h) = (left.width, left.height);
    // 1. Every pair of lines, independently (each thread reuses its working
    // vectors from line to line), or with inter-scanline support in order,
    // each with the row above's matches.
    let one_line = |buffers: &mut LineBuffers, y: usize| process_line_in(buffers, left.row(y), right.row(y), params, None);
    let lines: Vec<LineResult> = match (params.mode.features().contour, threads) {
        (Some(support), _) => {
            let mut buffers = LineBuffers::default();
            let mut above: Vec<ContourPoint> = Vec::new();
            (0..h)
                .map(|y| {
                    let line = process_line_in(&mut buffers, left.row(y), right.row(y), params, Some((&above, support)));
                    above.clear();
                    above.extend(line.contour_points());
                    line
                })
                .collect()
        }
        (None, Threads::One) => {
            let mut buffers = LineBuffers::default();
            (0..h).map(|y| one_line(&mut buffers, y)).collect()
        }
        (None, Threads::All) => (0..h).into_par_iter().map_init(LineBuffers::default, one_line).collect(),
    };
    Ok(finish_frame(lines, w, h, params, threads))
}

/// The steps of [`process_frame`] after the lines are matched, as the mode
/// asks: the check of matches against the neighbouring rows, the flag on
/// matches next to a depth edge, interpolation along each reference row of
/// `w` pixels, and a vertical median over the `h` rows. In hardware parity
/// (`params.hardware`), the check and the interpolation are the line
/// processor's on the matcher's fixed-point matches
/// ([`crate::hardware::row_check`], [`crate::hardware::interpolate`]): the
/// disparities are then the hardware's, multiples of `2^-pos_frac_bits`
/// px, and [`crate::hardware::depth::DepthStage::depth_map_mm`] gives the
/// hardware's depths of them.
pub fn finish_frame(mut lines: Vec<LineResult>, w: usize, h: usize, params: &Params, threads: Threads) -> FrameResult {
    let features = params.mode.features();
    // 2. Matches confirmed by a neighbouring row (in hardware parity, by
    // the line processor's row check on the matcher's fixed-point matches).
    if features.consistent {
        match params.hardware {
            Some(limits) => {
                let rows: Vec<Vec<FixedMatch>> = lines.iter().map(|l| fixed_matches(&l.matches, limits)).collect();
                for (line, kept) in lines.iter_mut().zip(row_check(&rows, limits)) {
                    let mut k = kept.into_iter();
                    line.matches.retain(|_| k.next().expect("a flag per match"));
                }
            }
            None => {
                let (kept, first) = confirmed_flags(&lines);
                for (line, &first) in lines.iter_mut().zip(&first) {
                    let mut k = kept[first..].iter();
                    line.matches.retain(|_| *k.next().expect("a flag per match"));
                }
            }
        }
    }
    // 3. Matches next to a disparity jump flagged.
    if let Some(jump) = features.edge_flag {
        for line in &mut lines {
            flag_edge_matches(&mut line.matches, jump);
        }
    }
    // 4. Interpolation along each reference row (every match anchors it),
    // 5. then the vertical median of the dense map.
    let disparity = match threads {
        Threads::One => interpolate_and_median(&lines, w, params),
        Threads::All => {
            let mut disparity = vec![0.0; w * h];
            let rows = lines.par_iter().zip(disparity.par_chunks_mut(w));
            match params.hardware {
                None => rows.for_each(|(line, out)| {
                    let anchors: Vec<Anchor> = line.matches.iter().map(|m| m.anchor()).collect();
                    interpolate_into(&anchors, params.ends, features.edge_jump, out);
                }),
                Some(limits) => {
                    let interpolator = Interpolator::of_features(limits, &features);
                    rows.for_each_init(HardwareRow::default, |row, (line, out)| row.interpolate(&interpolator, limits, line, out));
                }
            }
            if features.median_rows > 1 {
                let src = std::mem::replace(&mut disparity, vec![0.0; w * h]);
                disparity.par_chunks_mut(w).enumerate().for_each(|(y, out)| vertical_median(&src, w, features.median_rows, out, y));
            }
            disparity
        }
    };
    FrameResult { width: w, height: h, params: *params, lines, disparity }
}

/// A row's matches in the matcher's format ([`FixedMatch::of`]).
fn fixed_matches(matches: &[Match], limits: HardwareLimits) -> Vec<FixedMatch> {
    matches.iter().map(|m| FixedMatch::of(m, limits)).collect()
}

/// Step 4 of [`finish_frame`] in hardware parity, with its working rows:
/// the line processor's interpolator ([`Interpolator::row`]) on the
/// matcher's fixed-point matches (every match anchors it, as in the f64
/// mode), over the hardware's line, the row's first `w_max` pixels (the
/// others stay 0: the hardware sends none), in px (`LSB / 2^f`, exact).
/// The vertical median of step 5 then takes these values as the
/// hardware's median takes their LSBs: a median is one of its inputs, and
/// `LSB ↦ LSB / 2^f` is monotone and exact.
#[derive(Debug, Default)]
struct HardwareRow {
    matches: Vec<FixedMatch>,
    lsb: Vec<u16>,
}

impl HardwareRow {
    fn interpolate(&mut self, interpolator: &Interpolator, limits: HardwareLimits, line: &LineResult, out: &mut [f64]) {
        self.matches.clear();
        self.matches.extend(line.matches.iter().map(|m| FixedMatch::of(m, limits)));
        let width = out.len().min(limits.w_max);
        self.lsb.resize(width, 0);
        interpolator.row(&self.matches, &mut self.lsb);
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        for (o, &d) in out.iter_mut().zip(&self.lsb) {
            *o = d as f64 / unit;
        }
        out[width..].fill(0.0);
    }
}

/// Steps 4 and 5 of [`finish_frame`] on one thread, row by row: each row is
/// interpolated into a ring of ten rows and the medians of the nine rows
/// around two output rows are written out as soon as those rows are there,
/// so that the interpolated map is never stored whole (the same values as
/// [`interpolate_into`] on every row, then [`vertical_median`]).
fn interpolate_and_median(lines: &[LineResult], w: usize, params: &Params) -> Vec<f64> {
    let features = params.mode.features();
    let (h, rows) = (lines.len(), features.median_rows);
    let mut anchors: Vec<Anchor> = Vec::new();
    let hardware = params.hardware.map(|limits| (limits, Interpolator::of_features(limits, &features)));
    let mut row = HardwareRow::default();
    let mut interpolate = |line: &LineResult, out: &mut [f64]| match &hardware {
        None => {
            anchors.clear();
            anchors.extend(line.matches.iter().map(|m| m.anchor()));
            interpolate_chunked(&anchors, params.ends, features.edge_jump, out);
        }
        Some((limits, interpolator)) => row.interpolate(interpolator, *limits, line, out),
    };
    let mut disparity = Vec::with_capacity(w * h);
    if rows <= 1 {
        for line in lines {
            let start = disparity.len();
            disparity.resize(start + w, 0.0);
            interpolate(line, &mut disparity[start..]);
        }
        return disparity;
    }
    // The modes' median is MEDIAN_ROWS = 9 rows (the Features of every Mode).
    assert_eq!(rows, 9, "vertical median over {rows} rows on one thread: 1 or 9 are supported");
    // Two output rows at a time ([`median9_of_two_rows`]): rows y - 4 ..=
    // y + 5, clamped to the image, from a ring of ten.
    let mut ring = vec![0.0; 10 * w];
    let mut spare = vec![0.0; w];
    let mut next = 0;
    disparity.resize(w * h, 0.0);
    for y in (0..h).step_by(2) {
        while next < h && next <= y + 5 {
            interpolate(&lines[next], &mut ring[(next % 10) * w..][..w]);
            next += 1;
        }
        let around: [&[f64]; 10] = std::array::from_fn(|k| {
            let r = (y + k).saturating_sub(4).min(h - 1);
            &ring[(r % 10) * w..][..w]
        });
        let (top, rest) = disparity[y * w..].split_at_mut(w);
        let bottom = if y + 1 < h { &mut rest[..w] } else { &mut spare[..] };
        median9_of_two_rows(&around, top, bottom);
    }
    disparity
}

/// [`confirmed_matches`] as one flat list of flags, row after row (each
/// row's flags followed by three unused slots), and the index of each row's
/// first flag: the same merge of each pair of adjacent
/// rows, without a branch on the data where it can be avoided (such
/// branches are mispredicted often and would dominate its time). The
/// positions and disparities
/// are copied out of the matches, each row closed by three `+∞` positions;
/// a window's first three matches are checked unconditionally and a loop
/// runs only when it holds more (rare: matches are seldom closer than
/// [`CONSISTENT_DX`]).
fn confirmed_flags(lines: &[LineResult]) -> (Vec<bool>, Vec<usize>) {
    const PAD: usize = 3;
    let total: usize = lines.iter().map(|l| l.matches.len() + PAD).sum();
    let (mut x, mut d) = (Vec::with_capacity(total), Vec::with_capacity(total));
    let mut first = Vec::with_capacity(lines.len() + 1);
    for line in lines {
        first.push(x.len());
        x.extend(line.matches.iter().map(|m| m.x_ref));
        d.extend(line.matches.iter().map(|m| m.disparity));
        x.extend([f64::INFINITY; PAD]);
        d.extend([0.0; PAD]);
    }
    let mut keep = vec![false; total];
    for y in 1..lines.len() {
        // Row y - 1's matches are a0 .. a1, row y's start at b0.
        let (a0, a1, b0) = (first[y - 1], first[y] - PAD, first[y]);
        let mut lo = b0;
        for i in a0..a1 {
            let (left, right) = (x[i] - CONSISTENT_DX, x[i] + CONSISTENT_DX);
            // lo: row y's first match not left of the window (a +∞ stops
            // it). Positions are sorted: up to two steps are one sum of two
            // independent tests.
            lo += (x[lo] < left) as usize + (x[lo + 1] < left) as usize;
            while x[lo] < left {
                lo += 1;
            }
            let mut confirmed = false;
            let mut check = |j: usize| {
                let inside = x[j] <= right;
                let close = inside & ((d[j] - d[i]).abs() <= CONSISTENT_DD);
                keep[j] |= close;
                confirmed |= close;
                inside
            };
            // lo + 2 is at most the row's third +∞; past it only when it is inside.
            check(lo);
            check(lo + 1);
            if check(lo + 2) {
                let mut j = lo + 3;
                while check(j) {
                    j += 1;
                }
            }
            keep[i] |= confirmed;
        }
    }
    (keep, first)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::line::LineFeatures;

    fn line(matches: &[(f64, f64)]) -> LineResult {
        let empty = LineFeatures { sigma: 1.0, dt: 5.6, declivities: vec![] };
        let matches = matches
            .iter()
            .map(|&(x, d)| Match { ref_index: 0, other_index: 0, x_ref: x, x_other: x - d, disparity: d, gain: 1.0, edge: false })
            .collect();
        LineResult { reference: empty.clone(), other: empty, matches, path_gain: 0.0 }
    }

    #[test]
    fn matches_are_kept_when_a_neighbouring_row_confirms_them() {
        // The cases below are worked for these bounds.
        assert_eq!((CONSISTENT_DX, CONSISTENT_DD), (3.0, 1.0));
        let lines = [
            // Row 0: x 10 d 5 is confirmed by row 1's (11.5, 5.8): |Δx| 1.5 <= 3, |Δd| 0.8 <= 1.
            line(&[(10.0, 5.0), (30.0, 9.0)]),
            // Row 1: (11.5, 5.8) confirmed by row 0; (30.0, 7.5) has |Δd| 1.5 from row 0's and
            // |Δx| 3.5 > 3 from row 2's (33.5, 7.5): not confirmed.
            line(&[(11.5, 5.8), (30.0, 7.5), (50.0, 3.0)]),
            // Row 2: (53.0, 4.0) confirms row 1's (50, 3): |Δx| 3, |Δd| 1 (bounds included).
            line(&[(33.5, 7.5), (53.0, 4.0)]),
        ];
        let keep = confirmed_matches(&lines);
        assert_eq!(keep, vec![vec![true, false], vec![true, false, true], vec![false, true]]);
        // A single row confirms nothing.
        assert_eq!(confirmed_matches(&lines[..1]), vec![vec![false, false]]);
    }

    #[test]
    fn confirmed_flags_are_the_confirmed_matches_row_after_row() {
        let mut rng = crate::test_rng::TestRng::new(0x0c0f_f1a6_5eed_0001);
        for case in 0..2000 {
            // Positions on a grid of quarter pixels (bounds |Δx| = 3 and
            // |Δd| = 1 hit exactly), often closer than 3 px to each other.
            let rows = (rng.next() % 7) as usize;
            let lines: Vec<LineResult> = (0..rows)
                .map(|_| {
                    let n = (rng.next() % 12) as usize;
                    let mut x = (rng.next() % 8) as f64 / 4.0;
                    let m: Vec<(f64, f64)> = (0..n)
                        .map(|_| {
                            x += (1 + rng.next() % 24) as f64 / 4.0;
                            (x, (rng.next() % 12) as f64 / 4.0 + 1.0)
                        })
                        .collect();
                    line(&m)
                })
                .collect();
            let want: Vec<bool> = confirmed_matches(&lines).concat();
            let (flags, first) = confirmed_flags(&lines);
            let got: Vec<bool> =
                lines.iter().zip(&first).flat_map(|(l, &f)| flags[f..f + l.matches.len()].iter().copied()).collect();
            assert_eq!(got, want, "case {case}");
        }
    }

    /// A textured pair (the right view the left shifted by 4 px; the rows
    /// one texture of steps with a little noise, so that they confirm each
    /// other) of rows wider than a small hardware's `w_max`.
    fn shifted_pair(w: usize, h: usize, seed: u64) -> (GreyImage, GreyImage) {
        let mut rng = crate::test_rng::TestRng::new(seed);
        let mut level = 128i32;
        let texture: Vec<i32> = (0..w + 4)
            .map(|x| {
                // Plateaus of 5 px with steps of 30 to 90 grey levels: far
                // above the noise's d_t, so every step is a declivity.
                if x % 5 == 0 {
                    let step = 30 + (rng.next() % 61) as i32;
                    level = if level + step > 253 || (level - step >= 2 && rng.next() % 2 == 0) { level - step } else { level + step };
                }
                level
            })
            .collect();
        let (mut l, mut r) = (Vec::new(), Vec::new());
        for _ in 0..h {
            let row: Vec<u8> = texture.iter().map(|&v| (v + (rng.next() % 5) as i32 - 2) as u8).collect();
            l.extend_from_slice(&row[..w]);
            r.extend_from_slice(&row[4..]);
        }
        (GreyImage::new(w, h, l).unwrap(), GreyImage::new(w, h, r).unwrap())
    }

    #[test]
    fn parity_frames_take_the_hardware_steps_alike_on_one_thread_and_all() {
        use crate::params::Mode;
        let (w, h) = (150, 21);
        let (left, right) = shifted_pair(w, h, 0x9a21_7e57_0000_0001);
        let limits = HardwareLimits { w_max: 128, ..HardwareLimits::default() };
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        for mode in [Mode::Robust, Mode::Edges, Mode::Paper] {
            let params = Params { hardware: Some(limits), ..Params::with_mode(mode, 12.0).unwrap() };
            let one = process_frame(&left, &right, &params, Threads::One).unwrap();
            let all = process_frame(&left, &right, &params, Threads::All).unwrap();
            assert_eq!(one, all, "{mode:?}");
            assert!(one.matches() > 5 * h, "{mode:?}: the rows match: {}", one.matches());
            // The hardware's values (multiples of 1/16 px) on its line of
            // w_max pixels, none beyond.
            for row in one.disparity.chunks(w) {
                assert!(row.iter().all(|&d| (d * unit).fract() == 0.0), "{mode:?}");
                assert!(row[limits.w_max..].iter().all(|&d| d == 0.0), "{mode:?}");
                assert!(row[..limits.w_max].iter().any(|&d| d > 0.0), "{mode:?}");
            }
            // Without the median, each row is the interpolator's on the
            // row's (kept) matches.
            if one.params.mode.features().median_rows == 1 {
                let interpolator = Interpolator::of_features(limits, &mode.features());
                for (line, row) in one.lines.iter().zip(one.disparity.chunks(w)) {
                    let mut lsb = vec![0u16; limits.w_max];
                    interpolator.row(&fixed_matches(&line.matches, limits), &mut lsb);
                    let want: Vec<f64> = lsb.iter().map(|&d| d as f64 / unit).collect();
                    assert_eq!(&row[..limits.w_max], &want[..], "{mode:?}");
                }
            }
        }
    }

    /// Rows of 80 px on a background of 100 with bars of `bar` (start,
    /// level) 4 px wide.
    fn bars(bar: &[(usize, u8)]) -> Vec<u8> {
        let mut row = vec![100u8; 80];
        for &(x, level) in bar {
            row[x..x + 4].fill(level);
        }
        row
    }

    #[test]
    fn the_row_above_picks_the_texture_period_with_inter_scanline_support() {
        use crate::params::Mode;
        // Five bars of period 8 on the left, the true disparity 5. Row 0's
        // right view holds their five partners: only d = 5 matches them
        // all. Row 1's right view has a sixth bar 8 px further left, so
        // d = 13 matches every edge too, and its bars are exact where one of
        // d = 5's partners is a grey level brighter: alone, row 1 is matched
        // one period off. (The lines' σ is the floor, so gmax = 5.6/√12; the
        // brighter bar costs d = 5 two nodes of 3 levels each, less than
        // ten bonuses of gmax/2.)
        let left = bars(&[(30, 160), (38, 160), (46, 160), (54, 160), (62, 160)]);
        let right0 = bars(&[(25, 160), (33, 160), (41, 160), (49, 160), (57, 160)]);
        let right1 = bars(&[(17, 160), (25, 160), (33, 160), (41, 160), (49, 160), (57, 161)]);
        let disparities = |l: &LineResult| l.matches.iter().map(|m| m.disparity).collect::<Vec<f64>>();
        let robust = Params::with_mode(Mode::Robust, 16.0).unwrap();
        assert_eq!(disparities(&crate::line::process_line(&left, &right0, &robust)), vec![5.0; 10]);
        assert_eq!(disparities(&crate::line::process_line(&left, &right1, &robust)), vec![13.0; 10]);
        // With the row above's matches, row 1's edges continue contours at
        // d = 5, and the bonus makes the DP take that period.
        let (l, r) = ([left.clone(), left].concat(), [right0, right1].concat());
        let (l, r) = (GreyImage::new(80, 2, l).unwrap(), GreyImage::new(80, 2, r).unwrap());
        let params = Params::with_mode(Mode::Contour, 16.0).unwrap();
        for threads in [Threads::One, Threads::All] {
            let frame = process_frame(&l, &r, &params, threads).unwrap();
            assert_eq!(disparities(&frame.lines[0]), vec![5.0; 10], "{threads:?}");
            assert_eq!(disparities(&frame.lines[1]), vec![5.0; 10], "{threads:?}");
        }
    }

    #[test]
    fn matches_next_to_a_disparity_jump_are_flagged() {
        // Disparities 5, 5.5, 9 (a jump of 3.5 > 2), 9.5, 9.5: the two sides of
        // the jump are flagged, the others not; a step of exactly 2 is no jump.
        let mut l = line(&[(10.0, 5.0), (20.0, 5.5), (30.0, 9.0), (40.0, 9.5), (50.0, 11.5)]);
        flag_edge_matches(&mut l.matches, 2.0);
        let flags: Vec<bool> = l.matches.iter().map(|m| m.edge).collect();
        assert_eq!(flags, vec![false, true, true, false, false]);
    }
}
