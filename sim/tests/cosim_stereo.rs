//! The whole line processor's Verilog (`declivity verilog --top stereo`),
//! in each configuration: Verilator lint with the accepted list of the
//! blocks, Yosys without latches. (Generated with a 16-cell matcher, the size `cosim_matcher`
//! co-simulates: the cells are the matcher's; the joins are what is new.)

use sim::hdl::cosim;

fn design(config: sim::Config) -> String {
    sim::hdl::verilog::generate_with(config, sim::hdl::verilog::Top::Stereo, CELLS, rtl::matcher::declivity_matcher::GainRule::Robust).expect("a supported size")
}

/// Cells of the matcher in the checked Verilog.
const CELLS: usize = 16;

/// Verilator `-Wall` warnings accepted in the line processor's Verilog,
/// with why.
const ACCEPTED: &[(&str, &str)] = &[
    sim::hdl::cosim::ACCEPTED_LINT[0],
    sim::hdl::cosim::ACCEPTED_LINT[1],
    sim::hdl::cosim::DP16KD_UNUSED_OUTPUTS,
    ("UNUSEDSIGNAL", "outputs of the blocks that the line processor does not use (listed in UNUSED_OUTPUTS and checked one by one)"),
];

/// The blocks' outputs the line processor leaves unused: the detectors'
/// extrema and counts and the matcher's indices and counts serve the
/// blocks' own tests, reports and pictures; the interpolator's empty flag
/// is implied by its disparities (0); the row check's `c_eof` and `c_count`
/// (the top counts rows itself) and `crowded` (never raised by the
/// matcher's output, whose matches are a pixel apart).
const UNUSED_OUTPUTS: &[&str] = &[
    "left$m_start",
    "left$m_end",
    "left$m_count",
    "right$m_start",
    "right$m_end",
    "right$m_count",
    "matcher$m_ref",
    "matcher$m_other",
    "matcher$m_count",
    "matcher$m_n",
    "matcher$m_m",
    "interpolator$p_empty",
    "row_check$c_eof",
    "row_check$c_count",
    "row_check$crowded",
];

#[test]
fn stereo_verilog_lints_clean_but_for_the_accepted_warnings_in_each_configuration() {
    for config in sim::Config::ALL {
        let warnings = cosim::lint_verilator(&design(config)).unwrap_or_else(|e| panic!("{config}: {e}"));
        let counts = cosim::check_accepted(&warnings, ACCEPTED).unwrap_or_else(|e| panic!("{config}: {e}"));
        for w in warnings.iter().filter(|w| w.code == "UNUSEDSIGNAL") {
            assert!(UNUSED_OUTPUTS.iter().any(|name| w.message.ends_with(&format!("'{name}'"))), "{config}: an unused signal not in the list: {}", w.message);
        }
        eprintln!("{config}: accepted lint warnings: {counts:?}");
    }
}

#[test]
fn stereo_synthesizes_in_yosys_without_latches_in_each_configuration() {
    for config in sim::Config::ALL {
        let check = sim::hdl::synth::yosys_latch_check(&design(config), "top").unwrap_or_else(|e| panic!("{config}: {e}"));
        assert_eq!(check.latches, 0, "{config}: latches: {:?}", check.latch_cells);
        assert!(check.cells > 3000, "{config}: the line processor is not empty: {} cells", check.cells);
    }
}

// ---------------------------------------------------------------------------
// The top's Verilog on real frames, against the rust-hdl model.

mod frames {
    use golden::GreyImage;
    use rtl::params::N_CELLS;
    use sim::hdl::cosim::{Options, Simulator};
    use sim::drive::stereo::{StereoRun, StereoSim};
    use sim::hdl::frame::{differences, run_frame, FRAME_BEATS_FILE, FRAME_SUMMARY_FILE};

    /// Rows `rows` of `img`.
    fn crop(img: &GreyImage, rows: std::ops::Range<usize>) -> GreyImage {
        let w = img.width();
        GreyImage::new(w, rows.len(), img.pixels()[rows.start * w..rows.end * w].to_vec()).expect("a crop")
    }

    fn pair(name: &str) -> (GreyImage, GreyImage, u32) {
        let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(name)).expect("the pair loads");
        (data.left, data.right, sim::formats::dispmax_lsb(data.dispmax + 1.0, sim::Config::Sd).expect("dispmax"))
    }

    fn model<const N: usize>(left: &GreyImage, right: &GreyImage, hblank: usize, dispmax: u32) -> (StereoRun, f64) {
        let mut sim = StereoSim::<N>::robust(dispmax);
        let t = std::time::Instant::now();
        let run = sim.run(left, right, hblank, |_| {});
        let rate = run.cycles as f64 / t.elapsed().as_secs_f64();
        (run, rate)
    }

    /// The model with `N` cells against its Verilog under `simulator` on
    /// the frame: every field of the run equal.
    fn check<const N: usize>(simulator: Simulator, left: &GreyImage, right: &GreyImage, hblank: usize, dispmax: u32, what: &str) {
        let design = sim::hdl::verilog::generate_with(sim::Config::Sd, sim::hdl::verilog::Top::Stereo, N, rtl::matcher::declivity_matcher::GainRule::Robust).expect("a supported size");
        let (want, model_rate) = model::<N>(left, right, hblank, dispmax);
        assert!(want.rows.len() == left.height() && want.pixels_in > 0, "{what}: the model ran the frame");
        let got = run_frame(simulator, sim::Config::Sd, &design, left, right, hblank, sim::formats::SearchArea::below(dispmax), &Options::default()).unwrap_or_else(|e| panic!("{e}"));
        eprintln!(
            "{what}: {} clocks; rust-hdl {model_rate:.0} clocks/s, {} {:.0} clocks/s (build {:.1} s{})",
            want.cycles,
            simulator.name(),
            got.cycles_per_s(),
            got.compile.as_secs_f64(),
            if got.cached { ", cached" } else { "" }
        );
        let diff = differences(&want, &got.run);
        assert!(diff.is_empty(), "{what}: {} differs from the rust-hdl model: {diff:#?}", simulator.name());
    }

    /// Icarus is the slowest engine by far; a few lines with the 16 cells of
    /// the lint test keep the test short.
    /// (The lines have more declivities than 16 cells hold: `lines_full`
    /// counts them, and the Verilog must count them alike.)
    #[test]
    fn cosim_icarus_runs_four_lines_of_tsukuba_exactly_as_the_model() {
        let (left, right, dispmax) = pair("tsukuba");
        check::<{ super::CELLS }>(Simulator::Icarus, &crop(&left, 100..104), &crop(&right, 100..104), 16, dispmax, "tsukuba rows 100..104");
    }

    /// A frame cut short inside its second line by a reset of two clocks,
    /// then the recovery and the frame anew: under Icarus and Verilator,
    /// the frame after the reset is the rust-hdl model's after the same
    /// reset, clock for clock, and both are a fresh run's (the model's
    /// fresh run is the Verilog's, by the tests above).
    #[test]
    fn cosim_a_reset_mid_frame_gives_the_models_run_and_a_fresh_ones_in_icarus_and_verilator() {
        use rtl::stereo_line_processor::RESET_RECOVERY;
        use sim::hdl::frame::{run_frame_after_reset, FrameReset};
        let (left, right, dispmax) = pair("tsukuba");
        let (left, right) = (crop(&left, 100..104), crop(&right, 100..104));
        let hblank = 7;
        let reset = FrameReset { cut: (left.width() + hblank + left.width() / 2) as u64, clocks: 2, idle: RESET_RECOVERY as u64 + 3 };
        let design = sim::hdl::verilog::generate_with(sim::Config::Sd, sim::hdl::verilog::Top::Stereo, super::CELLS, rtl::matcher::declivity_matcher::GainRule::Robust).expect("a supported size");
        let (fresh, _) = model::<{ super::CELLS }>(&left, &right, hblank, dispmax);
        let mut sim = StereoSim::<{ super::CELLS }>::robust(dispmax);
        sim.run_cut(&left, &right, hblank, reset.cut);
        sim.reset(reset.clocks, reset.idle);
        let start = sim.cycle;
        let want = sim.run(&left, &right, hblank, |_| {}).counted_from(start);
        let diff = differences(&fresh, &want);
        assert!(diff.is_empty(), "the model after the reset differs from a fresh run: {diff:#?}");
        for simulator in [Simulator::Icarus, Simulator::Verilator] {
            let got = run_frame_after_reset(simulator, sim::Config::Sd, &design, &left, &right, hblank, sim::formats::SearchArea::below(dispmax), reset, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
            let diff = differences(&want, &got.run);
            assert!(diff.is_empty(), "{} after the reset differs from the rust-hdl model: {diff:#?}", simulator.name());
        }
    }

    /// Verilator's C++ driver and Icarus's Verilog testbench (the camera
    /// model written twice) write the same files byte for byte on two lines
    /// of tsukuba with the 16 cells of the lint test, blanking between the
    /// lines, and both runs are the model's.
    #[test]
    fn cosim_verilator_driver_writes_the_icarus_testbench_files_byte_for_byte() {
        let (left, right, dispmax) = pair("tsukuba");
        let (left, right) = (crop(&left, 120..122), crop(&right, 120..122));
        let design = sim::hdl::verilog::generate_with(sim::Config::Sd, sim::hdl::verilog::Top::Stereo, super::CELLS, rtl::matcher::declivity_matcher::GainRule::Robust).expect("a supported size");
        let opts = Options { keep: true, ..Options::default() };
        let (want, _) = model::<{ super::CELLS }>(&left, &right, 7, dispmax);
        let mut files = Vec::new();
        for simulator in [Simulator::Icarus, Simulator::Verilator] {
            let got = run_frame(simulator, sim::Config::Sd, &design, &left, &right, 7, sim::formats::SearchArea::below(dispmax), &opts).unwrap_or_else(|e| panic!("{e}"));
            let diff = differences(&want, &got.run);
            assert!(diff.is_empty(), "{} differs from the rust-hdl model: {diff:#?}", simulator.name());
            let dir = got.work_dir.expect("kept");
            let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
            files.push((read(FRAME_BEATS_FILE), read(FRAME_SUMMARY_FILE)));
            let _ = std::fs::remove_dir_all(&dir);
        }
        assert!(files[0].0.lines().count() == 2 * left.width(), "two lines of beats");
        assert_eq!(files[0].1, files[1].1, "summary");
        let first = files[0].0.lines().zip(files[1].0.lines()).position(|(a, b)| a != b);
        assert!(files[0].0 == files[1].0, "beats differ (icarus, verilator), first at line {first:?}");
    }

    /// The sensor's processor (32 cells) under Verilator against the
    /// rust-hdl model on a band of map, back to back: every output word on
    /// the same clock, the same stalls and status counters. (The model is
    /// slow per clock; whole frames are checked under Verilator against
    /// golden below.)
    #[test]
    fn cosim_verilator_runs_a_band_of_map_exactly_as_the_model() {
        let (left, right, dispmax) = pair("map");
        check::<N_CELLS>(Simulator::Verilator, &crop(&left, 60..100), &crop(&right, 60..100), 0, dispmax, "map rows 60..100");
    }

    /// A generated frame: plateaus of 2 to `max_run` pixels with steps of
    /// 20 to 80 grey levels (each a declivity), seeded; the right view is
    /// the left at disparity `shift` (`right[x] = left[x + shift]`, the last
    /// pixel repeated).
    fn steps_pair(width: usize, height: usize, max_run: u64, shift: usize, seed: u64) -> (GreyImage, GreyImage) {
        let mut rng = sim::rng::VectorRng(seed);
        let mut left = Vec::with_capacity(width * height);
        for _ in 0..height {
            let mut v: i64 = 128;
            let mut run = 0;
            for _ in 0..width {
                if run == 0 {
                    let r = rng.next();
                    let step = 20 + (r % 61) as i64;
                    v = if (v + step > 255) || (r >> 8) & 1 == 0 && v - step >= 0 { v - step } else { v + step };
                    run = 2 + (r >> 16) % (max_run - 1);
                }
                run -= 1;
                left.push(v as u8);
            }
        }
        let right: Vec<u8> = left.chunks(width).flat_map(|row| (0..width).map(move |x| row[(x + shift).min(width - 1)])).collect();
        (GreyImage::new(width, height, left).expect("a frame"), GreyImage::new(width, height, right).expect("a frame"))
    }

    /// Generated frames through the sensor's Verilog under Verilator, in
    /// each configuration, equal to golden's hardware parity in that
    /// configuration on every disparity and depth: lines of the
    /// configuration's `W_MAX` pixels with more than its `N_MAX`
    /// declivities (the detector keeps the first `N_MAX` and flags the line
    /// full, golden alike), and a narrower frame with blanking.
    #[test]
    fn generated_frames_under_verilator_equal_golden_hardware_parity_lines_over_n_max_included() {
        use rtl::post::depth_stage::DepthCamera;
        use sim::drive::stereo::{golden_depth_map, golden_map};
        for config in sim::Config::ALL {
            let (w_max, n_max) = (config.sizes().w_max, config.sizes().n_max);
            let design = sim::hdl::verilog::generate(config, sim::hdl::verilog::Top::Stereo);
            for (what, (left, right), hblank, dispmax, over_n_max) in [
                ("W_MAX lines of many steps", steps_pair(w_max, 24, 4, 9, 0x5eed_0001), 0, 24.0, true),
                ("plateaus with blanking", steps_pair(400, 30, 12, 5, 0x5eed_0002), 16, 12.0, false),
            ] {
                let what = format!("{config}: {what}");
                let lsb = sim::formats::dispmax_lsb(dispmax, config).expect("dispmax");
                let got = run_frame(Simulator::Verilator, config, &design, &left, &right, hblank, sim::formats::SearchArea::below(lsb), &Options::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
                let run = &got.run;
                assert_eq!(run.rows.len(), left.height(), "{what}: every line out");
                assert_eq!((run.lines_dropped, run.records_dropped, run.pixels_dropped), (0, 0, 0), "{what}: nothing dropped");
                assert_eq!(run.lines_full > 0, over_n_max, "{what}: lines over N_MAX = {n_max} flagged full ({})", run.lines_full);
                assert_eq!(run.lines_wide, 0, "{what}: no line wider than W_MAX = {w_max}");
                let rtl = run.disparity_px(left.height());
                let gold = golden_map(&left, &right, 0.0, dispmax, config).expect("golden runs");
                let depth = run.depth_mm(left.height());
                let gold_depth = golden_depth_map(&gold, &DepthCamera::default(), config);
                let matched = rtl.iter().filter(|&&d| d > 0.0).count();
                eprintln!("{what}: {} clocks, {} lines full, {matched} pixels with a disparity", run.cycles, run.lines_full);
                assert!(matched > rtl.len() / 2, "{what}: a dense map ({matched} of {})", rtl.len());
                for (i, (a, b)) in rtl.iter().zip(&gold).enumerate() {
                    assert_eq!(a, b, "{what}: disparity at ({}, {}) differs from golden's hardware parity", i % left.width(), i / left.width());
                }
                assert_eq!(depth.len(), gold_depth.len(), "{what}: every depth out");
                for (i, (a, b)) in depth.iter().zip(&gold_depth).enumerate() {
                    assert_eq!(a, b, "{what}: depth at ({}, {}) differs from golden's hardware parity", i % left.width(), i / left.width());
                }
            }
        }
    }

    /// Eq. 6 with a lower bound through the processor's `dispmin` input,
    /// in each configuration (tsukuba, and tsukuba up-scaled 2× in `hd`):
    /// every disparity and depth equal to golden's hardware parity for the
    /// same area, every disparity inside it, and the bound changes the map
    /// (golden without it has disparities at or below it).
    #[test]
    fn with_a_dispmin_real_frames_under_verilator_equal_golden_hardware_parity_and_stay_inside_the_area() {
        use sim::jobs::rtl_depth::{evaluate_pair_rtl, Engine};
        let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
        for (config, scale) in [(sim::Config::Sd, 1), (sim::Config::Hd, 2)] {
            let data = sim::eval::upscale::upscale_pair(&data, scale).expect("up-scaled");
            let (dispmin, dispmax) = (5.0 * scale as f64, data.dispmax + 1.0);
            let r = evaluate_pair_rtl(config, &data, dispmin, 0, Engine::Verilator, |_| {}).unwrap_or_else(|e| panic!("{config}: {e}"));
            eprintln!("{}", serde_json::to_string(&r).expect("serializes"));
            assert_eq!((r.run.dispmin, r.run.lines_out), (dispmin, data.left.height()), "{config}: the area run, every line out");
            assert_eq!((r.run.exact_px, r.run.exact_depth_px), (1.0, 1.0), "{config}: equal to golden's hardware parity with dispmin {dispmin}");
            let gold = sim::drive::stereo::golden_map(&data.left, &data.right, dispmin, dispmax, config).expect("golden runs");
            assert!(gold.iter().all(|&d| d == 0.0 || (d > dispmin && d < dispmax)), "{config}: a disparity outside {dispmin} < d < {dispmax}");
            assert!(r.density > 50.0, "{config}: a map above dispmin ({} %)", r.density);
            let without = sim::drive::stereo::golden_map(&data.left, &data.right, 0.0, dispmax, config).expect("golden runs");
            assert!(without.iter().any(|&d| d > 0.0 && d <= dispmin), "{config}: without dispmin some disparities are at or below it");
        }
    }

    /// A line of `N_MAX` declivities exactly is kept whole (not flagged
    /// full) and one more is flagged, in each configuration: the detector's
    /// count against golden's own count of the generated line.
    #[test]
    fn a_line_of_n_max_declivities_is_whole_and_one_more_is_full_in_each_configuration() {
        for config in sim::Config::ALL {
            let (w_max, n_max) = (config.sizes().w_max, config.sizes().n_max);
            let design = sim::hdl::verilog::generate(config, sim::hdl::verilog::Top::Stereo);
            // Steps of 60 grey levels every 3 pixels, up and down: one
            // declivity each (d_t of such a line is far below 60).
            let line = |segments: usize| -> Vec<u8> { (0..w_max).map(|x| if x / 3 < segments && (x / 3) % 2 == 1 { 160 } else { 100 }).collect() };
            // `k + 1` plateaus have `k` steps between them, and one more at
            // the end when the last is high (`k` odd).
            for (segments, full) in [(n_max + 1, false), (n_max + 2, true)] {
                let row = line(segments);
                let counted = golden::hardware::detect_line(&row, golden::hardware::HardwareLimits { n_max: usize::MAX, w_max: usize::MAX, ..config.limits() }).declivities.len();
                assert_eq!(counted > n_max, full, "{config}: the generated line has {counted} declivities");
                assert!(counted >= n_max, "{config}: {counted} declivities");
                let img = GreyImage::new(w_max, 12, row.repeat(12)).expect("a frame");
                let lsb = sim::formats::dispmax_lsb(16.0, config).expect("dispmax");
                let got = run_frame(Simulator::Verilator, config, &design, &img, &img, 0, sim::formats::SearchArea::below(lsb), &Options::default()).unwrap_or_else(|e| panic!("{config}: {e}"));
                assert_eq!(got.run.rows.len(), 12, "{config}: every line out");
                assert_eq!(got.run.lines_full > 0, full, "{config}: {counted} declivities a line, {} lines full", got.run.lines_full);
            }
        }
    }

    /// The eight pairs up-scaled 2× (`sim::eval::upscale`: 568 to 1482
    /// px wide), whole frames through the `hd` processor's Verilog under
    /// Verilator: every disparity and depth equal to golden's hardware
    /// parity in `hd`, one pixel per clock, no stall, every line out,
    /// nothing dropped.
    #[test]
    fn every_pair_up_scaled_2x_under_verilator_in_hd_equals_golden_hardware_parity_at_a_pixel_per_clock() {
        use sim::jobs::rtl_depth::{evaluate_pair_rtl, Engine};
        let dir = sim::eval::io::stereo_data_dir();
        let pairs = sim::eval::io::expand_pair_dirs(&[dir]).expect("the pairs");
        assert_eq!(pairs.len(), 8, "the eight Middlebury pairs of data/stereo");
        let mut widest = 0;
        for p in pairs {
            let data = sim::eval::upscale::upscale_pair(&sim::eval::io::load_pair_dir(&p).expect("the pair loads"), 2).expect("2x");
            widest = widest.max(data.left.width());
            let r = evaluate_pair_rtl(sim::Config::Hd, &data, 0.0, 0, Engine::Verilator, |_| {}).unwrap_or_else(|e| panic!("{}: {e}", data.name));
            eprintln!("{}", serde_json::to_string(&r).expect("serializes"));
            let run = &r.run;
            assert_eq!(run.lines_out, data.left.height(), "{}: every line out", data.name);
            assert_eq!((run.lines_dropped, run.records_dropped, run.pixels_dropped, run.lines_wide), (0, 0, 0, 0), "{}: nothing dropped", data.name);
            assert_eq!((run.px_per_clk, run.stall_cycles), (1.0, 0), "{}: a pixel per clock", data.name);
            assert_eq!(run.exact_px, 1.0, "{}: every disparity equal to golden's hardware parity", data.name);
            assert_eq!(run.exact_depth_px, 1.0, "{}: every depth equal to golden's hardware parity", data.name);
            assert!(r.density > 0.5, "{}: a dense map ({})", data.name, r.density);
        }
        assert!(widest > rtl::params::W_MAX, "a pair wider than sd's W_MAX ({widest} px)");
    }

    /// Every pair in the repository, whole frame, through the sensor's
    /// Verilog under Verilator: every disparity and every depth equal to
    /// golden's hardware parity (`golden::hardware`, computed from the
    /// pixels on, with no rtl code), every line out, nothing dropped.
    #[test]
    fn every_pair_whole_frame_under_verilator_equals_golden_hardware_parity_pixel_for_pixel() {
        use sim::jobs::rtl_depth::{evaluate_pair_rtl, Engine};
        let dir = sim::eval::io::stereo_data_dir();
        let pairs = sim::eval::io::expand_pair_dirs(&[dir]).expect("the pairs");
        assert_eq!(pairs.len(), 8, "the eight Middlebury pairs of data/stereo");
        for p in pairs {
            let data = sim::eval::io::load_pair_dir(&p).expect("the pair loads");
            let r = evaluate_pair_rtl(sim::Config::Sd, &data, 0.0, 0, Engine::Verilator, |_| {}).unwrap_or_else(|e| panic!("{}: {e}", data.name));
            eprintln!("{}", serde_json::to_string(&r).expect("serializes"));
            let run = &r.run;
            assert_eq!(run.lines_out, data.left.height(), "{}: every line out", data.name);
            assert_eq!((run.lines_dropped, run.records_dropped, run.pixels_dropped), (0, 0, 0), "{}: nothing dropped", data.name);
            assert_eq!(run.exact_px, 1.0, "{}: every disparity equal to golden's hardware parity", data.name);
            assert_eq!(run.exact_depth_px, 1.0, "{}: every depth equal to golden's hardware parity", data.name);
            assert!(r.density > 0.5, "{}: a dense map ({})", data.name, r.density);
        }
    }
}
