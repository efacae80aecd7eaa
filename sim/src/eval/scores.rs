//! Evaluation against ground truth, Middlebury style (definitions in
//! `data/stereo/README.md`).
//!
//! - Evaluation set E: pixels with valid ground truth (and, for the
//!   `nonocc` region, `nonocc.png > 127`). A pixel is bad when
//!   `|d - gt| > t` (strict).
//! - `bad1`, `bad2`: % of E bad at t = 1, 2 px, pixels without an output
//!   disparity counted as bad; `bad1v`, `bad2v`: over E ∩ {output}.
//! - `density`: % of all pixels that received a disparity.
//! - `sparse_acc1`: % of matched reference declivities, at pixels of E
//!   (rounded position), whose disparity is within 1 px of the ground truth:
//!   the paper's "more than 98 % of declivities correctly matched".

use std::time::Instant;

use golden::{process_frame, Declivity, FrameResult, LineResult, Params, RefView, Threads};
use serde::Serialize;

use crate::error::SimError;
use crate::eval::io::PairData;

/// Dense scores of a disparity map on one region.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DenseScores {
    /// % of E with no output or `|d - gt| > 1`.
    pub bad1: f64,
    /// % of E with no output or `|d - gt| > 2`.
    pub bad2: f64,
    /// % of E ∩ output with `|d - gt| > 1`.
    pub bad1v: f64,
    /// % of E ∩ output with `|d - gt| > 2`.
    pub bad2v: f64,
    /// % of all pixels with an output.
    pub density: f64,
    /// |E|.
    pub n_eval: usize,
}

fn pct(num: usize, den: usize) -> f64 {
    100.0 * num as f64 / den.max(1) as f64
}

/// A ground-truth value that counts: known (`> 0`) and finite.
fn is_truth(g: f64) -> bool {
    g > 0.0 && g.is_finite()
}

/// Dense scores of `disp` (0 = none) against `gt` (0 = unknown) over the
/// pixels where `mask` holds (all pixels without a mask).
pub fn dense_scores(disp: &[f64], gt: &[f64], mask: Option<&[bool]>) -> DenseScores {
    let (mut n_eval, mut n_valid, mut miss, mut b1, mut b2, mut b1v, mut b2v) = (0, 0, 0, 0, 0, 0, 0);
    for (k, (&d, &g)) in disp.iter().zip(gt).enumerate() {
        if !is_truth(g) || mask.is_some_and(|m| !m[k]) {
            continue;
        }
        n_eval += 1;
        if d <= 0.0 {
            miss += 1;
            continue;
        }
        n_valid += 1;
        let err = (d - g).abs();
        if err > 1.0 {
            b1v += 1;
        }
        if err > 2.0 {
            b2v += 1;
        }
    }
    b1 += miss + b1v;
    b2 += miss + b2v;
    let with_output = disp.iter().filter(|&&d| d > 0.0).count();
    DenseScores {
        bad1: pct(b1, n_eval),
        bad2: pct(b2, n_eval),
        bad1v: pct(b1v, n_valid),
        bad2v: pct(b2v, n_valid),
        density: pct(with_output, disp.len()),
        n_eval,
    }
}

/// The share of `rtl`'s pixels within a quarter pixel of `golden`'s (both
/// row-major px maps of one size).
pub fn agree_quarter_px(rtl: &[f64], golden: &[f64]) -> f64 {
    let close = rtl.iter().zip(golden).filter(|(a, b)| (*a - *b).abs() <= 0.25).count();
    close as f64 / rtl.len().max(1) as f64
}

/// The share of `rtl`'s pixels exactly equal to `golden`'s (both row-major
/// maps of one size: disparities in px, exact multiples of
/// `1/2^POS_FRAC_BITS` on both sides, or depths in mm).
pub fn exact_share<T: PartialEq>(rtl: &[T], golden: &[T]) -> f64 {
    let equal = rtl.iter().zip(golden).filter(|(a, b)| a == b).count();
    equal as f64 / rtl.len().max(1) as f64
}

/// Sparse accuracy: `(correct, evaluated)` matched reference declivities at
/// valid-GT pixels (position rounded to the nearest pixel), correct when
/// `|d - gt| ≤ 1`.
pub fn sparse_counts(frame: &FrameResult, gt: &[f64]) -> (usize, usize) {
    let w = frame.width;
    let (mut ok, mut n) = (0, 0);
    for (y, line) in frame.lines.iter().enumerate() {
        for m in line.matches.iter().filter(|m| !m.edge) {
            let Some(g) = truth_at(gt, w, y, m.x_ref) else { continue };
            n += 1;
            if (m.disparity - g).abs() <= 1.0 {
                ok += 1;
            }
        }
    }
    (ok, n)
}

/// One pair's evaluation: the `eval --json` object.
#[derive(Debug, Clone, Serialize)]
pub struct EvalReport {
    /// Pair folder name.
    pub pair: String,
    /// Matching mode.
    pub mode: &'static str,
    /// Reference view.
    pub ref_view: &'static str,
    /// Image width.
    pub width: usize,
    /// Image height.
    pub height: usize,
    /// Search bound used (eq. 6): the pair's `dispmax + 1`.
    pub search_bound: f64,
    /// Characteristic declivities of the reference view.
    pub declivities: usize,
    /// Matched reference declivities (reported; depth-edge matches apart).
    pub matches: usize,
    /// Matches flagged as lying next to a depth edge (anchors of the
    /// interpolation, not reported).
    pub edge_matches: usize,
    /// `matches / declivities`.
    pub match_frac: f64,
    /// % of matched reference declivities at valid-GT pixels within 1 px;
    /// `None` (JSON `null`) when no match lies at such a pixel (undefined).
    pub sparse_acc1: Option<f64>,
    /// Matched declivities at valid-GT pixels (the denominator of `sparse_acc1`).
    pub sparse_n: usize,
    /// Dense scores, all pixels with ground truth.
    pub bad1: f64,
    pub bad2: f64,
    pub bad1v: f64,
    pub bad2v: f64,
    pub density: f64,
    /// `bad2` on `nonocc.png > 127`; `null` without a mask.
    pub nonocc_bad2: Option<f64>,
    /// Golden time per frame, one thread, image loading excluded, median of
    /// `runs` runs (ms).
    pub ms: f64,
    /// Timed runs.
    pub runs: usize,
}

/// The ground truth for the reference view, or an error when the folder has
/// none for it.
pub(crate) fn reference_gt(pair: &PairData, ref_view: RefView) -> Result<&[f64], SimError> {
    match ref_view {
        RefView::Left => Ok(&pair.gt_left),
        RefView::Right => pair.gt_right.as_deref().ok_or_else(|| SimError::PairDir {
            path: pair.dir.clone(),
            msg: "has no disp_gt_right.* for --ref-view right".into(),
        }),
    }
}

/// Median of the times (ms) of `runs ≥ 1` single-thread frames, and the
/// frame's result.
fn timed_frame(pair: &PairData, params: &Params, runs: usize) -> Result<(FrameResult, f64), SimError> {
    let mut times = Vec::with_capacity(runs.max(1));
    let mut result = None;
    // One warm-up run, as the OpenCV baseline does.
    process_frame(&pair.left, &pair.right, params, Threads::One)?;
    for _ in 0..runs.max(1) {
        let t0 = Instant::now();
        let r = process_frame(&pair.left, &pair.right, params, Threads::One)?;
        times.push(t0.elapsed().as_secs_f64() * 1e3);
        result = Some(r);
    }
    times.sort_by(f64::total_cmp);
    let ms = times[times.len() / 2];
    Ok((result.expect("at least one run"), ms))
}

/// Runs golden on a pair with the search bound `dispmax + 1` and scores it.
/// `params.dispmax` is replaced by the pair's bound.
pub fn evaluate_pair(pair: &PairData, params: &Params, runs: usize) -> Result<(EvalReport, FrameResult), SimError> {
    let params = Params { dispmax: pair.dispmax + 1.0, ..*params };
    params.validate().map_err(|e| SimError::PairDir { path: pair.dir.clone(), msg: e.to_string() })?;
    let gt = reference_gt(pair, params.ref_view)?;
    let (frame, ms) = timed_frame(pair, &params, runs)?;
    let all = dense_scores(&frame.disparity, gt, None);
    let nonocc_bad2 = match (&pair.nonocc, params.ref_view) {
        (Some(mask), RefView::Left) => Some(dense_scores(&frame.disparity, gt, Some(mask)).bad2),
        _ => None,
    };
    let (ok, n) = sparse_counts(&frame, gt);
    let declivities = frame.reference_declivities();
    let matches = frame.matches();
    let report = EvalReport {
        pair: pair.name.clone(),
        mode: params.mode.name(),
        ref_view: match params.ref_view {
            RefView::Left => "left",
            RefView::Right => "right",
        },
        width: frame.width,
        height: frame.height,
        search_bound: params.dispmax,
        declivities,
        matches,
        edge_matches: frame.edge_matches(),
        match_frac: matches as f64 / declivities.max(1) as f64,
        sparse_acc1: (n > 0).then(|| pct(ok, n)),
        sparse_n: n,
        bad1: all.bad1,
        bad2: all.bad2,
        bad1v: all.bad1v,
        bad2v: all.bad2v,
        density: all.density,
        nonocc_bad2,
        ms,
        runs: runs.max(1),
    };
    Ok((report, frame))
}

/// The reports as a Markdown table (what `eval` prints without `--json`).
pub fn markdown_table(reports: &[EvalReport]) -> String {
    let mut s = String::from(
        "| pair | mode | size | declivities | matches | match_frac | sparse_acc1 | bad1 | bad2 | bad2v | density | nonocc bad2 | ms |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let or_dash = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.1}"));
    for r in reports {
        s += &format!(
            "| {} | {} | {}x{} | {} | {} | {:.3} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {} | {:.2} |\n",
            r.pair,
            r.mode,
            r.width,
            r.height,
            r.declivities,
            r.matches,
            r.match_frac,
            or_dash(r.sparse_acc1),
            r.bad1,
            r.bad2,
            r.bad2v,
            r.density,
            or_dash(r.nonocc_bad2),
            r.ms
        );
    }
    if reports.len() > 1 {
        let n = reports.len() as f64;
        let mean = |f: fn(&EvalReport) -> f64| reports.iter().map(f).sum::<f64>() / n;
        // sparse_acc1 over the pairs where it is defined.
        let defined: Vec<f64> = reports.iter().filter_map(|r| r.sparse_acc1).collect();
        let sparse_mean = (!defined.is_empty()).then(|| defined.iter().sum::<f64>() / defined.len() as f64);
        s += &format!(
            "| mean | | | | | {:.3} | {} | {:.1} | {:.1} | {:.1} | {:.1} | | {:.2} |\n",
            mean(|r| r.match_frac),
            or_dash(sparse_mean),
            mean(|r| r.bad1),
            mean(|r| r.bad2),
            mean(|r| r.bad2v),
            mean(|r| r.density),
            mean(|r| r.ms)
        );
    }
    s
}

/// Why the matcher fails where it fails: counts that separate the causes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Diagnosis {
    /// % of reference rows with characteristic declivities but no match.
    pub rows_without_match: f64,
    /// % of reference declivities at valid-GT pixels that have a *true
    /// partner*: an other-view declivity of the same polarity within 1 px of
    /// where the ground truth puts it.
    pub with_partner: f64,
    /// Of the declivities with a true partner, % whose node passes both
    /// photometric tests (`lpd < gmax` and `rpd < gmax`, eq. 7), with the
    /// distances of the frame's mode (offset-compensated in the modes that
    /// match so).
    pub partner_both_sides: f64,
    /// … % that pass exactly one side (gain ≤ 0 in paper mode: never matched).
    pub partner_one_side: f64,
    /// … % rejected on both sides.
    pub partner_rejected: f64,
    /// … % matched to that partner.
    pub partner_matched: f64,
    /// Mean |mean grey level difference| of the six neighbours of true
    /// partners (a brightness offset between the cameras shows here).
    pub partner_level_offset: f64,
    /// Median over rows of `max(d_t,L, d_t,R) / min(…)`: how differently the
    /// two views of one row are thresholded.
    pub dt_ratio_median: f64,
    /// % of bad2 pixels lying between two correct matches: interpolation
    /// bridging a depth discontinuity, not a wrong match.
    pub bad2_between_correct: f64,
    /// `sparse_acc1` when a match also counts as right if the ground truth of
    /// any pixel within 1.5 px of its sub-pixel position agrees within 1 px: the
    /// gap to `sparse_acc1` is the matches that sit on a depth edge, where the
    /// rounded position falls on the other side of the edge.
    pub sparse_acc1_edge_tolerant: f64,
}

/// What became of one reference declivity, judged against the ground truth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Fate {
    /// No valid ground truth at its (rounded) position.
    NoTruth,
    /// Matched, within 1 px of the ground truth.
    Correct,
    /// Matched, more than 1 px off.
    Wrong,
    /// Matched but flagged as lying next to a depth edge (not reported).
    Edge,
    /// Unmatched although it has a true partner (an other-view declivity of
    /// the same polarity within 1 px of where the ground truth puts it).
    Missed,
    /// Unmatched, and no true partner exists (occluded, or not detected in
    /// the other view).
    NoPartner,
}

/// Ground truth at a sub-pixel position of row `y`, if valid.
fn truth_at(gt: &[f64], w: usize, y: usize, x: f64) -> Option<f64> {
    let xr = x.round();
    (xr >= 0.0 && xr < w as f64).then(|| gt[y * w + xr as usize]).filter(|&g| is_truth(g))
}

/// The true partner of reference declivity `rd` with ground truth `d`: the
/// other-view declivity of the same polarity nearest to where `d` puts it,
/// if within 1 px.
fn true_partner<'a>(line: &'a LineResult, rd: &Declivity, d: f64, ref_view: RefView) -> Option<(usize, &'a Declivity)> {
    let target = match ref_view {
        RefView::Left => rd.position - d,
        RefView::Right => rd.position + d,
    };
    line.other
        .declivities
        .iter()
        .enumerate()
        .filter(|(_, od)| od.polarity() == rd.polarity())
        .min_by(|a, b| (a.1.position - target).abs().total_cmp(&(b.1.position - target).abs()))
        .filter(|(_, od)| (od.position - target).abs() <= 1.0)
}

/// The fate of every reference declivity of row `y`, in order.
fn fates(frame: &FrameResult, gt: &[f64], y: usize) -> Vec<Fate> {
    let line = &frame.lines[y];
    let mut matched = vec![None; line.reference.declivities.len()];
    for m in &line.matches {
        matched[m.ref_index] = Some((m.disparity, m.edge));
    }
    line.reference
        .declivities
        .iter()
        .zip(matched)
        .map(|(rd, m)| match (truth_at(gt, frame.width, y, rd.position), m) {
            (None, _) => Fate::NoTruth,
            (Some(_), Some((_, true))) => Fate::Edge,
            (Some(g), Some((d, false))) if (d - g).abs() <= 1.0 => Fate::Correct,
            (Some(_), Some(_)) => Fate::Wrong,
            (Some(g), None) if true_partner(line, rd, g, frame.params.ref_view).is_some() => Fate::Missed,
            (Some(_), None) => Fate::NoPartner,
        })
        .collect()
}

/// Counts the causes of failure of `frame` against the reference view's
/// ground truth `gt` (see [`Diagnosis`]).
pub(crate) fn diagnose(frame: &FrameResult, gt: &[f64]) -> Diagnosis {
    use golden::gain::{gmax, photometric_distances};
    let w = frame.width;
    let (mut rows_with, mut rows_none) = (0usize, 0usize);
    let (mut n_ref, mut partners, mut both, mut one, mut matched) = (0usize, 0usize, 0usize, 0usize, 0usize);
    let mut offset_sum = 0.0;
    let mut ratios = Vec::with_capacity(frame.height);
    let (mut bad, mut bad_between) = (0usize, 0usize);
    let (mut tolerant_ok, mut evaluated) = (0usize, 0usize);
    for (y, line) in frame.lines.iter().enumerate() {
        for m in line.matches.iter().filter(|m| !m.edge) {
            if truth_at(gt, w, y, m.x_ref).is_none() {
                continue;
            }
            evaluated += 1;
            let near = ((m.x_ref - 1.5).ceil().max(0.0) as usize)..=((m.x_ref + 1.5).floor().max(0.0) as usize).min(w - 1);
            tolerant_ok += near.into_iter().any(|x| {
                let g = gt[y * w + x];
                is_truth(g) && (m.disparity - g).abs() <= 1.0
            }) as usize;
        }
        let (r, o) = (&line.reference, &line.other);
        if !r.declivities.is_empty() {
            rows_with += 1;
            rows_none += line.matches.is_empty() as usize;
        }
        ratios.push(r.dt.max(o.dt) / r.dt.min(o.dt));
        let g = gmax(r.dt, o.dt);
        for (i, rd) in r.declivities.iter().enumerate() {
            let Some(d) = truth_at(gt, w, y, rd.position) else { continue };
            n_ref += 1;
            let Some((j, od)) = true_partner(line, rd, d, frame.params.ref_view) else { continue };
            partners += 1;
            // The mode's distances (eq. 4–5, or their offset-compensated
            // form); a partner has the declivity's polarity, so they exist.
            let Some((l, rr)) = photometric_distances(rd, od, frame.params.mode) else { continue };
            both += (l < g && rr < g) as usize;
            one += ((l < g) != (rr < g)) as usize;
            matched += line.matches.iter().any(|m| m.ref_index == i && m.other_index == j) as usize;
            let mean = |dcl: &Declivity| dcl.left.iter().chain(&dcl.right).map(|&v| v as f64).sum::<f64>() / 6.0;
            offset_sum += (mean(rd) - mean(od)).abs();
        }
        // Bad pixels between two correct matches.
        let anchors: Vec<(f64, bool)> = line
            .matches
            .iter()
            .map(|m| (m.x_ref, truth_at(gt, w, y, m.x_ref).is_some_and(|g| (m.disparity - g).abs() <= 1.0)))
            .collect();
        for x in 0..w {
            let gv = gt[y * w + x];
            if !is_truth(gv) {
                continue;
            }
            let dv = frame.disparity[y * w + x];
            if dv > 0.0 && (dv - gv).abs() <= 2.0 {
                continue;
            }
            bad += 1;
            let k = anchors.partition_point(|a| a.0 <= x as f64);
            bad_between += (k > 0 && anchors[k - 1].1 && k < anchors.len() && anchors[k].1) as usize;
        }
    }
    ratios.sort_by(f64::total_cmp);
    Diagnosis {
        rows_without_match: pct(rows_none, rows_with),
        with_partner: pct(partners, n_ref),
        partner_both_sides: pct(both, partners),
        partner_one_side: pct(one, partners),
        partner_rejected: pct(partners - both - one, partners),
        partner_matched: pct(matched, partners),
        partner_level_offset: offset_sum / partners.max(1) as f64,
        dt_ratio_median: ratios.get(ratios.len() / 2).copied().unwrap_or(1.0),
        bad2_between_correct: pct(bad_between, bad),
        sparse_acc1_edge_tolerant: pct(tolerant_ok, evaluated),
    }
}

/// Colours of [`error_picture`].
mod colours {
    /// No ground truth.
    pub(super) const NO_TRUTH: [u8; 3] = [40, 40, 40];
    /// Ground truth but no disparity.
    pub(super) const NO_OUTPUT: [u8; 3] = [20, 40, 150];
    /// `|d - gt| ≤ 1`.
    pub(super) const GOOD: [u8; 3] = [30, 130, 50];
    /// `1 < |d - gt| ≤ 2`.
    pub(super) const NEAR: [u8; 3] = [190, 170, 40];
    /// `|d - gt| > 2`.
    pub(super) const BAD: [u8; 3] = [200, 30, 30];
    /// A matched declivity within 1 px.
    pub(super) const DECL_CORRECT: [u8; 3] = [255, 255, 255];
    /// A matched declivity more than 1 px off.
    pub(super) const DECL_WRONG: [u8; 3] = [255, 0, 255];
    /// An unmatched declivity that has a true partner.
    pub(super) const DECL_MISSED: [u8; 3] = [0, 255, 255];
    /// A match flagged as lying next to a depth edge.
    pub(super) const DECL_EDGE: [u8; 3] = [255, 150, 0];
}

/// Where the method fails, in one picture: every pixel coloured by its
/// dense error (grey: no ground truth, blue: no disparity, green ≤ 1 px,
/// yellow ≤ 2 px, red > 2 px), and every reference declivity with ground
/// truth marked at its rounded position: white when matched correctly,
/// magenta when matched wrongly, orange when its match is flagged as lying
/// next to a depth edge, cyan when unmatched although its true partner exists (the photometric test of eq. 7 rejected it, or the path
/// went elsewhere). Unmatched declivities without a partner are not marked.
pub(crate) fn error_picture(frame: &FrameResult, gt: &[f64]) -> image::RgbImage {
    let w = frame.width;
    let mut img = image::RgbImage::from_fn(w as u32, frame.height as u32, |x, y| {
        let k = y as usize * w + x as usize;
        let (g, d) = (gt[k], frame.disparity[k]);
        image::Rgb(if !is_truth(g) {
            colours::NO_TRUTH
        } else if d <= 0.0 {
            colours::NO_OUTPUT
        } else if (d - g).abs() <= 1.0 {
            colours::GOOD
        } else if (d - g).abs() <= 2.0 {
            colours::NEAR
        } else {
            colours::BAD
        })
    });
    for y in 0..frame.height {
        let decls = &frame.lines[y].reference.declivities;
        for (rd, fate) in decls.iter().zip(fates(frame, gt, y)) {
            let colour = match fate {
                Fate::Correct => colours::DECL_CORRECT,
                Fate::Wrong => colours::DECL_WRONG,
                Fate::Missed => colours::DECL_MISSED,
                Fate::Edge => colours::DECL_EDGE,
                Fate::NoTruth | Fate::NoPartner => continue,
            };
            let x = rd.position.round().clamp(0.0, (w - 1) as f64) as u32;
            img.put_pixel(x, y as u32, image::Rgb(colour));
        }
    }
    img
}

/// The diagnoses as a Markdown table.
pub fn diagnosis_table(rows: &[(String, Diagnosis)]) -> String {
    let mut s = String::from(
        "| pair | rows without match % | declivities with a true partner % | … passing both sides % | … one side % | … rejected % | … matched to it % | partner level offset | median d_t ratio L/R | bad2 px between two correct matches % | sparse_acc1 edge-tolerant |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for (name, d) in rows {
        s += &format!(
            "| {name} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.1} | {:.1} |\n",
            d.rows_without_match,
            d.with_partner,
            d.partner_both_sides,
            d.partner_one_side,
            d.partner_rejected,
            d.partner_matched,
            d.partner_level_offset,
            d.dt_ratio_median,
            d.bad2_between_correct,
            d.sparse_acc1_edge_tolerant
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use golden::GreyImage;

    #[test]
    fn dense_scores_on_a_hand_case() {
        // 6 pixels; gt 0 = unknown at k = 5. Output 0 = none at k = 1.
        // k:     0    1    2    3    4    5
        // gt:   10   10   10   10   10    0
        // d:    10    0   11.5 12.5 13    9
        // E = {0..4} (5 px). Errors: 0, none, 1.5, 2.5, 3.
        // bad1: none + 1.5 + 2.5 + 3 -> 4/5 = 80 %; bad2: none + 2.5 + 3 -> 60 %.
        // With output: {0,2,3,4}: bad1v 3/4 = 75 %, bad2v 2/4 = 50 %.
        // density: 5 of 6 pixels have output -> 83.33 %.
        let s = dense_scores(&[10.0, 0.0, 11.5, 12.5, 13.0, 9.0], &[10.0, 10.0, 10.0, 10.0, 10.0, 0.0], None);
        assert_eq!(s.n_eval, 5);
        assert!((s.bad1 - 80.0).abs() < 1e-9 && (s.bad2 - 60.0).abs() < 1e-9, "{s:?}");
        assert!((s.bad1v - 75.0).abs() < 1e-9 && (s.bad2v - 50.0).abs() < 1e-9, "{s:?}");
        assert!((s.density - 500.0 / 6.0).abs() < 1e-9, "{s:?}");
        // A mask keeping k = 0 and 3 only: errors 0 and 2.5 -> bad2 50 %.
        let m = [true, false, false, true, false, true];
        let s = dense_scores(&[10.0, 0.0, 11.5, 12.5, 13.0, 9.0], &[10.0, 10.0, 10.0, 10.0, 10.0, 0.0], Some(&m));
        assert_eq!(s.n_eval, 2);
        assert!((s.bad2 - 50.0).abs() < 1e-9, "{s:?}");
    }

    /// A textured pair where the right view is the left shifted by `d`.
    fn shifted(w: usize, h: usize, d: usize) -> (GreyImage, GreyImage) {
        let tex = |x: usize, y: usize| (40 + ((x / 6 * 37 + y / 5 * 11) % 7) * 30) as u8;
        let l = (0..h).flat_map(|y| (0..w).map(move |x| tex(x, y))).collect();
        let r = (0..h).flat_map(|y| (0..w).map(move |x| tex(x + d, y))).collect();
        (GreyImage::new(w, h, l).unwrap(), GreyImage::new(w, h, r).unwrap())
    }

    #[test]
    fn fates_and_sparse_accuracy_follow_the_ground_truth() {
        let (l, r) = shifted(120, 6, 5);
        let frame = process_frame(&l, &r, &Params::paper(9.0).unwrap(), Threads::One).unwrap();
        assert!(frame.matches() > 10, "the shifted pair matches");
        // True ground truth: every matched declivity is correct.
        let gt = vec![5.0; 120 * 6];
        let (ok, n) = sparse_counts(&frame, &gt);
        assert_eq!((ok, n), (frame.matches(), frame.matches()));
        assert!(fates(&frame, &gt, 2).iter().all(|f| matches!(f, Fate::Correct | Fate::NoPartner | Fate::Missed)));
        // Ground truth 3 px off: every match is wrong; nothing is evaluated
        // where the truth is unknown.
        let off = vec![8.0; 120 * 6];
        assert_eq!(sparse_counts(&frame, &off).0, 0);
        assert!(fates(&frame, &off, 2).contains(&Fate::Wrong));
        assert_eq!(sparse_counts(&frame, &vec![0.0; 120 * 6]), (0, 0));
        assert!(fates(&frame, &vec![0.0; 120 * 6], 2).iter().all(|f| *f == Fate::NoTruth));
    }

    /// The right view 30 grey levels brighter: the paper's distances reject
    /// every true partner, the robust mode's offset-compensated ones pass
    /// them, and the diagnosis of each mode says so.
    #[test]
    fn diagnosis_tests_the_true_partners_with_the_modes_own_distances() {
        let (l, r) = shifted(120, 6, 5);
        let r = GreyImage::new(120, 6, r.pixels().iter().map(|&v| v + 30).collect()).unwrap();
        let gt = vec![5.0; 120 * 6];
        let both = |params: Params| {
            let frame = process_frame(&l, &r, &params, Threads::One).unwrap();
            let d = diagnose(&frame, &gt);
            assert!(d.with_partner > 50.0, "{d:?}");
            d.partner_both_sides
        };
        let (paper, robust) = (both(Params::paper(9.0).unwrap()), both(Params::new(9.0).unwrap()));
        assert!(paper < 5.0, "paper: {paper} % pass both sides");
        assert!(robust > 95.0, "robust: {robust} % pass both sides");
    }

    #[test]
    fn error_picture_colours_pixels_by_error_and_marks_declivities() {
        let (l, r) = shifted(120, 6, 5);
        let frame = process_frame(&l, &r, &Params::paper(9.0).unwrap(), Threads::One).unwrap();
        let mut gt = vec![5.0; 120 * 6];
        gt[0] = 0.0;
        let img = error_picture(&frame, &gt);
        assert_eq!(img.get_pixel(0, 0).0, colours::NO_TRUTH);
        // Away from the border the dense map is exact.
        assert_eq!(img.get_pixel(60, 3).0, colours::GOOD);
        let m = frame.lines[3].matches[2];
        assert_eq!(img.get_pixel(m.x_ref.round() as u32, 3).0, colours::DECL_CORRECT);
        let wrong = error_picture(&frame, &vec![9.0; 120 * 6]);
        assert_eq!(wrong.get_pixel(60, 3).0, colours::BAD);
        assert_eq!(wrong.get_pixel(m.x_ref.round() as u32, 3).0, colours::DECL_WRONG);
    }
}
