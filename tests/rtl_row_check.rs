//! The rtl row check (`rtl::post::row_check`) against golden's
//! hardware-parity row check (`golden::hardware::row_check`, the check
//! across neighbouring rows of `golden::frame::confirmed_matches` on the
//! matcher's fixed-point values), on generated frames and on every row of
//! real pairs (also against the matches golden's parity frame keeps), and
//! its timing against the constants in its doc comment.
//!
//! Both get the same fixed-point matches (`sim::drive::row_check`), so the
//! kept matches must be exactly equal.
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_row_check`).

use proptest::prelude::*;
use rtl::params::{CONSISTENT_DD_LSB, CONSISTENT_DX_LSB, N_MAX, POS_FRAC_BITS, W_MAX};
use rtl::post::row_check::{row_check_cycles, row_check_period, RowCheck, ROW_FIRST_LAG, ROW_RESTART_LAG, ROW_START_LAG};
use sim::drive::row_check::{frame_rows, golden_kept, row_beats, unchecked_rows, Beat, FixedMatch, RowCheckSim, RowRun, TimedRow};

/// One position LSB (1/16 px).
const PX: u64 = 1 << POS_FRAC_BITS;

/// The row check's output equals golden's kept matches, row by row, with
/// the rows' flags and counts.
fn check_kept(frames: &[&[Vec<FixedMatch>]], run: &RowRun) -> Result<(), String> {
    let want: Vec<(Vec<FixedMatch>, bool, bool)> = frames
        .iter()
        .flat_map(|f| {
            let h = f.len();
            golden_kept(f).into_iter().enumerate().map(move |(y, k)| (k, y == 0, y + 1 == h))
        })
        .collect();
    if run.rows.len() != want.len() {
        return Err(format!("{} rows out for {} in", run.rows.len(), want.len()));
    }
    for (y, (g, (k, sof, eof))) in run.rows.iter().zip(&want).enumerate() {
        if &g.kept != k || g.count != k.len() || g.sof != *sof || g.eof != *eof {
            return Err(format!(
                "row {y}: rtl kept {:?} (count {}, sof {}, eof {}), golden {:?} (sof {sof}, eof {eof})",
                g.kept, g.count, g.sof, g.eof, k
            ));
        }
    }
    Ok(())
}

/// The documented timing, clock by clock: row `y` starts at
/// `s = max(marker(y+1) + ROW_START_LAG, finish(y-1) + ROW_RESTART_LAG)` (its own marker
/// for a frame's last row); it finishes at `c = marker_out - 1` with
/// `c - s` at most `row_check_cycles` (exactly 1 for an empty row, at least
/// `row_check_cycles(0, n, 0)`, and exactly that without neighbour
/// matches); its kept
/// matches leave in order, one clock apart at least, from
/// `s + ROW_FIRST_LAG` on, before the marker (one clock apart exactly and
/// from `s + ROW_FIRST_LAG` exactly when it has no neighbour matches).
/// Returns the largest `c - s`.
fn check_timing(rows: &[TimedRow], run: &RowRun) -> Result<usize, String> {
    let mut free = 0u64;
    let mut worst = 0usize;
    let counts: Vec<usize> = rows.iter().map(|r| r.matches.len()).collect();
    for (y, out) in run.rows.iter().enumerate() {
        let r = &rows[y];
        let ready = if r.eof { run.markers[y] } else { run.markers[y + 1] } + ROW_START_LAG as u64;
        let s = ready.max(free);
        let finish = out.marker_cycle - 1;
        let c = (finish - s) as usize;
        let n = counts[y];
        let above = if r.sof { 0 } else { counts[y - 1] };
        let below = if r.eof { 0 } else { counts[y + 1] };
        let bound = row_check_cycles(above, n, below);
        let alone = row_check_cycles(0, n, 0);
        let ok = if n == 0 { c == 1 } else if above + below == 0 { c == alone } else { c >= alone && c <= bound };
        if !ok {
            return Err(format!("row {y}: {c} clocks from its start {s} for {above}/{n}/{below} matches, bound {bound}"));
        }
        let mut prev = s + ROW_FIRST_LAG as u64 - 1;
        for (i, &t) in out.match_cycles.iter().enumerate() {
            if t <= prev || t >= out.marker_cycle || (above + below == 0 && t != s + (ROW_FIRST_LAG + i) as u64) {
                return Err(format!("row {y}: match {i} out at {t}, start {s}, marker out {}", out.marker_cycle));
            }
            prev = t;
        }
        worst = worst.max(c);
        free = finish + ROW_RESTART_LAG as u64;
    }
    Ok(worst)
}

/// The largest `row_check_cycles` of a frame's rows plus
/// `ROW_RESTART_LAG`: a period that drops no row.
fn safe_period(frame: &[Vec<FixedMatch>], gap: usize) -> usize {
    let h = frame.len();
    let n = |y: usize| frame[y].len();
    let cycles = (0..h)
        .map(|y| row_check_cycles(if y == 0 { 0 } else { n(y - 1) }, n(y), if y + 1 == h { 0 } else { n(y + 1) }) + ROW_RESTART_LAG)
        .max()
        .unwrap_or(1);
    let beats = frame.iter().map(|r| r.len() * (gap + 1) + 1).max().unwrap_or(1);
    cycles.max(beats)
}

// ===========================================================================
// Generated frames
// ===========================================================================

/// Offsets of a neighbour's match from a scene point: on, just inside and
/// just outside the bounds of golden's check, in position and disparity.
fn near_bound(limit: u64) -> impl Strategy<Value = i64> {
    let l = limit as i64;
    prop_oneof![Just(0i64), Just(l), Just(-l), Just(l + 1), Just(-l - 1), Just(l - 1), Just(-l + 1), -2 * l..=2 * l]
}

/// A frame: 1 ..= 8 rows of 0 ..= N_MAX matches around shared scene
/// points (so windows hold several candidates), each match offset in `x`
/// and `d` by amounts on and around the check's bounds, then made at
/// least a pixel apart within its row (as declivities are) by dropping
/// those closer than 16 LSB to the previous one.
fn any_frame() -> impl Strategy<Value = Vec<Vec<FixedMatch>>> {
    let points = prop::collection::vec((PX..=12 * PX, 0u64..=40 * PX), 1..=N_MAX + 20);
    let row = prop::collection::vec((any::<bool>(), near_bound(CONSISTENT_DX_LSB), near_bound(CONSISTENT_DD_LSB)), N_MAX + 20);
    (points, prop::collection::vec(row, 1..=8), 0.0f64..=1.0).prop_map(|(points, rows, density)| {
        // Scene points by increasing x: steps of 1 to 12 px.
        let mut xs = Vec::new();
        let mut x = 0u64;
        for &(step, d) in &points {
            x += step;
            xs.push((x, d + 4 * PX));
        }
        rows.into_iter()
            .map(|offsets| {
                let mut m: Vec<FixedMatch> = Vec::new();
                for (&(px, pd), &(present, dx, dd)) in xs.iter().zip(&offsets) {
                    let keep = present || density > 0.5;
                    let (x, d) = ((px as i64 + dx) as u64, (pd as i64 + dd) as u64);
                    if keep && x < (W_MAX as u64) * PX && m.last().is_none_or(|&(lx, _)| x >= lx + PX) && m.len() < N_MAX {
                        m.push((x, d));
                    }
                }
                m
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// The kept matches of every row are exactly golden's
    /// `confirmed_matches` of the same fixed-point values, the rows come
    /// out whole, in order, with their flags, on the documented clocks,
    /// and no row is dropped at a period of the rows' `row_check_cycles`.
    #[test]
    fn prop_kept_matches_are_exactly_golden_confirmed_matches_on_the_documented_clocks(
        frame in any_frame(),
        gap in prop_oneof![Just(0usize), 0usize..3],
        extra in prop_oneof![Just(0usize), 0usize..400],
    ) {
        let period = safe_period(&frame, gap) + extra;
        let rows = frame_rows(&frame, period, gap);
        let mut sim = RowCheckSim::new();
        let run = sim.run_timed(&rows);
        prop_assert_eq!(sim.overflows, 0);
        prop_assert_eq!(sim.crowded, 0);
        check_kept(&[&frame], &run).map_err(TestCaseError::fail)?;
        check_timing(&rows, &run).map_err(TestCaseError::fail)?;
    }
}

// ===========================================================================
// Timing, frames, overflow, crowding
// ===========================================================================

/// Matches `k·step` px apart from `x0` px, disparity `d` px.
fn row(n: usize, x0: u64, step: u64, d: u64) -> Vec<FixedMatch> {
    (0..n as u64).map(|k| (x0 * PX + k * step, d * PX)).collect()
}

/// Without neighbour matches a row of `n` takes exactly
/// `row_check_cycles(0, n, 0)` clocks (`n + ROW_FIRST_LAG - 1`),
/// keeps nothing and is sent at once; an empty row takes one clock; a
/// one-row frame keeps nothing; rows with matching neighbours keep them
/// all, at most one per clock, within the bound.
#[test]
fn a_row_without_neighbour_matches_takes_n_plus_the_first_lag_clocks_and_a_confirmed_row_keeps_all_within_the_bound() {
    let frames: Vec<Vec<Vec<FixedMatch>>> = vec![
        vec![row(N_MAX, 2, 7 * PX, 5)],
        vec![vec![], row(40, 3, 20, 9), vec![]],
        vec![row(N_MAX, 2, 7 * PX, 5), row(N_MAX, 2, 7 * PX, 5), row(N_MAX, 2, 7 * PX, 5)],
        vec![row(10, 2, 3 * PX, 5), vec![], row(10, 2, 3 * PX, 5)],
    ];
    for frame in &frames {
        let rows = frame_rows(frame, safe_period(frame, 0), 0);
        let mut sim = RowCheckSim::new();
        let run = sim.run_timed(&rows);
        check_kept(&[frame], &run).expect("as golden");
        let worst = check_timing(&rows, &run).expect("the documented timing");
        eprintln!("{} rows: at most {worst} clocks a row", frame.len());
    }
    // Identical rows: every match confirmed; the one-row frame none.
    let mut sim = RowCheckSim::new();
    let run = sim.run(&frames[2], safe_period(&frames[2], 0));
    assert!(run.rows.iter().all(|r| r.count == N_MAX));
    let run = sim.run(&frames[0], safe_period(&frames[0], 0));
    assert_eq!(run.rows[0].count, 0);
}

/// The bound of the documentation on the worst rows it describes: a
/// neighbour of N_MAX matches a pixel apart, checked rows sparse or full,
/// or aligned with it and never confirmed (the most waits), and the period
/// that drops no row for any row.
#[test]
fn row_check_cycles_bounds_the_measured_clocks_of_dense_neighbours_and_the_period_drops_nothing() {
    let dense = row(N_MAX, 1, PX, 6);
    let cases: Vec<Vec<Vec<FixedMatch>>> = vec![
        vec![dense.clone(), row(16, 2, 8 * PX, 6), dense.clone()],
        vec![dense.clone(), row(16, 2, 8 * PX, 20), dense.clone()],
        vec![dense.clone(), dense.clone(), dense.clone()],
        vec![dense.clone(), row(N_MAX, 1, PX + 1, 20), dense.clone()],
        vec![row(N_MAX, 1, 7 * PX, 6), dense.clone(), row(N_MAX, 1, 7 * PX, 6)],
        // Aligned with its neighbours and never confirmed: every match
        // waits for one more entry of a full window.
        vec![dense.clone(), row(N_MAX, 1, PX, 20), dense.clone()],
        vec![dense.clone(), row(N_MAX, 1, PX, 20), vec![]],
    ];
    for frame in &cases {
        let rows = frame_rows(frame, row_check_period(), 0);
        let mut sim = RowCheckSim::new();
        let run = sim.run_timed(&rows);
        assert_eq!(sim.overflows, 0);
        check_kept(&[frame], &run).expect("as golden");
        let worst = check_timing(&rows, &run).expect("within the bound");
        let c = run.rows[1].marker_cycle - 1 - (run.markers[2] + ROW_START_LAG as u64);
        eprintln!("middle row of {} matches: {c} clocks, bound {}, frame at most {worst}", frame[1].len(), row_check_cycles(frame[0].len(), frame[1].len(), frame[2].len()));
    }
    assert_eq!(row_check_period(), row_check_cycles(N_MAX, N_MAX, N_MAX) + ROW_RESTART_LAG);
}

/// Two frames back to back, the first's last row equal to the second's
/// first: each frame is checked alone (the rows would confirm each other
/// if the frames mixed), and the frame's last two rows leave right after
/// its last marker.
#[test]
fn two_frames_back_to_back_do_not_mix_rows() {
    let a = vec![row(20, 5, 2 * PX, 10), row(20, 5, 2 * PX, 30), row(20, 5, 2 * PX, 50)];
    let b = vec![row(20, 5, 2 * PX, 50), row(20, 5, 2 * PX, 70), row(20, 5, 2 * PX, 70), vec![]];
    let joined: Vec<Vec<FixedMatch>> = a.iter().chain(&b).cloned().collect();
    assert_ne!(golden_kept(&joined)[2], golden_kept(&a)[2], "the test would see a mix");
    for period in [safe_period(&joined, 0), 400] {
        let mut sim = RowCheckSim::new();
        let run = sim.run_frames(&[&a, &b], period);
        assert_eq!(sim.overflows, 0);
        check_kept(&[&a, &b], &run).expect("each frame alone");
        let rows: Vec<TimedRow> = frame_rows(&a, period, 0).into_iter().chain(frame_rows(&b, period, 0)).collect();
        check_timing(&rows, &run).expect("the documented timing");
        // Rows 1 and 2 of the first frame leave after its last marker.
        assert!(run.rows[1].marker_cycle > run.markers[2] && run.rows[1].marker_cycle < run.markers[2] + period as u64);
    }
    // One-row frames back to back keep nothing.
    let one = vec![row(5, 1, 3 * PX, 4)];
    let mut sim = RowCheckSim::new();
    let run = sim.run_frames(&[&one, &one, &one], 20);
    assert_eq!(run.rows.len(), 3);
    assert!(run.rows.iter().all(|r| r.count == 0 && r.sof && r.eof));
}

/// A frame cut short (its last row has no `m_eof`, the next row starts a
/// frame): that last row can be checked only once the next frame has
/// begun, so it is dropped (`cut`), never leaves, and the next frame is
/// checked as if alone; every row's marker carries its last pixel through.
#[test]
fn a_frame_cut_short_loses_its_last_row_the_next_frame_is_checked_alone_and_markers_carry_the_last_pixel() {
    let a = vec![row(20, 5, 2 * PX, 10), row(20, 5, 2 * PX, 30), row(20, 5, 2 * PX, 50)];
    let b = vec![row(20, 5, 2 * PX, 50), row(20, 5, 2 * PX, 70), row(20, 5, 2 * PX, 70)];
    let period = safe_period(&a, 0).max(safe_period(&b, 0));
    let mut rows: Vec<TimedRow> = frame_rows(&a, period, 0).into_iter().chain(frame_rows(&b, period, 0)).collect();
    rows[2].eof = false; // frame a cut short: its last row never ends it
    for (y, r) in rows.iter_mut().enumerate() {
        r.last_x = 100 + y as u64;
    }
    let mut sim = RowCheckSim::new();
    let run = sim.run_timed(&rows);
    assert_eq!((run.cut, sim.overflows), (1, 0), "one row cut, none dropped for want of room");
    assert_eq!(run.rows.len(), 5, "a's last row does not leave");
    let last_x: Vec<u64> = run.rows.iter().map(|r| r.last_x).collect();
    assert_eq!(last_x, vec![100, 101, 103, 104, 105], "each row's marker carries its own last pixel");
    let flags: Vec<(bool, bool)> = run.rows.iter().map(|r| (r.sof, r.eof)).collect();
    assert_eq!(flags, vec![(true, false), (false, false), (true, false), (false, false), (false, true)]);
    let kept: Vec<Vec<FixedMatch>> = run.rows.iter().map(|r| r.kept.clone()).collect();
    let (ga, gb) = (golden_kept(&a), golden_kept(&b));
    assert_eq!(kept[..2], ga[..2], "a's rows 0 and 1 as golden checks them in a");
    assert_eq!(kept[2..], gb[..], "b as golden checks it alone");
}

/// Rows arriving faster than they are checked: a row that finds every
/// bank in use is dropped whole with `overflow`, never leaves, and the
/// rows left are checked against each other (the frame's last row among
/// the dropped ones here: the last row stored ends the frame); a frame
/// offered afterwards at a safe period is intact.
#[test]
fn a_row_without_a_free_bank_is_dropped_whole_and_flagged_and_a_later_frame_is_intact() {
    let dense = |d: u64| row(N_MAX, 1, PX, d);
    let frame: Vec<Vec<FixedMatch>> = (0..8).map(|y| dense(5 + (y % 2))).collect();
    let mut sim = RowCheckSim::new();
    let run = sim.run(&frame, N_MAX + 1);
    assert!(!run.dropped.is_empty(), "rows every N_MAX + 1 clocks, each needing more: some dropped");
    assert_eq!(sim.overflows as usize, run.dropped.len());
    assert_eq!(run.rows.len() + run.dropped.len(), frame.len());
    assert!(run.rows.last().is_some_and(|r| r.eof), "the frame still ends");
    let left: Vec<Vec<FixedMatch>> = frame.iter().enumerate().filter(|(y, _)| !run.dropped.contains(y)).map(|(_, r)| r.clone()).collect();
    check_kept(&[&left], &run).expect("the stored rows checked against each other");
    eprintln!("dropped rows {:?}", run.dropped);
    let later = vec![row(30, 4, 3 * PX, 9), row(30, 4, 3 * PX, 9)];
    let run = sim.run(&later, safe_period(&later, 0));
    assert_eq!(run.dropped, Vec::<usize>::new());
    check_kept(&[&later], &run).expect("a later frame is intact");
}

/// Matches closer than a pixel (not the matcher's output): more than
/// `ROW_WINDOW - 1` in a window flag `crowded`, and the row check goes on
/// (every row leaves).
#[test]
fn matches_denser_than_a_pixel_raise_crowded_and_every_row_still_leaves() {
    let dense = row(N_MAX, 1, 1, 5);
    let frame = vec![dense.clone(), row(N_MAX, 1, 1, 9), dense];
    let mut sim = RowCheckSim::new();
    let run = sim.run(&frame, 2000);
    assert!(sim.crowded > 0);
    assert_eq!(run.rows.len(), 3);
}

/// The rtl's thresholds are golden's.
#[test]
fn the_thresholds_are_golden_consistency_bounds() {
    assert_eq!(CONSISTENT_DX_LSB as f64, golden::params::CONSISTENT_DX * PX as f64);
    assert_eq!(CONSISTENT_DD_LSB as f64, golden::params::CONSISTENT_DD * PX as f64);
}

// ===========================================================================
// Real pairs
// ===========================================================================

/// golden's robust-mode matches of every row of `pair` before the check
/// across rows, quantised as the matcher emits them, one row per `width`
/// clocks (a sensor's line period): every row's kept matches are golden's
/// parity row check of the same values and the matches golden's parity
/// frame keeps, on the documented clocks, nothing dropped.
fn real_pair(pair: &str) {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(pair)).expect("the pair loads");
    let mut params = golden::Params::new(data.dispmax + 1.0).expect("params");
    params.hardware = Some(sim::Config::Sd.limits());
    assert!(params.mode.features().consistent, "the default mode checks across rows");
    let frame = unchecked_rows(&data.left, &data.right, &params);
    let w = data.left.width();
    let rows = frame_rows(&frame, w, 0);
    let mut sim = RowCheckSim::new();
    let run = sim.run_timed(&rows);
    assert_eq!(sim.overflows, 0);
    assert_eq!(sim.crowded, 0);
    check_kept(&[&frame], &run).unwrap_or_else(|e| panic!("{pair}: {e}"));
    let worst = check_timing(&rows, &run).unwrap_or_else(|e| panic!("{pair}: {e}"));
    let (n, kept): (usize, usize) = (frame.iter().map(Vec::len).sum(), run.rows.iter().map(|r| r.count).sum());
    let max_n = frame.iter().map(Vec::len).max().unwrap_or(0);
    eprintln!("{pair}: {} rows, {n} matches, {kept} kept, at most {max_n} per row, at most {worst} clocks a row (line {w}), {} clocks", frame.len(), sim.cycle);
    assert!(kept > n / 2 && kept < n, "{pair}: the check keeps most but not all");
    // golden's frame in hardware parity keeps the same matches.
    let limits = sim::Config::Sd.limits();
    let golden_frame = golden::process_frame(&data.left, &data.right, &params, golden::Threads::All).expect("golden runs");
    for (y, (line, out)) in golden_frame.lines.iter().zip(&run.rows).enumerate() {
        let kept: Vec<FixedMatch> = line
            .matches
            .iter()
            .map(|m| golden::hardware::row_check::FixedMatch::of(m, limits))
            .map(|m| (m.x as u64, m.d as u64))
            .collect();
        assert_eq!(kept, out.kept, "{pair} row {y}: golden's parity frame keeps other matches");
    }
}

#[test]
fn every_row_of_tsukuba_keeps_golden_confirmed_matches() {
    real_pair("tsukuba");
}

#[test]
fn every_row_of_cones_keeps_golden_confirmed_matches() {
    real_pair("cones");
}

// ===========================================================================
// Verilog
// ===========================================================================


#[test]
fn row_check_generates_verilog_that_lints_clean_but_for_the_accepted_warnings() {
    let v = sim::hdl::cosim::verilog_of(RowCheck::new());
    assert!(v.contains("module top") && v.contains("DP16KD"), "the Verilog holds the block and its block RAMs");
    if std::process::Command::new("verilator").arg("--version").output().is_err() {
        eprintln!("verilator not installed: lint skipped");
        return;
    }
    let warnings = sim::hdl::cosim::lint_verilator(&v).unwrap_or_else(|e| panic!("{e}"));
    let counts = sim::hdl::cosim::check_accepted(&warnings, sim::hdl::cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("accepted lint warnings: {counts:?}");
}

/// The generated Verilog under Icarus and Verilator gives the Rust model's
/// outputs, clock by clock, on frames of random rows (empty, sparse, a
/// pixel apart, denser than a pixel so that windows crowd) at periods from
/// too short (rows dropped) to long, with idle clocks between matches.
#[test]
fn row_check_verilog_replays_the_rust_model_under_icarus_and_verilator() {
    use sim::hdl::cosim::{self, Options, Simulator};
    let v = sim::hdl::cosim::verilog_of(RowCheck::new());
    let (ins, outs) = cosim::data_ports(&v).expect("ports");
    let names: Vec<String> = ins.iter().map(|p| p.name.clone()).collect();
    let mut rng = sim::rng::VectorRng(0x0c0f_fee5);
    let mut rows: Vec<TimedRow> = Vec::new();
    // Frames of `h` rows: `n` matches `step` apart, rows `period` clocks
    // apart; the first two fixed (denser than a pixel: crowded; full rows
    // back to back: dropped), the others random.
    for f in 0..8 {
        let h = match f {
            0 => 4,
            1 => 8,
            _ => 1 + (rng.next() % 6) as usize,
        };
        for y in 0..h {
            let r = rng.next();
            let n = [60, N_MAX + 2, [0, 3, 20, 60, N_MAX + 2][(r % 5) as usize]][f.min(2)];
            let step = [5, PX, [PX, PX + 3, 3 * PX, 5][((r >> 8) % 4) as usize]][f.min(2)];
            let d0 = 4 + (r >> 16) % 8;
            let gap = ((r >> 24) % 3) as usize * ((r >> 28) % 2) as usize;
            let x0 = (r >> 32) % (4 * PX);
            let matches = (0..n as u64).map(|i| (x0 + i * step, d0 * PX + (rng.next() % (3 * PX)))).collect();
            let period = [400, 0, [0usize, 40, 150, 400][((r >> 40) % 4) as usize]][f.min(2)];
            rows.push(TimedRow { matches, sof: y == 0, eof: y + 1 == h, period, gap, last_x: 0 });
        }
    }
    let (mut beats, _) = row_beats(&rows);
    beats.resize(beats.len() + row_check_period() * 3, Beat::default());
    let value = |b: &Beat, n: &str| match n {
        "m_valid" => b.valid as u64,
        "m_last" => b.last as u64,
        "m_x_ref" => b.x,
        "m_disp" => b.d,
        "m_sof" => b.sof as u64,
        "m_eof" => b.eof as u64,
        // The stimuli never reset the block.
        "reset" => 0,
        other => panic!("unknown input {other}"),
    };
    let stimulus: Vec<Vec<u64>> = beats.iter().map(|b| names.iter().map(|n| value(b, n)).collect()).collect();
    let mut reader = cosim::PortReader::new(&ins, &outs);
    let mut uut = RowCheck::new();
    let trace = cosim::record(
        &mut uut,
        &ins,
        &outs,
        |u: &mut RowCheck, level| u.clock.next = level.into(),
        |u: &mut RowCheck, x: &[u64]| {
            for (n, &x) in names.iter().zip(x) {
                match n.as_str() {
                    "m_valid" => u.m_valid.next = x != 0,
                    "m_last" => u.m_last.next = x != 0,
                    "m_x_ref" => u.m_x_ref.next = x.into(),
                    "m_disp" => u.m_disp.next = x.into(),
                    "m_sof" => u.m_sof.next = x != 0,
                    "m_eof" => u.m_eof.next = x != 0,
                    "reset" => u.reset.next = x != 0,
                    _ => {}
                }
            }
        },
        |u: &RowCheck| reader.read(u, &ins, &outs).unwrap_or_else(|e| panic!("{e}")).outputs,
        stimulus,
    )
    .expect("records");
    let out = |name: &str| outs.iter().position(|p| p.name == name).expect("an output");
    let (valid, last, over, crowd) = (out("c_valid"), out("c_last"), out("overflow"), out("crowded"));
    let count = |k: usize| trace.cycles.iter().filter(|c| c.outputs[k] != 0).count();
    eprintln!("{} clocks: {} beats out, {} rows, {} dropped, {} crowded", trace.len(), count(valid), count(last), count(over), count(crowd));
    assert!(count(last) > 10 && count(over) > 0 && count(crowd) > 0, "the stimulus reaches rows out, drops and crowding");
    for s in [Simulator::Icarus, Simulator::Verilator] {
        let run = cosim::check(s, &v, &trace, &Options::default()).unwrap_or_else(|e| panic!("{}: {e}", s.name()));
        eprintln!("{}: {} cycles, run {:.2} s", s.name(), trace.len(), run.run.as_secs_f64());
    }
}

/// Yosys and nextpnr place and route the row check on the ECP5-85K
/// (`sim::hdl::synth`, target 125 MHz): its six block RAMs (three copies of
/// two), no multiplier, no LUT RAM. The report (LUTs, FFs, Fmax, critical
/// path) is printed, not checked: Fmax and the critical path change with
/// nextpnr's placer seed.
#[test]
fn row_check_places_and_routes_on_ecp5_85k_with_six_block_rams() {
    let v = sim::hdl::cosim::verilog_of(RowCheck::new());
    let r = sim::hdl::synth::synthesize(&v, 125.0).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", sim::hdl::synth::report_table(&r));
    assert_eq!((r.brams, r.dsps, r.lutram), (6, 0, 0), "block RAMs, multipliers, LUT RAM");
}
