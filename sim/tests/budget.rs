//! `declivity budget` against the hardware: the per-stage clock numbers of
//! `sim::budget` equal the clocks measured by simulating the rtl detector
//! and matcher for several sizes (the matcher's worst line included, on the
//! sensor's 64-cell array); its memory sizes equal the memories of the
//! generated Verilog; its frame arithmetic equals numbers worked out by
//! hand; and the CLI refuses bad sizes with a message that names them.

use std::process::{Command, Output};
use std::sync::{Arc, Mutex};

use rtl::declivity_matcher::{DeclivityMatcher, GainRule, TAKE_AFTER_MARKER};
use rtl::params::{DT_FRAC_BITS, N_CELLS, N_MAX, POS_FRAC_BITS, W_MAX};
use sim::budget::{budget, matcher_cycles_per_line, Budget, BudgetRequest, StageBudget, MARKER_AFTER_NEXT_TAKE};
use sim::cosim::VectorRng;
use sim::detector::{run_lines, DetectorSim};
use sim::matcher::{golden_match, MatchLine, MatchRecord, MatcherSim};

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
/// above it, a real image's, `W_MAX`, and wider than `W_MAX` (the first
/// `W_MAX` pixels processed, the line flagged wide).
const DETECTOR_WIDTHS: [usize; 5] = [64, 300, 700, W_MAX, W_MAX + 100];

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
        // First pixel in to marker out, engines idle (the first line).
        let latency = run.lines[0].marker_cycle - run.first_pixel_cycle[0];
        assert_eq!(latency, det.latency_cycles, "W {width}: first pixel → marker ({})", det.latency_formula);
        // Steady state: the most clocks between consecutive line starts.
        let spacing = run.first_pixel_cycle.windows(2).skip(DETECTOR_WARM_UP).map(|w| w[1] - w[0]).max().expect("lines");
        assert_eq!(spacing, det.cycles_per_line, "W {width}: line starts {:?} ({})", run.first_pixel_cycle, det.formula);
        // The input is held exactly when the detector needs more than W.
        assert_eq!(run.stall_cycles > 0, det.cycles_per_line > width as u64, "W {width}: {} stall clocks", run.stall_cycles);
        let wide = width > W_MAX;
        assert!(run.lines.iter().all(|l| l.marker.wide == wide), "W {width}: wide flags");
        assert_eq!(b.wide, wide);
        if wide {
            assert!(b.notes.iter().any(|n| n.contains("wide")), "W {width}: the budget says the line is cut: {:?}", b.notes);
        }
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

/// The worst line of `n` declivities on `N` cells, twice back to back:
/// the first, taken by an idle engine, shows the latency; the second,
/// loaded while the engine works on the first, is taken as soon as the
/// engine is free, so the spacing of the two markers is the engine's
/// clocks per line. Both equal the budget's.
fn check_worst_line<const N: usize>(n: usize) -> Budget {
    let pair = worst_pair(n);
    let got = measure::<N>(&[pair.clone(), pair], WORST_DISPMAX);
    let (first, second) = (&got[0], &got[1]);
    assert_eq!((first.n, first.m, first.k, first.stop_diag), (n, n, n, 0), "the worst path: every pair, stop on anti-diagonal 0");
    assert!(second.input_done + TAKE_AFTER_MARKER < first.marker - 2, "the second pair waits for the engine");
    let b = budget(&request(W_MAX, n, N)).expect("a valid request");
    let m = stage(&b, "matcher");
    let latency = first.last_match.expect("matches") - first.input_done;
    assert_eq!(latency, m.latency_cycles, "{N} cells, N = {n}: second marker → last match ({})", m.latency_formula);
    assert_eq!(second.marker - first.marker, m.cycles_per_line, "{N} cells, N = {n}: back-to-back markers ({})", m.formula);
    assert_eq!(m.pe_count, Some(N));
    b
}

#[test]
fn matcher_worst_line_clocks_measured_in_simulation_equal_the_budget_on_small_arrays() {
    // No fold (n within the cells' low rows), with the fold, and a full
    // 16-cell array.
    check_worst_line::<8>(5);
    check_worst_line::<8>(16);
    check_worst_line::<16>(27);
    check_worst_line::<16>(32);
}

/// The sensor's matcher, 64 cells, on its worst line: n = m = N_MAX.
#[test]
fn matcher_worst_line_of_n_max_on_the_sensors_64_cells_equals_the_budget() {
    let b = check_worst_line::<N_CELLS>(N_MAX);
    // The worst line fits the line time of a W_MAX line without blanking.
    assert!(stage(&b, "matcher").cycles_per_line <= W_MAX as u64);
    assert_eq!(b.stall_cycles_per_line, 0);
}

/// Random line pairs of several sizes, back to back: every marker leaves
/// when the budget's per-line clocks say, the engine taking each pair
/// `TAKE_AFTER_MARKER` clocks after its second marker or, if busy, once
/// the previous pair's clocks per line are over; and no pair costs more
/// than the budget's worst line for `N = max(n, m)`.
#[test]
fn matcher_clocks_of_random_pairs_follow_the_per_line_formula_and_stay_within_the_worst() {
    const CELLS: usize = 8;
    let mut rng = VectorRng(0x5eed_0002);
    let mut next = || rng.next();
    let sizes = [(1, 1), (3, 7), (7, 3), (8, 8), (9, 2), (12, 16), (16, 11), (16, 16), (0, 5), (4, 0), (2, 2), (16, 1)];
    let pairs: Vec<(MatchLine, MatchLine)> =
        sizes.iter().map(|&(n, m)| (random_line(&mut next, n), random_line(&mut next, m))).collect();
    let got = measure::<CELLS>(&pairs, 40 * PX);
    let mut engine_free: Option<u64> = None;
    let mut waited = 0;
    for (g, &(n, m)) in got.iter().zip(&sizes) {
        let per_line = matcher_cycles_per_line(n, m, g.stop_diag, g.k, CELLS) as u64;
        let ready = g.input_done + TAKE_AFTER_MARKER;
        let take = engine_free.map_or(ready, |f| ready.max(f));
        waited += (take > ready) as usize;
        assert_eq!(g.marker, take + per_line + MARKER_AFTER_NEXT_TAKE as u64, "n {n} m {m} k {} stop {}", g.k, g.stop_diag);
        engine_free = Some(take + per_line);
        let worst = stage(&budget(&request(W_MAX, n.max(m).max(1), CELLS)).expect("valid"), "matcher").cycles_per_line;
        assert!(per_line <= worst, "n {n} m {m}: {per_line} > worst {worst}");
    }
    assert!(waited >= 3, "pairs taken back to back: {waited}");
}

// ===========================================================================
// The scanline's latency, resources
// ===========================================================================

/// The budget's latency of a scanline is the detector's measured first
/// pixel → marker plus the matcher's measured second marker → last match
/// plus the interpolator's measured marker → last pixel and the clock from
/// the matcher's last match to its marker (the stages wired directly,
/// engines idle).
#[test]
fn scanline_latency_is_the_sum_of_the_measured_stage_latencies() {
    const CELLS: usize = 8;
    let (width, n) = (700, 16);
    let mut rng = VectorRng(0x5eed_0003);
    let mut next = || rng.next();
    let line = textured_line(&mut next, width);
    let mut sim = DetectorSim::new();
    let run = run_lines(&mut sim, &[line.as_slice()], |_| false, |_| {}).expect("the detector runs");
    let detector = run.lines[0].marker_cycle - run.first_pixel_cycle[0];
    let pair = &measure::<CELLS>(&[worst_pair(n)], WORST_DISPMAX)[0];
    let matcher = pair.last_match.expect("matches") - pair.input_done;
    let line = sim::interpolator::AnchorLine {
        anchors: vec![sim::interpolator::FixedAnchor { x: 100, d: 40 }, sim::interpolator::FixedAnchor { x: 5000, d: 90 }],
        width,
        sof: true,
    };
    let mut interp = sim::interpolator::InterpolatorSim::robust();
    let (lines, markers) = interp.run(&[line], 0);
    let interpolator = lines[0].last_cycle - markers[0];
    let b = budget(&request(width, n, CELLS)).expect("valid");
    assert_eq!(b.latency_cycles, detector + matcher + 1 + interpolator, "{}", b.latency_formula);
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

/// The budget's memories are those of the generated Verilog: two
/// detectors, the sensor's matcher and the interpolator.
#[test]
fn memory_sizes_equal_the_memories_of_the_generated_verilog() {
    use sim::verilog::{generate, Top};
    let b = budget(&request(512, N_MAX, N_CELLS)).expect("valid");
    let detector = verilog_memory_bits(&generate(Top::Detector));
    let matcher = verilog_memory_bits(&generate(Top::Matcher));
    let interpolator = verilog_memory_bits(&generate(Top::Interpolator));
    assert!(detector > 0 && matcher > 0 && interpolator > 0, "memories found");
    let r = &b.resources;
    let stage_bits = |stage: &str| r.memories.iter().filter(|m| m.stage == stage).map(|m| m.bits).sum::<usize>();
    assert_eq!(2 * detector, r.line_buffer_bits + r.histogram_bits, "two detectors");
    assert_eq!(2 * detector + matcher + interpolator, r.memory_bits, "{:#?}", r.memories);
    assert_eq!(matcher, stage_bits("matcher"));
    assert_eq!(interpolator, stage_bits("interpolator"));
    assert_eq!((r.line_buffers, r.histogram_banks, r.pe_count, r.rows_per_cell), (2, 4, 64, 2));
}

// ===========================================================================
// Frame arithmetic, worked out by hand
// ===========================================================================

/// 512×512 at 125 MHz, hblank 88, N = 16 on 8 cells: the matcher's worst
/// line is far below 600 clocks, so the line period is the input's
/// 512 + 88 = 600 clocks and a frame 512 × 600 = 307 200 clocks =
/// 2.4576 ms, 406.9 frames/s.
#[test]
fn frame_time_of_512_by_512_at_125_mhz_with_an_input_bound_line_period() {
    let b = budget(&BudgetRequest { hblank: 88, cells: 8, ..BudgetRequest::new(512, 512, 16, 64.0, 125.0) }).expect("valid");
    assert!(b.stages.iter().all(|s| s.cycles_per_line < 600), "{:?}", b.stages);
    assert_eq!(b.line_period_cycles, 600);
    assert_eq!(b.stall_cycles_per_line, 0);
    assert_eq!(b.frame_cycles, 307_200);
    assert!((b.frame_time_ms - 2.4576).abs() < 1e-9, "{}", b.frame_time_ms);
    assert!((b.fps - 406.901_041_666).abs() < 1e-6, "{}", b.fps);
}

/// 1024×768 at 125 MHz with the 320 clocks of blanking of XGA timing
/// (1344 clocks per line): the sensor's matcher fits, the period is 1344
/// clocks and a frame 768 × 1344 = 1 032 192 clocks = 8.257 536 ms.
#[test]
fn frame_time_of_1024_by_768_at_125_mhz_with_xga_blanking() {
    let b = budget(&BudgetRequest { hblank: 320, ..BudgetRequest::new(1024, 768, N_MAX, 64.0, 125.0) }).expect("valid");
    assert_eq!(b.line_period_cycles, 1344);
    assert_eq!(b.frame_cycles, 1_032_192);
    assert!((b.frame_time_ms - 8.257_536).abs() < 1e-9, "{}", b.frame_time_ms);
    assert!((b.fps - 1000.0 / 8.257_536).abs() < 1e-9);
    assert!((b.latency_us - b.latency_cycles as f64 / 125.0).abs() < 1e-12);
}

/// A stage slower than the input sets the period; the input stalls by the
/// difference, which the least hblank removes, and one clock less leaves a
/// one-clock stall.
#[test]
fn a_stage_slower_than_the_input_stalls_it_by_the_difference() {
    let base = BudgetRequest::new(512, 512, N_MAX, 64.0, 125.0);
    let b = budget(&base).expect("valid");
    let slowest = b.stages.iter().map(|s| s.cycles_per_line).max().expect("stages");
    assert!(slowest > 512, "the sensor's worst line is longer than a 512-pixel line");
    assert_eq!(b.line_period_cycles, slowest);
    assert_eq!(b.stall_cycles_per_line, slowest - 512);
    assert_eq!(b.min_hblank_cycles, slowest - 512);
    assert!(b.stages.iter().all(|s| s.spare_cycles == 512 - s.cycles_per_line as i64));
    let want_ms = 512.0 * slowest as f64 / 125e6 * 1e3;
    assert!((b.frame_time_ms - want_ms).abs() < 1e-9);
    let h = b.min_hblank_cycles as usize;
    let fits = budget(&BudgetRequest { hblank: h, ..base }).expect("valid");
    assert_eq!((fits.line_period_cycles, fits.stall_cycles_per_line), (slowest, 0));
    let short = budget(&BudgetRequest { hblank: h - 1, ..base }).expect("valid");
    assert_eq!((short.line_period_cycles, short.stall_cycles_per_line), (slowest, 1));
}

// ===========================================================================
// The command line
// ===========================================================================

fn declivity(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_declivity")).args(args).output().expect("the binary runs")
}

const GOOD: [&str; 11] =
    ["budget", "--width", "512", "--height", "512", "--n-max", "128", "--dispmax", "64", "--clock-mhz", "125"];

/// `GOOD` with `flag` set to `value`.
fn with(flag: &str, value: &str) -> Vec<String> {
    let mut a: Vec<String> = GOOD.iter().map(|s| s.to_string()).collect();
    match a.iter().position(|s| s == flag) {
        Some(i) => a[i + 1] = value.to_string(),
        None => a.extend([flag.to_string(), value.to_string()]),
    }
    a
}

#[test]
fn cli_bad_sizes_exit_non_zero_with_a_message_naming_the_problem() {
    let cases = [
        ("--width", "0", "--width 0"),
        ("--height", "0", "--height 0"),
        ("--n-max", "0", "--n-max 0"),
        ("--n-max", "129", "N_MAX = 128"),
        ("--cells", "5", "--cells 5"),
        ("--cells", "32", "need at least 64 cells"),
        ("--clock-mhz", "0", "--clock-mhz 0"),
        ("--clock-mhz", "-125", "--clock-mhz -125"),
        ("--dispmax", "0.5", "greater than 1"),
        ("--dispmax", "5000", "W_MAX = 1024"),
        ("--width", "wide", "--width"),
    ];
    for (flag, value, says) in cases {
        let args = with(flag, value);
        let o = Command::new(env!("CARGO_BIN_EXE_declivity")).args(&args).output().expect("runs");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(err.contains(says), "{args:?}: stderr does not say `{says}`: {err}");
    }
}

#[test]
fn cli_json_is_one_object_with_the_budget_keys() {
    let o = declivity(&[&GOOD[..], &["--hblank", "100", "--json"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    for key in [
        "width",
        "height",
        "n_max",
        "dispmax",
        "clock_mhz",
        "hblank",
        "cells",
        "line_period_cycles",
        "stall_cycles_per_line",
        "min_hblank_cycles",
        "latency_cycles",
        "latency_us",
        "frame_time_ms",
        "fps",
        "stages",
        "resources",
        "not_included",
    ] {
        assert!(v.get(key).is_some(), "no key {key} in {v}");
    }
    let stages = v["stages"].as_array().expect("stages");
    assert_eq!(stages.len(), 3);
    for s in stages {
        for key in ["name", "cycles_per_line", "formula", "latency_cycles", "latency_formula", "memories"] {
            assert!(s.get(key).is_some(), "no key {key} in {s}");
        }
    }
    for key in ["line_buffer_bits", "histogram_banks", "pe_count", "rows_per_cell", "choice_memory_bits", "record_memory_bits"] {
        assert!(v["resources"].get(key).is_some(), "no resources.{key}");
    }
    // The frame time is H × period / F, by the numbers the object gives.
    let (h, p, f) = (v["height"].as_f64().unwrap(), v["line_period_cycles"].as_f64().unwrap(), v["clock_mhz"].as_f64().unwrap());
    assert!((v["frame_time_ms"].as_f64().unwrap() - h * p / (f * 1e3)).abs() < 1e-9);
    assert_eq!(v["hblank"].as_u64(), Some(100));
    let missing: Vec<&str> = v["not_included"].as_array().expect("a list").iter().filter_map(|m| m.as_str()).collect();
    assert!(missing.iter().any(|m| m.contains("depth stage")) && missing.iter().all(|m| !m.starts_with("interpolator")), "{missing:?}");
    assert_eq!(v["stages"][2]["name"].as_str(), Some("interpolator"));
}

#[test]
fn cli_text_names_the_stages_the_missing_ones_and_a_wide_line() {
    let o = declivity(&with("--width", "1500").iter().map(|s| s.as_str()).collect::<Vec<_>>());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for says in ["declivity detector", "matcher", "interpolator", "depth stage", "not yet included", "line period", "latency", "frames/s", "wide", "W_MAX = 1024"] {
        assert!(out.contains(says), "does not say `{says}`:\n{out}");
    }
}

#[test]
fn cli_help_explains_every_option() {
    let o = declivity(&["budget", "--help"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    for opt in ["--width", "--height", "--n-max", "--dispmax", "--clock-mhz", "--hblank", "--cells", "--json"] {
        assert!(out.contains(opt), "--help does not explain {opt}");
    }
    for says in ["line period", "latency", "stall", "interpolator", "worst line"] {
        assert!(out.contains(says), "--help does not say `{says}`");
    }
}
