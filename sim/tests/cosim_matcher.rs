//! The matcher's generated Verilog against its Rust model: bit-exact
//! co-simulation under Icarus and Verilator on committed vectors
//! (`vectors/matcher/`), Verilator lint with the detector's accepted list,
//! Yosys without latches and ECP5 place and route.
//!
//! The vectors are recorded from the Rust model (`sim::hdl::traces`); a
//! test fails when the committed files differ from a fresh recording.
//! Regenerate them with
//! `COSIM_BLESS=1 cargo test --release -p sim --test cosim_matcher`.
//!
//! The vectors (`corner.trace`, `corner_paper.trace`: the hand-built cases
//! under the robust and the paper gain rule; `real.trace`: 30 Tsukuba rows)
//! use a 16-cell array holding 64 reference declivities: Icarus runs them
//! in seconds (the sensor's 32-cell Verilog is twice the logic), and a
//! real Tsukuba row keeps most of its declivities (they have 30–80;
//! beyond the array's rows a line's records are dropped and it is flagged
//! full), in lines of one to four phases. The matcher's cycle behaviour
//! depends on the cell count only through that limit and the phases (the
//! cells' rows `c + k·N`): the record memories hold `N_MAX` entries per
//! bank at every size. The sensor's 32-cell array has its own vector
//! (`real_32_cells.trace`, 12 rows), run under Verilator only.

use std::path::{Path, PathBuf};
use std::time::Instant;

use rtl::matcher::declivity_matcher::GainRule;
use rtl::params::{DT_FRAC_BITS, N_CELLS, POS_FRAC_BITS, ROWS_PER_CELL};
use sim::hdl::cosim::{self, CosimError, Options, Simulator, Trace};
use sim::rng::VectorRng;
use sim::drive::matcher::{check_line, golden_match, image_lines, MatchLine, MatchRecord, MatchedLine};
use sim::hdl::traces::matcher_trace;
use sim::hdl::verilog::{generate_with, Top};

/// Cells of the array the vectors are recorded for.
const CELLS: usize = 16;
/// Declivities per side that array keeps.
const HELD: usize = ROWS_PER_CELL * CELLS;
/// The gain rule of the vectors (the sensor's default).
const RULE: GainRule = GainRule::Robust;
/// The corner vectors' search bound: 40 px.
const DISPMAX: u32 = 40 << POS_FRAC_BITS;

fn vectors() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/matcher")
}

fn design(cells: usize, rule: GainRule) -> String {
    generate_with(sim::Config::Sd, Top::Matcher, cells, rule).expect("a supported size")
}


/// `d_t` of `levels` grey levels in the matcher's format.
fn dt(levels: u32) -> u32 {
    levels << DT_FRAC_BITS
}

/// A record at `pos` (`X · 16`), of amplitude `amp`, flat on each side.
fn step(pos: u32, from: u8, to: u8) -> MatchRecord {
    MatchRecord { pos, amplitude: to as i32 - from as i32, left: [from; 3], right: [to; 3] }
}

fn line(dt_levels: u32, records: Vec<MatchRecord>) -> MatchLine {
    MatchLine { dt: dt(dt_levels), records, ..MatchLine::default() }
}

/// `n` random declivities from `x0` on, 1–20 px apart, random polarity,
/// amplitude and neighbour levels.
fn random_line(rng: &mut VectorRng, n: usize, x0: u32, dt_levels: u32) -> MatchLine {
    random_line_spaced(rng, n, x0, dt_levels, 20)
}

/// [`random_line`] with declivities 1 to `max_px` px apart.
fn random_line_spaced(rng: &mut VectorRng, n: usize, x0: u32, dt_levels: u32, max_px: u64) -> MatchLine {
    let mut pos = x0;
    let records = (0..n)
        .map(|_| {
            pos += 16 + (rng.next() % ((max_px - 1) * 16)) as u32;
            let lo = (rng.next() % 150) as u8;
            let hi = lo + 20 + (rng.next() % 85) as u8;
            let (from, to) = if rng.next().is_multiple_of(2) { (lo, hi) } else { (hi, lo) };
            let mut jitter = |v: u8| v.saturating_add((rng.next() % 7) as u8).saturating_sub(3);
            MatchRecord {
                pos,
                amplitude: to as i32 - from as i32,
                left: [jitter(from), jitter(from), jitter(from)],
                right: [jitter(to), jitter(to), jitter(to)],
            }
        })
        .collect();
    line(dt_levels, records)
}

/// `line` shifted left by `d` (`· 16`) with a little level noise: the other
/// view of a scene at disparity `d`.
fn shifted(rng: &mut VectorRng, l: &MatchLine, d: u32) -> MatchLine {
    let mut o = l.clone();
    o.records.retain(|r| r.pos >= d);
    for r in &mut o.records {
        r.pos -= d;
        for v in r.left.iter_mut().chain(r.right.iter_mut()) {
            *v = v.saturating_add((rng.next() % 5) as u8).saturating_sub(2);
        }
    }
    o
}

/// Hand-built line pairs (reference, other), each with what it is for.
fn corner_pairs() -> Vec<(&'static str, MatchLine, MatchLine)> {
    let mut rng = VectorRng(0x5eed_0011);
    let d = DISPMAX;
    let three = line(20, vec![step(800, 40, 160), step(1600, 160, 60), step(2400, 60, 200)]);
    let mut pairs = vec![
        ("empty reference line", line(20, vec![]), three.clone()),
        ("empty other line", three.clone(), line(20, vec![])),
        ("both lines empty", line(20, vec![]), line(20, vec![])),
        // Same polarity, disparities inside the area, but neighbour levels
        // of different shapes: both distances far above gmax (in either
        // rule), so every node is rejected.
        (
            "every node rejected",
            line(20, (0..5).map(|k| MatchRecord { pos: 1000 + 100 * k, amplitude: 240, left: [10; 3], right: [250; 3] }).collect()),
            line(
                20,
                (0..6)
                    .map(|k| MatchRecord { pos: 950 + 100 * k, amplitude: 40, left: [100, 180, 20], right: [140, 30, 230] })
                    .collect(),
            ),
        ),
        // Opposite polarities only: rejected by the robust rule's polarity test.
        (
            "opposite polarities",
            line(20, vec![step(1000, 50, 150), step(1200, 50, 150)]),
            line(20, vec![step(900, 150, 50), step(1100, 150, 50)]),
        ),
        // Three identical declivities against two: every increasing pair
        // of pairs has the same gain.
        (
            "ties between equal paths",
            line(20, vec![step(1000, 60, 140); 3].into_iter().enumerate().map(|(k, mut r)| { r.pos += 16 * k as u32; r }).collect()),
            line(20, vec![step(900, 60, 140); 2].into_iter().enumerate().map(|(k, mut r)| { r.pos += 16 * k as u32; r }).collect()),
        ),
        // Eq. 6 is 0 < X_ref - X_other < dispmax: pairs 125 px apart with
        // the other view's declivity at 0, 1/16, dispmax - 1/16 and dispmax
        // to the left; only the middle two are nodes.
        (
            "disparities on the search-area bounds",
            line(20, (0..4).map(|k| step(1000 + 2000 * k, 70, 170)).collect()),
            line(20, [0, 1, d - 1, d].iter().enumerate().map(|(k, &dk)| step(1000 + 2000 * k as u32 - dk, 70, 170)).collect()),
        ),
        // Positions at the ends of their range: X_ref - X_other wraps in
        // the port width and must still be out of the area.
        (
            "positions at 0 and at the largest value",
            line(20, vec![step(0, 30, 90), step(16383, 90, 30)]),
            line(20, vec![step(0, 30, 90), step(16383, 90, 30)]),
        ),
        // Largest amplitudes and levels 0/255, d_t zero on one side.
        (
            "extreme levels, d_t = 0 on one side",
            line(0, vec![step(500, 0, 255), step(700, 255, 0)]),
            line(30, vec![step(400, 0, 255), step(600, 255, 0)]),
        ),
        // The largest d_t: the port's largest on the reference, the
        // detector's largest (K · 255 grey levels) on the other; gmax near
        // 1770 grey levels, every node of the area kept with the largest
        // local gains. (Both at the port's largest, `⌈2·gmax⌉` would need
        // 13 bits: the detector never gives more than 1497 levels.)
        ("largest d_t", random_line(&mut rng, 6, 100, 0), random_line(&mut rng, 6, 50, 0)),
    ];
    if let Some(p) = pairs.last_mut() {
        p.1.dt = 0xffff;
        p.2.dt = (rtl::params::THRESHOLD_PER_MEDIAN * 255.0 * (1 << DT_FRAC_BITS) as f64).round() as u32;
    }
    // Exactly as many as the array holds, one more, and many more
    // (dropped, m_full).
    let full = random_line(&mut rng, HELD, 200, 15);
    pairs.push(("as many declivities as the array holds", full.clone(), shifted(&mut rng, &full, 5 * 16 + 3)));
    let over = random_line(&mut rng, HELD + 1, 200, 15);
    pairs.push(("one declivity more than the array holds", over.clone(), shifted(&mut rng, &over, 7 * 16)));
    // (Closer together: 2·HELD + 5 of them fit the position format.)
    let many = random_line_spaced(&mut rng, 2 * HELD + 5, 100, 12, 7);
    let mut many_other = shifted(&mut rng, &many, 3 * 16 + 9);
    many_other.records.truncate(HELD + 3);
    pairs.push(("more declivities than the array holds on both sides", many, many_other));
    // The detector's flags pass through to the marker.
    let mut flagged = random_line(&mut rng, 4, 300, 18);
    flagged.wide = true;
    let mut flagged_other = shifted(&mut rng, &flagged, 2 * 16);
    flagged_other.full = true;
    flagged_other.wide = false;
    pairs.push(("wide reference, full other line", flagged, flagged_other));
    // Random lines: shifted copies, and unrelated lines.
    for k in 0..8 {
        let r = random_line(&mut rng, 3 + 2 * k, 150, 8 + 3 * k as u32);
        let o = if k % 3 == 1 {
            random_line(&mut rng, 2 + 2 * k, 120, 12)
        } else {
            shifted(&mut rng, &r, (3 + 5 * k as u32) * 16 + k as u32)
        };
        pairs.push(("random lines", r, o));
    }
    // Start of frame on the first pair (both lines: the matcher pairs the
    // lines of one frame).
    (pairs[0].1.sof, pairs[0].2.sof) = (true, true);
    pairs
}

/// Tsukuba rows `ROWS` as the matcher takes them (golden's declivities in
/// hardware-parity mode, quantized), and the pair's search bound.
const ROWS: std::ops::Range<usize> = 140..170;

fn real_pairs() -> (Vec<(MatchLine, MatchLine)>, u32) {
    let dir = sim::eval::io::stereo_data_dir().join("tsukuba");
    let pair = sim::eval::io::load_pair_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e} (the pairs are in data/stereo)", dir.display()));
    let lines = image_lines(&pair.left, &pair.right);
    // The bound `dispmax + 1` that `eval` gives golden.
    let dispmax = ((pair.dispmax + 1.0) * (1 << POS_FRAC_BITS) as f64) as u32;
    (lines[ROWS].to_vec(), dispmax)
}

/// One committed vector: a file, the gain rule of its Verilog and the
/// line pairs that drive it.
struct Vector {
    file: &'static str,
    rule: GainRule,
    pairs: Vec<(MatchLine, MatchLine)>,
    dispmax: u32,
}

/// The vectors of the `CELLS`-cell array: the corner cases under both gain
/// rules (the rule changes the loader's levels and the cells' tests), the
/// real rows under the sensor's.
fn vectors_16() -> Vec<Vector> {
    let corner: Vec<(MatchLine, MatchLine)> = corner_pairs().into_iter().map(|(_, r, o)| (r, o)).collect();
    let (real, dispmax) = real_pairs();
    vec![
        Vector { file: "corner.trace", rule: RULE, pairs: corner.clone(), dispmax: DISPMAX },
        Vector { file: "corner_paper.trace", rule: GainRule::Paper, pairs: corner, dispmax: DISPMAX },
        Vector { file: "real.trace", rule: RULE, pairs: real, dispmax },
    ]
}

/// Records the Rust model of the `CELLS`-cell array for `v`.
fn record(d: &str, v: &Vector) -> (Trace, Vec<MatchedLine>) {
    matcher_trace::<CELLS>(d, v.rule, v.dispmax, &v.pairs).unwrap_or_else(|e| panic!("{}: {e}", v.file))
}

fn committed(name: &str, fresh: &Trace) -> Trace {
    cosim::committed_trace(&vectors().join(name), fresh).unwrap_or_else(|e| panic!("{e}"))
}

/// A line as an array of `cells` cells keeps it: its first
/// `ROWS_PER_CELL · cells` records, flagged full when some were dropped.
fn kept(l: &MatchLine, cells: usize) -> MatchLine {
    let mut k = l.clone();
    k.full |= k.records.len() > ROWS_PER_CELL * cells;
    k.records.truncate(ROWS_PER_CELL * cells);
    k
}

/// Every line's matches and marker against its inputs and golden's optimum
/// (on the kept records), and the flags on the marker.
fn check_against_golden(what: &str, v: &Vector, got: &[MatchedLine], cells: usize) {
    let (pairs, dispmax) = (&v.pairs, v.dispmax);
    assert_eq!(got.len(), pairs.len(), "{what}: one marker per pair");
    for (k, ((r, o), g)) in pairs.iter().zip(got).enumerate() {
        let (r, o) = (kept(r, cells), kept(o, cells));
        let golden = golden_match(&r, &o, dispmax, v.rule);
        check_line(&r, &o, g, &golden).unwrap_or_else(|e| panic!("{what}, pair {k}: {e}"));
        let m = g.marker;
        assert_eq!(
            (m.wide, m.full, m.sof),
            (r.wide || o.wide, r.full || o.full, r.sof),
            "{what}, pair {k}: the marker's flags"
        );
    }
}

fn valid_beats(t: &Trace) -> usize {
    let i = t.outputs.iter().position(|p| p.name == "m_valid").expect("m_valid");
    t.cycles.iter().filter(|c| c.outputs[i] == 1).count()
}

/// Clocks with an input offered but not taken (back-pressure in the vectors).
fn refused_beats(t: &Trace) -> usize {
    let port = |ps: &[cosim::Port], n: &str| ps.iter().position(|p| p.name == n).expect(n);
    let (rv, ov) = (port(&t.inputs, "r_valid"), port(&t.inputs, "o_valid"));
    let (rr, or) = (port(&t.outputs, "r_ready"), port(&t.outputs, "o_ready"));
    t.cycles
        .iter()
        .filter(|c| (c.inputs[rv] == 1 && c.outputs[rr] == 0) || (c.inputs[ov] == 1 && c.outputs[or] == 0))
        .count()
}

#[test]
fn cosim_matcher_vectors_are_current_and_carry_matches() {
    let t0 = Instant::now();
    let corner = corner_pairs();
    let case = |name: &str| corner.iter().position(|c| c.0 == name).expect(name);
    for v in vectors_16() {
        let (fresh, got) = record(&design(CELLS, v.rule), &v);
        let trace = committed(v.file, &fresh);
        check_against_golden(v.file, &v, &got, CELLS);
        // Matches and markers, and inputs held while the matcher is not
        // ready, so the comparison is not about an idle bus.
        assert!(valid_beats(&trace) > 100, "{}: {}", v.file, valid_beats(&trace));
        assert!(refused_beats(&trace) > 100, "{}: {}", v.file, refused_beats(&trace));
        eprintln!(
            "{}: {} pairs, {} clocks, {} output beats, {} clocks of back-pressure",
            v.file,
            v.pairs.len(),
            trace.len(),
            valid_beats(&trace),
            refused_beats(&trace)
        );
        if !v.file.starts_with("corner") {
            continue;
        }
        // The cases are what they say.
        let pair = |name: &str| &v.pairs[case(name)];
        assert_eq!(got[case("disparities on the search-area bounds")].pairs(), vec![(1, 1), (2, 2)], "eq. 6's bounds");
        let (r, o) = pair("every node rejected");
        let table = golden_match(r, o, DISPMAX, v.rule).table;
        assert!((0..5).all(|i| (0..6).all(|j| table.get(i, j).is_none())), "a node was kept");
        assert!(got[case("every node rejected")].matches.is_empty());
        for name in ["empty reference line", "empty other line", "both lines empty"] {
            assert_eq!(got[case(name)].marker.count, 0, "{name}");
        }
        let (r, o) = pair("ties between equal paths");
        let g = golden_match(r, o, DISPMAX, v.rule);
        assert_eq!((g.nodes.len(), g.path_gain(&[(0, 0), (2, 1)])), (2, Some(g.gain)), "several optimal paths");
        let over = got[case("more declivities than the array holds on both sides")].marker;
        assert_eq!((over.n, over.m, over.full), (HELD as u32, HELD as u32, true));
        let exact = got[case("as many declivities as the array holds")].marker;
        assert_eq!((exact.n, exact.full), (HELD as u32, false));
    }
    eprintln!("{:.1} s", t0.elapsed().as_secs_f64());
}

fn check_sim(sim: Simulator, d: &str, name: &str, trace: &Trace) {
    let run = cosim::check(sim, d, trace, &Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    eprintln!(
        "{} {name}: {} cycles, compile {:.2} s, run {:.2} s",
        sim.name(),
        trace.len(),
        run.compile.as_secs_f64(),
        run.run.as_secs_f64()
    );
}

/// Each `CELLS`-cell vector, replayed in the Verilog of its gain rule.
fn check_vectors(sim: Simulator) {
    for v in vectors_16() {
        let d = design(CELLS, v.rule);
        check_sim(sim, &d, v.file, &committed(v.file, &record(&d, &v).0));
    }
}

#[test]
fn cosim_matcher_icarus_matches_rust_on_corner_cases_and_real_rows() {
    check_vectors(Simulator::Icarus);
}

#[test]
fn cosim_matcher_verilator_matches_rust_on_corner_cases_and_real_rows() {
    check_vectors(Simulator::Verilator);
}

/// Rows of `real_pairs` for the sensor's 32-cell array.
const ROWS_SENSOR: usize = 12;

/// The sensor's matcher, `N_CELLS` = 32 cells holding `N_MAX` = 128
/// declivities, under Verilator on the first `ROWS_SENSOR` rows of the real
/// vectors, recorded on their own (`real_32_cells.trace`): with 128 rows no
/// record is dropped, so the engine's clocks, and with them the
/// back-pressure on the inputs, differ from the 16-cell array's (Icarus is
/// left to the 16-cell vectors).
#[test]
fn cosim_matcher_32_cells_verilator_matches_rust_on_real_rows() {
    const N: usize = N_CELLS;
    let t0 = Instant::now();
    let d = design(N, RULE);
    let (mut pairs, dispmax) = real_pairs();
    pairs.truncate(ROWS_SENSOR);
    let v = Vector { file: "real_32_cells.trace", rule: RULE, pairs, dispmax };
    let (fresh, got) = matcher_trace::<N>(&d, v.rule, v.dispmax, &v.pairs).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{N} cells: Verilog and recording {:.1} s", t0.elapsed().as_secs_f64());
    check_against_golden(v.file, &v, &got, N);
    assert!(got.iter().all(|l| !l.marker.full), "a row overflows {N} cells");
    check_sim(Simulator::Verilator, &d, v.file, &committed(v.file, &fresh));
}

/// The comparison can fail on this design: one flipped bit of the
/// disparity in the Verilog's output assignment is caught by the
/// simulator run, on every clock.
#[test]
fn cosim_matcher_icarus_catches_a_changed_design() {
    let v = vectors_16().into_iter().next().expect("the corner vector");
    let d = design(CELLS, v.rule);
    let trace = committed(v.file, &record(&d, &v).0);
    let from = "m_disp = out_disp$q;";
    assert!(d.contains(from), "the design text changed shape");
    let changed = d.replace(from, "m_disp = out_disp$q ^ 14'h4;");
    match cosim::check(Simulator::Icarus, &changed, &trace, &Options::default()) {
        Err(CosimError::Mismatch { mismatch, dir, .. }) => {
            let _ = std::fs::remove_dir_all(dir);
            let first = mismatch.first.expect("a first difference");
            assert_eq!((first.cycle, first.port.as_str()), (0, "m_disp"));
            assert_eq!(first.got, first.expected ^ 4);
            assert_eq!(mismatch.differing_cycles, trace.len(), "every clock's m_disp differs");
        }
        other => panic!("expected a mismatch, got {other:?}"),
    }
}


/// On the sensor's 32-cell Verilog.
#[test]
fn matcher_verilog_lints_clean_but_for_the_accepted_warnings() {
    let t0 = Instant::now();
    let warnings = cosim::lint_verilator(&design(N_CELLS, RULE)).unwrap_or_else(|e| panic!("{e}"));
    let counts = cosim::check_accepted(&warnings, sim::hdl::cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("accepted lint warnings: {counts:?} ({:.1} s)", t0.elapsed().as_secs_f64());
}

/// On the sensor's 32-cell Verilog.
#[test]
fn matcher_synthesizes_in_yosys_without_latches() {
    let t0 = Instant::now();
    let check = sim::hdl::synth::yosys_latch_check(&design(N_CELLS, RULE), "top").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(check.latches, 0, "latches: {:?}", check.latch_cells);
    assert!(check.cells > 5_000, "the matcher is not empty: {} cells", check.cells);
    eprintln!("{} cells after proc, no latch ({:.1} s)", check.cells, t0.elapsed().as_secs_f64());
}

/// A 4-cell array through the ECP5 flow (a small array, so that the run
/// stays short). The counts are reported, not pinned: the bounds only
/// say that the record memories are in block RAM, that the array is not
/// empty, that four cells fit in a quarter of the device's 83 640 LUT4s, and
/// that the clock has a register-to-register Fmax (above a floor of 30 MHz).
#[test]
fn matcher_places_and_routes_on_ecp5_85k() {
    let r = sim::hdl::synth::synthesize(&design(4, RULE), 100.0).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", sim::hdl::synth::report_table(&r));
    // The record memories (two banks of N_MAX entries per field) are as
    // deep at every size, and go to block RAM.
    assert!(r.brams > 0, "block RAMs: {}", r.brams);
    assert!(r.luts > 500 && r.ffs > 200, "LUTs {} FFs {}", r.luts, r.ffs);
    assert!(r.luts < 83_640 / 4, "4 cells in a quarter of the device: LUTs {}", r.luts);
    assert!(r.fmax_mhz.is_finite() && r.fmax_mhz > 30.0, "Fmax {}", r.fmax_mhz);
}
