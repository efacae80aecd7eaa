//! A penalty on disparity jumps along the optimal path, measured on the eight
//! Middlebury pairs in the `robust` mode.
//!
//! The `robust` mode's DP (eq. 9) is replaced by one of two variants that
//! penalise a jump of disparity between consecutive nodes of a path by
//! `λ·gmax·max(0, |d(i,j) − d(m,n)| − τ)` (`gmax` of the line, eq. 8); every
//! other step of the mode is golden's, unchanged: the gains (relative +
//! one-sided, eq. 4–8, `golden::gain::LineGain`) in the search bands of eq. 6
//! (`golden::line::search_bands`), then the row confirmation, the edge flag,
//! the interpolation holding the background across jumps and the vertical
//! median (`golden::frame::finish_frame`, as `process_frame` runs them);
//! scores by `sim::eval::scores`.
//!
//! - `exact`: `G(i,j) = g(i,j) + max(0, max_{m<i,n<j} [G(m,n) − pen])` over
//!   the nodes that exist, `O(K²)` per line for `K` nodes (the upper bound;
//!   it loses the separable prefix maximum the systolic array relies on).
//!   Ties are broken as the prefix-max traceback breaks them (a node in the
//!   corner column, the lowest such; else the first row holding the maximum,
//!   its rightmost node), so that `λ = 0` gives golden's paths exactly.
//! - `approx`: golden's prefix-max recurrence, where every `P(i,j)` also
//!   carries the disparity of the last node of the path it stands for (from
//!   the winning candidate), and `G(i,j) = g(i,j) + P(i−1,j−1) − pen` with
//!   `pen` against that disparity (none when `P(i−1,j−1) = 0`: the path
//!   starts at the node); same tie-break and traceback as golden.
//!
//! `--caps` caps the penalty at `cap·gmax` (a bounded penalty for large
//! jumps, as SGM's P2; default `inf`, the linear penalty of the question).
//!
//! With `λ = 0` both variants are checked against `golden::process_frame` in
//! the robust mode, path for path (the count of differing rows is printed).
//! Per setting: mean sparse_acc1 and bad2 over the eight pairs, and per pair
//! sparse_acc1 / match_frac (`*`: match_frac below the paper mode's).
//!
//! `cargo run --release -p sim --example path_continuity -- [--variants approx,exact]
//!  [--lambdas 0,0.25,0.5,1,2] [--taus 0.5,1,2] [--caps inf] [STEREO_DIR]`
use std::path::PathBuf;
use std::time::Instant;

use golden::dp::{traceback, Choice};
use golden::frame::finish_frame;
use golden::gain::{gmax, pair_disparity, LineGain, Neighbours, REJECTED};
use golden::line::{line_features, search_bands, LineFeatures, LineResult, Match};
use golden::{process_frame, FrameResult, Mode, Params, RefView, Threads};
use rayon::prelude::*;
use sim::eval::scores::{dense_scores, sparse_counts};
use sim::eval::io::{load_pair_dir, PairData};

const PAIRS: [&str; 8] = ["tsukuba", "cones", "motorcycle", "art", "map", "sawtooth", "teddy", "venus"];

#[derive(Debug, Clone, Copy, PartialEq)]
enum Variant {
    Approx,
    Exact,
}

/// One row's graph: the two lines, their bands (eq. 6) and gains.
struct LineGraph {
    reference: LineFeatures,
    other: LineFeatures,
    refs: Vec<f64>,
    others: Vec<f64>,
    bands: Vec<(usize, usize)>,
    /// Gains of the band cells, row after row; `offs[i]` = first of row `i`.
    gains: Vec<f64>,
    offs: Vec<usize>,
    gmax: f64,
    /// Largest penalty, in units of `gmax` (`∞`: the linear penalty).
    cap: f64,
}

impl LineGraph {
    fn new(left: &[u8], right: &[u8], params: &Params) -> Self {
        assert_eq!(params.ref_view, RefView::Left);
        let (reference, other) = (line_features(left), line_features(right));
        let refs: Vec<f64> = reference.declivities.iter().map(|d| d.position).collect();
        let others: Vec<f64> = other.declivities.iter().map(|d| d.position).collect();
        let bands = search_bands(&refs, &others, params);
        let rule = LineGain::new(reference.dt, other.dt, params.mode);
        let rn: Vec<Neighbours> = reference.declivities.iter().map(Neighbours::from).collect();
        let on: Vec<Neighbours> = other.declivities.iter().map(Neighbours::from).collect();
        let (mut gains, mut offs) = (Vec::new(), Vec::new());
        for (i, &(lo, hi)) in bands.iter().enumerate() {
            offs.push(gains.len());
            gains.extend((lo..hi).map(|j| rule.gain(&rn[i], &on[j])));
        }
        let g = gmax(reference.dt, other.dt);
        LineGraph { reference, other, refs, others, bands, gains, offs, gmax: g, cap: f64::INFINITY }
    }

    fn n(&self) -> usize {
        self.refs.len()
    }

    fn m(&self) -> usize {
        self.others.len()
    }

    /// Gain of cell `(i, j)` (0-based), [`REJECTED`] outside the band or where rejected.
    fn gain(&self, i: usize, j: usize) -> f64 {
        let (lo, hi) = self.bands[i];
        if j >= lo && j < hi {
            self.gains[self.offs[i] + j - lo]
        } else {
            REJECTED
        }
    }

    fn d(&self, i: usize, j: usize) -> f64 {
        pair_disparity(self.refs[i], self.others[j], RefView::Left)
    }

    fn pen(&self, lam: f64, tau: f64, d: f64, d_prev: f64) -> f64 {
        self.gmax * (lam * ((d - d_prev).abs() - tau).max(0.0)).min(self.cap)
    }

    /// The approximate variant: prefix max carrying the last node's disparity.
    fn approx(&self, lam: f64, tau: f64) -> Vec<(usize, usize)> {
        let (n, m) = (self.n(), self.m());
        let w = m + 1;
        let mut p = vec![0.0f64; (n + 1) * w];
        let mut dp = vec![0.0f64; (n + 1) * w];
        let mut ch = vec![Choice::Start; (n + 1) * w];
        for i in 1..=n {
            for j in 1..=m {
                let (local, d) = (self.gain(i - 1, j - 1), self.d(i - 1, j - 1));
                let k = i * w + j;
                let (kd, ku, kl) = (k - w - 1, k - w, k - 1);
                let diag = p[kd];
                let pen = if diag > 0.0 { self.pen(lam, tau, d, dp[kd]) } else { 0.0 };
                let g = local + diag - pen;
                // Tie-break of golden::dp: start, node, up, left, strictly greater.
                let (mut best, mut c, mut bd) = (0.0, Choice::Start, 0.0);
                if g > best {
                    (best, c, bd) = (g, Choice::Node, d);
                }
                if p[ku] > best {
                    (best, c, bd) = (p[ku], Choice::Up, dp[ku]);
                }
                if p[kl] > best {
                    (best, c, bd) = (p[kl], Choice::Left, dp[kl]);
                }
                (p[k], ch[k], dp[k]) = (best, c, bd);
            }
        }
        traceback(n, m, |i, j| ch[i * w + j])
    }

    /// The exact variant: eq. 9 with the penalty inside the quadrant max.
    fn exact(&self, lam: f64, tau: f64) -> Vec<(usize, usize)> {
        // Nodes that exist, row after row, left to right; row_start[i] = first of row i.
        let mut nodes: Vec<(usize, usize, f64, f64)> = Vec::new();
        let mut row_start = Vec::with_capacity(self.n() + 1);
        for (i, &(lo, hi)) in self.bands.iter().enumerate() {
            row_start.push(nodes.len());
            for j in lo..hi {
                let g = self.gain(i, j);
                if g != REJECTED {
                    nodes.push((i, j, g, self.d(i, j)));
                }
            }
        }
        row_start.push(nodes.len());
        // Among equal values, the node the prefix-max walk from corner column
        // `c` reaches: one in column c (the lowest), else the first row, its
        // rightmost node.
        let key = |q: usize, c: usize| {
            let (m, n, _, _) = nodes[q];
            if n == c {
                (1, m as i64, n)
            } else {
                (0, -(m as i64), n)
            }
        };
        let mut gv = vec![0.0f64; nodes.len()];
        let mut pred: Vec<Option<usize>> = vec![None; nodes.len()];
        for k in 0..nodes.len() {
            let (i, j, g, d) = nodes[k];
            let (mut best_v, mut best) = (0.0f64, None::<usize>);
            if j > 0 {
                for q in 0..row_start[i] {
                    let (_, nq, _, dq) = nodes[q];
                    if nq >= j || gv[q] < best_v {
                        continue;
                    }
                    let v = gv[q] - self.pen(lam, tau, d, dq);
                    let take = match best {
                        None => v > best_v,
                        Some(b) => v > best_v || (v == best_v && key(q, j - 1) > key(b, j - 1)),
                    };
                    if take {
                        (best_v, best) = (v, Some(q));
                    }
                }
            }
            gv[k] = g + best_v;
            pred[k] = best;
        }
        // The end: the best G over the whole table, walked from (N, M).
        let (mut best_v, mut best) = (0.0f64, None::<usize>);
        let c = self.m().saturating_sub(1);
        for q in 0..nodes.len() {
            let take = match best {
                None => gv[q] > best_v,
                Some(b) => gv[q] > best_v || (gv[q] == best_v && key(q, c) > key(b, c)),
            };
            if take {
                (best_v, best) = (gv[q], Some(q));
            }
        }
        let mut path = Vec::new();
        while let Some(q) = best {
            path.push((nodes[q].0, nodes[q].1));
            best = pred[q];
        }
        path.reverse();
        path
    }

    fn result(&self, path: &[(usize, usize)]) -> LineResult {
        let matches = path
            .iter()
            .map(|&(i, j)| Match {
                ref_index: i,
                other_index: j,
                x_ref: self.refs[i],
                x_other: self.others[j],
                disparity: self.d(i, j),
                gain: self.gain(i, j),
                edge: false,
            })
            .collect();
        let path_gain = path.iter().map(|&(i, j)| self.gain(i, j)).sum();
        LineResult { reference: self.reference.clone(), other: self.other.clone(), matches, path_gain }
    }
}

#[derive(Clone, Copy)]
struct Score {
    acc: f64,
    frac: f64,
    bad2: f64,
}

fn score(frame: &FrameResult, pair: &PairData) -> Score {
    let (ok, n) = sparse_counts(frame, &pair.gt_left);
    Score {
        acc: 100.0 * ok as f64 / n.max(1) as f64,
        frac: frame.matches() as f64 / frame.reference_declivities().max(1) as f64,
        bad2: dense_scores(&frame.disparity, &pair.gt_left, None).bad2,
    }
}

fn list(s: &str) -> Vec<f64> {
    s.split(',').map(|v| v.trim().parse().expect("a number")).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let (mut variants, mut lambdas, mut taus) = (vec![Variant::Approx, Variant::Exact], list("0,0.25,0.5,1,2"), list("0.5,1,2"));
    let mut caps = vec![f64::INFINITY];
    let mut root = sim::eval::io::stereo_data_dir();
    while let Some(a) = args.next() {
        match a.as_str() {
            "--variants" => {
                variants = args
                    .next()
                    .expect("a list")
                    .split(',')
                    .map(|v| match v {
                        "approx" => Variant::Approx,
                        "exact" => Variant::Exact,
                        _ => panic!("variant {v}: approx or exact"),
                    })
                    .collect()
            }
            "--lambdas" => lambdas = list(&args.next().expect("a list")),
            "--taus" => taus = list(&args.next().expect("a list")),
            "--caps" => caps = list(&args.next().expect("a list")),
            _ => root = PathBuf::from(a),
        }
    }

    // Pairs, their graphs (independent of λ, τ), the paper and robust baselines.
    struct Pair {
        data: PairData,
        params: Params,
        graphs: Vec<LineGraph>,
        paper: Score,
        robust: Score,
        golden_paths: Vec<Vec<(usize, usize)>>,
    }
    let mut pairs = Vec::new();
    for name in PAIRS {
        let data = load_pair_dir(&root.join(name))?;
        let bound = data.dispmax + 1.0;
        let params = Params::with_mode(Mode::Robust, bound)?;
        let paper_frame = process_frame(&data.left, &data.right, &Params::with_mode(Mode::Paper, bound)?, Threads::All)?;
        // Golden's own paths before the row check: the robust frame with the
        // consistency step undone is not available, so run the lines.
        let golden_paths = (0..data.left.height())
            .into_par_iter()
            .map(|y| {
                let r = golden::process_line(data.left.row(y), data.right.row(y), &params);
                r.matches.iter().map(|m| (m.ref_index, m.other_index)).collect()
            })
            .collect();
        let robust_frame = process_frame(&data.left, &data.right, &params, Threads::All)?;
        let graphs =
            (0..data.left.height()).into_par_iter().map(|y| LineGraph::new(data.left.row(y), data.right.row(y), &params)).collect();
        let (paper, robust) = (score(&paper_frame, &data), score(&robust_frame, &data));
        pairs.push(Pair { data, params, graphs, paper, robust, golden_paths });
    }
    let nodes: usize = pairs.iter().flat_map(|p| &p.graphs).map(|g| g.gains.iter().filter(|&&v| v != REJECTED).count()).sum();
    let rows: usize = pairs.iter().map(|p| p.graphs.len()).sum();
    println!("{rows} rows, {:.0} nodes per row on average", nodes as f64 / rows as f64);

    let header = || {
        let mut s = String::from("variant  λ     τ    cap  | mean acc1  mean bad2 |");
        for p in PAIRS {
            s += &format!(" {p:>16} |");
        }
        s
    };
    let row = |label: String, scores: &[Score], paper: &[Score]| {
        let n = scores.len() as f64;
        let acc = scores.iter().map(|s| s.acc).sum::<f64>() / n;
        let bad2 = scores.iter().map(|s| s.bad2).sum::<f64>() / n;
        let mut s = format!("{label} | {acc:9.3}  {bad2:9.3} |");
        let mut below = 0;
        for (sc, pp) in scores.iter().zip(paper) {
            let flag = if sc.frac < pp.frac { below += 1; '*' } else { ' ' };
            s += &format!(" {:6.2} / {:.4}{flag} |", sc.acc, sc.frac);
        }
        s += &format!(" below paper: {below}");
        s
    };
    println!("{}", header());
    let paper: Vec<Score> = pairs.iter().map(|p| p.paper).collect();
    let robust: Vec<Score> = pairs.iter().map(|p| p.robust).collect();
    println!("{}", row(format!("{:<25}", "paper (golden)"), &paper, &paper));
    println!("{}", row(format!("{:<25}", "robust (golden)"), &robust, &paper));

    for &variant in &variants {
        let mut settings = vec![(0.0, 0.0, f64::INFINITY)];
        for &c in &caps {
            for &l in lambdas.iter().filter(|&&l| l != 0.0) {
                for &t in &taus {
                    settings.push((l, t, c));
                }
            }
        }
        let t_variant = Instant::now();
        for (lam, tau, cap) in settings {
            let t0 = Instant::now();
            let mut scores = Vec::new();
            let mut differing = 0;
            for p in &mut pairs {
                p.graphs.iter_mut().for_each(|g| g.cap = cap);
            }
            for p in &pairs {
                let paths: Vec<Vec<(usize, usize)>> = p
                    .graphs
                    .par_iter()
                    .map(|g| match variant {
                        Variant::Approx => g.approx(lam, tau),
                        Variant::Exact => g.exact(lam, tau),
                    })
                    .collect();
                if lam == 0.0 {
                    differing += paths.iter().zip(&p.golden_paths).filter(|(a, b)| a != b).count();
                }
                let lines = p.graphs.iter().zip(&paths).map(|(g, path)| g.result(path)).collect();
                let frame = finish_frame(lines, p.data.left.width(), p.data.left.height(), &p.params, Threads::All);
                scores.push(score(&frame, &p.data));
            }
            let label = format!(
                "{:<7} {lam:<5} {:<4} {:<4}",
                format!("{variant:?}").to_lowercase(),
                if lam == 0.0 { "-".to_string() } else { tau.to_string() },
                if cap.is_infinite() { "-".to_string() } else { cap.to_string() }
            );
            println!("{}  ({:.1} s)", row(label, &scores, &paper), t0.elapsed().as_secs_f64());
            if lam == 0.0 {
                let worst = scores
                    .iter()
                    .zip(&robust)
                    .map(|(a, b)| (a.acc - b.acc).abs().max((a.frac - b.frac).abs()).max((a.bad2 - b.bad2).abs()))
                    .fold(0.0, f64::max);
                println!("  λ = 0 against golden robust: {differing} rows with another path, largest metric difference {worst:.2e}");
            }
        }
        println!("  {variant:?}: {:.1} s for the sweep", t_variant.elapsed().as_secs_f64());
    }
    Ok(())
}
