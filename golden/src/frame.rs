//! A whole rectified image pair, line by line, on one thread or all cores.

use rayon::prelude::*;

use crate::disparity::{interpolate_into, vertical_median, Anchor};
use crate::error::GoldenError;
use crate::line::{process_line, LineResult, Match};
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
/// lines are independent.
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
pub fn flag_edge_matches(matches: &mut [Match], jump: f64) {
    let d: Vec<f64> = matches.iter().map(|m| m.disparity).collect();
    for (k, m) in matches.iter_mut().enumerate() {
        let before = k > 0 && (d[k] - d[k - 1]).abs() > jump;
        let after = k + 1 < d.len() && (d[k] - d[k + 1]).abs() > jump;
        m.edge = before || after;
    }
}

/// Runs the method on a rectified pair: every row of `left` with the same
/// row of `right`, then (as the mode asks) the check of matches against the
/// neighbouring rows, the flag on matches next to a depth edge,
/// interpolation along each reference row, and a vertical median.
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
    // 1. Every pair of lines, independently.
    let one_line = |y: usize| process_line(left.row(y), right.row(y), params);
    let lines: Vec<LineResult> = match threads {
        Threads::One => (0..h).map(one_line).collect(),
        Threads::All => (0..h).into_par_iter().map(one_line).collect(),
    };
    Ok(finish_frame(lines, w, h, params, threads))
}

/// The steps of [`process_frame`] after the lines are matched, as the mode
/// asks: the check of matches against the neighbouring rows, the flag on
/// matches next to a depth edge, interpolation along each reference row of
/// `w` pixels, and a vertical median over the `h` rows.
pub fn finish_frame(mut lines: Vec<LineResult>, w: usize, h: usize, params: &Params, threads: Threads) -> FrameResult {
    let features = params.mode.features();
    // 2. Matches confirmed by a neighbouring row.
    if features.consistent {
        let kept = confirmed_matches(&lines);
        for (line, kept) in lines.iter_mut().zip(kept) {
            let mut k = kept.into_iter();
            line.matches.retain(|_| k.next().unwrap_or(false));
        }
    }
    // 3. Matches next to a disparity jump flagged.
    if let Some(jump) = features.edge_flag {
        for line in &mut lines {
            flag_edge_matches(&mut line.matches, jump);
        }
    }
    // 4. Interpolation along each reference row (every match anchors it).
    let mut disparity = vec![0.0; w * h];
    let interpolate = |(line, out): (&LineResult, &mut [f64])| {
        let anchors: Vec<Anchor> = line.matches.iter().map(|m| m.anchor()).collect();
        interpolate_into(&anchors, params.ends, features.edge_jump, out);
    };
    match threads {
        Threads::One => lines.iter().zip(disparity.chunks_mut(w)).for_each(interpolate),
        Threads::All => lines.par_iter().zip(disparity.par_chunks_mut(w)).for_each(interpolate),
    }
    // 5. Vertical median of the dense map.
    if features.median_rows > 1 {
        let src = std::mem::replace(&mut disparity, vec![0.0; w * h]);
        let median = |(y, out): (usize, &mut [f64])| vertical_median(&src, w, features.median_rows, out, y);
        match threads {
            Threads::One => disparity.chunks_mut(w).enumerate().for_each(median),
            Threads::All => disparity.par_chunks_mut(w).enumerate().for_each(median),
        }
    }
    FrameResult { width: w, height: h, params: *params, lines, disparity }
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
    fn matches_next_to_a_disparity_jump_are_flagged() {
        // Disparities 5, 5.5, 9 (a jump of 3.5 > 2), 9.5, 9.5: the two sides of
        // the jump are flagged, the others not; a step of exactly 2 is no jump.
        let mut l = line(&[(10.0, 5.0), (20.0, 5.5), (30.0, 9.0), (40.0, 9.5), (50.0, 11.5)]);
        flag_edge_matches(&mut l.matches, 2.0);
        let flags: Vec<bool> = l.matches.iter().map(|m| m.edge).collect();
        assert_eq!(flags, vec![false, true, true, false, false]);
    }
}
