//! The streaming declivity detector (`rtl::detector::declivity_detector`) against
//! golden's hardware-parity detector (`golden::hardware`), and its cycle
//! counts against the latency model in its doc comment (`DESIGN.md` §4).
//!
//! Everything drives the rtl block cycle by cycle through `sim::drive::detector`
//! (direct drive, no testbench threads): lines are streamed with
//! `run_lines` and each line's records are compared with golden by
//! `compare_line`. Where the clock of every record is needed, [`run_timed`]
//! arranges `run_lines`' clocks per line.
//!
//! - Agreement, exact: golden's parity mode computes the detector's
//!   fixed-point `d_t` and positions, so every record must be identical.
//!   proptest properties over generated lines (random walks, steps,
//!   plateaus, Gaussian noise, flat lines, 0/255 extremes), widths 1 to
//!   `W_MAX` biased to small widths and the edges, several lines per case
//!   back to back, random `tvalid` gaps; lines built to sit on the
//!   threshold (generated and real); the overflow rules (`W_MAX`, `N_MAX`);
//!   every row of the eight real pairs; golden's constants against
//!   `rtl::params`.
//! - Cycle counts: `marker_latency(W)` on idle engines, the record timing
//!   rule, 1 pixel per clock at a line period of `MIN_LINE_PERIOD` and
//!   stalls (between lines only) below it.
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_detector`): a debug build simulates the detector far more slowly.

use declivity_tests::{any_line, block_line, seeded};
use golden::declivity::all_declivities;
use golden::hardware::LimitedLine;
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::{TestCaseError, TestRunner};
use rand::Rng;
use rand_distr::{Distribution, Normal};
use rtl::detector::declivity_detector::{marker_latency, MIN_LINE_PERIOD};
use rtl::params::{DT_FRAC_BITS, N_MAX, W_MAX};
use sim::drive::detector::{
    compare_line, golden_lines, run_lines, run_lines_as_frames, DetectorRun, DetectorSim, HwLine, LineComparison, RecordBeat,
};
use std::cell::RefCell;
use std::time::Instant;

// ===========================================================================
// Drivers
// ===========================================================================

/// A `gap` closure for `run_lines`: `tvalid` low with probability `p` on
/// each clock, from a seeded generator (reproducible with the case).
fn random_gaps(p: f64, seed: u64) -> impl FnMut(u64) -> bool {
    let mut rng = seeded(seed);
    move |_| p > 0.0 && rng.gen_bool(p)
}

/// Streams `lines` through a fresh detector (each line a frame of its own:
/// generated lines have any widths) and golden; checks that every line came
/// out, and returns the run, golden's lines and the comparisons.
fn stream_and_compare(
    lines: &[Vec<u8>],
    gap: impl FnMut(u64) -> bool,
) -> Result<(DetectorRun, Vec<LimitedLine>, Vec<LineComparison>), TestCaseError> {
    let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
    let mut sim = DetectorSim::new();
    let run = run_lines_as_frames(&mut sim, &refs, gap, |_| {}).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert_eq!(run.lines.len(), lines.len(), "one marker per line");
    let gold = golden_lines(&refs);
    let cmp = run.lines.iter().zip(&gold).map(|(h, g)| compare_line(h, g)).collect();
    Ok((run, gold, cmp))
}

/// A readable account of a line's difference, for failure messages: the
/// line, the comparison, and the first record where the two lists differ.
fn describe_difference(y: usize, line: &[u8], hw: &HwLine, gold: &LimitedLine, c: &LineComparison) -> String {
    let pos_lsb = (1u64 << rtl::params::POS_FRAC_BITS) as f64;
    let mut s = format!(
        "line {y} (width {}): {c:?}\n  rtl: {} records, d_t {} (x32 = {}), wide {}, full {}, count {}\n  \
         golden: {} declivities, d_t {} (x32 = {}), wide {}, full {}\n",
        line.len(),
        hw.records.len(),
        hw.dt(),
        hw.marker.dt,
        hw.marker.wide,
        hw.marker.full,
        hw.marker.count,
        gold.declivities.len(),
        gold.dt,
        gold.dt_lsb,
        gold.wide,
        gold.full
    );
    let n = hw.records.len().max(gold.declivities.len());
    for i in 0..n {
        let h = hw.records.get(i);
        let g = gold.declivities.get(i);
        let same = match (h, g) {
            (Some(h), Some(g)) => {
                (h.start as usize, h.end as usize, h.amplitude, h.left, h.right)
                    == (g.start, g.end, g.amplitude, g.left, g.right)
                    && h.pos as f64 == g.position * pos_lsb
            }
            _ => false,
        };
        if !same {
            s += &format!("  first difference at record {i}:\n    rtl    {h:?}\n    golden {g:?}\n");
            break;
        }
    }
    if line.len() <= 64 {
        s += &format!("  pixels {line:?}\n");
    }
    s
}

/// One line out of [`run_timed`]: its records with their clocks.
#[derive(Debug, Clone)]
struct TimedLine {
    records: Vec<(u64, RecordBeat)>,
    marker: RecordBeat,
    marker_cycle: u64,
    /// Clock at which the line's first / last pixel was accepted.
    first_pixel_cycle: u64,
    last_pixel_cycle: u64,
}

/// What [`run_timed`] saw.
#[derive(Debug, Clone, Default)]
struct TimedRun {
    lines: Vec<TimedLine>,
    /// Stalls (`tvalid` high, `tready` low) on a line's first pixel.
    stalls_between_lines: u64,
    /// Stalls on any other pixel of a line.
    stalls_inside_lines: u64,
}

/// [`run_lines_as_frames`] with its clocks arranged per line (a hang fails
/// the test).
fn run_timed(sim: &mut DetectorSim, lines: &[&[u8]], gap: impl FnMut(u64) -> bool) -> TimedRun {
    let run = run_lines_as_frames(sim, lines, gap, |_| {}).unwrap_or_else(|e| panic!("{e}"));
    TimedRun {
        stalls_between_lines: run.stall_cycles - run.stalls_inside_lines,
        stalls_inside_lines: run.stalls_inside_lines,
        lines: run
            .lines
            .into_iter()
            .enumerate()
            .map(|(k, l)| TimedLine {
                records: l.record_cycles.into_iter().zip(l.records).collect(),
                marker: l.marker,
                marker_cycle: l.marker_cycle,
                first_pixel_cycle: run.first_pixel_cycle[k],
                last_pixel_cycle: run.last_pixel_cycle[k],
            })
            .collect(),
    }
}

/// The pixel at which the tracker closes the declivity ending at `end`
/// (tight plateau rule): the next non-zero gradient `g(x) = I(x+1) - I(x)`,
/// `x ≥ end`, or the stored line's last pixel.
fn closing_pixel(stored: &[u8], end: usize) -> usize {
    (end..stored.len().saturating_sub(1)).find(|&x| stored[x + 1] != stored[x]).unwrap_or(stored.len() - 1)
}

/// Checks the record timing rule of the detector's doc on one timed line:
/// a record of a declivity closing at pixel `x` of a line of `W` stored
/// pixels leaves `(W - 1 - x) + 1` clocks before the marker (the last
/// declivity, closed by the line's last pixel, one clock before it).
fn check_record_timing(line: &[u8], t: &TimedLine) -> Result<(), String> {
    let stored = &line[..line.len().min(W_MAX)];
    let w = stored.len();
    for (k, (cycle, r)) in t.records.iter().enumerate() {
        let x = closing_pixel(stored, r.end as usize);
        let want = (w - 1 - x) as u64 + 1;
        let got = t.marker_cycle - cycle;
        if got != want {
            return Err(format!(
                "record {k} of a {}-px line ({w} stored), start {} end {}, closes at pixel {x}: \
                 {got} clocks before its marker, the rule says {want}",
                line.len(),
                r.start,
                r.end
            ));
        }
    }
    // And the marker itself: records precede it, in order.
    if t.records.windows(2).any(|p| p[0].0 >= p[1].0) || t.records.last().is_some_and(|r| r.0 >= t.marker_cycle) {
        return Err("records out of order or not before their marker".into());
    }
    Ok(())
}

// ===========================================================================
// Generators
// ===========================================================================

/// Line widths 1 ..= `W_MAX`, biased to small widths and to the edges.
fn any_width() -> impl Strategy<Value = usize> {
    prop_oneof![
        3 => prop::sample::select(vec![1usize, 2, 3, 4, W_MAX - 1, W_MAX]),
        4 => 1usize..=16,
        3 => 17usize..=200,
        2 => 201usize..=W_MAX,
    ]
}

/// `segments` (length, level) repeated until `w` pixels, cut at `w`.
fn from_segments(w: usize, segments: &[(usize, u8)]) -> Vec<u8> {
    let mut out = Vec::with_capacity(w);
    while out.len() < w {
        for &(len, level) in segments {
            out.extend(std::iter::repeat(level).take(len));
        }
    }
    out.truncate(w);
    out
}

/// A random walk: a start level and steps of up to ±`k`, clamped to 0–255.
fn walk_line(w: usize) -> BoxedStrategy<Vec<u8>> {
    (any::<u8>(), 1i32..=40)
        .prop_flat_map(move |(s, k)| (Just(s), vec(-k..=k, w - 1)))
        .prop_map(|(s, steps)| {
            let mut v = s as i32;
            std::iter::once(s)
                .chain(steps.into_iter().map(|d| {
                    v = (v + d).clamp(0, 255);
                    v as u8
                }))
                .collect()
        })
        .boxed()
}

/// Steps: runs of 1–24 pixels at any level.
fn step_line(w: usize) -> BoxedStrategy<Vec<u8>> {
    vec((1usize..=24, any::<u8>()), 1..=(w / 4 + 1).min(64)).prop_map(move |s| from_segments(w, &s)).boxed()
}

/// Plateaus: long flat runs (1–200 pixels) on a palette of 2–4 levels.
fn plateau_line(w: usize) -> BoxedStrategy<Vec<u8>> {
    (vec(any::<u8>(), 2..=4), vec((1usize..=200, any::<prop::sample::Index>()), 1..=16))
        .prop_map(move |(palette, runs)| {
            let s: Vec<(usize, u8)> = runs.iter().map(|(len, i)| (*len, *i.get(&palette))).collect();
            from_segments(w, &s)
        })
        .boxed()
}

/// Gaussian noise of σ 0.3–30 around a level (clamped at 0 and 255).
fn noise_line(w: usize) -> BoxedStrategy<Vec<u8>> {
    (0.0f64..=255.0, 0.3f64..30.0, any::<u64>())
        .prop_map(move |(level, sigma, seed)| {
            let mut rng = seeded(seed);
            let normal = Normal::new(level, sigma).expect("sigma > 0");
            (0..w).map(|_| normal.sample(&mut rng).round().clamp(0.0, 255.0) as u8).collect()
        })
        .boxed()
}

/// Every pixel the same level.
fn flat_line(w: usize) -> BoxedStrategy<Vec<u8>> {
    any::<u8>().prop_map(move |v| vec![v; w]).boxed()
}

/// The 0/255 extremes: saturated zig-zags (runs of 1–3 pixels alternating
/// 0 and 255, sometimes after a flat part) and 0↔255 steps (long runs).
fn extreme_line(w: usize) -> BoxedStrategy<Vec<u8>> {
    prop_oneof![
        (vec(1usize..=3, 1..=32), any::<bool>(), 0usize..=600).prop_map(move |(runs, high_first, flat)| {
            let mut s = vec![(flat, 0u8)];
            for (i, len) in runs.into_iter().enumerate() {
                s.push((len, if (i % 2 == 0) == high_first { 255 } else { 0 }));
            }
            from_segments(w, &s)
        }),
        (vec((1usize..=300, any::<bool>()), 1..=8)).prop_map(move |runs| {
            let s: Vec<(usize, u8)> = runs.into_iter().map(|(len, hi)| (len, if hi { 255 } else { 0 })).collect();
            from_segments(w, &s)
        }),
    ]
    .boxed()
}

/// Any line the detector should take, of width 1 ..= `W_MAX`.
fn any_hw_line() -> BoxedStrategy<Vec<u8>> {
    any_width()
        .prop_flat_map(|w| {
            prop_oneof![
                2 => walk_line(w),
                2 => step_line(w),
                2 => plateau_line(w),
                2 => noise_line(w),
                1 => flat_line(w),
                2 => extreme_line(w),
                1 => any_line(w, w),
            ]
        })
        .boxed()
}

/// A case: 1–4 lines back to back, a `tvalid` gap probability (none half
/// of the time) and the gaps' seed.
fn any_stream() -> impl Strategy<Value = (Vec<Vec<u8>>, f64, u64)> {
    (vec(any_hw_line(), 1..=4), prop_oneof![Just(0.0), 0.0f64..0.6], any::<u64>())
}

/// The proptest cases of each agreement property: ~2 k clocks each.
const CASES: u32 = 48;

// ===========================================================================
// 1. Agreement with golden on generated lines
// ===========================================================================

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn prop_every_rtl_line_has_zero_mismatches_with_golden_parity_mode(case in any_stream()) {
        let (lines, p, seed) = case;
        let (run, gold, cmp) = stream_and_compare(&lines, random_gaps(p, seed))?;
        for (y, c) in cmp.iter().enumerate() {
            prop_assert!(c.mismatches == 0, "{}", describe_difference(y, &lines[y], &run.lines[y], &gold[y], c));
        }
    }

    #[test]
    fn prop_rtl_positions_are_golden_parity_positions_the_f64_ones_rounded_down(case in any_stream()) {
        let (lines, p, seed) = case;
        let (run, gold, cmp) = stream_and_compare(&lines, random_gaps(p, seed))?;
        for (y, c) in cmp.iter().enumerate() {
            prop_assert!(c.max_pos_err_lsb == 0.0, "{}", describe_difference(y, &lines[y], &run.lines[y], &gold[y], c));
            // The divider floors: below golden's f64 eq. 3 by less than an
            // LSB (an f64 a hair below an exact multiple is that multiple).
            let stored = &lines[y][..lines[y].len().min(W_MAX)];
            for h in &run.lines[y].records {
                let x = h.pos as f64 / (1u64 << rtl::params::POS_FRAC_BITS) as f64;
                let f = golden::declivity::position(stored, h.start as usize, h.end as usize);
                prop_assert!(x <= f + 1e-9 && f - x < 1.0 / (1u64 << rtl::params::POS_FRAC_BITS) as f64, "line {}: rtl position {} vs golden's f64 {}", y, x, f);
            }
        }
    }

    #[test]
    fn prop_rtl_dt_is_golden_parity_dt_within_half_an_lsb_of_the_f64_one(case in any_stream()) {
        let (lines, p, seed) = case;
        let (run, gold, cmp) = stream_and_compare(&lines, random_gaps(p, seed))?;
        for (y, c) in cmp.iter().enumerate() {
            prop_assert!(c.dt_err_lsb == 0.0, "{}", describe_difference(y, &lines[y], &run.lines[y], &gold[y], c));
            // The threshold engine's bound: half an LSB plus about 0.001
            // grey level from golden's f64 eq. 2.
            let stored = &lines[y][..lines[y].len().min(W_MAX)];
            let f = golden::noise::line_threshold(stored);
            prop_assert!((run.lines[y].dt() - f).abs() <= 0.5 / (1u64 << DT_FRAC_BITS) as f64 + 0.002, "line {}: d_t {} vs f64 {}", y, run.lines[y].dt(), f);
            // Every record carries its line's d_t.
            for r in &run.lines[y].records {
                prop_assert_eq!(r.dt, run.lines[y].marker.dt);
            }
        }
    }

    #[test]
    fn prop_records_leave_w_minus_closing_pixel_clocks_before_their_marker(case in any_stream()) {
        let (lines, p, seed) = case;
        let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
        let mut rng = seeded(seed);
        let mut sim = DetectorSim::new();
        let run = run_timed(&mut sim, &refs, |_| p > 0.0 && rng.gen_bool(p));
        for (y, t) in run.lines.iter().enumerate() {
            if let Err(e) = check_record_timing(&lines[y], t) {
                return Err(TestCaseError::fail(format!("line {y}: {e}")));
            }
        }
        prop_assert_eq!(run.stalls_inside_lines, 0, "tready low inside a line");
    }
}

// ===========================================================================
// 1b. Lines on the threshold
// ===========================================================================

/// A step written into a line by [`place_threshold_steps`]: a single
/// gradient at pixel `x` (`I(x+1) - I(x)`, rising or falling) between two
/// gradients of the other sign, so that it is a declivity of its own whose
/// amplitude is the gradient, `⌊d_t⌋ + offset` of the line's own `d_t`.
#[derive(Debug, Clone, Copy)]
struct ThresholdStep {
    x: usize,
    rising: bool,
    /// -1, 0 or +1: the amplitude below, at, or just above `⌊d_t⌋`.
    offset: i32,
}

/// The line `base` with `steps` written in, each at `⌊d_t⌋ + offset` (at
/// least 1) of the finished line's `d_t` as golden's parity mode computes
/// it, and that `d_t` (in LSBs). The amplitudes change the |ΔI| histogram
/// only in their own bins (above the median) and at the pixels beside the
/// steps, so the amplitudes and `d_t` settle after a pass or two; `None`
/// when they do not within eight.
///
/// A rising step of `A` at `x` is the four pixels `L + 1, L, L + A, L + A - 1`
/// from `x - 1` (falling ones mirrored), `L` taken from the base line and
/// clamped so that all four are grey levels.
fn place_threshold_steps(base: &[u8], steps: &[ThresholdStep]) -> Option<(Vec<u8>, u32)> {
    let limits = sim::Config::Sd.limits();
    let mut amps: Vec<i32> = vec![1; steps.len()];
    for _ in 0..8 {
        let mut line = base.to_vec();
        for (s, &a) in steps.iter().zip(&amps) {
            let l = (base[s.x] as i32).clamp(0, 255 - a);
            let window = if s.rising { [l + 1, l, l + a, l + a - 1] } else { [l + a - 1, l + a, l, l + 1] };
            for (k, v) in window.into_iter().enumerate() {
                line[s.x - 1 + k] = v as u8;
            }
        }
        let dt_lsb = golden::hardware::detect_line(&line, limits).dt_lsb;
        let threshold = (dt_lsb >> DT_FRAC_BITS) as i32;
        let want: Vec<i32> = steps.iter().map(|s| (threshold + s.offset).clamp(1, 254)).collect();
        if want == amps {
            return Some((line, dt_lsb));
        }
        amps = want;
    }
    None
}

/// Of the widths `w - cut` for `cut` in `0 .. cuts` (the steps lie before
/// them), the line whose `d_t` is an integer or the least above one
/// (`d_t·2^DT_FRAC_BITS mod 2^DT_FRAC_BITS` smallest): golden's f64 `d_t`
/// is within about half an LSB of the fixed-point one, so an integer
/// fixed-point `d_t` has the f64 one on either side of it.
fn on_the_threshold(base: &[u8], steps: &[ThresholdStep], cuts: usize) -> Option<(Vec<u8>, u32)> {
    let unit = 1u32 << DT_FRAC_BITS;
    (0..cuts.min(base.len()))
        .filter_map(|cut| place_threshold_steps(&base[..base.len() - cut], steps))
        .min_by_key(|(_, dt)| dt % unit)
}

/// Sites for `count` steps in a line of `w` pixels: `x` in `2 .. w - 40`,
/// at least 6 pixels apart, each rising or falling with an offset of -1, 0
/// or +1.
fn step_sites(count: usize, w: usize) -> impl Strategy<Value = Vec<ThresholdStep>> {
    vec((any::<prop::sample::Index>(), any::<bool>(), -1i32..=1), count).prop_map(move |picks| {
        let slots = (w.saturating_sub(42)) / 6;
        let mut sites: Vec<ThresholdStep> = picks
            .into_iter()
            .filter(|_| slots > 0)
            .map(|(i, rising, offset)| ThresholdStep { x: 2 + 6 * i.index(slots), rising, offset })
            .collect();
        sites.sort_by_key(|s| s.x);
        sites.dedup_by_key(|s| s.x);
        sites
    })
}

/// A background for threshold steps: flat runs at random levels (other
/// declivities between them) plus noise of `0 ..= spread` grey levels on a
/// fraction `density` of the pixels. Low densities and spreads put `σ` at
/// the quantisation floor (the median |ΔI| in bin 0, `d_t` at or near
/// `DT_FLOOR`); higher ones move the median into the bins above.
fn threshold_background(w: usize) -> impl Strategy<Value = Vec<u8>> {
    (vec((4usize..=160, 40u8..=215), 1..=12), 0u8..=12, prop_oneof![Just(0.0), 0.0f64..=0.4, 0.4f64..=1.0], any::<u64>())
        .prop_map(move |(runs, spread, density, seed)| {
            let mut rng = seeded(seed);
            from_segments(w, &runs)
                .into_iter()
                .map(|v| if spread > 0 && rng.gen_bool(density) { v.saturating_add(rng.gen_range(0..=spread)) } else { v })
                .collect()
        })
}

/// Generated lines on the threshold: a background, up to 12 steps at
/// `⌊d_t⌋ - 1`, `⌊d_t⌋`, `⌊d_t⌋ + 1` of its own `d_t`, and the width chosen
/// among 24 so that `d_t` sits on an integer or just above one.
fn generated_line_on_threshold() -> impl Strategy<Value = (Vec<u8>, Vec<ThresholdStep>)> {
    prop_oneof![1 => 48usize..=160, 3 => 161usize..=W_MAX]
        .prop_flat_map(|w| (threshold_background(w), step_sites(12, w)))
        .prop_filter_map("steps that settle", |(base, steps)| on_the_threshold(&base, &steps, 24).map(|(line, _)| (line, steps)))
}

/// The rows of both views of the eight real pairs (loaded once).
fn real_rows() -> &'static [Vec<u8>] {
    static ROWS: std::sync::OnceLock<Vec<Vec<u8>>> = std::sync::OnceLock::new();
    ROWS.get_or_init(|| {
        let root = sim::eval::io::stereo_data_dir();
        let dirs = sim::eval::io::expand_pair_dirs(&[root.clone()]).unwrap_or_else(|e| panic!("{}: {e}", root.display()));
        assert_eq!(dirs.len(), 8, "eight pairs expected in {}", root.display());
        let mut rows = vec![];
        for d in dirs {
            let pair = sim::eval::io::load_pair_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display()));
            for img in [&pair.left, &pair.right] {
                rows.extend((0..img.height()).map(|y| img.row(y).to_vec()));
            }
        }
        rows
    })
}

/// Real lines on the threshold: a row of a real pair, with up to 6 steps
/// at the threshold written in and the width chosen among 24 as for
/// generated lines.
fn real_line_on_threshold() -> impl Strategy<Value = (Vec<u8>, Vec<ThresholdStep>)> {
    (any::<prop::sample::Index>(), 0usize..=6)
        .prop_flat_map(|(row, count)| {
            let base = real_rows()[row.index(real_rows().len())].clone();
            let w = base.len();
            (Just(base), step_sites(count, w))
        })
        .prop_filter_map("steps that settle", |(base, steps)| on_the_threshold(&base, &steps, 24).map(|(line, _)| (line, steps)))
}

/// What the threshold property saw, over all its cases.
#[derive(Debug, Default)]
struct ThresholdTally {
    lines: usize,
    /// Steps at `⌊d_t⌋ - 1`, `⌊d_t⌋`, `⌊d_t⌋ + 1`.
    steps: [usize; 3],
    /// Declivities (of the whole lines) with `|a|` at `⌊d_t⌋` or `⌊d_t⌋ + 1`.
    at_threshold: usize,
    /// Lines whose `d_t` uses the floor `DT_FLOOR`.
    floor_lines: usize,
    /// Lines where golden's f64 `d_t` has another integer part than the
    /// detector's: the f64 test decides an amplitude there differently.
    f64_threshold_differs: usize,
    /// Declivities whose f64 eq. 3 position, rounded down, is not the
    /// divider's quotient (none can be: the quotient `S1/(2·S0)` of these
    /// integers is at least `1/(32·S0)` from a multiple of 1/16 unless it
    /// is one, far more than the f64 division's rounding error).
    f64_position_differs: usize,
    records: usize,
    /// Clocks simulated, and the seconds they took.
    clocks: u64,
    sim_seconds: f64,
}

/// Streams `lines` (each with its steps) through the rtl detector and
/// golden's parity mode: every record identical, and each step on the side
/// of the rtl's own threshold its amplitude puts it (`|a| > ⌊d_t⌋`).
fn check_lines_on_threshold(cases: &[(Vec<u8>, Vec<ThresholdStep>)], tally: &mut ThresholdTally) -> Result<(), TestCaseError> {
    let lines: Vec<Vec<u8>> = cases.iter().map(|c| c.0.clone()).collect();
    let t = Instant::now();
    let (run, gold, cmp) = stream_and_compare(&lines, |_| false)?;
    tally.sim_seconds += t.elapsed().as_secs_f64();
    tally.clocks += run.cycles;
    for (y, ((line, steps), c)) in cases.iter().zip(&cmp).enumerate() {
        let (h, g) = (&run.lines[y], &gold[y]);
        prop_assert!(c.mismatches == 0, "{}", describe_difference(y, line, h, g, c));
        // The steps against the rtl's d_t alone.
        let threshold = (h.marker.dt >> DT_FRAC_BITS) as i32;
        let stored = &line[..line.len().min(W_MAX)];
        for s in steps {
            let a = stored[s.x + 1] as i32 - stored[s.x] as i32;
            prop_assert_eq!(a.abs(), (threshold + s.offset).clamp(1, 254), "line {}: step at {} ({:?})", y, s.x, s);
            let sent = h.records.iter().any(|r| r.start as usize == s.x && r.end as usize == s.x + 1 && r.amplitude == a);
            // (A full line may have dropped a characteristic step.)
            if a.abs() <= threshold || !h.marker.full {
                prop_assert_eq!(sent, a.abs() > threshold, "line {}: step at {} of |a| {}, d_t {}", y, s.x, a.abs(), h.dt());
            }
            let k = a.abs() - threshold;
            if (-1..=1).contains(&k) {
                tally.steps[(k + 1) as usize] += 1;
            }
        }
        tally.lines += 1;
        tally.records += h.records.len();
        tally.at_threshold +=
            all_declivities(stored).iter().filter(|d| matches!(d.amplitude.abs() - threshold, 0 | 1)).count();
        tally.floor_lines += (h.marker.dt as u64 == rtl::params::DT_FLOOR) as usize;
        let f64_dt = golden::noise::line_threshold(stored);
        tally.f64_threshold_differs += (golden::declivity::integer_threshold(f64_dt) != threshold as u32) as usize;
        tally.f64_position_differs += h
            .records
            .iter()
            .filter(|r| {
                let f = golden::declivity::position(stored, r.start as usize, r.end as usize);
                (f * (1u64 << rtl::params::POS_FRAC_BITS) as f64).floor() as u32 != r.pos
            })
            .count();
    }
    Ok(())
}

/// Golden's hardware-parity mode and the rtl detector agree on every
/// declivity of lines built to sit on the threshold: steps whose
/// amplitudes are `⌊d_t⌋ - 1`, `⌊d_t⌋` and `⌊d_t⌋ + 1` of the line's own
/// fixed-point `d_t`, with `d_t` on an integer or just above one (where
/// the f64 `d_t` falls on either side of it) and `σ` from the quantisation floor
/// up, on generated backgrounds and on rows of the eight real pairs. Every
/// record is identical, and the rtl keeps exactly the steps above its own
/// `⌊d_t⌋`. Fixed seeds: every run replays the same lines.
#[test]
fn golden_parity_and_the_rtl_detector_agree_on_every_declivity_of_lines_on_the_threshold() {
    let t = Instant::now();
    let tally = RefCell::new(ThresholdTally::default());
    let config = |cases, seed| ProptestConfig {
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        ..ProptestConfig::with_cases(cases)
    };
    // Three generated lines per case, back to back; two real ones.
    let mut runner = TestRunner::new(config(80, 0x7e5e_0001));
    let result = runner.run(&vec(generated_line_on_threshold(), 3), |cases| check_lines_on_threshold(&cases, &mut tally.borrow_mut()));
    if let Err(e) = result {
        panic!("generated lines: {e}");
    }
    let generated = tally.borrow().lines;
    let mut runner = TestRunner::new(config(40, 0x7e5e_0002));
    let result = runner.run(&vec(real_line_on_threshold(), 2), |cases| check_lines_on_threshold(&cases, &mut tally.borrow_mut()));
    if let Err(e) = result {
        panic!("real lines: {e}");
    }
    let tally = tally.into_inner();
    println!("{tally:?} ({generated} generated lines) in {:.1} s", t.elapsed().as_secs_f64());
    // The lines reach what they are built for.
    assert!(tally.lines >= 300, "{tally:?}");
    assert!(tally.steps.iter().all(|&n| n >= 300), "steps at each offset: {tally:?}");
    assert!(tally.floor_lines >= 10, "lines at the floor: {tally:?}");
    assert!(tally.f64_threshold_differs >= 10, "lines where the f64 d_t would decide differently: {tally:?}");
}

#[test]
fn golden_parity_derives_the_threshold_engines_constants_of_rtl_params() {
    use golden::hardware::threshold as g;
    use rtl::params as r;
    assert_eq!(g::THRESHOLD_PER_MEDIAN, r::THRESHOLD_PER_MEDIAN);
    assert_eq!(g::MEDIAN_FRAC_BITS as usize, r::MEDIAN_FRAC_BITS);
    assert_eq!(g::DT_ACC_FRAC_BITS as usize, r::DT_ACC_FRAC_BITS);
    assert_eq!(g::K_FRAC_BITS as usize, r::K_FRAC_BITS);
    assert_eq!(g::K_HALF, r::K_HALF);
    assert_eq!(g::K_FRAC, r::K_FRAC);
    assert_eq!(g::dt_floor_lsb(r::DT_FRAC_BITS as u32) as u64, r::DT_FLOOR);
    // golden's default hardware is the generated one.
    assert_eq!(golden::hardware::HardwareLimits::default(), sim::Config::Sd.limits());
}

// ===========================================================================
// 2. Overflow: lines wider than W_MAX, more than N_MAX declivities
// ===========================================================================

/// `flat` pixels at `lo`, then a zig-zag `hi`/`lo` to `width`: while the flat
/// part is longer than the zig-zag inside the stored pixels, the median
/// |ΔI| is 0, `d_t` is the floor, and every zig-zag gradient is a
/// characteristic declivity.
fn zigzag_after_flat(flat: usize, width: usize, lo: u8, hi: u8) -> Vec<u8> {
    let mut line = vec![lo; flat];
    line.extend((0..width - flat).map(|x| if x % 2 == 0 { hi } else { lo }));
    line
}

#[test]
fn wide_and_full_lines_set_the_flags_keep_golden_truncated_records_and_the_stream_stays_aligned() {
    let mut rng = seeded(0xde_c1_1e);
    let mut wide_1025 = block_line(&mut rng, W_MAX + 1);
    wide_1025[W_MAX] = wide_1025[W_MAX - 1] ^ 0x80; // a step in the dropped pixel
                                                    // (line, wide, full)
    let specials: Vec<(Vec<u8>, bool, bool)> = vec![
        (zigzag_after_flat(200, 360, 50, 150), false, true), // 160 declivities
        (wide_1025, true, false),
        (zigzag_after_flat(320, 600, 0, 255), false, true), // 280 declivities at 0/255
        (block_line(&mut rng, 1500), true, false),
        (zigzag_after_flat(600, 1100, 50, 150), true, true), // 424 declivities in the first W_MAX px
        ((0..2 * W_MAX + 3).map(|_| rng.gen()).collect(), true, false), // uniform noise: d_t > 255
    ];
    let mut lines = vec![];
    let mut expect = vec![];
    for (special, wide, full) in specials {
        lines.push(special);
        expect.push((wide, full));
        // A normal line after each: the stream must stay aligned.
        lines.push(block_line(&mut rng, 384));
        expect.push((false, false));
    }
    for (label, p) in [("no gaps", 0.0), ("tvalid gaps 30 %", 0.3)] {
        let (run, gold, cmp) = stream_and_compare(&lines, random_gaps(p, 7)).unwrap_or_else(|e| panic!("{label}: {e}"));
        for (y, c) in cmp.iter().enumerate() {
            let (h, g) = (&run.lines[y], &gold[y]);
            assert_eq!((g.wide, g.full), expect[y], "{label}: the test's own lines: golden's flags on line {y}");
            assert_eq!((h.marker.wide, h.marker.full), (g.wide, g.full), "{label}: flags of line {y}");
            assert!(c.mismatches == 0 && c.borderline == 0, "{label}: {}", describe_difference(y, &lines[y], h, g, c));
            assert_eq!(h.records.len(), g.declivities.len(), "{label}: line {y}");
            assert_eq!(h.marker.count as usize, h.records.len(), "{label}: line {y}");
            if g.full {
                assert_eq!(h.records.len(), N_MAX, "{label}: a full line sends N_MAX records");
            }
            assert!(h.marker.sof, "{label}: line {y} starts a frame of its own (stream_and_compare)");
        }
    }
}

#[test]
fn a_line_of_exactly_n_max_declivities_is_not_full_and_one_more_is() {
    // n zig-zag pixels after a flat part of 300: n non-zero gradients (the
    // first one from the flat part), each a characteristic declivity.
    for (n, full) in [(N_MAX, false), (N_MAX + 1, true)] {
        let line = zigzag_after_flat(300, 300 + n, 50, 150);
        let (run, gold, cmp) = stream_and_compare(&[line.clone()], |_| false).unwrap();
        let all = golden::declivity::characteristic_declivities(&line, gold[0].dt).len();
        assert_eq!(all, n, "the test line has {n} characteristic declivities");
        let h = &run.lines[0];
        assert_eq!((h.marker.full, gold[0].full), (full, full), "{n} declivities");
        assert_eq!(h.records.len(), n.min(N_MAX));
        assert_eq!(cmp[0].mismatches, 0, "{}", describe_difference(0, &line, h, &gold[0], &cmp[0]));
    }
}

// ===========================================================================
// 3. Real images: every row of both views of the eight pairs
// ===========================================================================

struct PairResult {
    name: String,
    pixels: u64,
    cycles: u64,
    records: usize,
    borderline: usize,
    mismatches: usize,
    max_pos_err: f64,
    max_dt_err: f64,
    stalls: u64,
    px_per_clk: [f64; 2],
    sof_ok: bool,
    clocks_per_s: f64,
    first_bad: Option<String>,
}

fn run_pair(dir: &std::path::Path) -> PairResult {
    let pair = sim::eval::io::load_pair_dir(dir).unwrap_or_else(|e| panic!("cannot load {}: {e}", dir.display()));
    let mut sim = DetectorSim::new();
    let mut r = PairResult {
        name: pair.name.clone(),
        pixels: 0,
        cycles: 0,
        records: 0,
        borderline: 0,
        mismatches: 0,
        max_pos_err: 0.0,
        max_dt_err: 0.0,
        stalls: 0,
        px_per_clk: [0.0; 2],
        sof_ok: true,
        clocks_per_s: 0.0,
        first_bad: None,
    };
    let t = Instant::now();
    // The two views back to back through one detector, each as a frame
    // (its first pixel carries tuser).
    for (v, img) in [&pair.left, &pair.right].into_iter().enumerate() {
        let lines: Vec<&[u8]> = (0..img.height()).map(|y| img.row(y)).collect();
        let start = sim.cycle;
        let run =
            run_lines(&mut sim, &lines, |_| false, |_| {}).unwrap_or_else(|e| panic!("{} view {v}: {e}", pair.name));
        r.cycles += sim.cycle - start;
        r.pixels += run.pixels;
        r.stalls += run.stall_cycles;
        r.px_per_clk[v] = run.px_per_clk();
        let gold = golden_lines(&lines);
        for (y, (h, g)) in run.lines.iter().zip(&gold).enumerate() {
            let c = compare_line(h, g);
            r.records += h.records.len();
            r.borderline += c.borderline;
            r.mismatches += c.mismatches;
            r.max_pos_err = r.max_pos_err.max(c.max_pos_err_lsb);
            r.max_dt_err = r.max_dt_err.max(c.dt_err_lsb);
            r.sof_ok &= h.marker.sof == (y == 0);
            if c.mismatches > 0 && r.first_bad.is_none() {
                r.first_bad = Some(format!("view {v} {}", describe_difference(y, lines[y], h, g, &c)));
            }
        }
        if run.lines.len() != lines.len() {
            r.mismatches += 1;
        }
    }
    r.clocks_per_s = r.cycles as f64 / t.elapsed().as_secs_f64();
    r
}

#[test]
fn every_row_of_both_views_of_the_eight_real_pairs_matches_golden_at_one_pixel_per_clock() {
    let root = sim::eval::io::stereo_data_dir();
    assert!(
        root.is_dir(),
        "the real pairs are missing: {} (set DECLIVITY_DATA to the folder of the eight Middlebury pairs)",
        root.display()
    );
    let mut dirs = sim::eval::io::expand_pair_dirs(&[root.clone()]).unwrap_or_else(|e| panic!("{}: {e}", root.display()));
    assert_eq!(dirs.len(), 8, "eight pairs expected in {}", root.display());
    // Largest first, so that two workers end together.
    dirs.sort_by_key(|d| std::cmp::Reverse(std::fs::metadata(d.join("left_gray.png")).map(|m| m.len()).unwrap_or(0)));
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results = std::sync::Mutex::new(Vec::new());
    let t = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(d) = dirs.get(i) else { break };
                let r = run_pair(d);
                println!(
                    "{:<11} {:>7} px {:>7} clk {:>6} records {:>3} borderline, max pos err {} LSB, \
                     max d_t err {} LSB, {} mismatches, {} stalls, {:.0} clk/s",
                    r.name,
                    r.pixels,
                    r.cycles,
                    r.records,
                    r.borderline,
                    r.max_pos_err,
                    r.max_dt_err,
                    r.mismatches,
                    r.stalls,
                    r.clocks_per_s
                );
                results.lock().unwrap().push(r);
            });
        }
    });
    let results = results.into_inner().unwrap();
    println!("eight pairs in {:.1} s", t.elapsed().as_secs_f64());
    assert_eq!(results.len(), 8);
    for r in &results {
        assert!(
            r.mismatches == 0,
            "{}: {} mismatches; first: {}",
            r.name,
            r.mismatches,
            r.first_bad.as_deref().unwrap_or("-")
        );
        assert!(r.max_pos_err == 0.0 && r.max_dt_err == 0.0 && r.borderline == 0, "{}", r.name);
        assert_eq!(r.stalls, 0, "{}: stalls", r.name);
        assert!(r.px_per_clk == [1.0, 1.0], "{}: {:?} px/clk", r.name, r.px_per_clk);
        assert!(r.sof_ok, "{}: sof on a line other than each view's first", r.name);
    }
}

// ===========================================================================
// 4. Cycle counts
// ===========================================================================

#[test]
fn marker_leaves_marker_latency_of_the_stored_width_after_the_last_stored_pixel_on_idle_engines() {
    let mut rng = seeded(0x1a7e);
    let mut sim = DetectorSim::new();
    let widths = [1usize, 2, 3, 50, 279, 280, 384, 1023, W_MAX, W_MAX + 1, 1500];
    for &w in &widths {
        for gappy in [false, true] {
            let line = block_line(&mut rng, w);
            // One line per call: run_lines returns after the marker, so the
            // engines are free when the next line comes.
            let mut g = random_gaps(if gappy { 0.4 } else { 0.0 }, w as u64);
            let run = run_lines(&mut sim, &[line.as_slice()], &mut g, |_| {}).unwrap();
            // (A line wider than W_MAX is cut, and processed, at its
            // W_MAX-th pixel.)
            let got = run.lines[0].marker_cycle - run.last_stored_cycle[0];
            let stored = w.min(W_MAX);
            assert_eq!(got as usize, marker_latency(stored), "width {w} (stored {stored}), tvalid gaps {gappy}");
            // The records are right too.
            let gold = golden_lines(&[line.as_slice()]);
            let c = compare_line(&run.lines[0], &gold[0]);
            assert_eq!(c.mismatches, 0, "{}", describe_difference(0, &line, &run.lines[0], &gold[0], &c));
        }
    }
}

#[test]
fn records_leave_w_minus_closing_pixel_clocks_before_the_marker_on_real_and_overflow_lines() {
    let pair = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba"))
        .unwrap_or_else(|e| panic!("the test needs the tsukuba pair: {e}"));
    let mut lines: Vec<Vec<u8>> = (100..110).map(|y| pair.left.row(y).to_vec()).collect();
    lines.push(zigzag_after_flat(200, 360, 50, 150)); // full
    lines.push(zigzag_after_flat(600, 1100, 0, 255)); // wide and full
    lines.push(block_line(&mut seeded(3), 1500)); // wide
    lines.push(vec![7; 5]);
    lines.push(vec![9]);
    let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
    let mut sim = DetectorSim::new();
    let run = run_timed(&mut sim, &refs, |_| false);
    let mut records = 0;
    for (y, t) in run.lines.iter().enumerate() {
        check_record_timing(&lines[y], t).unwrap_or_else(|e| panic!("line {y}: {e}"));
        records += t.records.len();
    }
    assert!(records > 500, "{records} records checked");
}

/// `count` lines of `width` pixels, one every `period` clocks (`tvalid`
/// low in between), streamed with clock-accurate timing.
fn periodic(width: usize, period: u64, count: usize, seed: u64) -> (Vec<Vec<u8>>, TimedRun) {
    let mut rng = seeded(seed);
    let lines: Vec<Vec<u8>> = (0..count).map(|_| block_line(&mut rng, width)).collect();
    let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
    let mut sim = DetectorSim::new();
    let run = run_timed(&mut sim, &refs, |c| c % period >= width as u64);
    (lines, run)
}

#[test]
fn short_lines_one_every_min_line_period_clocks_never_stall_and_keep_marker_latency() {
    let period = MIN_LINE_PERIOD as u64;
    for width in [1usize, 2, 50, 200, MIN_LINE_PERIOD - 1] {
        let (lines, run) = periodic(width, period, 24, width as u64);
        assert_eq!(run.stalls_between_lines + run.stalls_inside_lines, 0, "width {width}, period {period}");
        let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
        for ((k, t), g) in run.lines.iter().enumerate().zip(golden_lines(&refs)) {
            assert_eq!(t.first_pixel_cycle, k as u64 * period, "width {width}: line {k} started late");
            // At this period the engines are free when each line ends.
            assert_eq!(t.marker_cycle - t.last_pixel_cycle, marker_latency(width) as u64, "width {width}: line {k}");
            let h = HwLine {
                records: t.records.iter().map(|r| r.1).collect(),
                record_cycles: t.records.iter().map(|r| r.0).collect(),
                marker: t.marker,
                marker_cycle: t.marker_cycle,
            };
            let c = compare_line(&h, &g);
            assert_eq!(c.mismatches, 0, "{}", describe_difference(k, &lines[k], &h, &g, &c));
        }
    }
}

#[test]
fn back_to_back_lines_of_one_width_of_at_least_min_line_period_stream_at_exactly_one_pixel_per_clock() {
    let mut rng = seeded(0xb2b);
    for (width, count) in [(MIN_LINE_PERIOD, 40), (MIN_LINE_PERIOD + 1, 12), (384, 24), (741, 8), (W_MAX, 8)] {
        let lines: Vec<Vec<u8>> = (0..count).map(|_| block_line(&mut rng, width)).collect();
        let (run, gold, cmp) = stream_and_compare(&lines, |_| false).unwrap();
        assert_eq!(run.stall_cycles, 0, "width {width}");
        assert_eq!(run.px_per_clk(), 1.0, "width {width}: {} px in {} clocks", run.pixels, run.input_cycles);
        for (y, c) in cmp.iter().enumerate() {
            assert_eq!(c.mismatches, 0, "{}", describe_difference(y, &lines[y], &run.lines[y], &gold[y], c));
        }
    }
}

/// FAILS (reported): the doc promises 1 pixel per clock "whenever the line
/// period is at least MIN_LINE_PERIOD clocks", but with two banks a line
/// n + 2 waits until the reader has finished line n - 1 and started line n,
/// so a long line followed by lines of MIN_LINE_PERIOD pixels stalls even
/// though every line period is ≥ MIN_LINE_PERIOD. (Lines of one width, as in
/// an image, do not: see the test above.)
#[test]
fn back_to_back_lines_of_mixed_widths_start_on_the_clocks_of_the_documented_recurrence() {
    // Mixed widths stall even when each is at least MIN_LINE_PERIOD (line
    // n + 2 waits for line n's reading, which waits for line n - 1's):
    // the measured first-pixel clocks must be exactly `line_starts`.
    let mut rng = seeded(0x313);
    let cases: Vec<Vec<usize>> = vec![
        vec![2 * MIN_LINE_PERIOD, MIN_LINE_PERIOD, MIN_LINE_PERIOD, MIN_LINE_PERIOD],
        vec![MIN_LINE_PERIOD; 6],
        vec![MIN_LINE_PERIOD - 1; 6],
        vec![1, 2, 3, 500, 1, 1, 1, 300, 1024, 1030, 5, 700],
        vec![40; 8],
    ];
    for widths in cases {
        let lines: Vec<Vec<u8>> = widths.iter().map(|&w| block_line(&mut rng, w)).collect();
        let (run, gold, cmp) = stream_and_compare(&lines, |_| false).unwrap();
        for (y, c) in cmp.iter().enumerate() {
            assert_eq!(c.mismatches, 0, "{}", describe_difference(y, &lines[y], &run.lines[y], &gold[y], c));
        }
        let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
        let timed = run_timed(&mut DetectorSim::new(), &refs, |_| false);
        let starts: Vec<u64> = timed.lines.iter().map(|l| l.first_pixel_cycle).collect();
        assert_eq!(starts, rtl::detector::declivity_detector::line_starts(&widths), "widths {widths:?}");
        // Stalls are the gaps the recurrence leaves between lines.
        let expected_stalls: u64 = starts.windows(2).zip(&widths).map(|(s, &w)| s[1] - (s[0] + w as u64)).sum();
        assert_eq!(run.stall_cycles, expected_stalls, "widths {widths:?}");
    }
}

#[test]
fn back_to_back_lines_shorter_than_min_line_period_stall_between_lines_only_and_records_stay_right() {
    for (width, count) in [(MIN_LINE_PERIOD / 2, 16), (100, 12), (3, 12), (1, 12)] {
        let mut rng = seeded(width as u64);
        let lines: Vec<Vec<u8>> = (0..count).map(|_| block_line(&mut rng, width)).collect();
        let (run, gold, cmp) = stream_and_compare(&lines, |_| false).unwrap();
        assert!(run.stall_cycles > 0, "width {width}: no stalls below MIN_LINE_PERIOD");
        assert!(run.px_per_clk() < 1.0);
        for (y, c) in cmp.iter().enumerate() {
            assert_eq!(
                c.mismatches,
                0,
                "width {width}: {}",
                describe_difference(y, &lines[y], &run.lines[y], &gold[y], c)
            );
        }
        let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
        let timed = run_timed(&mut DetectorSim::new(), &refs, |_| false);
        assert_eq!(timed.stalls_inside_lines, 0, "width {width}: tready low inside a line");
        assert_eq!(timed.stalls_between_lines, run.stall_cycles, "width {width}: every stall falls between lines");
    }
}

/// FAILS (reported): MIN_LINE_PERIOD is documented as the *shortest* line
/// period that never stalls, and lines shorter than it back to back as
/// waiting; lines of MIN_LINE_PERIOD - 1 pixels back to back do not stall.
#[test]
fn lines_one_pixel_shorter_than_min_line_period_back_to_back_stall() {
    let mut rng = seeded(0x279);
    let width = MIN_LINE_PERIOD - 1;
    let lines: Vec<Vec<u8>> = (0..40).map(|_| block_line(&mut rng, width)).collect();
    let (run, _, cmp) = stream_and_compare(&lines, |_| false).unwrap();
    assert!(cmp.iter().all(|c| c.mismatches == 0));
    assert!(
        run.stall_cycles > 0,
        "40 lines of {width} px (MIN_LINE_PERIOD - 1) back to back: {} stall clocks, {} px/clk",
        run.stall_cycles,
        run.px_per_clk()
    );
}

/// The `hd` configuration's detector (`rtl-hd`, `W_MAX` 2048, `N_MAX` 256)
/// on lines `sd` cannot hold whole: rows of the motorcycle pair up-scaled 2×
/// (1 482 px, as `declivity rtl detect --config hd` runs them), generated
/// lines of 1 025 to 2 048 px and one of 2 049, back to back with random
/// idle clocks. Every line equals golden's hardware parity in `hd`'s limits
/// record for record; the up-scaled rows are wider than `sd`'s W_MAX and
/// come out whole (not `wide`), the 2 049-px line `wide`; the same rows
/// through `sd`'s detector are all `wide`.
#[test]
fn in_the_hd_configuration_lines_wider_than_sd_holds_equal_golden_record_for_record() {
    use sim::drive::detector::{golden_lines_in, HdDetector};
    use sim::Config;
    let hd_w_max = Config::Hd.sizes().w_max;
    let pair = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("motorcycle"))
        .unwrap_or_else(|e| panic!("the test needs the motorcycle pair: {e}"));
    let up = sim::eval::upscale::upscale_pair(&pair, 2).expect("2x");
    let mut lines: Vec<Vec<u8>> = (500..516).map(|y| up.left.row(y).to_vec()).collect();
    assert!(lines[0].len() > W_MAX && lines[0].len() <= hd_w_max, "{} px", lines[0].len());
    let mut rng = seeded(35);
    for width in [W_MAX + 1, 1_280, 1_920, hd_w_max, hd_w_max + 1] {
        lines.push(block_line(&mut rng, width));
    }
    let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
    let mut sim = DetectorSim::<HdDetector>::build();
    let run = run_lines_as_frames(&mut sim, &refs, random_gaps(0.05, 35), |_| {}).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(run.lines.len(), lines.len(), "one marker per line");
    let gold = golden_lines_in(&refs, Config::Hd);
    let mut records = 0;
    for (y, (h, g)) in run.lines.iter().zip(&gold).enumerate() {
        let c = compare_line(h, g);
        assert_eq!(c.mismatches, 0, "{}", describe_difference(y, &lines[y], h, g, &c));
        assert_eq!(h.marker.wide, lines[y].len() > hd_w_max, "line {y} of {} px", lines[y].len());
        records += h.records.len();
    }
    assert!(records > 1_000, "{records} records compared");
    // sd keeps the first W_MAX pixels of the same rows and marks them wide.
    let mut sd = DetectorSim::new();
    let sd_run = run_lines(&mut sd, &refs[..16], |_| false, |_| {}).unwrap_or_else(|e| panic!("{e}"));
    assert!(sd_run.lines.iter().all(|l| l.marker.wide), "sd marks every up-scaled row wide");
}

// ===========================================================================
// Faulty cameras: golden's framing (`golden::hardware::framing`)
// ===========================================================================

/// One camera line of a faulty stream: its pixels, `tuser` on its first
/// beat, `tlast` on its last.
fn faulty_line() -> impl Strategy<Value = (Vec<u8>, bool, bool)> {
    (1usize..=48, any::<u64>(), prop::bool::weighted(0.2), prop::bool::weighted(0.8)).prop_map(|(w, seed, user, last)| {
        let mut rng = seeded(seed);
        let mut level = 128i32;
        let px = (0..w)
            .map(|_| {
                level = (level + rng.gen_range(-40..=40)).clamp(0, 255);
                level as u8
            })
            .collect();
        (px, user, last)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    /// Lines of mixed widths, `tlast` missing, `tuser` on any line: the
    /// detector stores and sends exactly the lines golden's framing cuts
    /// (the frame's width from its first line, lines cut there and the rest
    /// dropped to `tlast`, a `tuser` ending a line), each as golden's parity
    /// mode detects it, its marker's `end` its last stored pixel.
    #[test]
    fn prop_a_faulty_stream_is_cut_into_golden_framings_lines_and_each_detected_as_golden_does(lines in vec(faulty_line(), 1..=8)) {
        use golden::hardware::framing::{frame_lines, StreamBeat};
        use sim::drive::detector::{run_stream, DetectorSim, PixelBeat};
        let mut beats = Vec::new();
        for (y, (px, user, last)) in lines.iter().enumerate() {
            for (x, &p) in px.iter().enumerate() {
                beats.push(StreamBeat { pixel: p, user: (*user || y == 0) && x == 0, last: *last && x + 1 == px.len() });
            }
        }
        // The last line ends: without a tlast it would wait for a next beat.
        if let Some(b) = beats.last_mut() {
            b.last = true;
        }
        let limits = golden::hardware::HardwareLimits::default();
        let want = frame_lines(&beats, limits.w_max);
        let pixel_beats: Vec<PixelBeat> = beats.iter().map(|b| PixelBeat { tdata: b.pixel, tvalid: true, tuser: b.user, tlast: b.last, reset: false }).collect();
        let mut sim = DetectorSim::new();
        let got = run_stream(&mut sim, &pixel_beats, 4096);
        prop_assert_eq!(got.len(), want.len(), "lines stored");
        for (y, (h, g)) in got.iter().zip(&want).enumerate() {
            prop_assert_eq!((h.marker.end as usize + 1, h.marker.sof, h.marker.wide), (g.pixels.len(), g.sof, g.wide), "line {}: width, sof, cut", y);
            let gold = golden::hardware::detect_line(&g.pixels, limits);
            let c = compare_line(h, &LimitedLine { wide: g.wide, ..gold.clone() });
            prop_assert!(c.mismatches == 0, "{}", describe_difference(y, &g.pixels, h, &gold, &c));
        }
    }
}
