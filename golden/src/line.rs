//! One pair of epipolar lines through the whole method: thresholds (eq. 2),
//! characteristic declivities (eq. 3), nodes and gains (eq. 4–8), the optimal
//! path (eq. 9), the matches and their disparities.

use crate::declivity::{characteristic_declivities_with, Declivity};
use crate::disparity::Anchor;
use crate::dp::{banded_dp_in, DpBuffers, GainTable};
#[cfg(test)]
use crate::dp::BandedGains;
#[cfg(doc)]
use crate::dp::{banded_dp, banded_dp_with};
use crate::gain::{contour_term, gmax, node_gain, pair_disparity, LineGain, Neighbours};
use crate::noise::{noise_sigma, threshold};
use crate::params::{ContourSupport, Params, RefView};

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

/// [`line_features`], or with `Some(limits)` as the streaming detector of
/// those sizes finds them and sends them to the matcher
/// (`crate::hardware::detect_line`, `crate::hardware::matcher_view`): `d_t`
/// and the positions are then the matcher's, and σ the one the detector's
/// fixed-point `d_t` stands for, `d_t / 5.6` (the hardware computes no σ
/// of its own).
pub(crate) fn line_features_with(line: &[u8], limits: Option<crate::hardware::HardwareLimits>) -> LineFeatures {
    match limits {
        None => line_features(line),
        Some(limits) => {
            let d = crate::hardware::detect_line(line, limits);
            let (dt, declivities) = crate::hardware::matcher_view(&d, limits);
            LineFeatures { sigma: d.dt / crate::noise::THRESHOLD_FACTOR, dt, declivities }
        }
    }
}

/// Segments one line: σ, `d_t` (eq. 2) and the characteristic declivities.
pub fn line_features(line: &[u8]) -> LineFeatures {
    line_features_in(&mut LineBuffers::default(), line)
}

/// [`line_features`] with the working vectors of `buffers`.
fn line_features_in(buffers: &mut LineBuffers, line: &[u8]) -> LineFeatures {
    let sigma = noise_sigma(line);
    let dt = threshold(sigma);
    LineFeatures { sigma, dt, declivities: characteristic_declivities_with(line, dt, &mut buffers.spans) }
}

/// The working vectors of the segmentation and the matching of a line, kept
/// from one line to the next ([`process_line_in`]; `process_frame` keeps
/// one per thread) so that a frame does not allocate and free them for
/// every line. Their contents between calls mean nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct LineBuffers {
    spans: Vec<(usize, usize)>,
    refs: Vec<f64>,
    others: Vec<f64>,
    bands: Vec<(usize, usize)>,
    neighbours: Vec<Neighbours>,
    contour: Vec<f64>,
    dp: DpBuffers,
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
    /// Flagged as lying next to a depth edge ([`crate::Features::edge_flag`]):
    /// it anchors the interpolation but is not reported as a match.
    pub edge: bool,
}

impl Match {
    /// The disparity anchored at the reference position, for interpolation.
    pub fn anchor(&self) -> Anchor {
        Anchor { x: self.x_ref, d: self.disparity }
    }
}

/// A matched reference declivity of a row as the row below's
/// inter-scanline support reads it ([`crate::Features::contour`]): what
/// the hardware's line buffer keeps of each match.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContourPoint {
    /// Position `X` (eq. 3) of the matched reference declivity.
    pub x: f64,
    /// Its disparity.
    pub disparity: f64,
    /// Its polarity: rising (`a_i > 0`).
    pub rising: bool,
}

/// The disparity of the edge contour that each reference declivity
/// (sorted by position) continues ([`crate::Features::contour`]): that of
/// the nearest match of the row above (`above`, sorted by position) with
/// the same polarity and a position within `dx` px (of two equally near,
/// the left one), `NaN` when there is none. One sweep over both lists.
pub fn contour_disparities(refs: &[Declivity], above: &[ContourPoint], dx: f64, out: &mut Vec<f64>) {
    let mut lo = 0usize;
    out.clear();
    out.extend(refs.iter().map(|r| {
        while lo < above.len() && above[lo].x < r.position - dx {
            lo += 1;
        }
        let rising = r.amplitude > 0;
        let mut best = (f64::INFINITY, f64::NAN);
        for a in above[lo..].iter().take_while(|a| a.x <= r.position + dx) {
            let dist = (a.x - r.position).abs();
            if a.rising == rising && dist < best.0 {
                best = (dist, a.disparity);
            }
        }
        best.1
    }));
}

/// The result for one pair of lines.
#[derive(Debug, Clone, PartialEq)]
pub struct LineResult {
    /// Segmentation of the reference view's line.
    pub reference: LineFeatures,
    /// Segmentation of the other view's line.
    pub other: LineFeatures,
    /// Matches along the optimal path, in reference order (after
    /// [`crate::frame::process_frame`] in a mode with row confirmation, only
    /// the confirmed ones).
    pub matches: Vec<Match>,
    /// Gain of the optimal path (sum of its nodes' gains).
    pub path_gain: f64,
}

impl LineResult {
    /// The row's matches as the row below's inter-scanline support reads
    /// them, in reference order.
    pub fn contour_points(&self) -> impl Iterator<Item = ContourPoint> + '_ {
        self.matches.iter().map(|m| ContourPoint {
            x: m.x_ref,
            disparity: m.disparity,
            rising: self.reference.declivities[m.ref_index].amplitude > 0,
        })
    }
}

/// The columns of the other view that eq. 6 allows for each reference
/// declivity: `lo .. hi` (0-based, possibly empty) in the sorted positions
/// `others`, one pair per position of `refs` (sorted too). Both bounds are
/// non-decreasing, so one sweep finds them all.
pub fn search_bands(refs: &[f64], others: &[f64], params: &Params) -> Vec<(usize, usize)> {
    let mut padded = Vec::with_capacity(others.len() + BAND_PAD);
    padded.extend_from_slice(others);
    padded.extend([f64::INFINITY; BAND_PAD]);
    let mut bands = Vec::with_capacity(refs.len());
    search_bands_padded(refs, &padded, params, &mut bands);
    bands
}

/// `+∞` sentinels after the other view's positions in [`search_bands_padded`].
const BAND_PAD: usize = 4;

/// [`search_bands`] on `others` followed by [`BAND_PAD`] `+∞` sentinels,
/// which no bound passes in either view (their disparity is `-∞` or `+∞`):
/// each bound moves up to four steps without a branch, then loops only when
/// it moves further.
fn search_bands_padded(refs: &[f64], others: &[f64], params: &Params, bands: &mut Vec<(usize, usize)>) {
    debug_assert!(others.len() >= BAND_PAD && others[others.len() - BAND_PAD..] == [f64::INFINITY; BAND_PAD]);
    let (dispmin, dispmax) = (params.dispmin, params.dispmax);
    // Moves a bound past the columns `before` holds for. Positions are
    // sorted, so `before` holds for a run of columns from `k` on (if at all)
    // and the first steps are one sum of independent tests, not a chain:
    // the next ones are a loop, seldom taken.
    fn advance(mut k: usize, before: impl Fn(usize) -> bool) -> usize {
        k += (0..BAND_PAD).map(|t| before(k + t) as usize).sum::<usize>();
        while before(k) {
            k += 1;
        }
        k
    }
    let (mut lo, mut hi) = (0usize, 0usize);
    bands.clear();
    bands.extend(refs.iter().map(|&x_ref| {
        let d = |j: usize| pair_disparity(x_ref, others[j], params.ref_view);
        // Column j is before the band / before its end (eq. 6: dispmin < d
        // < dispmax).
        match params.ref_view {
            // d falls as x_other grows.
            RefView::Left => {
                lo = advance(lo, |j| d(j) >= dispmax);
                hi = advance(hi, |j| d(j) > dispmin);
            }
            // d grows with x_other.
            RefView::Right => {
                lo = advance(lo, |j| d(j) <= dispmin);
                hi = advance(hi, |j| d(j) < dispmax);
            }
        }
        (lo, hi.max(lo))
    }));
}

/// The graph of two lines as bands of nodes with their gains (eq. 4–8); the
/// columns outside each band are outside the search area (eq. 6).
/// With `contour`, the row above's matches and the settings of the
/// inter-scanline support, each node's gain has the contour's term
/// ([`contour_term`]) added.
#[cfg(test)]
fn banded_gains(reference: &LineFeatures, other: &LineFeatures, params: &Params, contour: Option<(&[ContourPoint], ContourSupport)>) -> BandedGains {
    let refs: Vec<f64> = reference.declivities.iter().map(|d| d.position).collect();
    let others: Vec<f64> = other.declivities.iter().map(|d| d.position).collect();
    let g = gmax(reference.dt, other.dt);
    let spans = search_bands(&refs, &others, params);
    let cells = spans.iter().map(|(lo, hi)| hi - lo).sum();
    let mut bands = BandedGains::with_capacity(others.len(), refs.len(), cells);
    let mut dc = Vec::new();
    if let Some((above, support)) = contour {
        contour_disparities(&reference.declivities, above, support.dx, &mut dc);
    }
    for (i, (r, &(lo, hi))) in reference.declivities.iter().zip(&spans).enumerate() {
        bands.push_row(
            lo,
            other.declivities[lo..hi].iter().map(|o| {
                let gain = node_gain(r, o, g, (params.dispmin, params.dispmax), params.ref_view, params.mode);
                match contour {
                    None => gain,
                    Some((_, support)) => {
                        let d = pair_disparity(r.position, o.position, params.ref_view);
                        gain.map(|v| v + contour_term(d, dc[i], support.dd, support.weight * g))
                    }
                }
            }),
        );
    }
    bands
}

/// The dense gain table of two lines (for pictures of the graph and tests).
pub fn gain_table(reference: &LineFeatures, other: &LineFeatures, params: &Params) -> GainTable {
    let g = gmax(reference.dt, other.dt);
    GainTable::from_fn(reference.declivities.len(), other.declivities.len(), |i, j| {
        node_gain(
            &reference.declivities[i],
            &other.declivities[j],
            g,
            (params.dispmin, params.dispmax),
            params.ref_view,
            params.mode,
        )
    })
}

/// Matches two segmented lines: the optimal path (eq. 9) through the nodes
/// of the search area (eq. 6) with their gains (eq. 4–8), and the disparity
/// of each matched reference declivity. Returns the matches in reference
/// order and the path's gain. (The same as [`banded_dp`] on
/// [`banded_gains`], with the gains computed as the DP sweeps them.)
#[cfg(test)]
fn match_lines(reference: &LineFeatures, other: &LineFeatures, params: &Params) -> (Vec<Match>, f64) {
    match_lines_in(&mut LineBuffers::default(), reference, other, params, None)
}

/// [`match_lines`] with the working vectors of `buffers`; with `contour`,
/// the row above's matches and the settings of the inter-scanline support,
/// each node's gain has the contour's term ([`contour_term`]) added, and
/// so has each match's.
fn match_lines_in(
    buffers: &mut LineBuffers,
    reference: &LineFeatures,
    other: &LineFeatures,
    params: &Params,
    contour: Option<(&[ContourPoint], ContourSupport)>,
) -> (Vec<Match>, f64) {
    let LineBuffers { refs, others, bands, neighbours, contour: dc, dp, .. } = buffers;
    refs.clear();
    refs.extend(reference.declivities.iter().map(|d| d.position));
    others.clear();
    others.extend(other.declivities.iter().map(|d| d.position));
    others.extend([f64::INFINITY; BAND_PAD]);
    search_bands_padded(refs, others, params, bands);
    others.truncate(others.len() - BAND_PAD);
    let rule = LineGain::new(reference.dt, other.dt, params.mode);
    // The reference declivities' neighbours, then the other view's.
    neighbours.clear();
    neighbours.extend(reference.declivities.iter().chain(&other.declivities).map(|d| rule.neighbours(d)));
    let (rn, on) = neighbours.split_at(refs.len());
    // The contour's term of node (i, j): none without a contour (and the
    // DP's loop then as without the feature), or the term of `contour_term`.
    let ref_view = params.ref_view;
    let (dd, bonus) = match contour {
        None => {
            dc.clear();
            dc.resize(refs.len(), f64::NAN);
            (0.0, 0.0)
        }
        Some((above, support)) => {
            contour_disparities(&reference.declivities, above, support.dx, dc);
            (support.dd, support.weight * gmax(reference.dt, other.dt))
        }
    };
    let term = |i: usize, j: usize| contour_term(pair_disparity(refs[i], others[j], ref_view), dc[i], dd, bonus);
    let path_gain = match contour {
        None => banded_dp_in(dp, others.len(), bands, |i, j| rule.gain(&rn[i], &on[j])),
        Some(_) => banded_dp_in(dp, others.len(), bands, |i, j| rule.gain(&rn[i], &on[j]) + term(i, j)),
    };
    let matches = dp
        .nodes
        .iter()
        .map(|&(i, j)| Match {
            ref_index: i,
            other_index: j,
            x_ref: refs[i],
            x_other: others[j],
            disparity: pair_disparity(refs[i], others[j], params.ref_view),
            gain: rule.gain(&rn[i], &on[j]) + term(i, j),
            edge: false,
        })
        .collect();
    (matches, path_gain)
}

/// One pair of epipolar lines (same row of the left and right image) through
/// segmentation and matching, with the reference view of `params`.
/// Without the row above, the mode's inter-scanline support
/// ([`crate::Features::contour`]) has nothing to add.
pub fn process_line(left: &[u8], right: &[u8], params: &Params) -> LineResult {
    process_line_in(&mut LineBuffers::default(), left, right, params, None)
}

/// [`process_line`] with the working vectors of `buffers`, and with
/// `contour`, the row above's matches and the settings of the
/// inter-scanline support ([`match_lines_in`]).
pub(crate) fn process_line_in(
    buffers: &mut LineBuffers,
    left: &[u8],
    right: &[u8],
    params: &Params,
    contour: Option<(&[ContourPoint], ContourSupport)>,
) -> LineResult {
    let mut features = |line: &[u8]| match params.hardware {
        None => line_features_in(buffers, line),
        Some(_) => line_features_with(line, params.hardware),
    };
    let (l, r) = (features(left), features(right));
    let (reference, other) = match params.ref_view {
        RefView::Left => (l, r),
        RefView::Right => (r, l),
    };
    let (matches, path_gain) = match_lines_in(buffers, &reference, &other, params, contour);
    LineResult { reference, other, matches, path_gain }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gain::in_search_area;

    #[test]
    fn search_bands_are_exactly_the_columns_inside_the_search_area() {
        let mut rng = crate::test_rng::TestRng::new(0x0bad_5eed_1234_5678u64);
        let mut next = move || rng.next();
        for case in 0..4000 {
            let mut sorted = |len: u64| {
                let mut v: Vec<f64> = (0..next() % len).map(|_| (next() % 4000) as f64 / 8.0).collect();
                v.sort_by(f64::total_cmp);
                v.dedup();
                v
            };
            let (refs, others) = (sorted(40), sorted(40));
            let dispmax = 1.0 + (next() % 400) as f64 / 4.0;
            // The paper's 0 in half the cases, a lower bound in the others.
            let dispmin = if case % 2 == 0 { 0.0 } else { (next() % 400) as f64 / 4.0 * ((dispmax - 1.0).max(0.0) / 100.0) };
            for ref_view in [RefView::Left, RefView::Right] {
                let params = Params { dispmax, dispmin, ref_view, ..Params::paper(2.0).unwrap() };
                let bands = search_bands(&refs, &others, &params);
                assert_eq!(bands.len(), refs.len());
                assert!(bands.windows(2).all(|w| w[0].0 <= w[1].0 && w[0].1 <= w[1].1), "case {case}: bands move right");
                for (i, &(lo, hi)) in bands.iter().enumerate() {
                    let inside: Vec<usize> = (0..others.len())
                        .filter(|&j| in_search_area(pair_disparity(refs[i], others[j], ref_view), dispmin, dispmax))
                        .collect();
                    let want = inside.first().map_or((lo, lo), |&f| (f, inside.last().unwrap() + 1));
                    assert_eq!(inside.len(), want.1 - want.0, "case {case}: the area is contiguous");
                    assert_eq!((lo, hi), want, "case {case}, row {i}, {ref_view:?}, dispmin {dispmin}, dispmax {dispmax}");
                }
            }
        }
    }
}

#[cfg(test)]
mod reference_tests {
    use super::*;
    use crate::dp::banded_dp;
    use crate::params::Mode;

    /// A line of random steps (`w` px) and the same line shifted left by
    /// 1–12 px with a little noise added.
    fn random_pair(rng: &mut crate::test_rng::TestRng) -> (Vec<u8>, Vec<u8>) {
        let w = 40 + (rng.next() % 200) as usize;
        let mut level = 128i32;
        let left: Vec<u8> = (0..w)
            .map(|_| {
                level = (level + (rng.next() % 61) as i32 - 30).clamp(0, 255);
                level as u8
            })
            .collect();
        let shift = 1 + (rng.next() % 12) as usize;
        let right: Vec<u8> = (0..w).map(|x| left[(x + shift).min(w - 1)].saturating_add((rng.next() % 9) as u8)).collect();
        (left, right)
    }

    /// A row above for `reference`: most declivities continued within
    /// 1.5 px, with the true disparity or another, of either polarity.
    fn random_row_above(rng: &mut crate::test_rng::TestRng, reference: &LineFeatures) -> Vec<ContourPoint> {
        let mut above: Vec<ContourPoint> = reference
            .declivities
            .iter()
            .filter_map(|d| {
                (rng.next() % 4 != 0).then(|| ContourPoint {
                    x: d.position + (rng.next() % 13) as f64 / 4.0 - 1.5,
                    disparity: (1 + rng.next() % 14) as f64 + (rng.next() % 4) as f64 / 4.0,
                    rising: (d.amplitude > 0) != (rng.next() % 5 == 0),
                })
            })
            .collect();
        above.sort_by(|a, b| a.x.total_cmp(&b.x));
        above
    }

    #[test]
    fn match_lines_takes_the_path_of_the_dp_on_the_readable_gains_in_every_mode() {
        // match_lines computes gains with the integer `LineGain` as the DP
        // sweeps them; `banded_gains` computes them with the per-equation
        // `node_gain`. Both must give the same path, gain for gain.
        let mut rng = crate::test_rng::TestRng::new(0x5a5a_1234_0f0f_9876);
        let mut matched = 0;
        for case in 0..300 {
            let (left, right) = random_pair(&mut rng);
            for mode in Mode::ALL {
                for ref_view in [RefView::Left, RefView::Right] {
                    let params = Params { ref_view, ..Params::with_mode(mode, 20.0).unwrap() };
                    let (lr, rr) = (line_features(&left), line_features(&right));
                    let (reference, other) = if ref_view == RefView::Left { (lr, rr) } else { (rr, lr) };
                    let (matches, gain) = match_lines(&reference, &other, &params);
                    let path = banded_dp(&banded_gains(&reference, &other, &params, None));
                    let nodes: Vec<(usize, usize)> = matches.iter().map(|m| (m.ref_index, m.other_index)).collect();
                    assert_eq!(nodes, path.nodes, "case {case}, {mode:?}, {ref_view:?}");
                    assert_eq!(gain, path.gain, "case {case}, {mode:?}, {ref_view:?}");
                    matched += matches.len();
                }
            }
        }
        assert!(matched > 1000, "the lines match: {matched}");
    }

    #[test]
    fn match_lines_with_a_row_above_takes_the_path_of_the_dp_on_the_readable_gains_and_contour_terms() {
        // As above, with inter-scanline support: the fast path (the term
        // added as the DP sweeps) against `banded_gains` with the term of
        // `contour_term` added to `node_gain`'s.
        let mut rng = crate::test_rng::TestRng::new(0x0c07_0a12_5eed_0036);
        let (mut changed, mut matched) = (0, 0);
        for case in 0..300 {
            let (left, right) = random_pair(&mut rng);
            for ref_view in [RefView::Left, RefView::Right] {
                let params = Params { ref_view, ..Params::with_mode(Mode::Contour, 20.0).unwrap() };
                let support = params.mode.features().contour.expect("the contour mode has inter-scanline support");
                let (lr, rr) = (line_features(&left), line_features(&right));
                let (reference, other) = if ref_view == RefView::Left { (lr, rr) } else { (rr, lr) };
                let above = random_row_above(&mut rng, &reference);
                let mut buffers = LineBuffers::default();
                let (matches, gain) = match_lines_in(&mut buffers, &reference, &other, &params, Some((&above, support)));
                let path = banded_dp(&banded_gains(&reference, &other, &params, Some((&above, support))));
                let nodes: Vec<(usize, usize)> = matches.iter().map(|m| (m.ref_index, m.other_index)).collect();
                assert_eq!(nodes, path.nodes, "case {case}, {ref_view:?}");
                assert_eq!(gain, path.gain, "case {case}, {ref_view:?}");
                let sum: f64 = matches.iter().map(|m| m.gain).sum();
                assert!((sum - gain).abs() <= 1e-9 * gain.abs().max(1.0), "case {case}: the matches' gains add up to the path's");
                changed += (matches != match_lines(&reference, &other, &params).0) as usize;
                matched += matches.len();
            }
        }
        assert!(matched > 1000, "the lines match: {matched}");
        assert!(changed > 30, "the row above changes paths: {changed} of 600");
    }

    #[test]
    fn inter_scanline_support_of_weight_zero_changes_nothing() {
        // The feature off (no row above, or a bonus of 0) is the robust
        // mode: the same matches, gains and path gain.
        let mut rng = crate::test_rng::TestRng::new(0x0c07_0a12_5eed_0000);
        for case in 0..300 {
            let (left, right) = random_pair(&mut rng);
            let robust = Params::with_mode(Mode::Robust, 20.0).unwrap();
            let contour = Params { mode: Mode::Contour, ..robust };
            let (reference, other) = (line_features(&left), line_features(&right));
            let above = random_row_above(&mut rng, &reference);
            let want = match_lines(&reference, &other, &robust);
            let zero = ContourSupport { weight: 0.0, ..contour.mode.features().contour.unwrap() };
            let got = match_lines_in(&mut LineBuffers::default(), &reference, &other, &contour, Some((&above, zero)));
            assert_eq!(got, want, "case {case}: weight 0");
            assert_eq!(match_lines(&reference, &other, &contour), want, "case {case}: no row above");
            assert_eq!(process_line(&left, &right, &contour), process_line(&left, &right, &robust), "case {case}");
        }
    }

    #[test]
    fn a_declivity_continues_the_nearest_match_of_its_polarity_within_dx() {
        let decl = |position: f64, amplitude: i32| Declivity { start: 0, end: 1, amplitude, position, left: [0; 3], right: [0; 3] };
        let point = |x: f64, disparity: f64, rising: bool| ContourPoint { x, disparity, rising };
        let refs = [decl(10.0, 20), decl(20.0, -20), decl(30.0, 20), decl(40.0, 20), decl(50.0, -20)];
        let above = [
            // 10: the nearer of two rising matches within 1 px.
            point(9.0, 7.0, true),
            point(10.5, 6.0, true),
            // 20: a rising match only, the wrong polarity.
            point(20.2, 5.0, true),
            // 30: exactly 1 px away (included); 40: 1.25 px (not).
            point(31.0, 4.0, true),
            point(38.75, 3.0, true),
            // 50: two falling matches equally near, the left one.
            point(49.5, 2.0, false),
            point(50.5, 1.0, false),
        ];
        let mut out = Vec::new();
        contour_disparities(&refs, &above, 1.0, &mut out);
        let got: Vec<Option<f64>> = out.iter().map(|&d| (!d.is_nan()).then_some(d)).collect();
        assert_eq!(got, vec![Some(6.0), None, Some(4.0), None, Some(2.0)]);
        contour_disparities(&refs, &[], 1.0, &mut out);
        assert!(out.len() == refs.len() && out.iter().all(|d| d.is_nan()), "no row above, no contour");
    }
}
