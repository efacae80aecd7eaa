//! The whole line processor (`rtl::stereo_line_processor`) on a band of a
//! real pair: two camera streams in, the disparity and depth map out, equal
//! to its blocks run one after the other, equal after the matcher to
//! golden's hardware parity on the matcher's matches (the row check, the
//! interpolator, the median, the depth), and compared with golden's
//! hardware parity from the pixels on.

use rtl::matcher::declivity_matcher::GainRule;
use rtl::post::depth_stage::DepthCamera;
use rtl::post::interpolator::LINE_QUEUE;
use rtl::params::{EDGE_JUMP_LSB, N_CELLS};
use rtl::stereo_line_processor::LINES_IN_FLIGHT;
use sim::drive::stereo::{blocks_one_after_the_other, golden_after_matcher, golden_depth_map, golden_map, BlocksRun, StereoRun, StereoSim};
use sim::eval::scores::{agree_quarter_px, exact_share};
use sim::hdl::frame::differences;

/// Rows `rows` of both images of `pair`.
fn crop(img: &golden::GreyImage, rows: std::ops::Range<usize>) -> golden::GreyImage {
    let w = img.width();
    golden::GreyImage::new(w, rows.len(), img.pixels()[rows.start * w..rows.end * w].to_vec()).expect("a crop")
}

/// The line processor's output is its blocks' run one after the other, row
/// for row; and from the matcher's matches on, golden's hardware parity,
/// every disparity and depth.
fn check_blocks_and_golden_after_matcher(run: &StereoRun, blocks: &BlocksRun, width: usize) {
    assert_eq!(blocks.disparity.len(), run.rows.len());
    for (y, (a, b)) in run.rows.iter().zip(&blocks.disparity).enumerate() {
        assert_eq!(a, b, "row {y}: the line processor differs from its blocks run one after the other");
    }
    assert_eq!(run.depth_rows, blocks.depth, "the depths differ from the depth stage's on the same map");
    let (disparity, depth) = golden_after_matcher(&blocks.matches, width, &DepthCamera::default());
    for (y, ((row, depths), (want, want_depth))) in run.rows.iter().zip(&run.depth_rows).zip(disparity.chunks(width).zip(depth.chunks(width))).enumerate() {
        for x in 0..width {
            assert_eq!(row[x] as f64 / 16.0, want[x], "({x}, {y}): the disparity differs from golden's parity on the matcher's matches");
            assert_eq!(depths[x], want_depth[x], "({x}, {y}): the depth differs from golden's parity on the matcher's matches");
        }
    }
}

/// The line processor against golden's hardware parity from the pixels on:
/// the shares of pixels with the same disparity and the same depth, and
/// within 1/4 px.
fn against_golden(run: &StereoRun, left: &golden::GreyImage, right: &golden::GreyImage, dispmax: f64) -> (f64, f64, f64) {
    let golden = golden_map(left, right, 0.0, dispmax, sim::Config::Sd).expect("golden runs");
    let rtl = run.disparity_px(left.height());
    let depth = run.depth_mm(left.height());
    let golden_depth = golden_depth_map(&golden, &DepthCamera::default(), sim::Config::Sd);
    (exact_share(&rtl, &golden), exact_share(&depth, &golden_depth), agree_quarter_px(&rtl, &golden))
}

#[test]
fn a_band_of_tsukuba_through_the_line_processor_equals_its_blocks_one_after_the_other_and_golden_parity() {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
    let (left, right) = (crop(&data.left, 100..116), crop(&data.right, 100..116));
    let dispmax = data.dispmax + 1.0;
    let run = run_and_report("tsukuba rows 100..116", &left, &right, dispmax);
    let (exact, exact_depth, agree) = against_golden(&run, &left, &right, dispmax);
    eprintln!("tsukuba rows 100..116: exact {exact:.4}, exact depth {exact_depth:.4}, agree {agree:.4}, latency {:?}, px/clk {:.4}", run.latency_cycles(), run.px_per_clk());
    assert_eq!(run.rows.len(), left.height());
    assert_eq!((run.records_dropped, run.lines_dropped, run.pixels_dropped, run.stall_cycles), (0, 0, 0, 0));
    let blocks = blocks_one_after_the_other::<N_CELLS>(&left, &right, GainRule::Robust, Some(EDGE_JUMP_LSB), DepthCamera::default(), sim::formats::dispmax_lsb(dispmax, sim::Config::Sd).expect("dispmax"));
    check_blocks_and_golden_after_matcher(&run, &blocks, left.width());
    // From the pixels on, golden's hardware parity (the detector's formats
    // and the steps after the matcher): every pixel.
    assert_eq!((exact, exact_depth), (1.0, 1.0), "agree {agree}");
}

/// Runs the pair through the default line processor (`dispmax` px) and
/// prints what came out, the speed and the queues' peaks.
fn run_and_report(what: &str, left: &golden::GreyImage, right: &golden::GreyImage, dispmax: f64) -> StereoRun {
    let mut sim = StereoSim::<N_CELLS>::robust(sim::formats::dispmax_lsb(dispmax, sim::Config::Sd).expect("dispmax"));
    let t = std::time::Instant::now();
    let run = sim.run(left, right, 0, |_| {});
    let secs = t.elapsed().as_secs_f64();
    let peak = run.probe.peak;
    eprintln!(
        "{what}: {} rows out, {} clocks ({:.0} clocks/s), dropped {} lines {} records, stalls {}; peaks: interpolator {} lines {} segments, in flight {}, record queues {:?} beats {:?} lines, row check {} rows, held {} clocks",
        run.rows.len(),
        run.cycles,
        run.cycles as f64 / secs,
        run.lines_dropped,
        run.records_dropped,
        run.stall_cycles,
        peak.interp_lines,
        peak.interp_segments,
        peak.in_flight,
        peak.record_beats,
        peak.record_lines,
        peak.row_check_rows,
        peak.held_clocks
    );
    run
}

/// Prints the probe's state on each dropped line and the lines' clocks
/// through the stages around it (diagnostics).
fn print_probe(what: &str, run: &StereoRun, width: usize) {
    let p = &run.probe;
    eprintln!("{what}: peaks {:?} (interpolator's lines at clock {})", p.peak, p.peak_interp_cycle);
    for d in &p.drops {
        eprintln!("{what}: drop {d:?}");
    }
    // Each line's clocks relative to its last pixel in, in lines of `width`.
    eprintln!("{what}: line, in, matched-in, checked-in, interpolated-in (clocks)");
    for (k, &t) in p.line_in.iter().enumerate() {
        let rel = |v: &Vec<u64>| v.get(k).map_or("-".to_string(), |&c| format!("{} ({:.2} W)", c as i64 - t as i64, (c as f64 - t as f64) / width as f64));
        eprintln!("{what}: {k:4} {t:8} {} {} {}", rel(&p.matched), rel(&p.checked), rel(&p.interpolated));
    }
}

/// Venus rows 228..310: the matcher falls behind on rows 231–246 (their
/// matching takes longer than their 434-clock line) and the record queues
/// hold the backlog; the interpolator's output, which sends a line per line
/// time and so never catches up, stays that far behind while the matcher
/// catches up, so that the interpolator holds more than four lines at once.
/// The line processor keeps at most `LINES_IN_FLIGHT` lines between the
/// matcher's input and the interpolator's output, all of which the
/// interpolator holds (`LINE_QUEUE`): no line is dropped.
#[test]
fn venus_after_its_slow_stretch_loses_no_line() {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("venus")).expect("the pair loads");
    let rows = 228..310;
    let (left, right) = (crop(&data.left, rows.clone()), crop(&data.right, rows.clone()));
    let dispmax = data.dispmax + 1.0;
    let run = run_and_report(&format!("venus rows {rows:?}"), &left, &right, dispmax);
    let peak = run.probe.peak;
    let (exact, exact_depth, agree) = against_golden(&run, &left, &right, dispmax);
    eprintln!("venus rows {rows:?}: exact {exact:.4}, exact depth {exact_depth:.4}, agree {agree:.4}");
    assert_eq!((run.lines_dropped, run.records_dropped, run.pixels_dropped, run.stall_cycles), (0, 0, 0, 0));
    assert_eq!(run.rows.len(), left.height());
    assert_eq!((exact, exact_depth), (1.0, 1.0), "agree {agree}");
    assert!(peak.in_flight as usize <= LINES_IN_FLIGHT && peak.interp_lines as usize <= LINE_QUEUE, "{peak:?}");
    // The band stresses the queue: more than four lines at once.
    assert!(peak.interp_lines > 4, "the band no longer fills the interpolator's queue: {peak:?}");
}

/// A synthetic pair whose first `heavy` rows have a declivity every 3 px
/// (their matching takes about twice their line time) and whose other rows
/// have one every `light_step` px, the right view the left shifted by 5 px.
fn backlog_pair(width: usize, height: usize, heavy: usize, light_step: usize) -> (golden::GreyImage, golden::GreyImage) {
    let mut seed = 0x2545_f491_u64;
    let mut next = move || {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (seed >> 33) as u32
    };
    let shift = 5;
    let mut left = Vec::with_capacity(width * height);
    let mut right = Vec::with_capacity(width * height);
    for y in 0..height {
        let step = if y < heavy { 3 } else { light_step };
        let mut row = Vec::with_capacity(width + shift);
        let mut high = false;
        while row.len() < width + shift {
            let level = if high { 150 + next() % 80 } else { 20 + next() % 60 };
            row.extend(std::iter::repeat_n(level as u8, step));
            high = !high;
        }
        // left(x) = right(x - 5): disparity 5 px.
        left.extend_from_slice(&row[..width]);
        right.extend_from_slice(&row[shift..shift + width]);
    }
    let img = |p: Vec<u8>| golden::GreyImage::new(width, height, p).expect("an image");
    (img(left), img(right))
}

/// Lines after a backlog held back, not dropped: ten rows slower to match
/// than their line time, then lighter rows on which the matcher catches
/// up, faster than the interpolator sends lines. The limit on lines in
/// flight holds the reference queue (the interpolator would otherwise need
/// more lines than its queue); no line or record is lost and the output is
/// that of the blocks one after the other.
#[test]
fn lines_after_a_backlog_are_held_in_the_record_queues_not_dropped() {
    let (width, height) = (300, 40);
    let (left, right) = backlog_pair(width, height, 10, 16);
    let dispmax = 16.0;
    let run = run_and_report(&format!("backlog pair {width}x{height}"), &left, &right, dispmax);
    let peak = run.probe.peak;
    print_probe("backlog", &run, width);
    assert_eq!((run.lines_dropped, run.records_dropped, run.pixels_dropped, run.stall_cycles), (0, 0, 0, 0));
    assert_eq!(run.rows.len(), height);
    // The limit was reached and held lines back.
    assert_eq!(peak.in_flight as usize, LINES_IN_FLIGHT, "{peak:?}");
    assert!(peak.held_clocks > 0, "{peak:?}");
    assert!(peak.interp_lines as usize <= LINE_QUEUE, "{peak:?}");
    let blocks = blocks_one_after_the_other::<N_CELLS>(&left, &right, GainRule::Robust, Some(EDGE_JUMP_LSB), DepthCamera::default(), sim::formats::dispmax_lsb(dispmax, sim::Config::Sd).expect("dispmax"));
    check_blocks_and_golden_after_matcher(&run, &blocks, width);
}

#[test]
fn a_reset_mid_line_and_mid_frame_leaves_the_next_frame_equal_to_a_fresh_runs_beat_for_beat() {
    use rtl::stereo_line_processor::RESET_RECOVERY;
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
    let dispmax = sim::formats::dispmax_lsb(data.dispmax + 1.0, sim::Config::Sd).expect("dispmax");
    // Frame B, run fresh; frame A, cut short by the reset.
    let (left, right) = (crop(&data.left, 150..156), crop(&data.right, 150..156));
    let (cut_left, cut_right) = (crop(&data.left, 60..76), crop(&data.right, 60..76));
    let w = left.width() as u64;
    let fresh = StereoSim::<N_CELLS>::robust(dispmax).run(&left, &right, 0, |_| {});
    assert_eq!(fresh.rows.len(), left.height());
    // Cut in line 2 (records of line 0 in the matcher), and in line 9
    // (every stage busy, output lines leaving): both inside a line.
    // A reset of one clock, and one of three.
    for (cut, reset_clocks) in [(2 * w + w / 3, 1), (9 * w + w / 2, 3)] {
        let mut sim = StereoSim::<N_CELLS>::robust(dispmax);
        let before = sim.run_cut(&cut_left, &cut_right, 0, cut);
        assert_eq!(sim.cycle, cut);
        sim.reset(reset_clocks, RESET_RECOVERY as u64 + 2);
        let start = sim.cycle;
        let after = sim.run(&left, &right, 0, |_| {});
        let diff = differences(&fresh, &after.counted_from(start));
        assert!(diff.is_empty(), "a reset of {reset_clocks} clocks at clock {cut} (after {} lines out): {diff:#?}", before.rows.len());
    }
    // The negative control: the same cut without a reset leaves the cut
    // frame's lines in the processor, and the next frame differs.
    let mut sim = StereoSim::<N_CELLS>::robust(dispmax);
    sim.run_cut(&cut_left, &cut_right, 0, 9 * w + w / 2);
    let start = sim.cycle;
    let after = sim.run(&left, &right, 0, |_| {});
    assert!(!differences(&fresh, &after.counted_from(start)).is_empty(), "without a reset the cut frame must show");
}
