//! The rtl matcher (`rtl::matcher::declivity_matcher`: gain cells, systolic array,
//! traceback) against golden's matcher (eq. 4–9, `golden::gain`,
//! `golden::dp`), and its cycle counts against the formulas in its doc
//! comments (`DESIGN.md` §4).
//!
//! Both models get the same declivities in the hardware's fixed-point
//! formats (`sim::drive::matcher`): every local gain is then an integer number of
//! `2^-GAIN_FRAC_BITS` grey levels in both, golden's f64 sums of them are
//! exact, and the gain tolerance is zero. So the properties are strict: the
//! rtl path is golden's node for node (ties included: both break them in
//! the order start, node, up, left), and the path gain on the marker is
//! golden's optimum exactly. `sim::drive::matcher::agreement` still counts a line
//! whose path differs but has golden's optimal gain ("equal gain") apart
//! from a true mismatch; the tests require identical lines.
//!
//! Generated line pairs cover what the issue lists: empty lines, one side
//! empty, every node rejected, exactly as many declivities as cells, equal
//! gains (repeated declivities), disparities on the search-area bounds,
//! shifted copies (long paths) and random sets. They run on a small array
//! of `CELLS` cells holding `ROWS` = 4·`CELLS` reference declivities, with
//! lines of one to four phases (the cells' rows `c + k·CELLS`: up to two
//! phases an anti-diagonal every two clocks, beyond every four): the cells
//! a line does not use never reach the outputs, and the clock counts
//! depend on the cells only through the phases. The real pairs run on
//! the sensor's matcher, `N_CELLS` = 32 cells for `N_MAX` = 128 rows.
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_matcher`): a debug build simulates the 32-cell matcher far more
//! slowly.

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestCaseError;
use rtl::matcher::declivity_matcher::{
    line_cycles, line_period, schedule, sweep_cycles, EngineLine, GainRule, OUTPUT_LAG, TAKE_AFTER_MARKER,
};
use rtl::matcher::traceback::traceback_cycles;
use rtl::params::{N_CELLS, N_MAX, POS_FRAC_BITS, ROWS_PER_CELL, SOF_SKEW_MAX, STAMP_BITS, STAMP_SHIFT, W_MAX};
use sim::drive::matcher::{
    agreement, check_line, golden_match, golden_match_in, image_lines, match_image, Agreement, MatchLine, MatchRecord,
    MatchedLine, MatcherSim,
};
use sim::formats::SearchArea;

/// Cells of the matcher in the generated cases.
const CELLS: usize = 16;
/// Reference declivities (and other-view ones) the `CELLS`-cell matcher
/// keeps per line.
const ROWS: usize = ROWS_PER_CELL * CELLS;
/// Cases per property.
const CASES: u32 = 48;
/// One position LSB (1/16 px).
const PX: u32 = 1 << POS_FRAC_BITS;

// ===========================================================================
// Generators
// ===========================================================================

/// What a generated line pair is meant to exercise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Random,
    /// The other line is the reference shifted by a disparity, levels
    /// jittered: many nodes, long paths.
    Shifted,
    /// One declivity repeated: many paths of equal gain.
    Ties,
    /// Levels far apart and a small threshold: no node survives eq. 7.
    Rejected,
    /// Disparities on and next to both bounds of eq. 6.
    Bounds,
    /// One or both lines empty.
    Empty,
    /// Exactly `ROWS` declivities on the reference side.
    Full,
}

/// A pair of lines for the matcher and its search bound (1/16 px).
#[derive(Debug, Clone)]
struct Case {
    kind: Kind,
    reference: MatchLine,
    other: MatchLine,
}

fn record(pos: u32, rising: bool, left: [u8; 3], right: [u8; 3]) -> MatchRecord {
    MatchRecord { pos, amplitude: if rising { 40 } else { -40 }, left, right }
}

/// Increasing positions from `start`, steps of `1 ..= max_step` LSB.
fn positions(n: usize, start: u32, max_step: u32) -> impl Strategy<Value = Vec<u32>> {
    prop::collection::vec(1..=max_step, n).prop_map(move |steps| {
        steps
            .iter()
            .scan(start, |p, s| {
                *p += s;
                Some(*p)
            })
            .collect()
    })
}

fn levels() -> impl Strategy<Value = [u8; 3]> {
    prop::array::uniform3(60u8..200)
}

fn random_line(n: usize, start: u32) -> impl Strategy<Value = MatchLine> {
    // d_t: the detector's range, and now and then the largest the port
    // holds (the sum of two saturates ⌈2·gmax⌉).
    let dt = prop_oneof![6 => 32u32..3000, 1 => 65_500u32..65_536];
    (positions(n, start, 12 * PX), prop::collection::vec((any::<bool>(), levels(), levels()), n), dt).prop_map(
        |(pos, attrs, dt)| MatchLine {
            dt,
            records: pos.iter().zip(attrs).map(|(&p, (r, l, rr))| record(p, r, l, rr)).collect(),
            ..MatchLine::default()
        },
    )
}

/// `other` = `reference` moved left by `d` LSB, levels jittered by up to
/// `jitter`, a few declivities dropped.
fn shifted(reference: &MatchLine, d: u32, jitter: &[i16], drop: &[bool]) -> MatchLine {
    let records = reference
        .records
        .iter()
        .enumerate()
        .filter(|(k, r)| !drop[*k % drop.len()] && r.pos > d)
        .map(|(k, r)| {
            let j = |v: u8, s: usize| (v as i16 + jitter[(k * 6 + s) % jitter.len()]).clamp(0, 255) as u8;
            MatchRecord {
                pos: r.pos - d,
                left: [j(r.left[0], 0), j(r.left[1], 1), j(r.left[2], 2)],
                right: [j(r.right[0], 3), j(r.right[1], 4), j(r.right[2], 5)],
                ..*r
            }
        })
        .collect();
    MatchLine { records, ..reference.clone() }
}

fn any_case(dispmax: u32) -> BoxedStrategy<Case> {
    let random = (0..=ROWS, 0..=ROWS)
        .prop_flat_map(|(n, m)| (random_line(n, 0), random_line(m, 0)))
        .prop_map(|(reference, other)| Case { kind: Kind::Random, reference, other });
    let shifted_pair = (1..=ROWS, 1..dispmax, prop::collection::vec(-6i16..=6, 24), prop::collection::vec(prop::bool::weighted(0.15), 7))
        .prop_flat_map(|(n, d, jitter, drop)| (random_line(n, 4 * PX * ROWS as u32), Just(d), Just(jitter), Just(drop)))
        .prop_map(|(reference, d, jitter, drop)| {
            let other = shifted(&reference, d, &jitter, &drop);
            Case { kind: Kind::Shifted, reference, other }
        });
    let ties = (1..=ROWS, 1..=ROWS, levels(), levels(), 1u32..=PX, 300u32..2000).prop_map(|(n, m, l, r, step, dt)| {
        let line = |k: usize, off: u32| MatchLine {
            dt,
            records: (0..k).map(|i| record(off + step * i as u32, true, l, r)).collect(),
            ..MatchLine::default()
        };
        Case { kind: Kind::Ties, reference: line(n, 2 * PX), other: line(m, PX) }
    });
    let rejected = (1..=ROWS, 1..=ROWS).prop_flat_map(|(n, m)| (positions(n, 2 * PX, 4 * PX), positions(m, 0, 4 * PX))).prop_map(
        |(rp, op)| {
            // Left and right levels swapped between the views: distances of
            // 3·160 grey levels (offset-compensated or not) against gmax = 1.
            let line = |p: &[u32], l: u8, r: u8| MatchLine {
                dt: 32,
                records: p.iter().map(|&x| record(x, true, [l; 3], [r; 3])).collect(),
                ..MatchLine::default()
            };
            Case { kind: Kind::Rejected, reference: line(&rp, 40, 200), other: line(&op, 200, 40) }
        },
    );
    let bounds = (levels(), levels(), 200u32..1500).prop_map(move |(l, r, dt)| {
        // Reference declivities 4 px apart; each has partners at
        // d = 0, 1 LSB, dispmax - 1 LSB and dispmax.
        let base = dispmax + 2 * PX;
        let n = ROWS / 4;
        let refs: Vec<u32> = (0..n as u32).map(|k| base + k * (dispmax + 8 * PX)).collect();
        let mut others: Vec<u32> = refs.iter().flat_map(|&x| [x - dispmax, x - (dispmax - 1), x - 1, x]).collect();
        others.sort_unstable();
        others.dedup();
        let line = |p: &[u32]| MatchLine { dt, records: p.iter().map(|&x| record(x, true, l, r)).collect(), ..MatchLine::default() };
        Case { kind: Kind::Bounds, reference: line(&refs), other: line(&others) }
    });
    let empty = (0..3usize, random_line(ROWS / 2, 0)).prop_map(|(which, line)| {
        let none = MatchLine { dt: line.dt, ..MatchLine::default() };
        let (reference, other) = match which {
            0 => (none.clone(), line),
            1 => (line, none),
            _ => (none.clone(), none),
        };
        Case { kind: Kind::Empty, reference, other }
    });
    let full = (random_line(ROWS, PX * 20), prop::collection::vec(-4i16..=4, 12), 1..dispmax).prop_map(|(reference, jitter, d)| {
        let other = shifted(&reference, d.min(PX * 20), &jitter, &[false]);
        Case { kind: Kind::Full, reference, other }
    });
    prop_oneof![3 => random, 3 => shifted_pair, 1 => ties, 1 => rejected, 1 => bounds, 1 => empty, 1 => full].boxed()
}

/// A stream of cases back to back and its search bound (1/16 px; sometimes
/// not a whole number of pixels).
fn any_stream() -> impl Strategy<Value = (Vec<Case>, u32, GainRule)> {
    (2 * PX..40 * PX, prop_oneof![Just(GainRule::Robust), Just(GainRule::Paper)])
        .prop_flat_map(|(dispmax, rule)| (prop::collection::vec(any_case(dispmax), 1..5), Just(dispmax), Just(rule)))
}

// ===========================================================================
// Drivers
// ===========================================================================

fn pairs_of(cases: &[Case]) -> Vec<(MatchLine, MatchLine)> {
    cases.iter().map(|c| (c.reference.clone(), c.other.clone())).collect()
}

/// Runs `cases` through a fresh `CELLS`-cell matcher and checks one marker
/// per pair.
fn run(cases: &[Case], dispmax: u32, rule: GainRule, one_at_a_time: bool) -> Result<Vec<MatchedLine>, TestCaseError> {
    let mut sim = MatcherSim::<CELLS>::new(rule, dispmax);
    let got = sim.run(&pairs_of(cases), one_at_a_time, || {});
    prop_assert_eq!(got.len(), cases.len(), "one marker per line pair");
    Ok(got)
}

fn describe(c: &Case, got: &MatchedLine, dispmax: u32, rule: GainRule) -> String {
    let g = golden_match(&c.reference, &c.other, dispmax, rule);
    format!(
        "{:?} case, {} × {} declivities, dispmax {} LSB, {rule:?}:\n  golden {:?} gain {}\n  rtl    {:?}\n  ref {:?}\n  other {:?}",
        c.kind,
        c.reference.records.len(),
        c.other.records.len(),
        dispmax,
        g.nodes,
        g.gain,
        got.pairs(),
        c.reference,
        c.other
    )
}

// ===========================================================================
// Agreement with golden
// ===========================================================================

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    /// Ties included: the fixed-point gains are golden's exactly and both
    /// break ties in one order.
    #[test]
    fn prop_rtl_path_is_golden_optimal_path_node_for_node((cases, dispmax, rule) in any_stream()) {
        let got = run(&cases, dispmax, rule, false)?;
        for (c, g) in cases.iter().zip(&got) {
            let want = golden_match(&c.reference, &c.other, dispmax, rule);
            prop_assert_eq!(agreement(&want, &g.pairs()), Agreement::Identical, "{}", describe(c, g, dispmax, rule));
        }
    }

    #[test]
    fn prop_rtl_path_has_golden_optimal_gain_by_golden_gains_and_the_marker_counts_it((cases, dispmax, rule) in any_stream()) {
        let got = run(&cases, dispmax, rule, false)?;
        for (c, g) in cases.iter().zip(&got) {
            let want = golden_match(&c.reference, &c.other, dispmax, rule);
            prop_assert_eq!(want.path_gain(&g.pairs()), Some(want.gain), "{}", describe(c, g, dispmax, rule));
            prop_assert_eq!(g.marker.count as usize, g.matches.len());
            prop_assert_eq!((g.marker.n as usize, g.marker.m as usize), (c.reference.records.len(), c.other.records.len()));
        }
    }

    #[test]
    fn prop_matches_carry_their_declivities_positions_and_disparities_inside_the_search_area(
        (cases, dispmax, rule) in any_stream()
    ) {
        let got = run(&cases, dispmax, rule, false)?;
        for (c, g) in cases.iter().zip(&got) {
            let want = golden_match(&c.reference, &c.other, dispmax, rule);
            check_line(&c.reference, &c.other, g, &want).map_err(TestCaseError::fail)?;
            for b in &g.matches {
                prop_assert!(b.disp > 0 && b.disp < dispmax, "disparity {} LSB outside (0, {dispmax})", b.disp);
            }
            let refs: Vec<u32> = g.matches.iter().map(|b| b.ref_index).collect();
            prop_assert!(refs.windows(2).all(|w| w[0] < w[1]), "reference order: {:?}", refs);
        }
    }

    /// Eq. 6 with a lower bound, `dispmin < d < dispmax`: the matcher's
    /// `dispmin` input (the columns' positions moved by it in the engine)
    /// gives golden's path for the same area, and no match outside it.
    #[test]
    fn prop_with_a_dispmin_rtl_path_is_golden_optimal_path_and_every_disparity_is_inside_dispmin_dispmax(
        (cases, dispmax, rule) in any_stream(),
        permille in 0u32..1000,
    ) {
        let area = SearchArea { dispmin: (dispmax - PX - 1) * permille / 1000, dispmax };
        let mut sim = MatcherSim::<CELLS>::in_area(rule, area);
        let got = sim.run(&pairs_of(&cases), false, || {});
        prop_assert_eq!(got.len(), cases.len(), "one marker per line pair");
        for (c, g) in cases.iter().zip(&got) {
            let want = golden_match_in(&c.reference, &c.other, area, rule);
            prop_assert_eq!(agreement(&want, &g.pairs()), Agreement::Identical, "{:?}\n{}", area, describe(c, g, dispmax, rule));
            for b in &g.matches {
                prop_assert!(b.disp > area.dispmin && b.disp < dispmax, "disparity {} LSB outside {:?}", b.disp, area);
            }
        }
    }

    /// `line_cycles(n, m, stop_diag, k, CELLS)` from the engine taking a pair
    /// (`TAKE_AFTER_MARKER` clocks after its second marker, engine idle) to its
    /// marker.
    #[test]
    fn prop_engine_clocks_per_line_equal_the_documented_formula((cases, dispmax, rule) in any_stream()) {
        let got = run(&cases, dispmax, rule, true)?;
        for (c, g) in cases.iter().zip(&got) {
            let want = golden_match(&c.reference, &c.other, dispmax, rule);
            let (n, m, k) = (c.reference.records.len(), c.other.records.len(), want.nodes.len());
            let formula = line_cycles(n, m, want.stop_diag, k, CELLS) as u64;
            prop_assert_eq!(g.marker_cycle - g.input_done_cycle - TAKE_AFTER_MARKER, formula, "{:?}: n {} m {} k {} stop {}", c.kind, n, m, k, want.stop_diag);
        }
    }
}

/// The engine's timing as `rtl::matcher::declivity_matcher::schedule` states it, for
/// pairs whose work is known from golden (n, m, the walk's stop diagonal, the
/// pairs).
fn engine_lines(cases: &[Case], got: &[MatchedLine], dispmax: u32, rule: GainRule, cells: usize) -> Vec<EngineLine> {
    cases
        .iter()
        .zip(got)
        .map(|(c, g)| {
            let want = golden_match(&c.reference, &c.other, dispmax, rule);
            let (n, m) = (c.reference.records.len(), c.other.records.len());
            EngineLine {
                input_done: g.input_done_cycle,
                sweep: sweep_cycles(n, m, cells) as u64,
                traceback: traceback_cycles(n, m, want.stop_diag, want.nodes.len()) as u64,
            }
        })
        .collect()
}

/// Back to back, pairs load while the engine works, and the traceback of a
/// pair overlaps the sweep of the next: every marker leaves on the clock the
/// documented schedule gives (`schedule`: the next pair taken the clock
/// after the traceback of this one starts, the traceback waiting for the
/// one before), and many lines are taken before the previous one's marker
/// (a one-engine matcher, sweep then traceback, would take them after).
#[test]
fn the_traceback_of_a_pair_overlaps_the_sweep_of_the_next_on_the_documented_schedule() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = prop::collection::vec(any_case(20 * PX), 6..10);
    let (mut overlapped, mut waited) = (0, 0);
    for _ in 0..8 {
        let cases = strategy.new_tree(&mut runner).expect("a case").current();
        let got = run(&cases, 20 * PX, GainRule::Robust, false).expect("runs");
        let lines = engine_lines(&cases, &got, 20 * PX, GainRule::Robust, CELLS);
        let times = schedule(&lines);
        for (k, (g, t)) in got.iter().zip(&times).enumerate() {
            assert_eq!(g.marker_cycle, t.marker, "pair {k} of {:?}: {:?}", cases.iter().map(|c| c.kind).collect::<Vec<_>>(), lines);
            if k > 0 {
                overlapped += usize::from(t.take < got[k - 1].marker_cycle - OUTPUT_LAG as u64);
                waited += usize::from(t.start > t.take + lines[k].sweep);
            }
        }
    }
    assert!(overlapped >= 20, "pairs taken while the traceback before them ran: {overlapped}");
    assert!(waited >= 1, "tracebacks that waited for the one before: {waited}");
}

/// More records than the cells hold: the first `ROWS` are matched, the rest
/// dropped, the marker says `full`, and the next line is unaffected.
#[test]
fn records_beyond_the_cells_are_dropped_the_line_is_flagged_full_and_the_next_is_intact() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let line = |n: usize, r: &mut proptest::test_runner::TestRunner| random_line(n, 0).new_tree(r).expect("a line").current();
    let (big_ref, big_other) = (line(ROWS + 5, &mut runner), line(ROWS + 1, &mut runner));
    let (next_ref, next_other) = (line(7, &mut runner), line(9, &mut runner));
    let dispmax = 30 * PX;
    let mut sim = MatcherSim::<CELLS>::new(GainRule::Robust, dispmax);
    let pairs = vec![(big_ref.clone(), big_other.clone()), (next_ref.clone(), next_other.clone())];
    let got = sim.run(&pairs, false, || {});
    let cut = |l: &MatchLine| MatchLine { records: l.records[..ROWS].to_vec(), ..l.clone() };
    assert!(got[0].marker.full && !got[1].marker.full);
    assert_eq!((got[0].marker.n as usize, got[0].marker.m as usize), (ROWS, ROWS));
    let want = golden_match(&cut(&big_ref), &cut(&big_other), dispmax, GainRule::Robust);
    assert_eq!(got[0].pairs(), want.nodes);
    let want = golden_match(&next_ref, &next_other, dispmax, GainRule::Robust);
    assert_eq!(got[1].pairs(), want.nodes);
    check_line(&next_ref, &next_other, &got[1], &want).expect("second line intact");
}

/// The worst line, `N_MAX` declivities on both sides along one long path,
/// on the full-size matcher: alone its clocks equal `line_cycles`; back to
/// back, its pairs' markers follow one another by `line_period`, which
/// fits in the line time of a `W_MAX`-pixel line.
#[test]
fn the_worst_line_pair_of_n_max_declivities_fits_in_the_line_time_of_a_w_max_line() {
    let (l, r) = ([100, 110, 120], [150, 160, 170]);
    let reference =
        MatchLine { dt: 400, records: (0..N_MAX as u32).map(|k| record(PX * (40 + 7 * k), true, l, r)).collect(), ..MatchLine::default() };
    let other = MatchLine { records: reference.records.iter().map(|r| MatchRecord { pos: r.pos - 3 * PX, ..*r }).collect(), ..reference.clone() };
    let dispmax = 5 * PX;
    let pairs = vec![(reference.clone(), other.clone()); 3];
    let mut sim = MatcherSim::<N_CELLS>::new(GainRule::Robust, dispmax);
    let got = sim.run(&pairs, false, || {});
    let want = golden_match(&reference, &other, dispmax, GainRule::Robust);
    assert_eq!(want.nodes.len(), N_MAX, "the path takes every pair");
    for g in &got {
        assert_eq!(g.pairs(), want.nodes);
    }
    let clocks = got[0].marker_cycle - got[0].input_done_cycle - TAKE_AFTER_MARKER;
    assert_eq!(clocks, line_cycles(N_MAX, N_MAX, want.stop_diag, N_MAX, N_CELLS) as u64);
    let period = line_period(N_MAX, N_MAX, want.stop_diag, N_MAX, N_CELLS) as u64;
    for k in 1..got.len() {
        assert!(got[k].input_done_cycle + TAKE_AFTER_MARKER < got[k - 1].marker_cycle, "pair {k} waits for the engine");
        assert_eq!(got[k].marker_cycle - got[k - 1].marker_cycle, period);
    }
    assert!(period <= W_MAX as u64, "{period} clocks per worst line back to back against {W_MAX} pixels of a W_MAX line");
    eprintln!("worst line: {clocks} clocks alone, {period} back to back (stop diagonal {})", want.stop_diag);
}

// ===========================================================================
// Real pairs
// ===========================================================================

/// Every row of `pair` through the sensor's matcher; all lines identical.
/// (The rust-hdl model is slow per clock: tsukuba is checked here, block by
/// block; every pair's whole frame is checked through the whole processor's
/// Verilog under Verilator against golden's hardware parity in
/// `sim/tests/cosim_stereo.rs`.)
fn real_pair(pair: &str, rule: GainRule) {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(pair)).expect("the pair loads");
    let lines = image_lines(&data.left, &data.right);
    let dispmax = ((data.dispmax + 1.0) * PX as f64) as u32;
    let (report, outcomes) = match_image::<N_CELLS>(pair, &lines, rule, SearchArea::below(dispmax), 2, &|| {});
    eprintln!("{}", serde_json::to_string(&report).expect("serializes"));
    for (y, o) in outcomes.iter().enumerate() {
        assert_eq!(o.agreement, Agreement::Identical, "{pair} row {y}: golden {:?}, rtl {:?}", o.golden.nodes, o.rtl.pairs());
    }
    assert_eq!(report.identical_lines, data.left.height());
    assert_eq!((report.mismatch_lines, report.equal_gain_lines, report.malformed_lines), (0, 0, 0));
    assert_eq!(report.matches_rtl, report.matches_golden);
    assert!(report.matches_rtl > report.declivities_ref / 4, "a real pair has many matches: {report:?}");
    // Back to back, the engine keeps up with lines of W_MAX pixels.
    assert!(report.max_engine_period <= W_MAX as u64, "{report:?}");
    // Every marker on the clock the engine's documented schedule gives.
    assert_eq!(report.off_schedule_lines, 0, "{report:?}");
}

#[test]
fn every_row_of_tsukuba_matches_golden_node_for_node_robust() {
    real_pair("tsukuba", GainRule::Robust);
}

#[test]
fn every_row_of_tsukuba_matches_golden_node_for_node_paper() {
    real_pair("tsukuba", GainRule::Paper);
}

/// Eq. 6's lower bound on real lines: rows of tsukuba (dispmax 16 px) with
/// `dispmin` 6 px match golden's paths for that area node for node, every
/// match is inside it, and the bound changes the paths (golden without it
/// matches some of these declivities at 6 px or less).
#[test]
fn with_a_dispmin_real_rows_match_golden_node_for_node_and_every_disparity_is_inside_the_area() {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
    let lines: Vec<_> = image_lines(&data.left, &data.right).into_iter().skip(100).take(32).collect();
    let area = SearchArea { dispmin: 6 * PX, dispmax: ((data.dispmax + 1.0) * PX as f64) as u32 };
    let (report, outcomes) = match_image::<N_CELLS>("tsukuba", &lines, GainRule::Robust, area, 2, &|| {});
    assert_eq!((report.identical_lines, report.mismatch_lines, report.malformed_lines), (lines.len(), 0, 0), "{report:?}");
    let inside = outcomes.iter().flat_map(|o| &o.rtl.matches).all(|b| b.disp > area.dispmin && b.disp < area.dispmax);
    assert!(inside, "a match outside {area:?}");
    assert!(report.matches_rtl > 0, "matches above dispmin: {report:?}");
    let below = lines.iter().flat_map(|(r, o)| {
        let g = golden_match(r, o, area.dispmax, GainRule::Robust);
        g.nodes.into_iter().map(move |(i, j)| r.records[i].pos as i64 - o.records[j].pos as i64)
    });
    assert!(below.filter(|&d| d <= area.dispmin as i64).count() > 0, "the rows have matches at or below dispmin without it");
}

/// An image wider than `W_MAX`: each line is its first `W_MAX` pixels, as
/// the detector sends it, flagged wide on the marker, and matched as golden
/// matches those pixels' declivities.
#[test]
fn lines_wider_than_w_max_are_matched_on_their_first_w_max_pixels_and_flagged_wide() {
    use declivity_tests::{block_line, seeded, shift_left_to_right};
    let (w, h) = (W_MAX + 77, 2);
    let mut rng = seeded(11);
    let rows: Vec<Vec<u8>> = (0..h).map(|_| block_line(&mut rng, w)).collect();
    let left = golden::GreyImage::new(w, h, rows.concat()).expect("an image");
    let right_rows: Vec<u8> = rows.iter().flat_map(|r| shift_left_to_right(r, 5)).collect();
    let right = golden::GreyImage::new(w, h, right_rows).expect("an image");
    let lines = image_lines(&left, &right);
    assert!(lines.iter().all(|(l, r)| l.wide && r.wide));
    assert!(lines.iter().flat_map(|(l, r)| l.records.iter().chain(&r.records)).all(|rec| (rec.pos >> POS_FRAC_BITS) < W_MAX as u32));
    let dispmax = 10 * PX;
    let mut sim = MatcherSim::<N_CELLS>::new(GainRule::Robust, dispmax);
    let got = sim.run(&lines, false, || {});
    for ((l, r), g) in lines.iter().zip(&got) {
        assert!(g.marker.wide);
        let want = golden_match(l, r, dispmax, GainRule::Robust);
        assert!(want.nodes.len() > l.records.len() / 2, "the shifted copy matches: {} of {}", want.nodes.len(), l.records.len());
        assert_eq!(g.pairs(), want.nodes);
    }
}

/// The `hd` configuration's matcher (`rtl-hd`: 64 cells, `N_MAX` 256) on
/// rows of the motorcycle pair up-scaled 2× (1 482 px) with more than
/// `sd`'s 128 declivities, and on a generated pair of 256: every path
/// golden's node for node (golden in `hd`'s limits, where `sd` would cut
/// the lines at 128 records and flag them full), every marker on the clock
/// `hd`'s documented schedule gives.
#[test]
fn in_the_hd_configuration_rows_of_more_than_128_declivities_match_golden_node_for_node_on_schedule() {
    use sim::drive::matcher::{image_lines_in, match_image_on, HdMatcher};
    use sim::Config;
    const HD: usize = 64;
    let hd = Config::Hd.sizes();
    assert_eq!((hd.cells, hd.n_max), (HD, 256));
    let pair = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("motorcycle")).expect("the pair loads");
    let up = sim::eval::upscale::upscale_pair(&pair, 2).expect("2x");
    let all = image_lines_in(&up.left, &up.right, Config::Hd);
    // The rows with the most reference declivities, and a 256 × 256 pair.
    let mut rows: Vec<usize> = (0..all.len()).collect();
    rows.sort_by_key(|&y| std::cmp::Reverse(all[y].0.records.len()));
    let mut lines: Vec<_> = rows[..6].iter().map(|&y| all[y].clone()).collect();
    assert!(lines.iter().all(|(l, _)| l.records.len() > N_MAX && !l.full), "rows above sd's N_MAX, whole");
    let (l, r) = ([100, 110, 120], [150, 160, 170]);
    let reference = MatchLine { dt: 400, records: (0..hd.n_max as u32).map(|k| record(PX * (40 + 7 * k), true, l, r)).collect(), ..MatchLine::default() };
    let other = MatchLine { records: reference.records.iter().map(|r| MatchRecord { pos: r.pos - 3 * PX, ..*r }).collect(), ..reference.clone() };
    lines.push((reference, other));
    let area = SearchArea::below(((2.0 * pair.dispmax + 1.0) * PX as f64) as u32);
    let (report, outcomes) = match_image_on::<HD, HdMatcher<HD>>("motorcycle 2x", &lines, GainRule::Robust, area, 2, &|| {});
    eprintln!("{}", serde_json::to_string(&report).expect("serializes"));
    for (k, o) in outcomes.iter().enumerate() {
        assert_eq!(o.agreement, Agreement::Identical, "line {k}: golden {:?}, rtl {:?}", o.golden.nodes, o.rtl.pairs());
    }
    assert_eq!((report.mismatch_lines, report.malformed_lines, report.off_schedule_lines), (0, 0, 0), "{report:?}");
    assert_eq!(outcomes.last().map(|o| o.rtl.matches.len()), Some(hd.n_max), "the generated pair takes every node");
    assert!(report.max_engine_period <= hd.w_max as u64, "{report:?}");
}

/// Lines are paired by frame (the matcher's Pairing): a line that meets the
/// other side's first line of a frame while it is not one itself is a line
/// of the frame before, one more than the other camera sent; it is dropped
/// and flagged (`r_unpaired` or `o_unpaired`, on either side), and the
/// next frame is paired from its first line, each pair matched as golden
/// matches it. Tsukuba rows 140..146 as two frames of three rows, with one
/// row more in the first frame on one side, then on the other.
#[test]
fn a_line_more_on_either_side_is_dropped_unpaired_and_the_next_frame_is_paired_from_its_first_line() {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
    let all = image_lines(&data.left, &data.right);
    let dispmax = 16 * PX;
    let frame = |rows: std::ops::Range<usize>| -> Vec<(MatchLine, MatchLine)> {
        let mut lines: Vec<(MatchLine, MatchLine)> = all[rows].to_vec();
        for (k, (l, r)) in lines.iter_mut().enumerate() {
            (l.sof, r.sof) = (k == 0, k == 0);
        }
        lines
    };
    let (a, b) = (frame(140..143), frame(143..146));
    let extra = all[150].clone();
    for extra_on_reference in [false, true] {
        let mut refs: Vec<MatchLine> = a.iter().map(|p| p.0.clone()).collect();
        let mut others: Vec<MatchLine> = a.iter().map(|p| p.1.clone()).collect();
        if extra_on_reference {
            refs.push(MatchLine { sof: false, ..extra.0.clone() });
        } else {
            others.push(MatchLine { sof: false, ..extra.1.clone() });
        }
        refs.extend(b.iter().map(|p| p.0.clone()));
        others.extend(b.iter().map(|p| p.1.clone()));
        let mut sim = MatcherSim::<CELLS>::new(GainRule::Robust, dispmax);
        let (got, r_unpaired, o_unpaired) = sim.run_sides(&refs, &others, 2_000);
        let what = if extra_on_reference { "a reference line more" } else { "an other line more" };
        assert_eq!((r_unpaired, o_unpaired), if extra_on_reference { (1, 0) } else { (0, 1) }, "{what}: the extra line flagged on its side, once");
        assert_eq!(got.len(), a.len() + b.len(), "{what}: one line out per pair, none for the extra line");
        for (k, ((l, r), g)) in a.iter().chain(&b).zip(&got).enumerate() {
            let want = golden_match(l, r, dispmax, GainRule::Robust);
            assert!(!want.nodes.is_empty(), "{what}, pair {k}: the rows match");
            assert_eq!(g.pairs(), want.nodes, "{what}, pair {k}: matched with its own partner");
            assert_eq!(g.marker.sof, k == 0 || k == a.len(), "{what}, pair {k}: the frame's first line starts the frame");
        }
    }
}

/// Frame starts are paired by time (the matcher's Pairing): a line that
/// starts a frame on one side only (its camera restarted the frame and the
/// other camera's restart line was lost) meets the other side's next frame
/// start. Their stamps more than `SOF_SKEW_MAX` clocks apart (in ticks of
/// `2^STAMP_SHIFT`), the older is dropped and flagged on its side, and the
/// next frame is paired from its first line, each pair as golden matches
/// it. Two frame starts exactly `SOF_SKEW_MAX` apart (either side the
/// later) are paired and nothing is dropped. The stamps are compared
/// modulo `2^STAMP_BITS`: the same holds across the wrap. Tsukuba rows: a
/// restart line, then a frame of three rows.
#[test]
fn a_frame_start_more_than_the_skew_bound_older_than_the_other_cameras_is_dropped_and_one_within_it_paired() {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
    let all = image_lines(&data.left, &data.right);
    let dispmax = 16 * PX;
    let skew_ticks = (SOF_SKEW_MAX >> STAMP_SHIFT) as u32;
    let wrap = 1u32 << STAMP_BITS;
    let restart = all[120].clone();
    for on_reference in [false, true] {
        for base in [1000u32, wrap - 3] {
            for apart in [skew_ticks, skew_ticks + 1] {
                let side = if on_reference { "reference" } else { "other" };
                let stamp = |ticks: u32| (base + ticks) % wrap;
                // The frame, its lines stamped `apart` ticks after `base` on
                // both sides, or, within the bound, on the `side` only.
                let within = apart <= skew_ticks;
                let frame: Vec<(MatchLine, MatchLine)> = all[140..143]
                    .iter()
                    .enumerate()
                    .map(|(k, (l, r))| {
                        let (tl, tr) = match (within, on_reference) {
                            (false, _) => (stamp(apart + 5 * k as u32), stamp(apart + 5 * k as u32)),
                            (true, true) => (stamp(apart + 5 * k as u32), stamp(5 * k as u32)),
                            (true, false) => (stamp(5 * k as u32), stamp(apart + 5 * k as u32)),
                        };
                        (MatchLine { sof: k == 0, stamp: tl, ..l.clone() }, MatchLine { sof: k == 0, stamp: tr, ..r.clone() })
                    })
                    .collect();
                let mut refs: Vec<MatchLine> = Vec::new();
                let mut others: Vec<MatchLine> = Vec::new();
                let what = if within {
                    format!("the {side} side's frame start {apart} ticks after the other's, from stamp {base}")
                } else {
                    if on_reference {
                        refs.push(MatchLine { sof: true, stamp: stamp(0), ..restart.0.clone() });
                    } else {
                        others.push(MatchLine { sof: true, stamp: stamp(0), ..restart.1.clone() });
                    }
                    format!("a restart on the {side} side at stamp {base}, both cameras' next frame {apart} ticks later")
                };
                refs.extend(frame.iter().map(|p| p.0.clone()));
                others.extend(frame.iter().map(|p| p.1.clone()));
                let mut sim = MatcherSim::<CELLS>::new(GainRule::Robust, dispmax);
                let (got, r_unpaired, o_unpaired) = sim.run_sides(&refs, &others, 2_000);
                let dropped = match (within, on_reference) {
                    (true, _) => (0, 0),
                    (false, true) => (1, 0),
                    (false, false) => (0, 1),
                };
                assert_eq!((r_unpaired, o_unpaired), dropped, "{what}: (reference, other) lines dropped");
                assert_eq!(got.len(), frame.len(), "{what}: one line out per pair of the frame");
                for (k, ((l, r), g)) in frame.iter().zip(&got).enumerate() {
                    assert_eq!(g.pairs(), golden_match(l, r, dispmax, GainRule::Robust).nodes, "{what}, pair {k}: matched with its own partner");
                    assert_eq!(g.marker.sof, k == 0, "{what}, pair {k}");
                }
            }
        }
    }
}
