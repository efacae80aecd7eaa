//! The rtl depth stage (`rtl::post::depth_stage`) against golden's
//! hardware-parity depth stage (`golden::hardware::depth`) on the same
//! fixed-point disparities: random disparities and cameras, every
//! disparity for four cameras, golden's parity disparity of two real
//! pairs; golden's numerator and table against the rtl's; its timing clock
//! by clock; its generation-time checks; its Verilog (Verilator lint, and
//! Icarus and Verilator replaying the Rust model's outputs).
//!
//! golden computes what the stage computes (the camera's numerator, the
//! table with its slopes, the interpolation, the shift and the rounding):
//! every depth must be equal, 0 for a disparity of 0. (golden's parity
//! depth is eq. 1 within `½ + Z·2^-15` mm: `golden::hardware::depth`'s
//! tests.)
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_depth_stage`).

use proptest::prelude::*;
use rtl::post::depth_stage::{depth_table, DepthCamera, DepthError, DepthScale, DepthStage, DEPTH_LAG};
use rtl::params::{DEPTH_INDEX_BITS, DEPTH_K_LIMIT, DEPTH_MAX_MM, DEPTH_SCALE_MAX, DEPTH_SCALE_MIN, DEPTH_WEIGHT_BITS, POS_BITS, POS_FRAC_BITS};
use sim::formats::disparity_lsb;
use golden::hardware::depth::DepthStage as GoldenStage;
use sim::drive::depth_stage::{golden_camera, golden_stage, DepthIn, DepthOut, DepthStageSim};

/// The largest disparity (LSB).
const D_MAX: u64 = (1 << POS_BITS) - 1;

/// Checks one depth against golden's parity depth stage `gold`: equal.
fn check_depth(d: u64, z_rtl: u16, gold: &GoldenStage) -> Result<(), String> {
    let want = gold.depth_mm(d as u32);
    if z_rtl != want {
        return Err(format!("d {d} (numerator {:?}): rtl {z_rtl} mm, golden {want} mm", gold.scale()));
    }
    Ok(())
}

/// The cameras at both ends of the supported `f_px · b_mm` range.
fn extreme_cameras() -> [DepthCamera; 2] {
    let unit = (1u64 << POS_FRAC_BITS) as f64;
    let min = DEPTH_K_LIMIT as f64 / unit / 2f64.powi(DEPTH_SCALE_MAX as i32 + 1);
    let max = DEPTH_K_LIMIT as f64 / unit / 2f64.powi(DEPTH_SCALE_MIN as i32);
    [DepthCamera { focal_px: min / 4.0, baseline_mm: 4.0 }, DepthCamera { focal_px: (max - 1.0) / 100.0, baseline_mm: 100.0 }]
}

/// Every disparity `0 ..< 2^POS_BITS` through the stage for `cam`, one per
/// clock; each depth as golden's; returns the saturated count.
fn sweep(cam: DepthCamera) -> usize {
    let mut sim = DepthStageSim::new(cam).expect("the camera is in range");
    let gold = golden_stage(&cam).expect("the camera is in range");
    let all: Vec<u64> = (0..=D_MAX).collect();
    let run = sim.run(std::slice::from_ref(&all), 0);
    assert_eq!(run.pixels.len(), all.len());
    let mut saturated = 0;
    for (&d, o) in all.iter().zip(&run.pixels) {
        assert_eq!(o.d, d, "the disparity passes through");
        check_depth(d, o.z_mm, &gold).unwrap_or_else(|e| panic!("{e}"));
        saturated += (o.z_mm as u64 == DEPTH_MAX_MM) as usize;
    }
    eprintln!("camera {cam:?}: every depth as golden's, {saturated} saturated");
    saturated
}

/// golden's numerator and table for `cam` are the rtl's, entry for entry.
fn check_table(cam: &DepthCamera) -> Result<(), String> {
    let hw = DepthScale::of(cam).map_err(|e| e.to_string())?;
    let limits = sim::Config::Sd.limits();
    let gold = golden::hardware::depth::DepthScale::of(&golden_camera(cam), limits).map_err(|e| e.to_string())?;
    if (gold.k, gold.scale) != (hw.k, hw.scale) {
        return Err(format!("{cam:?}: golden K {} s {}, rtl K {} s {}", gold.k, gold.scale, hw.k, hw.scale));
    }
    let g = golden::hardware::depth::depth_table(&gold, limits);
    let slope_bits = rtl::params::DEPTH_SLOPE_BITS;
    for (i, (e, &word)) in g.iter().zip(&depth_table(&hw)).enumerate() {
        let (t, slope) = (word >> slope_bits, word & ((1 << slope_bits) - 1));
        if (e.entry as u64, e.slope as u64) != (t, slope) {
            return Err(format!("{cam:?} entry {i}: golden {e:?}, rtl {t} slope {slope}"));
        }
    }
    Ok(())
}

// ===========================================================================
// Generated disparities and cameras
// ===========================================================================

/// A disparity with every normalisation shift equally likely (its top bit
/// anywhere), and 0 now and then.
fn any_disparity() -> impl Strategy<Value = u64> {
    prop_oneof![1 => Just(0u64), 1 => Just(D_MAX), 20 => (0..POS_BITS as u32).prop_flat_map(|k| (1u64 << k)..(1u64 << (k + 1)))]
}

/// A camera anywhere in the supported range: `f_px · b_mm` log-uniform
/// between its ends, the focal length between 50 and 8000 px.
fn any_camera() -> impl Strategy<Value = DepthCamera> {
    let [lo, hi] = extreme_cameras().map(|c| c.product().log2());
    (lo..hi, 50f64..8000.0).prop_map(|(p, f)| DepthCamera { focal_px: f, baseline_mm: 2f64.powf(p) / f })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// Each depth is golden's parity depth of the same disparity, and
    /// leaves `DEPTH_LAG` clocks after its disparity with its flags and
    /// disparity, through idle clocks; golden's table is the rtl's.
    #[test]
    fn prop_depth_is_golden_parity_depth_after_depth_lag(
        cam in any_camera(),
        ds in prop::collection::vec((any_disparity(), any::<bool>(), 0u8..4), 1..200),
    ) {
        check_table(&cam).map_err(TestCaseError::fail)?;
        let mut sim = DepthStageSim::new(cam).expect("in range");
        let gold = golden_stage(&cam).expect("in range");
        // Beats: a pixel, `last` on some, idle clocks between some.
        let mut beats = Vec::new();
        for (k, &(d, last, idle)) in ds.iter().enumerate() {
            beats.push(DepthIn { valid: true, d, last, sof: k == 0 });
            beats.extend((0..idle.saturating_sub(1)).map(|_| DepthIn::default()));
        }
        beats.extend((0..DEPTH_LAG).map(|_| DepthIn::default()));
        let outs: Vec<DepthOut> = beats.iter().map(|&b| sim.step(b)).collect();
        for (c, b) in beats.iter().enumerate() {
            let o = outs.get(c + DEPTH_LAG).copied().unwrap_or_default();
            prop_assert_eq!((o.valid, o.d, o.last, o.sof), (b.valid, if b.valid { b.d } else { 0 }, b.last, b.sof), "clock {}", c);
            if b.valid {
                check_depth(b.d, o.z_mm, &gold).map_err(TestCaseError::fail)?;
            } else {
                prop_assert_eq!(o.z_mm, 0);
            }
        }
    }
}

// ===========================================================================
// Every disparity
// ===========================================================================

/// All 2^14 disparities for Middlebury's Motorcycle camera at full and at
/// quarter resolution: every depth as golden's, the small disparities
/// saturated.
#[test]
fn every_disparity_gives_golden_depth_for_the_motorcycle_cameras() {
    // f·b = 768 123 px·mm: D·1/16 px below 11.72 px saturates: D < 187.5.
    assert_eq!(sweep(DepthCamera::MOTORCYCLE_FULL), 187);
    // f·b/4: below 2.93 px, D ≤ 46.
    assert_eq!(sweep(DepthCamera::MOTORCYCLE_QUARTER), 46);
}

/// All 2^14 disparities for the cameras at both ends of the supported
/// range: the smallest `f·b` gives 1 mm (not 0) at the largest disparity,
/// the largest saturates all but the largest disparities.
#[test]
fn every_disparity_gives_golden_depth_at_both_ends_of_the_camera_range() {
    let [lo, hi] = extreme_cameras();
    sweep(lo);
    let mut sim = DepthStageSim::new(lo).expect("in range");
    let run = sim.run(&[vec![D_MAX]], 0);
    assert_eq!(run.z, vec![vec![1u16]], "the farthest depth of the smallest camera is 1 mm");
    let sat = sweep(hi);
    assert!(sat > 16000, "{sat}");
}

/// golden derives the stage's formats, each camera's numerator and its
/// table from the hardware's sizes as the rtl does: the same constants and
/// the same table entry for entry for the four cameras of the sweeps (a
/// change on one side fails here; random cameras in the property above).
#[test]
fn golden_depth_formats_numerator_and_table_equal_the_rtl() {
    use golden::hardware::depth as g;
    let limits = sim::Config::Sd.limits();
    assert_eq!(g::depth_k_limit(limits), DEPTH_K_LIMIT);
    assert_eq!(g::depth_weight_bits(limits) as usize, DEPTH_WEIGHT_BITS);
    assert_eq!((g::DEPTH_INDEX_BITS as usize, g::DEPTH_SCALE_MIN, g::DEPTH_SCALE_MAX), (DEPTH_INDEX_BITS, DEPTH_SCALE_MIN, DEPTH_SCALE_MAX));
    assert_eq!((g::DEPTH_BITS as usize, g::DEPTH_TABLE_BITS as usize, g::DEPTH_SLOPE_BITS as usize), (rtl::params::DEPTH_BITS, rtl::params::DEPTH_TABLE_BITS, rtl::params::DEPTH_SLOPE_BITS));
    assert_eq!((g::DEPTH_SHIFT_BITS as usize, g::DEPTH_MAX_MM as u64), (rtl::params::DEPTH_SHIFT_BITS, DEPTH_MAX_MM));
    let [lo, hi] = extreme_cameras();
    for cam in [lo, hi, DepthCamera::MOTORCYCLE_FULL, DepthCamera::MOTORCYCLE_QUARTER] {
        check_table(&cam).unwrap_or_else(|e| panic!("{e}"));
    }
    // Out of range on both sides alike.
    let small = DepthCamera { focal_px: lo.focal_px * 0.999, ..lo };
    assert!(golden_stage(&small).is_err() && DepthScale::of(&small).is_err());
}

/// Without the table's interpolation (a plain 512-entry table) the depths
/// differ from golden's on most disparities: the exact check sees the
/// interpolation (it can fail).
#[test]
fn a_plain_table_without_interpolation_is_not_golden_depth() {
    let cam = DepthCamera::MOTORCYCLE_QUARTER;
    let gold = golden_stage(&cam).expect("in range");
    let scale = DepthScale::of(&cam).expect("in range");
    let table = depth_table(&scale);
    let mut broken = 0;
    for d in 1..=D_MAX {
        let lz = d.leading_zeros() as u64 - (64 - POS_BITS as u64);
        let m = d << lz;
        let i = (m >> DEPTH_WEIGHT_BITS) & ((1 << DEPTH_INDEX_BITS) - 1);
        let t = (table[i as usize] >> rtl::params::DEPTH_SLOPE_BITS) as f64;
        let z = (t * 2f64.powi(lz as i32 - scale.scale as i32)).round().min(DEPTH_MAX_MM as f64) as u16;
        broken += check_depth(d, z, &gold).is_err() as usize;
    }
    assert!(broken > 1000, "{broken}");
}

// ===========================================================================
// Timing
// ===========================================================================

/// Clock by clock: the output at clock `c + DEPTH_LAG` is the input of clock
/// `c` (valid, disparity, last, sof, its depth); nothing valid comes out
/// before; idle clocks give all-zero outputs; lines back to back keep one
/// pixel per clock.
#[test]
fn each_pixel_leaves_depth_lag_clocks_after_it_came_with_its_flags_and_idle_clocks_give_zeros() {
    let cam = DepthCamera::MOTORCYCLE_QUARTER;
    let gold = golden_stage(&cam).expect("in range");
    let mut sim = DepthStageSim::new(cam).expect("in range");
    let px = 1u64 << POS_FRAC_BITS;
    let pattern = [
        DepthIn { valid: true, d: 20 * px, last: false, sof: true },
        DepthIn { valid: true, d: 0, last: false, sof: false },
        DepthIn::default(),
        DepthIn { valid: true, d: 3, last: true, sof: false },
        DepthIn { valid: true, d: D_MAX, last: false, sof: false },
        DepthIn { valid: false, d: 77, last: true, sof: true },
        DepthIn { valid: true, d: 60 * px + 5, last: true, sof: false },
    ];
    let mut beats: Vec<DepthIn> = pattern.to_vec();
    beats.extend((0..DEPTH_LAG + 3).map(|_| DepthIn::default()));
    let outs: Vec<DepthOut> = beats.iter().map(|&b| sim.step(b)).collect();
    for o in &outs[..DEPTH_LAG] {
        assert_eq!(*o, DepthOut::default(), "nothing before the lag");
    }
    for (c, b) in beats.iter().enumerate() {
        let o = outs.get(c + DEPTH_LAG).copied().unwrap_or_default();
        if b.valid {
            assert!(o.valid && o.d == b.d && o.last == b.last && o.sof == b.sof, "clock {c}: {o:?} for {b:?}");
            check_depth(b.d, o.z_mm, &gold).expect("as golden");
        } else {
            assert_eq!(o, DepthOut::default(), "clock {c}: an idle clock gives zeros (inputs {b:?})");
        }
    }
    // Lines of a frame back to back and with a period: the run's pixels
    // leave DEPTH_LAG clocks after they came, in order, lines split at last.
    for period in [0, 37] {
        let lines: Vec<Vec<u64>> = (0..5u64).map(|y| (0..20 + 3 * y).map(|x| (x * 97 + y * 13) % (D_MAX + 1)).collect()).collect();
        let mut sim = DepthStageSim::new(cam).expect("in range");
        let run = sim.run(&lines, period);
        assert_eq!(run.z.len(), lines.len());
        assert_eq!(run.in_cycles.len(), run.out_cycles.len());
        for (i, o) in run.in_cycles.iter().zip(&run.out_cycles) {
            assert_eq!(o - i, DEPTH_LAG as u64);
        }
        assert_eq!(run.pixels.iter().filter(|p| p.sof).count(), 1);
        assert!(run.pixels[0].sof);
        for (l, z) in lines.iter().zip(&run.z) {
            assert_eq!(l.len(), z.len());
            for (&d, &z) in l.iter().zip(z) {
                check_depth(d, z, &gold).expect("as golden");
            }
        }
    }
}

// ===========================================================================
// Generation-time checks
// ===========================================================================

/// Cameras outside the supported range are refused with the matching
/// error; the ends of the range are accepted, each numerator in its range.
#[test]
fn cameras_outside_the_range_are_refused_with_typed_errors() {
    let nan = DepthCamera { focal_px: f64::NAN, baseline_mm: 100.0 };
    assert!(matches!(DepthStage::new(nan), Err(DepthError::NotPositive { .. })));
    let neg = DepthCamera { focal_px: 500.0, baseline_mm: -1.0 };
    assert!(matches!(DepthScale::of(&neg), Err(DepthError::NotPositive { .. })));
    let [lo, hi] = extreme_cameras();
    for c in [lo, hi, DepthCamera::MOTORCYCLE_FULL, DepthCamera::MOTORCYCLE_QUARTER] {
        let s = DepthScale::of(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        assert!(s.k * 2 >= DEPTH_K_LIMIT && s.k <= DEPTH_K_LIMIT && (DEPTH_SCALE_MIN..=DEPTH_SCALE_MAX).contains(&s.scale), "{s:?}");
        // K = round(f·b·16·2^s).
        assert_eq!(s.k, (c.product() * 16.0 * 2f64.powi(s.scale as i32)).round() as u64);
    }
    let small = DepthCamera { focal_px: lo.focal_px * 0.999, ..lo };
    assert!(matches!(DepthScale::of(&small), Err(DepthError::ProductTooSmall { .. })));
    let large = DepthCamera { focal_px: hi.focal_px * 1.001, ..hi };
    assert!(matches!(DepthScale::of(&large), Err(DepthError::ProductTooLarge { .. })));
    assert!(DepthStage::new(large).is_err());
}

// ===========================================================================
// Real pairs
// ===========================================================================

/// golden's dense disparity of `pair` (default mode, hardware parity: every
/// value a multiple of 1/16 px), row by row through the stage for `cam`,
/// one row per line period: every depth as golden's.
fn real_pair(pair: &str, cam: DepthCamera) {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(pair)).expect("the pair loads");
    let disparity = sim::drive::stereo::golden_map(&data.left, &data.right, 0.0, data.dispmax + 1.0, sim::Config::Sd).expect("golden runs");
    let w = data.left.width();
    let lines: Vec<Vec<u64>> = disparity.chunks(w).map(|r| r.iter().map(|&d| disparity_lsb(d, sim::Config::Sd)).collect()).collect();
    let want = sim::drive::stereo::golden_depth_map(&disparity, &cam, sim::Config::Sd);
    let gold = golden_stage(&cam).expect("in range");
    let mut sim = DepthStageSim::new(cam).expect("in range");
    let run = sim.run(&lines, w + 8);
    assert_eq!(run.z.len(), lines.len());
    let (mut with, mut sat) = (0usize, 0usize);
    for (y, ((l, z), want)) in lines.iter().zip(&run.z).zip(want.chunks(w)).enumerate() {
        assert_eq!(l.len(), z.len(), "{pair} row {y}");
        for (x, (&d, &z)) in l.iter().zip(z).enumerate() {
            check_depth(d, z, &gold).unwrap_or_else(|e| panic!("{pair} ({x}, {y}): {e}"));
            assert_eq!(z, want[x], "{pair} ({x}, {y}): golden's depth map");
            with += (d > 0) as usize;
            sat += (z as u64 == DEPTH_MAX_MM) as usize;
        }
    }
    for (i, o) in run.in_cycles.iter().zip(&run.out_cycles) {
        assert_eq!(o - i, DEPTH_LAG as u64);
    }
    eprintln!("{pair}: {} pixels, {with} with a disparity, {sat} saturated, every depth as golden's", w * lines.len());
    assert!(with > w * lines.len() / 2, "{pair}: a dense map");
}

/// Tsukuba (d = 5 to 14 px) with Motorcycle's quarter-size camera (depths
/// of 13.7 to 38 m, in range) and its full-resolution one (55 m, and
/// saturation below 11.7 px: most pixels).
#[test]
fn golden_dense_disparity_of_tsukuba_gives_golden_depths() {
    real_pair("tsukuba", DepthCamera::MOTORCYCLE_QUARTER);
    real_pair("tsukuba", DepthCamera::MOTORCYCLE_FULL);
}

/// Motorcycle with its own camera at the pair's quarter size.
#[test]
fn golden_dense_disparity_of_motorcycle_gives_golden_depths() {
    real_pair("motorcycle", DepthCamera::MOTORCYCLE_QUARTER);
}

// ===========================================================================
// Verilog
// ===========================================================================

fn design() -> String {
    sim::hdl::cosim::verilog_of(DepthStage::default())
}


#[test]
fn depth_stage_verilog_generates_and_lints_clean_but_for_the_accepted_warnings() {
    let v = design();
    assert!(v.contains("module top"), "a top module");
    if std::process::Command::new("verilator").arg("--version").output().is_err() {
        eprintln!("verilator not installed: lint skipped");
        return;
    }
    let warnings = sim::hdl::cosim::lint_verilator(&v).unwrap_or_else(|e| panic!("{e}"));
    let counts = sim::hdl::cosim::check_accepted(&warnings, sim::hdl::cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("accepted lint warnings: {counts:?}");
}

/// The generated Verilog under Icarus and Verilator gives the Rust model's
/// outputs, clock by clock, on every disparity and random ones with idle
/// clocks.
#[test]
fn depth_stage_verilog_replays_the_rust_model_under_icarus_and_verilator() {
    use sim::hdl::cosim::{self, Options, Simulator};
    let v = design();
    let (ins, outs) = cosim::data_ports(&v).expect("ports");
    let names: Vec<String> = ins.iter().map(|p| p.name.clone()).collect();
    let mut rng = sim::rng::VectorRng(0xdeb7_0001);
    let mut beats: Vec<DepthIn> = (0..=D_MAX).map(|d| DepthIn { valid: true, d, last: d % 97 == 0, sof: d == 0 }).collect();
    beats.extend((0..3000).map(|_| {
        let r = rng.next();
        DepthIn { valid: !r.is_multiple_of(5), d: ((r >> 8) % (D_MAX + 1)) >> ((r >> 40) % 14), last: r.is_multiple_of(7), sof: r.is_multiple_of(11) }
    }));
    beats.extend((0..DEPTH_LAG + 2).map(|_| DepthIn::default()));
    let value = |b: &DepthIn, n: &str| match n {
        "p_valid" => b.valid as u64,
        "p_d" => b.d,
        "p_last" => b.last as u64,
        "p_sof" => b.sof as u64,
        // The stimuli never reset the block.
        "reset" => 0,
        other => panic!("unknown input {other}"),
    };
    let stimulus: Vec<Vec<u64>> = beats.iter().map(|b| names.iter().map(|n| value(b, n)).collect()).collect();
    let mut reader = cosim::PortReader::new(&ins, &outs);
    let mut uut = DepthStage::default();
    let trace = cosim::record(
        &mut uut,
        &ins,
        &outs,
        |u: &mut DepthStage, level| u.clock.next = level.into(),
        |u: &mut DepthStage, x: &[u64]| {
            for (n, &x) in names.iter().zip(x) {
                match n.as_str() {
                    "p_valid" => u.p_valid.next = x != 0,
                    "p_d" => u.p_d.next = x.into(),
                    "p_last" => u.p_last.next = x != 0,
                    "p_sof" => u.p_sof.next = x != 0,
                    "reset" => u.reset.next = x != 0,
                    _ => {}
                }
            }
        },
        |u: &DepthStage| reader.read(u, &ins, &outs).unwrap_or_else(|e| panic!("{e}")).outputs,
        stimulus,
    )
    .expect("records");
    for s in [Simulator::Icarus, Simulator::Verilator] {
        let run = cosim::check(s, &v, &trace, &Options::default()).unwrap_or_else(|e| panic!("{}: {e}", s.name()));
        eprintln!("{}: {} cycles, run {:.2} s", s.name(), trace.len(), run.run.as_secs_f64());
    }
}

/// Yosys and nextpnr on the ECP5-85K: the table in one block RAM, the step's
/// product in one multiplier (the slope and weight in its own input
/// registers), no LUT RAM, a few hundred LUTs (under 600), and the sensor's
/// 125 MHz target met.
#[test]
fn depth_stage_places_and_routes_on_ecp5_85k_at_125_mhz_with_one_block_ram_and_one_multiplier() {
    let r = sim::hdl::synth::synthesize(&design(), 125.0).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", sim::hdl::synth::report_table(&r));
    assert_eq!((r.brams, r.dsps, r.lutram), (1, 1, 0), "block RAMs, multipliers, LUT RAM");
    assert!(r.luts < 600, "LUTs {}", r.luts);
    assert!(r.meets_target, "Fmax {} MHz", r.fmax_mhz);
}
