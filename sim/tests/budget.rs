//! `declivity budget` against the hardware: the per-stage clock numbers of
//! `sim::budget` equal the clocks measured by simulating the rtl detector,
//! matcher and interpolator for several sizes (the matcher's worst line
//! included, on the sensor's 32-cell array, alone and back to back on the
//! matcher's schedule); the whole line processor's
//! latency (first pixel in → first disparity out), its output's span
//! (first → last disparity out: the output rows a line period apart, then
//! the frame's end) and its flush equal the budget's formulas on frames of
//! several sizes whose rows' work is known; its memory sizes and `DP16KD`s
//! equal those of the generated Verilog; its frame arithmetic equals
//! numbers worked out by hand (the CLI's refusals are in `cli/tests/budget.rs`).

use std::sync::{Arc, Mutex};

use rtl::matcher::declivity_matcher::{line_cycles, line_period, schedule, sweep_cycles, DeclivityMatcher, EngineLine, GainRule, TAKE_AFTER_MARKER};
use rtl::params::{DT_FRAC_BITS, N_CELLS, N_MAX, POS_FRAC_BITS, W_MAX};
use rtl::post::row_check::ROW_FIRST_LAG;
use rtl::stream::skid_buffer::SKID_LAG;
use rtl::stereo_line_processor::CHECK_REGISTER_LAG;
use rtl::post::depth_stage::DepthCamera;
use rtl::matcher::traceback::traceback_cycles;
use sim::budget::{budget, budget_with_load, Budget, BudgetRequest, RowLoad, StageBudget};
use sim::rng::VectorRng;
use sim::drive::detector::{run_lines, DetectorSim};
use sim::drive::matcher::{golden_match, MatchLine, MatchRecord, MatcherSim};

/// One pixel of a matcher position (`POS_FRAC_BITS` fraction bits).
const PX: u32 = 1 << POS_FRAC_BITS;

fn stage<'a>(b: &'a Budget, name: &str) -> &'a StageBudget {
    b.stages.iter().find(|s| s.name == name).unwrap_or_else(|| panic!("no stage {name} in {:?}", b.stages))
}

fn request(width: usize, n: usize, cells: usize) -> BudgetRequest {
    BudgetRequest { cells, ..BudgetRequest::new(width, 480, n, 64.0, 125.0) }
}

// ===========================================================================
// The detector
// ===========================================================================

/// A textured line: steps of random height every few pixels, with noise.
fn textured_line(next: &mut impl FnMut() -> u64, width: usize) -> Vec<u8> {
    let mut level = 128i32;
    (0..width)
        .map(|x| {
            if x % 9 == 0 {
                level = 40 + (next() % 176) as i32;
            }
            (level + (next() % 5) as i32 - 2).clamp(0, 255) as u8
        })
        .collect()
}

/// Back-to-back lines per width: the first sees idle engines (its marker
/// latency is the formula's), the later ones the steady state.
const DETECTOR_LINES: usize = 7;
/// Line starts skipped before the steady state: the first line's start is
/// clock 0, and short lines settle one line later.
const DETECTOR_WARM_UP: usize = 2;

/// Widths: shorter than `MIN_LINE_PERIOD` (the σ scan sets the pace), just
/// above it, a real image's, and `W_MAX` (the budget refuses wider lines).
const DETECTOR_WIDTHS: [usize; 4] = [64, 300, 700, W_MAX];

#[test]
fn detector_clocks_measured_in_simulation_equal_the_budget() {
    let mut rng = VectorRng(0x5eed_0001);
    let mut next = || rng.next();
    for width in DETECTOR_WIDTHS {
        let lines: Vec<Vec<u8>> = (0..DETECTOR_LINES).map(|_| textured_line(&mut next, width)).collect();
        let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
        let mut sim = DetectorSim::new();
        let run = run_lines(&mut sim, &refs, |_| false, |_| {}).expect("the detector runs");
        assert_eq!(run.stalls_inside_lines, 0, "W {width}: a stall inside a line");
        let b = budget(&request(width, 16, 8)).expect("a valid request");
        let det = stage(&b, "declivity detector");
        // First pixel in to marker out, engines idle (the first line); the
        // top's register slice in front of the detector is not in the
        // block (the whole line processor's runs below count it).
        let latency = run.lines[0].marker_cycle - run.first_pixel_cycle[0] + SKID_LAG as u64;
        assert_eq!(latency, det.latency_cycles, "W {width}: first pixel → marker ({})", det.latency_formula);
        // Steady state: the most clocks between consecutive line starts.
        let spacing = run.first_pixel_cycle.windows(2).skip(DETECTOR_WARM_UP).map(|w| w[1] - w[0]).max().expect("lines");
        assert_eq!(spacing, det.cycles_per_line, "W {width}: line starts {:?} ({})", run.first_pixel_cycle, det.formula);
        // The input is held exactly when the detector needs more than W.
        assert_eq!(run.stall_cycles > 0, det.cycles_per_line > width as u64, "W {width}: {} stall clocks", run.stall_cycles);
        assert!(run.lines.iter().all(|l| !l.marker.wide), "W {width}: no line flagged wide");
    }
}

// ===========================================================================
// The matcher
// ===========================================================================

/// The matcher's worst line pair for `n` declivities per side: evenly
/// spaced rising steps, the other view the same shifted by 3 px, within a
/// 5 px search bound, so that the optimal path takes every diagonal pair
/// and stops on anti-diagonal 0 (checked against golden below).
fn worst_pair(n: usize) -> (MatchLine, MatchLine) {
    let (left, right) = ([100, 110, 120], [150, 160, 170]);
    let records = (0..n as u32).map(|k| MatchRecord { pos: PX * (40 + 7 * k), amplitude: 50, left, right }).collect();
    let reference = MatchLine { dt: 400, records, ..MatchLine::default() };
    let other = MatchLine {
        records: reference.records.iter().map(|r| MatchRecord { pos: r.pos - 3 * PX, ..*r }).collect(),
        ..reference.clone()
    };
    (reference, other)
}

/// Search bound of [`worst_pair`]: 5 px.
const WORST_DISPMAX: u32 = 5 * PX;

/// A line of `n` random declivities (both polarities, random levels).
fn random_line(next: &mut impl FnMut() -> u64, n: usize) -> MatchLine {
    let mut pos = 0u32;
    let records = (0..n)
        .map(|_| {
            pos += PX + (next() % (12 * PX as u64)) as u32;
            let amplitude = if next().is_multiple_of(3) { -45 } else { 45 };
            let mut level = || 90 + (next() % 60) as u8;
            MatchRecord { pos, amplitude, left: [level(), level(), level()], right: [level(), level(), level()] }
        })
        .collect();
    MatchLine { dt: 20 << DT_FRAC_BITS, records, ..MatchLine::default() }
}

/// What the simulation shows of one line pair.
#[derive(Debug)]
struct Measured {
    n: usize,
    m: usize,
    /// Golden's path (the rtl's, checked): matches and the anti-diagonal it
    /// stops on.
    k: usize,
    stop_diag: usize,
    /// Clock of the pair's second marker taken on the ports.
    input_done: u64,
    /// Clock of its last match on the outputs (`None` without matches).
    last_match: Option<u64>,
    /// Clock of its marker on the outputs.
    marker: u64,
}

/// Runs `pairs` back to back through a matcher of `N` cells (each side's
/// records offered as soon as it is ready), recording the clock of every
/// output beat, and measures each pair.
fn measure<const N: usize>(pairs: &[(MatchLine, MatchLine)], dispmax: u32) -> Vec<Measured> {
    let beats: Arc<Mutex<Vec<(u64, bool)>>> = Arc::default();
    let mut sim = MatcherSim::<N>::new(GainRule::Robust, dispmax);
    let (log, mut clock) = (beats.clone(), 0u64);
    sim.observer = Some(Box::new(move |u: &DeclivityMatcher<N>| {
        if u.m_valid.val() {
            log.lock().expect("the beat log").push((clock, u.m_last.val()));
        }
        clock += 1;
    }));
    let got = sim.run(pairs, false, || {});
    let beats = beats.lock().expect("the beat log").clone();
    pairs
        .iter()
        .zip(&got)
        .enumerate()
        .map(|(p, ((r, o), line))| {
            let want = golden_match(r, o, dispmax, GainRule::Robust);
            assert_eq!(line.pairs(), want.nodes, "pair {p}: the rtl path is golden's");
            let at = beats.iter().position(|&(c, last)| last && c == line.marker_cycle).expect("the marker's beat");
            let last_match = at.checked_sub(1).map(|i| beats[i]).filter(|b| !b.1).map(|b| b.0);
            assert_eq!(last_match.is_some(), !want.nodes.is_empty(), "pair {p}: matches before the marker");
            Measured {
                n: r.records.len(),
                m: o.records.len(),
                k: want.nodes.len(),
                stop_diag: want.stop_diag,
                input_done: line.input_done_cycle,
                last_match,
                marker: line.marker_cycle,
            }
        })
        .collect()
}

/// The engine's lines of measured pairs on `cells` cells: each one's
/// second marker, its sweep and its traceback.
fn engine_lines(got: &[Measured], cells: usize) -> Vec<EngineLine> {
    got.iter()
        .map(|g| EngineLine {
            input_done: g.input_done,
            sweep: sweep_cycles(g.n, g.m, cells) as u64,
            traceback: traceback_cycles(g.n, g.m, g.stop_diag, g.k) as u64,
        })
        .collect()
}

/// The worst line of `n` declivities on `N` cells, twice back to back:
/// the first, taken by an idle engine, shows the latency; the second,
/// loaded while the engine sweeps the first, is taken the clock after the
/// first's traceback starts and its traceback starts when its sweep ends
/// (`rtl::matcher::declivity_matcher::schedule`), so the spacing of the two markers
/// is the engine's clocks per line back to back, `line_period`. Both equal
/// the budget's.
fn check_worst_line<const N: usize>(n: usize) -> Budget {
    let pair = worst_pair(n);
    let got = measure::<N>(&[pair.clone(), pair], WORST_DISPMAX);
    let (first, second) = (&got[0], &got[1]);
    assert_eq!((first.n, first.m, first.k, first.stop_diag), (n, n, n, 0), "the worst path: every pair, stop on anti-diagonal 0");
    let times = schedule(&engine_lines(&got, N));
    assert_eq!((first.marker, second.marker), (times[0].marker, times[1].marker), "{N} cells, N = {n}: the markers on the documented schedule");
    assert_eq!(times[0].take, first.input_done + TAKE_AFTER_MARKER, "the first pair taken by an idle engine");
    assert_eq!(times[1].take, times[0].start + 1, "the second pair waits for the engine: taken the clock after the first's traceback starts");
    assert!(second.input_done + TAKE_AFTER_MARKER < times[1].take, "the second pair is in before the engine takes it");
    let b = budget(&request(W_MAX, n, N)).expect("a valid request");
    let m = stage(&b, "matcher");
    let latency = first.marker - first.input_done;
    assert_eq!(latency, TAKE_AFTER_MARKER + line_cycles(n, n, 0, n, N) as u64, "alone: TAKE_AFTER_MARKER + line_cycles");
    assert_eq!(latency, m.latency_cycles, "{N} cells, N = {n}: second marker → the pair's marker ({})", m.latency_formula);
    assert_eq!(first.last_match.expect("matches") + 1, first.marker, "the last match leaves the clock before the marker");
    assert_eq!(second.marker - first.marker, line_period(n, n, 0, n, N) as u64, "back to back: line_period");
    assert_eq!(second.marker - first.marker, m.cycles_per_line, "{N} cells, N = {n}: back-to-back markers ({})", m.formula);
    assert_eq!(m.pe_count, Some(N));
    eprintln!("{N} cells, N = {n}: alone {latency} clocks, back to back {} ({})", m.cycles_per_line, m.formula);
    b
}

#[test]
fn matcher_worst_line_clocks_measured_in_simulation_equal_the_budget_on_small_arrays() {
    // Two phases without the second (n within the cells' first rows) and
    // with it (n = 2·K), four phases with the last row's cell early (the
    // phase before's last row ends the sweep) and late (n = 4·K, its own
    // ends it), and a 16-cell array full on two phases.
    check_worst_line::<8>(5);
    check_worst_line::<8>(16);
    check_worst_line::<8>(27);
    check_worst_line::<8>(32);
    check_worst_line::<16>(32);
}

/// The sensor's matcher, 32 cells of four rows, on its worst line: n = m =
/// N_MAX (four phases).
#[test]
fn matcher_worst_line_of_n_max_on_the_sensors_32_cells_equals_the_budget() {
    assert_eq!(N_CELLS, 32, "the sensor's array");
    let b = check_worst_line::<N_CELLS>(N_MAX);
    let m = stage(&b, "matcher");
    // 845 clocks back to back, 3 + 1239 alone (rtl::matcher::declivity_matcher's
    // doc and tests/rtl_matcher.rs).
    assert_eq!((m.cycles_per_line, m.latency_cycles), (845, 3 + 1239));
    // The worst line fits the line time of a W_MAX line without blanking;
    // the row check's bound for rows of N_MAX matches (1160, see
    // a_stage_slower_than_the_input_sets_the_period) does not: 136 clocks.
    assert!(m.cycles_per_line <= W_MAX as u64);
    assert_eq!(b.stall_cycles_per_line, 1160 - W_MAX as u64);
}

/// Random line pairs of several sizes (two phases and four), back to back:
/// every marker leaves when the matcher's schedule
/// (`rtl::matcher::declivity_matcher::schedule`: the pair taken `TAKE_AFTER_MARKER`
/// after its second marker or the clock after the previous traceback
/// starts, its traceback started when its sweep and the previous traceback
/// are over) says; and no pair costs more than the budget's worst line for
/// `N = max(n, m)`, alone or back to back.
#[test]
fn matcher_clocks_of_random_pairs_follow_the_schedule_and_stay_within_the_worst() {
    const CELLS: usize = 8;
    let mut rng = VectorRng(0x5eed_0002);
    let mut next = || rng.next();
    let sizes = [
        (1, 1),
        (3, 7),
        (7, 3),
        (8, 8),
        (9, 2),
        (12, 16),
        (16, 11),
        (20, 9),
        (16, 16),
        (0, 5),
        (4, 0),
        (2, 2),
        (32, 30),
        (25, 3),
        (16, 1),
        // Light lines right after a heavy one: their sweeps end before the
        // heavy line's traceback, so their tracebacks wait for it.
        (32, 32),
        (1, 2),
        (2, 1),
    ];
    let pairs: Vec<(MatchLine, MatchLine)> =
        sizes.iter().map(|&(n, m)| (random_line(&mut next, n), random_line(&mut next, m))).collect();
    let got = measure::<CELLS>(&pairs, 40 * PX);
    let times = schedule(&engine_lines(&got, CELLS));
    let (mut waited, mut walk_waited) = (0, 0);
    for ((g, t), &(n, m)) in got.iter().zip(&times).zip(&sizes) {
        assert_eq!((g.n, g.m), (n, m));
        assert_eq!(g.marker, t.marker, "n {n} m {m} k {} stop {}: {t:?}", g.k, g.stop_diag);
        waited += (t.take > g.input_done + TAKE_AFTER_MARKER) as usize;
        walk_waited += (t.start > t.take + sweep_cycles(n, m, CELLS) as u64) as usize;
        let b = budget(&request(W_MAX, n.max(m).max(1), CELLS)).expect("valid");
        let worst = stage(&b, "matcher");
        let period = line_period(n, m, g.stop_diag, g.k, CELLS) as u64;
        assert!(period <= worst.cycles_per_line, "n {n} m {m}: {period} > worst {}", worst.cycles_per_line);
        let alone = TAKE_AFTER_MARKER + line_cycles(n, m, g.stop_diag, g.k, CELLS) as u64;
        assert!(alone <= worst.latency_cycles, "n {n} m {m}: {alone} > worst {}", worst.latency_cycles);
    }
    assert!(waited >= 3, "pairs taken back to back: {waited}");
    assert!(walk_waited >= 1, "a traceback waited for the one before: {walk_waited}");
    eprintln!("{waited} of {} pairs waited for the engine, {walk_waited} tracebacks for the one before", sizes.len());
}

// ===========================================================================
// The stages' latencies on their blocks
// ===========================================================================

/// The detector's, matcher's and interpolator's latencies in the budget are
/// the clocks measured on their blocks: first pixel → marker, the pair's
/// second marker → its marker, and the marker → the line's first pixel (the
/// row check's marker, as the interpolator takes the row check's stream,
/// through the top's `CHECK_REGISTER_LAG`).
#[test]
fn stage_latencies_equal_the_clocks_measured_on_their_blocks() {
    const CELLS: usize = 8;
    let (width, n) = (700, 16);
    let mut rng = VectorRng(0x5eed_0003);
    let mut next = || rng.next();
    let line = textured_line(&mut next, width);
    let mut sim = DetectorSim::new();
    let run = run_lines(&mut sim, &[line.as_slice()], |_| false, |_| {}).expect("the detector runs");
    let detector = run.lines[0].marker_cycle - run.first_pixel_cycle[0];
    let pair = &measure::<CELLS>(&[worst_pair(n)], WORST_DISPMAX)[0];
    let matcher = pair.marker - pair.input_done;
    let line = sim::drive::interpolator::AnchorLine {
        anchors: vec![sim::drive::interpolator::FixedAnchor { x: 100, d: 40 }, sim::drive::interpolator::FixedAnchor { x: 5000, d: 90 }],
        width,
        sof: true,
    };
    let mut interp = sim::drive::interpolator::InterpolatorSim::robust();
    let (lines, markers) = interp.run(&[line], 0);
    let interpolator = lines[0].first_cycle - markers[0];
    assert_eq!(lines[0].last_cycle - lines[0].first_cycle, width as u64 - 1, "one pixel a clock");
    let b = budget(&BudgetRequest { height: 100, ..request(width, n, CELLS) }).expect("valid");
    // The top's registers between the row check and the interpolator and
    // in front of the detector are not in the blocks: the whole line
    // processor's runs below count them.
    let interpolator = interpolator + CHECK_REGISTER_LAG as u64;
    let detector = detector + SKID_LAG as u64;
    for (name, measured) in [("declivity detector", detector), ("matcher", matcher), ("interpolator", interpolator)] {
        let s = stage(&b, name);
        assert_eq!(measured, s.latency_cycles, "{name}: {} ({})", s.latency_span, s.latency_formula);
    }
}

// ===========================================================================
// The whole line processor
// ===========================================================================

/// The line processor's array for these tests (16 reference rows).
const TOP_CELLS: usize = 8;
/// Their search bound: 16 px.
const TOP_DISPMAX: u32 = 16 * PX;
/// Their disparity: the right view is the left shifted by 3 px.
const TOP_SHIFT: usize = 3;

/// Which rows of a test frame carry steps.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Rows {
    /// Every row the same `steps` steps.
    All,
    /// The odd rows; the even rows flat (no declivity, so no match).
    Odd,
}

/// A `w × h` pair whose textured rows (`rows`) are flat with `steps`
/// vertical edges of 110 grey levels, alternately up and down, evenly
/// spaced: `steps` declivities per textured line in each view, the right
/// view the left shifted by [`TOP_SHIFT`] px.
fn stepped_pair(w: usize, h: usize, steps: usize, rows: Rows) -> (golden::GreyImage, golden::GreyImage) {
    let gap = (w - TOP_SHIFT - 8) / (steps + 1);
    let (mut left, mut right) = (Vec::with_capacity(w * h), Vec::with_capacity(w * h));
    for y in 0..h {
        let textured = rows == Rows::All || y % 2 == 1;
        let scene: Vec<u8> = (0..w + TOP_SHIFT)
            .map(|x| {
                let edges = if textured && x >= 4 { ((x - 4) / gap).min(steps) } else { 0 };
                if edges % 2 == 0 {
                    70
                } else {
                    180
                }
            })
            .collect();
        left.extend_from_slice(&scene[..w]);
        right.extend_from_slice(&scene[TOP_SHIFT..]);
    }
    (golden::GreyImage::new(w, h, left).expect("a pair"), golden::GreyImage::new(w, h, right).expect("a pair"))
}

/// What a frame's rows cost the matcher and the row check, from the blocks'
/// own models: each row's line pair as the detectors send it
/// (`sim::drive::matcher::image_lines`), golden's path through it (the matcher's,
/// by `matcher_*` tests above), and the row check's clocks for each row,
/// measured by simulating the rtl row check on the frame's matches. Also
/// the declivities per textured line in each view.
fn frame_load(left: &golden::GreyImage, right: &golden::GreyImage) -> (RowLoad, Vec<(usize, usize)>) {
    let h = left.height();
    let lines = sim::drive::matcher::image_lines(left, right);
    let paths: Vec<_> = lines.iter().map(|(r, o)| golden_match(r, o, TOP_DISPMAX, GainRule::Robust)).collect();
    let counts: Vec<(usize, usize)> = lines.iter().map(|(r, o)| (r.records.len(), o.records.len())).collect();
    let line_of = |y: usize| (counts[y].0, counts[y].1, paths[y].stop_diag, paths[y].nodes.len());
    // The latency takes row 3's line, the frame's end row H - 1's: one load
    // holds both only if they are alike.
    assert_eq!(line_of(3), line_of(h - 1), "rows 3 and H - 1 match alike");
    let frame: Vec<Vec<sim::drive::row_check::FixedMatch>> = lines
        .iter()
        .zip(&paths)
        .map(|((r, o), g)| g.nodes.iter().map(|&(i, j)| (r.records[i].pos as u64, (r.records[i].pos - o.records[j].pos) as u64)).collect())
        .collect();
    // Rows a line period of the widest apart: each row is checked alone.
    let run = sim::drive::row_check::RowCheckSim::new().run(&frame, rtl::post::row_check::row_check_period());
    assert_eq!(run.rows.len(), h, "every row checked");
    // Row y < H - 1 starts ROW_START_LAG after row y + 1's marker in, the
    // last ROW_RESTART_LAG after row H - 2 finished; each marker leaves the
    // clock after its row's finish.
    let start_lag = rtl::post::row_check::ROW_START_LAG as u64;
    let restart_lag = rtl::post::row_check::ROW_RESTART_LAG as u64;
    let check = |y: usize| (run.rows[y].marker_cycle - run.markers[y + 1] - start_lag - 1) as usize;
    let last_check = (run.rows[h - 1].marker_cycle - run.rows[h - 2].marker_cycle - restart_lag) as usize;
    assert_eq!(check(2), check(h - 2), "rows 2 and H - 2 checked alike");
    let (n, m, stop_diag, k) = line_of(3);
    (RowLoad { n, m, stop_diag, k, check: check(2), first_check: check(0), last_check }, counts)
}

/// One frame through the line processor against the budget for its rows:
/// returns (measured, budgeted) first pixel in → first disparity out.
fn check_frame(w: usize, h: usize, steps: usize, rows: Rows, hblank: usize) -> (u64, u64) {
    let (left, right) = stepped_pair(w, h, steps, rows);
    let (load, counts) = frame_load(&left, &right);
    for (y, &(n, m)) in counts.iter().enumerate() {
        let want = if rows == Rows::All || y % 2 == 1 { steps } else { 0 };
        assert_eq!((n, m), (want, want), "W {w}: row {y}'s declivities");
    }
    assert_eq!((load.k, load.stop_diag), (steps, 0), "W {w}: every step matched, the path down to (0, 0)");
    let mut sim = sim::drive::stereo::StereoSim::<TOP_CELLS>::new(GainRule::Robust, Some(rtl::params::EDGE_JUMP_LSB), DepthCamera::default(), TOP_DISPMAX)
        .expect("the default camera");
    let run = sim.run(&left, &right, hblank, |_| {});
    let what = format!("W {w} H {h} {rows:?} hblank {hblank}, {load:?}");
    assert_eq!(run.rows.len(), h, "{what}: every row out");
    assert!(run.rows.iter().all(|r| r.len() == w), "{what}: rows of W pixels");
    assert_eq!(
        (run.records_dropped, run.lines_dropped, run.pixels_dropped, run.lines_full, run.lines_wide),
        (0, 0, 0, 0, 0),
        "{what}: nothing dropped"
    );
    let r = BudgetRequest { hblank, cells: TOP_CELLS, ..BudgetRequest::new(w, h, steps.max(1), TOP_DISPMAX as f64 / PX as f64, 125.0) };
    let b = budget_with_load(&r, &load).expect("valid");
    // The rows come every P: the input's, or the detector's for short lines.
    let det = stage(&b, "declivity detector").cycles_per_line;
    assert_eq!(b.line_period_cycles, det.max((w + hblank) as u64), "{what}: no stage slower than the input");
    let latency = run.latency_cycles().expect("a disparity out");
    assert_eq!(latency, b.latency_cycles, "{what}: first pixel in → first disparity out ({})", b.latency_formula);
    // Output rows 0 … H − 6 one a line period, then the frame's end.
    let (first_out, last_out) = (run.first_out.expect("out"), run.last_out.expect("out"));
    assert_eq!(last_out - first_out, b.output_span_cycles, "{what}: first → last disparity out ({})", b.output_span_formula);
    assert_eq!(run.last_in - run.first_in, b.last_in_cycle, "{what}: the frame's last pixel in");
    assert_eq!(last_out - run.last_in, b.flush_cycles, "{what}: last pixel in → last disparity out");
    // The input is held only by the detector, for short lines.
    assert_eq!(run.stall_cycles, b.last_in_cycle - ((h - 1) * (w + hblank) + w - 1) as u64, "{what}: input stalls");
    eprintln!(
        "{what}: latency {latency} (budget {}), first → last out {} (budget {}), flush {} (budget {}), P {}",
        b.latency_cycles,
        last_out - first_out,
        b.output_span_cycles,
        last_out - run.last_in,
        b.flush_cycles,
        b.line_period_cycles
    );
    // The budget for the worst rows of as many declivities bounds it.
    let worst = budget(&r).expect("valid");
    assert!(latency <= worst.latency_cycles && last_out - first_out <= worst.output_span_cycles, "{what}: within the worst");
    (latency, b.latency_cycles)
}

/// Frames of odd rows with steps, even rows flat: the row check's clocks
/// are the doc's exact ones (1 for an empty row, `n + ROW_FIRST_LAG − 1`
/// for a row whose neighbours have no match), so every term is rtl's by name. Widths below
/// `MIN_LINE_PERIOD` (the detector sets the line period and holds the
/// input) and above.
#[test]
fn line_processor_latency_and_frame_end_equal_the_budget_for_rows_with_flat_neighbours() {
    for (w, steps) in [(64, 3), (128, 5), (300, 6)] {
        let (left, right) = stepped_pair(w, 6, steps, Rows::Odd);
        let (load, _) = frame_load(&left, &right);
        assert_eq!((load.check, load.last_check), (1, steps + ROW_FIRST_LAG - 1), "W {w}: the row check's exact clocks");
        check_frame(w, 6, steps, Rows::Odd, 0);
    }
}

/// Frames whose rows are all alike (the row check's clocks within
/// `row_check_cycles`, measured on the block), with and without hblank;
/// lines of up to `2·TOP_CELLS` = 16 declivities take the matcher's two
/// phases, 20 its four.
#[test]
fn line_processor_latency_and_frame_end_equal_the_budget_for_rows_alike() {
    for (w, h, steps, hblank) in [(64, 9, 4, 0), (128, 8, 7, 0), (300, 6, 16, 0), (300, 6, 20, 0), (300, 7, 9, 37)] {
        let (left, right) = stepped_pair(w, h, steps, Rows::All);
        let (load, _) = frame_load(&left, &right);
        let bound = rtl::post::row_check::row_check_cycles(steps, steps, steps);
        assert!(load.check <= bound && load.last_check <= rtl::post::row_check::row_check_cycles(steps, steps, 0), "W {w}: {load:?}");
        check_frame(w, h, steps, Rows::All, hblank);
    }
}

/// `reg[A:0] mem[B:0];` declarations of a Verilog text (RAMs; ROMs write
/// `mem [B:0]`): their bits.
fn verilog_memory_bits(v: &str) -> usize {
    v.lines()
        .filter_map(|l| {
            let t = l.trim().trim_start_matches("(* no_rw_check *)").trim();
            let rest = t.strip_prefix("reg[")?;
            let (hi, rest) = rest.split_once(":0] mem[").or_else(|| rest.split_once(":0] mem ["))?;
            let (depth, _) = rest.split_once(":0];")?;
            Some((hi.parse::<usize>().ok()? + 1) * (depth.parse::<usize>().ok()? + 1))
        })
        .sum()
}

/// `DP16KD` instances of a Verilog text (`rtl::primitives::block_ram::BlockRam`).
fn verilog_dp16kd(v: &str) -> usize {
    v.matches("DP16KD #(").count()
}

/// The budget's memories are those of the generated Verilog: two
/// detectors, the sensor's matcher and the interpolator, each alone; and
/// the line processor's (on 8 cells, beside the 8-cell matcher) beyond
/// those blocks are the record queues', the row check's, the median's and
/// the depth stage's. The same for the `DP16KD`s the blocks instantiate.
#[test]
fn memory_sizes_equal_the_memories_of_the_generated_verilog() {
    use sim::hdl::verilog::{generate, generate_with, Top};
    let b = budget(&request(512, N_MAX, N_CELLS)).expect("valid");
    let (det_v, mat_v, int_v) = (generate(sim::Config::Sd, Top::Detector), generate(sim::Config::Sd, Top::Matcher), generate(sim::Config::Sd, Top::Interpolator));
    let (detector, matcher, interpolator) = (verilog_memory_bits(&det_v), verilog_memory_bits(&mat_v), verilog_memory_bits(&int_v));
    assert!(detector > 0 && matcher > 0 && interpolator > 0, "memories found");
    let r = &b.resources;
    let of = |stages: &[&str], f: fn(&sim::budget::Memory) -> usize| {
        r.memories.iter().filter(|m| stages.contains(&m.stage)).map(f).sum::<usize>()
    };
    let bits = |m: &sim::budget::Memory| m.bits;
    let rams = |m: &sim::budget::Memory| m.dp16kd.unwrap_or(0);
    assert_eq!(2 * detector, r.line_buffer_bits + r.histogram_bits, "two detectors");
    assert_eq!(matcher, of(&["matcher"], bits));
    assert_eq!(interpolator, of(&["interpolator"], bits));
    assert_eq!(2 * verilog_dp16kd(&det_v), of(&["declivity detector"], rams), "two detectors");
    assert_eq!(verilog_dp16kd(&mat_v), of(&["matcher"], rams));
    assert_eq!(verilog_dp16kd(&int_v), of(&["interpolator"], rams));
    let new_stages = ["record queues", "row check", "vertical median", "depth stage"];
    let rule = GainRule::default();
    let top = generate_with(sim::Config::Sd, Top::Stereo, 8, rule).expect("8 cells");
    let matcher8 = generate_with(sim::Config::Sd, Top::Matcher, 8, rule).expect("8 cells");
    let beyond = |f: fn(&str) -> usize| f(&top) - f(&matcher8) - 2 * f(&det_v) - f(&int_v);
    assert_eq!(beyond(verilog_memory_bits), of(&new_stages, bits), "{:#?}", r.memories);
    assert_eq!(beyond(verilog_dp16kd), of(&new_stages, rams));
    assert_eq!(r.memory_bits, 2 * detector + matcher + interpolator + beyond(verilog_memory_bits));
    assert_eq!(r.dp16kd_instances, 2 * verilog_dp16kd(&det_v) + verilog_dp16kd(&mat_v) + verilog_dp16kd(&int_v) + beyond(verilog_dp16kd));
    assert_eq!((r.line_buffers, r.histogram_banks, r.pe_count, r.rows_per_cell, r.median_line_buffers), (2, 4, 32, 4, 8));
    // The cells' rows in LUT RAM: the primitives the matcher instantiates,
    // 16 bits used of each (4 words of 4 bits), the last of each RAM partly.
    assert_eq!(mat_v.matches("TRELLIS_DPR16X4 #(").count(), r.reference_row_dpr16x4);
    assert!(r.reference_row_bits <= 16 * r.reference_row_dpr16x4 && r.reference_row_bits > 16 * (r.reference_row_dpr16x4 - 2 * r.pe_count));
}

// ===========================================================================
// Frame arithmetic, worked out by hand
// ===========================================================================

/// 512×512 at 125 MHz, hblank 88, N = 16 on 8 cells: every stage's worst
/// line is below 600 clocks, so the line period is the input's
/// 512 + 88 = 600 clocks. The vertical blanking: the last row's check
/// (row_check_cycles(16, 16, 0) = 6 + 16 + 16 + 6·16 = 134), the row
/// before the flush and the median's flush of four rows take
/// max(134 + 2, 512) + 5·512 = 3072 clocks, and the first row's check is
/// 16 clocks faster than a row's inside (150 − 134): ⌈3088 / 600⌉ − 2 = 4
/// lines. A frame is (512 + 4) × 600 = 309 600 clocks = 2.4768 ms, 403.7
/// frames/s.
#[test]
fn frame_time_of_512_by_512_at_125_mhz_with_an_input_bound_line_period() {
    let b = budget(&BudgetRequest { hblank: 88, cells: 8, ..BudgetRequest::new(512, 512, 16, 64.0, 125.0) }).expect("valid");
    assert!(b.stages.iter().all(|s| s.cycles_per_line < 600), "{:?}", b.stages);
    assert_eq!(b.line_period_cycles, 600);
    assert_eq!(b.stall_cycles_per_line, 0);
    assert_eq!((b.load.check, b.load.first_check, b.load.last_check), (150, 134, 134));
    assert_eq!(b.vblank_lines, 4, "{}", b.vblank_formula);
    assert_eq!(b.frame_cycles, 309_600);
    assert!((b.frame_time_ms - 2.4768).abs() < 1e-9, "{}", b.frame_time_ms);
    assert!((b.fps - 1000.0 / 2.4768).abs() < 1e-9, "{}", b.fps);
    // Output rows 0 … H − 6 a line period apart, then the frame's end.
    assert_eq!(b.output_span_cycles, 506 * 600 + 512 + 5 * 512 - 1);
    assert_eq!(b.last_in_cycle, 511 * 600 + 511);
    assert_eq!(b.flush_cycles, b.latency_cycles + b.output_span_cycles - b.last_in_cycle);
}

/// 1024×768 at 125 MHz with the 320 clocks of blanking of XGA timing
/// (1344 clocks per line): the sensor's matcher fits, the period is 1344
/// clocks; the vertical blanking ⌈(1024 + 5·1024 + 900 − 516) / 1344⌉ − 2
/// = 3 lines, a frame (768 + 3) × 1344 = 1 036 224 clocks = 8.289 792 ms.
#[test]
fn frame_time_of_1024_by_768_at_125_mhz_with_xga_blanking() {
    let b = budget(&BudgetRequest { hblank: 320, ..BudgetRequest::new(1024, 768, N_MAX, 64.0, 125.0) }).expect("valid");
    assert_eq!(b.line_period_cycles, 1344);
    assert_eq!(b.vblank_lines, 3, "{}", b.vblank_formula);
    assert_eq!(b.frame_cycles, 1_036_224);
    assert!((b.frame_time_ms - 8.289_792).abs() < 1e-9, "{}", b.frame_time_ms);
    assert!((b.fps - 1000.0 / 8.289_792).abs() < 1e-9);
    assert!((b.latency_us - b.latency_cycles as f64 / 125.0).abs() < 1e-12);
}

/// A stage slower than the input sets the period: the input must be paced
/// by the difference, which the least hblank gives, and one clock less
/// leaves the stage a clock behind per line.
#[test]
fn a_stage_slower_than_the_input_sets_the_period() {
    let base = BudgetRequest::new(512, 512, N_MAX, 64.0, 125.0);
    let b = budget(&base).expect("valid");
    let slowest = b.stages.iter().map(|s| s.cycles_per_line).max().expect("stages");
    assert!(slowest > 512, "the sensor's worst line is longer than a 512-pixel line");
    // The row check's bound for rows of N_MAX matches: row_check_period()
    // = row_check_cycles(128, 128, 128) + ROW_RESTART_LAG = (6 + 128 + 256
    // + 6·128) + 2 = 1160, above the matcher's worst line.
    assert_eq!(b.slowest_stage, "row check");
    assert_eq!(slowest, 1160);
    assert!(stage(&b, "matcher").cycles_per_line < slowest);
    assert_eq!(b.line_period_cycles, slowest);
    assert_eq!(b.stall_cycles_per_line, slowest - 512);
    assert_eq!(b.min_hblank_cycles, slowest - 512);
    assert!(b.stages.iter().all(|s| s.spare_cycles == 512 - s.cycles_per_line as i64));
    assert!(b.notes.iter().any(|n| n.contains("row check falls behind") && n.contains("lines_dropped")), "{:?}", b.notes);
    let want_ms = (512 + b.vblank_lines) as f64 * slowest as f64 / 125e6 * 1e3;
    assert!((b.frame_time_ms - want_ms).abs() < 1e-9);
    let h = b.min_hblank_cycles as usize;
    let fits = budget(&BudgetRequest { hblank: h, ..base }).expect("valid");
    assert_eq!((fits.line_period_cycles, fits.stall_cycles_per_line), (slowest, 0));
    let short = budget(&BudgetRequest { hblank: h - 1, ..base }).expect("valid");
    assert_eq!((short.line_period_cycles, short.stall_cycles_per_line), (slowest, 1));
}
