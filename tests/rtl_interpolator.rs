//! The rtl interpolator (`rtl::post::interpolator`) against golden's
//! hardware-parity interpolator (`golden::hardware::interpolate`), on
//! generated lines and on the matches of every row of real pairs, and its
//! timing against the constants in its doc comment.
//!
//! Both get the same fixed-point anchors (`sim::drive::interpolator`), and
//! golden computes what the hardware computes (the segments, the
//! reciprocal table, the weight and its rounding): every pixel must be
//! equal. golden's reciprocal table is built from golden's own formats and
//! must equal the rtl's, entry for entry.
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_interpolator`).

use golden::disparity::{interpolate_into, Anchor};
use golden::params::EndRule;
use proptest::prelude::*;
use rtl::post::interpolator::{recip_table, LINE_QUEUE, PIXEL_LAG, SEGMENT_LAG};
use rtl::params::{EDGE_JUMP_LSB, N_MAX, POS_BITS, POS_FRAC_BITS, RECIP_BITS, RECIP_INDEX_BITS, RECIP_SHIFT, WEIGHT_FRAC_BITS, W_MAX};
use sim::drive::interpolator::{fixed_anchors, golden_line, AnchorLine, FixedAnchor, InterpolatorSim, PixelLine};

/// One position LSB (1/16 px).
const PX: u32 = 1 << POS_FRAC_BITS;

/// Checks one line pixel by pixel against golden's parity interpolator:
/// its length, its flags and every pixel equal.
fn check_line(line: &AnchorLine, jump: Option<u64>, got: &PixelLine) -> Result<(), String> {
    let want = golden_line(line, jump);
    if got.d.len() != line.width {
        return Err(format!("{} pixels for a line of {}", got.d.len(), line.width));
    }
    if got.empty != line.anchors.is_empty() || got.sof != line.sof {
        return Err(format!("flags: empty {} sof {} for {} anchors, sof {}", got.empty, got.sof, line.anchors.len(), line.sof));
    }
    if let Some(x) = (0..line.width).find(|&x| got.d[x] != want[x]) {
        return Err(format!("pixel {x}: rtl {}, golden {} in {line:?}", got.d[x], want[x]));
    }
    Ok(())
}

/// golden's f64 interpolation (`golden::disparity::interpolate_into`) of
/// the same anchors, rounded to LSBs: what the interpolator approximates.
fn golden_f64_line(line: &AnchorLine, jump: Option<u64>) -> Vec<u32> {
    let unit = PX as f64;
    let anchors: Vec<Anchor> = line.anchors.iter().map(|a| Anchor { x: a.x as f64 / unit, d: a.d as f64 / unit }).collect();
    let mut out = vec![0.0; line.width];
    interpolate_into(&anchors, EndRule::Hold, jump.map(|j| j as f64 / unit), &mut out);
    out.iter().map(|v| (v * unit).round() as u32).collect()
}

/// The documented timing: each line's first pixel leaves `SEGMENT_LAG +
/// PIXEL_LAG` clocks after its marker, or on the clock after the previous
/// line's last pixel if that is later, and its pixels on consecutive clocks.
fn check_timing(got: &[PixelLine], markers: &[u64]) -> Result<(), String> {
    let mut free = 0u64;
    for (k, (g, m)) in got.iter().zip(markers).enumerate() {
        let want = (m + (SEGMENT_LAG + PIXEL_LAG) as u64).max(free);
        if g.first_cycle != want || g.last_cycle + 1 - g.first_cycle != g.d.len() as u64 {
            return Err(format!("line {k}: pixels at {}..={}, marker at {m}, expected from {want}", g.first_cycle, g.last_cycle));
        }
        free = g.last_cycle + 1;
    }
    Ok(())
}

// ===========================================================================
// Generated lines
// ===========================================================================

/// A line: width, anchors by strictly increasing x below 16·width (steps
/// from one LSB, several anchors in one pixel, to tens of pixels),
/// disparities with small steps, jumps beyond the edge jump and the
/// largest values.
fn any_line() -> impl Strategy<Value = AnchorLine> {
    let width = prop_oneof![1usize..=8, 8usize..=300, Just(W_MAX), 300usize..=W_MAX];
    let steps = prop::collection::vec((prop_oneof![1u32..=3, 1u32..=PX, PX..=40 * PX], 0u32..3, 0u32..(1 << POS_BITS)), 0..=N_MAX);
    (width, steps, any::<bool>(), 1u32..=64 * PX).prop_map(|(width, steps, sof, d0)| {
        let mut anchors = Vec::new();
        let (mut x, mut d) = (0u32, d0);
        for (k, (step, how, far)) in steps.into_iter().enumerate() {
            if k > 0 {
                x += step;
            }
            if x >= width as u32 * PX {
                break;
            }
            d = match how {
                0 => d.saturating_add(far % (4 * PX)).min((1 << POS_BITS) - 1),
                1 => d.saturating_sub(far % (4 * PX)),
                _ => far,
            };
            anchors.push(FixedAnchor { x, d });
        }
        AnchorLine { anchors, width, sof }
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Each line's pixels are golden's parity interpolation of the same
    /// anchors, every one; lines come out whole, in order, with their flags.
    #[test]
    fn prop_every_pixel_equals_golden_parity_interpolation(
        lines in prop::collection::vec(any_line(), 1..=3),
        bridged in any::<bool>(),
        period in prop_oneof![Just(0usize), 0usize..2000],
    ) {
        let jump = (!bridged).then_some(EDGE_JUMP_LSB);
        let mut sim = InterpolatorSim::new(jump);
        let (got, markers) = sim.run(&lines, period);
        prop_assert_eq!(sim.overflows, 0);
        prop_assert_eq!(got.len(), lines.len());
        check_timing(&got, &markers).map_err(TestCaseError::fail)?;
        for (l, g) in lines.iter().zip(&got) {
            check_line(l, jump, g).map_err(TestCaseError::fail)?;
        }
    }
}

// ===========================================================================
// Timing and overflow
// ===========================================================================

/// A line's first pixel leaves `SEGMENT_LAG + PIXEL_LAG` clocks after its
/// marker when the interpolator is idle; lines waiting in the queue leave
/// back to back, one pixel per clock.
#[test]
fn the_first_pixel_follows_the_marker_by_the_documented_lag_and_queued_lines_leave_back_to_back() {
    let line = |w: usize| AnchorLine {
        anchors: vec![FixedAnchor { x: 3 * PX + 5, d: 10 * PX }, FixedAnchor { x: 20 * PX, d: 12 * PX }],
        width: w,
        sof: false,
    };
    // Idle: lines far apart.
    let mut sim = InterpolatorSim::robust();
    let lines = [line(40), line(300), line(1)];
    let (got, markers) = sim.run(&lines, 2000);
    assert_eq!(got.len(), 3);
    for (g, m) in got.iter().zip(&markers) {
        assert_eq!(g.first_cycle - m, (SEGMENT_LAG + PIXEL_LAG) as u64);
        assert_eq!(g.last_cycle - g.first_cycle + 1, g.d.len() as u64, "one pixel per clock");
    }
    check_timing(&got, &markers).expect("the documented timing");
    // Queued: the markers arrive while the first line is still going out.
    let mut sim = InterpolatorSim::robust();
    let lines = [line(500), line(37), line(1), line(200)];
    let (got, markers) = sim.run(&lines, 0);
    assert_eq!(got.len(), 4);
    assert_eq!(got[0].first_cycle - markers[0], (SEGMENT_LAG + PIXEL_LAG) as u64);
    for w in got.windows(2) {
        assert_eq!(w[1].first_cycle, w[0].last_cycle + 1, "back to back");
    }
    for (l, g) in lines.iter().zip(&got) {
        check_line(l, Some(EDGE_JUMP_LSB), g).expect("as golden");
    }
}

/// Lines of one to three pixels queued behind a long one leave back to
/// back as golden's, a line of one pixel ending on the clock it starts:
/// the pixel engine takes a line's first pixel's place (in the head, in a
/// segment, the line's last) from flags written with the line, every later
/// one from comparisons made a clock ahead, so these lines are the ones
/// where the two meet on consecutive clocks.
#[test]
fn lines_of_one_to_three_pixels_queued_back_to_back_are_golden_interpolation() {
    let a = |x: u32, d: u32| FixedAnchor { x, d };
    let l = |anchors: Vec<FixedAnchor>, width: usize, sof: bool| AnchorLine { anchors, width, sof };
    let long = || l(vec![a(3 * PX, 10 * PX), a(200 * PX, 30 * PX)], 500, true);
    let runs = [
        vec![
            long(),
            l(vec![], 1, false),
            l(vec![a(0, 7 * PX)], 1, false),
            l(vec![a(0, 7 * PX), a(PX, 9 * PX)], 2, false),
            l(vec![a(PX / 2, 4 * PX)], 1, true),
            l(vec![a(0, 3 * PX), a(PX + 3, 8 * PX), a(2 * PX, 2 * PX)], 3, false),
            l(vec![a(2 * PX + 1, 5 * PX)], 3, false),
            l(vec![], 2, false),
        ],
        vec![
            long(),
            l(vec![a(0, 6 * PX), a(PX, 40 * PX)], 2, false),
            l(vec![a(0, 6 * PX), a(1, 9 * PX)], 1, false),
            l(vec![a(PX, 6 * PX), a(2 * PX, 2 * PX)], 3, false),
            l(vec![a(PX - 1, 12 * PX)], 1, false),
            l(vec![], 3, true),
            l(vec![a(0, PX), a(PX, 2 * PX), a(2 * PX, 4 * PX)], 3, false),
            l(vec![a(5, 9 * PX)], 1, false),
        ],
    ];
    for lines in runs {
        let mut sim = InterpolatorSim::robust();
        let (got, markers) = sim.run(&lines, 0);
        assert_eq!(sim.overflows, 0);
        assert_eq!(got.len(), lines.len());
        check_timing(&got, &markers).expect("the documented timing");
        for w in got.windows(2) {
            assert_eq!(w[1].first_cycle, w[0].last_cycle + 1, "back to back");
        }
        for (l, g) in lines.iter().zip(&got) {
            check_line(l, Some(EDGE_JUMP_LSB), g).expect("as golden");
        }
    }
}

/// More lines than the queue holds arriving at once: the first ones come
/// out, the one without room is dropped whole with `overflow`, and the
/// next line, offered once there is room again, is intact.
#[test]
fn a_line_without_room_in_the_queue_is_dropped_whole_and_flagged_and_later_lines_are_intact() {
    let line = |k: u32| AnchorLine {
        anchors: (0..50).map(|i| FixedAnchor { x: i * 7 * PX + k, d: 5 * PX + i * 3 + k }).collect(),
        width: W_MAX,
        sof: k == 0,
    };
    let burst: Vec<AnchorLine> = (0..LINE_QUEUE as u32 + 1).map(line).collect();
    let mut sim = InterpolatorSim::robust();
    let (got, _) = sim.run(&burst, 0);
    assert_eq!(sim.overflows, 1, "exactly the line beyond the queue is dropped");
    assert_eq!(got.len(), LINE_QUEUE);
    for (l, g) in burst.iter().zip(&got) {
        check_line(l, Some(EDGE_JUMP_LSB), g).expect("the admitted lines are whole");
    }
    let later = [line(9)];
    let (got, _) = sim.run(&later, 0);
    assert_eq!(sim.overflows, 1);
    check_line(&later[0], Some(EDGE_JUMP_LSB), &got[0]).expect("the next line is intact");
}

/// A full queue of the fullest lines at once: `LINE_QUEUE` lines of
/// `N_MAX` matches (`N_MAX - 1` segments each) arriving back to back are all
/// admitted, whole (the segment memory holds the other lines' segments and
/// a line's reserve when the last one starts, as the line processor's
/// limit on lines in flight relies on); one more is dropped.
#[test]
fn a_full_queue_of_lines_of_n_max_matches_is_admitted_whole() {
    let line = |k: u32| AnchorLine {
        anchors: (0..N_MAX as u32).map(|i| FixedAnchor { x: i * 7 * PX + k, d: 5 * PX + (i * 5 + k) % 64 }).collect(),
        width: W_MAX,
        sof: k == 0,
    };
    let full: Vec<AnchorLine> = (0..LINE_QUEUE as u32).map(line).collect();
    let mut sim = InterpolatorSim::robust();
    let (got, _) = sim.run(&full, 0);
    assert_eq!(sim.overflows, 0, "every line of a full queue is admitted");
    assert_eq!(got.len(), LINE_QUEUE);
    for (l, g) in full.iter().zip(&got) {
        check_line(l, Some(EDGE_JUMP_LSB), g).expect("whole");
    }
    let over: Vec<AnchorLine> = (0..LINE_QUEUE as u32 + 1).map(line).collect();
    let (got, _) = InterpolatorSim::robust().run(&over, 0);
    assert_eq!(got.len(), LINE_QUEUE, "the line beyond the queue is dropped");
}

/// Every entry of the reciprocal table is within `2^-(RECIP_INDEX_BITS+1)`
/// + `2^-15` (relative: half a bucket, then the entry's truncation) of
/// `2^RECIP_SHIFT / m` for every normalised distance `m` of its bucket,
/// and fits its bits.
#[test]
fn reciprocal_table_is_within_its_relative_bound_of_every_distance_of_its_bucket() {
    let table = recip_table();
    let low = POS_BITS - 1 - RECIP_INDEX_BITS;
    assert_eq!(table.len(), 1 << RECIP_INDEX_BITS);
    for m in (1u64 << (POS_BITS - 1))..(1u64 << POS_BITS) {
        let r = table[((m >> low) & ((1 << RECIP_INDEX_BITS) - 1)) as usize];
        assert!(r < 1 << 16, "entry {r} fits 16 bits");
        let exact = (1u64 << RECIP_SHIFT) as f64 / m as f64;
        let rel = (r as f64 - exact).abs() / exact;
        let bound = 1.0 / (1u64 << (RECIP_INDEX_BITS + 1)) as f64 + 1.0 / (1u64 << 15) as f64;
        assert!(rel < bound, "m {m}: {r} vs {exact}");
    }
}

/// golden derives the interpolator's formats and its reciprocal table from
/// the hardware's sizes as the rtl does: the same widths, and the same
/// table entry for entry (a change on one side fails here).
#[test]
fn golden_reciprocal_table_and_formats_equal_the_rtl_entry_for_entry() {
    use golden::hardware::interpolate as g;
    let limits = sim::Config::Sd.limits();
    assert_eq!(g::position_bits(limits) as usize, POS_BITS);
    assert_eq!(g::recip_shift(limits) as usize, RECIP_SHIFT);
    assert_eq!((g::RECIP_INDEX_BITS as usize, g::RECIP_BITS as usize, g::WEIGHT_FRAC_BITS as usize), (RECIP_INDEX_BITS, RECIP_BITS, WEIGHT_FRAC_BITS));
    assert_eq!(g::MUL_OPERAND_BITS as usize, rtl::primitives::dsp_multiplier::MUL_OPERAND_BITS);
    let (gold, hw) = (g::recip_table(limits), recip_table());
    assert_eq!(gold.len(), hw.len());
    for (i, (&a, &b)) in gold.iter().zip(&hw).enumerate() {
        assert_eq!(a as u64, b, "entry {i}");
    }
}

/// The rtl's edge jump is golden's default mode's.
#[test]
fn the_edge_jump_is_golden_default_mode_edge_jump() {
    assert_eq!(EDGE_JUMP_LSB as f64, golden::params::EDGE_JUMP * PX as f64);
    assert_eq!(golden::Mode::default().features().edge_jump, Some(golden::params::EDGE_JUMP));
}

// ===========================================================================
// Real pairs
// ===========================================================================

/// golden's matches of every row of `pair` (default mode, hardware parity,
/// after the check against neighbouring rows) through the interpolator,
/// one line per line period of `width` clocks, as a sensor's come: every
/// pixel as golden's parity interpolator, nothing dropped, the pixels
/// leaving back to back. The pixels where golden's f64 interpolation
/// rounds differently are counted and required (the exact check sees the
/// interpolator's arithmetic).
fn real_pair(pair: &str) {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(pair)).expect("the pair loads");
    let mut params = golden::Params::new(data.dispmax + 1.0).expect("params");
    params.hardware = Some(sim::Config::Sd.limits());
    let frame = golden::process_frame(&data.left, &data.right, &params, golden::Threads::All).expect("golden runs");
    let w = data.left.width();
    let lines: Vec<AnchorLine> = frame.lines.iter().enumerate().map(|(y, l)| fixed_anchors(&l.matches, w, y == 0)).collect();
    let mut sim = InterpolatorSim::robust();
    let (got, markers) = sim.run(&lines, w);
    assert_eq!(sim.overflows, 0);
    assert_eq!(got.len(), lines.len());
    let mut f64_differs = 0;
    for (y, (l, g)) in lines.iter().zip(&got).enumerate() {
        check_line(l, Some(EDGE_JUMP_LSB), g).unwrap_or_else(|e| panic!("{pair} row {y}: {e}"));
        f64_differs += golden_f64_line(l, Some(EDGE_JUMP_LSB)).iter().zip(&g.d).filter(|(a, b)| a != b).count();
    }
    check_timing(&got, &markers).unwrap_or_else(|e| panic!("{pair}: {e}"));
    let pixels = w * lines.len();
    eprintln!("{pair}: {pixels} pixels equal to golden's parity interpolator, {f64_differs} round otherwise in f64, {} clocks", sim.cycle);
    assert!(f64_differs > 0, "{pair}: golden's f64 interpolation would pass the exact check too");
}

#[test]
fn every_row_of_tsukuba_interpolates_as_golden() {
    real_pair("tsukuba");
}

#[test]
fn every_row_of_cones_interpolates_as_golden() {
    real_pair("cones");
}
