//! The rtl vertical median (`rtl::post::vertical_median`) against golden's
//! (`golden::disparity::vertical_median`, `MEDIAN_ROWS` rows), on generated
//! frames and on the robust mode's dense maps of real pairs before their
//! median, and its timing against `MEDIAN_LAG` and the flush rule of its
//! doc comment, clock by clock.
//!
//! Both get the same fixed-point values (`sim::drive::vertical_median`): golden
//! takes them as reals (`d / 16`, exact). A median is one of its inputs, so
//! the two must be equal on every pixel.
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_vertical_median`).

use golden::disparity::vertical_median;
use golden::hardware::interpolate::Interpolator;
use golden::hardware::row_check::FixedMatch;
use golden::params::MEDIAN_ROWS;
use proptest::prelude::*;
use rtl::params::{MEDIAN_HALF, MEDIAN_LINE_BUFFERS, MEDIAN_TAPS, POS_BITS, W_MAX};
use rtl::post::vertical_median::MEDIAN_LAG;
use sim::hdl::cosim::{self, Options, Simulator};
use sim::hdl::traces::{median_trace, median_verilog};
use sim::drive::vertical_median::{
    frame_beats, golden_median, quantise_map, split_rows, MedianBeat, MedianTiming, VerticalMedianSim,
};

/// The largest disparity.
const TOP: u64 = (1 << POS_BITS) - 1;

/// The documented output clocks of a frame whose pixels came in at
/// `input` (clock of each pixel, by row): pixel `(x, y)` with `y + 4 < h`
/// leaves `MEDIAN_LAG` clocks after pixel `(x, y + 4)`; the flush starts
/// on the clock after the last row's last pixel, rows `h - 4 ..= h - 1`
/// (those `>= 0`) at one pixel per clock, each `MEDIAN_LAG` after its
/// clock.
fn expected_clocks(input: &[Vec<u64>]) -> Vec<Vec<u64>> {
    let (h, w) = (input.len(), input[0].len());
    let lag = MEDIAN_LAG as u64;
    let mut out: Vec<Vec<u64>> = (MEDIAN_HALF..h).map(|y| input[y].iter().map(|&t| t + lag).collect()).collect();
    let flush = input[h - 1][w - 1] + 1;
    let flushed = h.min(MEDIAN_HALF);
    for r in 0..flushed {
        out.push((0..w).map(|x| flush + (r * w + x) as u64 + lag).collect());
    }
    out
}

/// A frame's output against golden and the documented timing.
fn check_frame(frame: &[Vec<u64>], rows: &[Vec<u64>], t: &MedianTiming) -> Result<(), String> {
    let want = golden_median(frame).map_err(|e| e.to_string())?;
    if t.overflows != 0 {
        return Err(format!("{} overflows", t.overflows));
    }
    if rows.len() != want.len() {
        return Err(format!("{} rows out of {}", rows.len(), want.len()));
    }
    for (y, (g, w)) in rows.iter().zip(&want).enumerate() {
        if let Some(x) = (0..w.len()).find(|&x| g.get(x) != Some(&w[x])) {
            return Err(format!("row {y} pixel {x}: rtl {:?}, golden {}", g.get(x), w[x]));
        }
        if g.len() != w.len() {
            return Err(format!("row {y}: {} pixels for {}", g.len(), w.len()));
        }
    }
    let sof: Vec<bool> = (0..rows.len()).map(|y| y == 0).collect();
    if t.sof != sof {
        return Err(format!("v_sof on rows {:?}", t.sof));
    }
    let clocks = expected_clocks(&t.input);
    if let Some(y) = (0..clocks.len()).find(|&y| clocks[y] != t.output[y]) {
        return Err(format!("row {y} left at {:?}, expected {:?}", t.output[y], clocks[y]));
    }
    Ok(())
}

// ===========================================================================
// Generated frames
// ===========================================================================

/// A frame: 1 to 13 rows of 1 to 64 pixels (now and then `W_MAX`), each
/// pixel one of four values of the frame (0 among them, the largest
/// disparity sometimes), so that the nine rows of a median tie often.
fn any_frame() -> impl Strategy<Value = Vec<Vec<u64>>> {
    let width = prop_oneof![8 => 1usize..=64, 1 => Just(W_MAX)];
    let values = (1u64..=TOP, 1u64..=TOP, any::<bool>());
    (1usize..=13, width, values).prop_flat_map(|(h, w, (v1, v2, top))| {
        let palette = [0, v1, v2, if top { TOP } else { v1 / 2 }];
        prop::collection::vec(prop::collection::vec(prop::sample::select(palette.to_vec()), w..=w), h..=h)
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Every output pixel is golden's median of the same fixed-point
    /// values, exactly, and leaves on the documented clock (rows back to
    /// back or apart, the flush after the last row).
    #[test]
    fn prop_every_pixel_equals_golden_median_exactly_and_leaves_on_its_documented_clock(
        frame in any_frame(),
        idle in prop_oneof![Just(0usize), 0usize..40],
    ) {
        let period = frame[0].len() + idle;
        let mut sim = VerticalMedianSim::new();
        let (rows, t) = sim.run(&frame, period).expect("a frame");
        check_frame(&frame, &rows, &t).map_err(TestCaseError::fail)?;
    }

    /// Idle clocks inside rows and between them only delay: each output
    /// pixel still leaves `MEDIAN_LAG` clocks after the pixel four rows
    /// below it, and equals golden's median.
    #[test]
    fn prop_idle_clocks_inside_rows_only_delay_each_pixel_by_the_same_lag(
        frame in any_frame().prop_filter("narrow", |f| f[0].len() <= 64),
        gaps in prop::collection::vec(0usize..3, 64 * 13),
    ) {
        let (h, w) = (frame.len(), frame[0].len());
        let mut beats = Vec::new();
        let mut input = vec![Vec::new(); h];
        let mut g = gaps.iter().cycle();
        for (y, r) in frame.iter().enumerate() {
            for (x, &d) in r.iter().enumerate() {
                beats.extend(std::iter::repeat_n(MedianBeat::default(), *g.next().unwrap()));
                input[y].push(beats.len() as u64);
                beats.push(MedianBeat { valid: true, d, last: x + 1 == w, sof: y == 0 && x == 0, eof: y + 1 == h });
            }
        }
        let mut sim = VerticalMedianSim::new();
        let pixels = sim.run_beats(&beats, MEDIAN_HALF * w + MEDIAN_LAG + 2);
        let (rows, output, sof) = split_rows(&pixels);
        let t = MedianTiming { input, output, sof, overflows: sim.overflows };
        check_frame(&frame, &rows, &t).map_err(TestCaseError::fail)?;
    }
}

/// Frames of one to nine rows, one to three pixels wide, rows back to
/// back (a word is read on the clock it is written when rows are one
/// pixel wide): every pixel as golden, clamped at both ends.
#[test]
fn frames_of_one_to_nine_rows_clamp_at_both_ends_even_with_one_pixel_rows_back_to_back() {
    let mut n = 0;
    for h in 1..=MEDIAN_TAPS {
        for w in 1..=3usize {
            // Distinct values per row and column: any wrong row shows.
            let frame: Vec<Vec<u64>> = (0..h).map(|y| (0..w).map(|x| (7 * y as u64 + 3 * x as u64 * x as u64 + 1) % 11).collect()).collect();
            let mut sim = VerticalMedianSim::new();
            let (rows, t) = sim.run(&frame, w).expect("a frame");
            check_frame(&frame, &rows, &t).unwrap_or_else(|e| panic!("{h}x{w}: {e}"));
            n += 1;
        }
    }
    assert_eq!(n, 3 * MEDIAN_TAPS);
}

/// The row of a new frame arriving during the flush is dropped whole,
/// also its pixels after the flush's end, `overflow` high for each of them
/// (a clock later); the frame's own rows all leave as golden's, and the
/// next row is row 0 of a new frame (without `p_sof`).
#[test]
fn a_row_arriving_during_the_flush_is_dropped_whole_with_overflow_and_the_next_row_starts_a_frame() {
    let w = 20usize;
    let first: Vec<Vec<u64>> = (0..6).map(|y| (0..w as u64).map(|x| 16 * (y as u64 * 3 + x % 5)).collect()).collect();
    let second: Vec<Vec<u64>> = (0..3).map(|y| (0..w as u64).map(|x| 1000 + 17 * (y as u64 + x)).collect()).collect();
    let mut beats = frame_beats(&first, w).expect("beats");
    // A row 5 clocks before the end of the flush (its 4·w clocks start on
    // the clock after the last row): 5 pixels in the flush, 15 after.
    beats.extend(std::iter::repeat_n(MedianBeat::default(), MEDIAN_HALF * w - 5));
    let dropped_at = beats.len();
    beats.extend(frame_beats(&[vec![TOP; w]], w).expect("beats").into_iter().map(|b| MedianBeat { eof: false, ..b }));
    // Then the second frame at once, without p_sof.
    beats.extend(frame_beats(&second, w).expect("beats").into_iter().map(|b| MedianBeat { sof: false, ..b }));
    let mut sim = VerticalMedianSim::new();
    let mut overflow_at = Vec::new();
    let mut pixels = Vec::new();
    for b in beats.iter().copied().chain(std::iter::repeat_n(MedianBeat::default(), MEDIAN_HALF * w + MEDIAN_LAG + 2)) {
        let before = sim.overflows;
        let now = sim.cycle;
        pixels.extend(sim.clock(b));
        if sim.overflows > before {
            overflow_at.push(now);
        }
    }
    let want: Vec<u64> = (0..w as u64).map(|x| dropped_at as u64 + x + 1).collect();
    assert_eq!(overflow_at, want, "overflow a clock after each dropped pixel");
    let (rows, _, sof) = split_rows(&pixels);
    let mut expected = golden_median(&first).expect("golden");
    expected.extend(golden_median(&second).expect("golden"));
    assert_eq!(rows, expected, "both frames whole, the dropped row nowhere");
    assert_eq!(sof, [vec![true], vec![false; 5], vec![true], vec![false; 2]].concat());
}

/// Two frames back to back, the second starting right after the first's
/// flush (the least vertical blanking, four row widths): the second
/// frame's rows are its own median, nothing of the first mixed in; a frame
/// cut short by a start of frame (no `p_eof`) emits its rows up to `h - 5`
/// and the new frame starts clean.
#[test]
fn two_frames_back_to_back_do_not_mix_rows_and_a_start_of_frame_restarts_the_rows() {
    let w = 33usize;
    let a: Vec<Vec<u64>> = (0..11).map(|y| (0..w as u64).map(|x| (y as u64 * 50 + x) * 3).collect()).collect();
    let b: Vec<Vec<u64>> = (0..6).map(|y| (0..w as u64).map(|x| TOP - (y as u64 * 40 + x)).collect()).collect();
    let mut beats = frame_beats(&a, w).expect("beats");
    beats.extend(std::iter::repeat_n(MedianBeat::default(), MEDIAN_HALF * w));
    beats.extend(frame_beats(&b, w).expect("beats"));
    let mut sim = VerticalMedianSim::new();
    let pixels = sim.run_beats(&beats, MEDIAN_HALF * w + MEDIAN_LAG + 2);
    let (rows, _, sof) = split_rows(&pixels);
    assert_eq!(sim.overflows, 0);
    let mut expected = golden_median(&a).expect("golden");
    expected.extend(golden_median(&b).expect("golden"));
    assert_eq!(rows, expected);
    assert_eq!(sof, [vec![true], vec![false; 10], vec![true], vec![false; 5]].concat());
    // Back to back as the first frame's rows: nine rows of `a` without
    // eof, then `b`.
    let cut: Vec<Vec<u64>> = a[..9].to_vec();
    let mut beats: Vec<MedianBeat> = frame_beats(&cut, w).expect("beats").into_iter().map(|x| MedianBeat { eof: false, ..x }).collect();
    beats.extend(frame_beats(&b, w).expect("beats"));
    let mut sim = VerticalMedianSim::new();
    let (rows, _, _) = split_rows(&sim.run_beats(&beats, MEDIAN_HALF * w + MEDIAN_LAG + 2));
    let full = golden_median(&a).expect("golden");
    let mut expected: Vec<Vec<u64>> = full[..5].to_vec();
    expected.extend(golden_median(&b).expect("golden"));
    assert_eq!(rows, expected);
}

/// The rtl's taps and buffers are golden's default mode's.
#[test]
fn the_median_has_golden_default_mode_rows_and_one_buffer_per_row_above() {
    assert_eq!(MEDIAN_TAPS, MEDIAN_ROWS);
    assert_eq!(golden::Mode::default().features().median_rows, MEDIAN_ROWS);
    assert_eq!(MEDIAN_LINE_BUFFERS, MEDIAN_ROWS - 1);
}

// ===========================================================================
// Real pairs
// ===========================================================================

/// The robust mode's dense map of `pair` before its median (hardware
/// parity): golden's matches after the neighbouring-row check and the edge
/// flag, interpolated as its step 4 does (the line processor's
/// interpolator, `golden::hardware::interpolate`: multiples of 1/16 px).
/// Checked: golden's median of it is golden's final map.
fn robust_map_before_median(pair: &str) -> (Vec<f64>, usize) {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(pair)).expect("the pair loads");
    let mut params = golden::Params::new(data.dispmax + 1.0).expect("params");
    params.hardware = Some(sim::Config::Sd.limits());
    let frame = golden::process_frame(&data.left, &data.right, &params, golden::Threads::All).expect("golden runs");
    let w = frame.width;
    let limits = sim::Config::Sd.limits();
    let interpolator = Interpolator::of_features(limits, &params.mode.features());
    let mut map = vec![0.0; w * frame.height];
    for (line, out) in frame.lines.iter().zip(map.chunks_mut(w)) {
        let matches: Vec<FixedMatch> = line.matches.iter().map(|m| FixedMatch::of(m, limits)).collect();
        let mut lsb = vec![0u16; w];
        interpolator.row(&matches, &mut lsb);
        out.iter_mut().zip(&lsb).for_each(|(o, &d)| *o = d as f64 / 16.0);
    }
    let mut medianed = vec![0.0; w * frame.height];
    for (y, out) in medianed.chunks_mut(w).enumerate() {
        vertical_median(&map, w, MEDIAN_ROWS, out, y);
    }
    assert!(medianed == frame.disparity, "{pair}: the rebuilt map is the one golden's median took");
    (map, w)
}

/// Every row of the pair's pre-median map, quantised, through the rtl one
/// row per row period of `width` clocks (as the interpolator sends them):
/// every pixel golden's median, on its documented clock.
fn real_pair(pair: &str) {
    let (map, w) = robust_map_before_median(pair);
    assert!(w <= W_MAX);
    let frame = quantise_map(&map, w);
    let mut sim = VerticalMedianSim::new();
    let (rows, t) = sim.run(&frame, w).expect("a frame");
    check_frame(&frame, &rows, &t).unwrap_or_else(|e| panic!("{pair}: {e}"));
    let changed = rows.iter().flatten().zip(frame.iter().flatten()).filter(|(a, b)| a != b).count();
    eprintln!("{pair}: {}x{} pixels, {changed} changed by the median, {} clocks", w, frame.len(), sim.cycle);
    assert!(changed > 0, "{pair}: the median changed nothing: not a test");
}

#[test]
fn every_pixel_of_tsukuba_robust_map_medians_as_golden() {
    real_pair("tsukuba");
}

#[test]
fn every_pixel_of_cones_robust_map_medians_as_golden() {
    real_pair("cones");
}

// ===========================================================================
// Verilog
// ===========================================================================

/// Small frames of every height, one-pixel rows back to back, a dropped
/// row, two frames: the stimulus of the co-simulation.
fn cosim_beats() -> Vec<MedianBeat> {
    let mut beats = Vec::new();
    for h in 1..=10usize {
        let w = if h % 2 == 0 { 1 } else { 5 };
        let frame: Vec<Vec<u64>> = (0..h).map(|y| (0..w as u64).map(|x| (y as u64 * 977 + x * 131) % (TOP + 1)).collect()).collect();
        beats.extend(frame_beats(&frame, w).expect("beats"));
        beats.extend(std::iter::repeat_n(MedianBeat::default(), if h == 5 { 2 } else { MEDIAN_HALF * w }));
    }
    beats
}

#[test]
fn vertical_median_verilog_generates_and_matches_rust_under_icarus() {
    let v = median_verilog();
    assert!(v.contains("module top"), "a top module");
    assert_eq!(v.matches("DP16KD #(").count(), MEDIAN_LINE_BUFFERS, "one DP16KD per line buffer");
    let trace = median_trace(&v, &cosim_beats(), MEDIAN_HALF * 5 + MEDIAN_LAG + 2).expect("records");
    let valid = trace.outputs.iter().position(|p| p.name == "v_valid").expect("v_valid");
    let overflow = trace.outputs.iter().position(|p| p.name == "overflow").expect("overflow");
    let count = |i: usize| trace.cycles.iter().filter(|c| c.outputs[i] == 1).count();
    // (The 5-row frame's flush is cut into by the next frames: dropped
    // rows, then a frame taken from a row without p_sof.)
    assert!(count(valid) > 40, "{} pixels out", count(valid));
    assert!(count(overflow) > 0, "a dropped pixel");
    let run = cosim::check(Simulator::Icarus, &v, &trace, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("icarus: {} cycles, {} pixels, {} overflows, {:.2} s", trace.len(), count(valid), count(overflow), run.run.as_secs_f64());
}

#[test]
fn vertical_median_verilog_lints_clean_but_for_the_accepted_warnings() {
    let warnings = cosim::lint_verilator(&median_verilog()).unwrap_or_else(|e| panic!("{e}"));
    // (PINMISSING is accepted on DP16KD data outputs only: check_accepted.)
    let counts = cosim::check_accepted(&warnings, cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{e}"));
    // Each DP16KD: port A's 18 outputs and port B's 4 above POS_BITS.
    assert_eq!(counts.get("PINMISSING"), Some(&(MEDIAN_LINE_BUFFERS * (18 + 18 - POS_BITS))));
    eprintln!("accepted lint warnings: {counts:?}");
}
