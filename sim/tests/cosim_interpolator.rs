//! The interpolator's generated Verilog against its Rust model: bit-exact
//! co-simulation under Icarus and Verilator on committed vectors
//! (`vectors/interpolator/`), Verilator lint with a short accepted list,
//! Yosys without latches, and a place and route on the ECP5-85K.
//!
//! The vectors are recorded from the Rust model; a test fails when the
//! committed files differ from a fresh recording. Regenerate them with
//! `COSIM_BLESS=1 cargo test --release -p sim --test cosim_interpolator`.

use std::path::{Path, PathBuf};

use rtl::post::interpolator::{LINE_QUEUE, PIXEL_LAG, SEGMENT_LAG};
use rtl::params::{N_MAX, POS_BITS, POS_FRAC_BITS, W_MAX};
use sim::hdl::cosim::{self, Options, Simulator, Trace};
use sim::rng::VectorRng;
use sim::drive::interpolator::{fixed_anchors, AnchorLine, FixedAnchor};
use sim::hdl::traces::interpolator_trace;

/// One position LSB (1/16 px).
const PX: u32 = 1 << POS_FRAC_BITS;

fn vectors() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/interpolator")
}

fn design() -> String {
    sim::hdl::verilog::generate(sim::Config::Sd, sim::hdl::verilog::Top::Interpolator)
}

/// A random line of `n` anchors: steps of one LSB to 20 px, disparities
/// walking by up to 8 px (so some steps are jumps) and now and then
/// anywhere.
fn random_line(rng: &mut VectorRng, n: usize, width: usize) -> AnchorLine {
    let (mut x, mut d) = (rng.next() as u32 % (4 * PX), 20 * PX);
    let mut anchors = Vec::new();
    for _ in 0..n {
        if x >= width as u32 * PX {
            break;
        }
        anchors.push(FixedAnchor { x, d });
        x += 1 + rng.next() as u32 % (20 * PX);
        d = match rng.next() % 8 {
            0 => rng.next() as u32 % (1 << POS_BITS),
            _ => (d + rng.next() as u32 % (16 * PX)).saturating_sub(8 * PX).min((1 << POS_BITS) - 1),
        };
    }
    AnchorLine { anchors, width, sof: false }
}

/// Empty lines, one anchor, anchors sharing a pixel, anchors on pixel
/// centres, the largest disparity, a one-pixel line, a `W_MAX` line with
/// `N_MAX` anchors, random lines, then a burst beyond the line queue (one
/// line dropped, `overflow`).
fn corner_trace(design: &str) -> Trace {
    let mut rng = VectorRng(0x1e7e_0001);
    let a = |x: u32, d: u32| FixedAnchor { x, d };
    let mut lines = vec![
        AnchorLine { anchors: vec![], width: 30, sof: true },
        AnchorLine { anchors: vec![a(5 * PX + 3, 7 * PX)], width: 12, sof: false },
        AnchorLine { anchors: vec![a(4 * PX + 1, 3 * PX), a(4 * PX + 2, 30 * PX), a(4 * PX + 9, 5 * PX)], width: 9, sof: false },
        AnchorLine { anchors: vec![a(2 * PX, 10 * PX), a(6 * PX, 14 * PX), a(9 * PX, 2 * PX)], width: 12, sof: false },
        AnchorLine { anchors: vec![a(0, (1 << POS_BITS) - 1), a(3 * PX + 8, 0)], width: 5, sof: false },
        AnchorLine { anchors: vec![a(7, 3 * PX)], width: 1, sof: false },
        random_line(&mut rng, N_MAX, W_MAX),
    ];
    lines.extend((0..6).map(|k| random_line(&mut rng, 5 + 20 * k, 40 + 60 * k)));
    // Each line taking as long as it or the line before it leaves (at
    // least 40 clocks), the last one until the queue is empty; then lines
    // arriving faster than they leave.
    let burst: Vec<AnchorLine> = (0..LINE_QUEUE + 1).map(|_| random_line(&mut rng, 30, 300)).collect();
    let mut timed: Vec<(&AnchorLine, usize)> = Vec::new();
    for (k, l) in lines.iter().enumerate() {
        let before = if k == 0 { 0 } else { lines[k - 1].width };
        let last = k + 1 == lines.len();
        timed.push((l, if last { 2 * W_MAX } else { l.width.max(before).max(40) }));
    }
    timed.extend(burst.iter().map(|l| (l, 0)));
    interpolator_trace(design, &timed, (LINE_QUEUE + 1) * 300 + SEGMENT_LAG + PIXEL_LAG).expect("records")
}

/// golden's matches of six rows of cones (default mode, hardware parity),
/// one line per line period.
fn real_trace(design: &str) -> Trace {
    let data = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("cones")).expect("the pair loads");
    let mut params = golden::Params::new(data.dispmax + 1.0).expect("params");
    params.hardware = Some(sim::Config::Sd.limits());
    let frame = golden::process_frame(&data.left, &data.right, &params, golden::Threads::All).expect("golden runs");
    let w = data.left.width();
    let lines: Vec<AnchorLine> = (180..186).map(|y| fixed_anchors(&frame.lines[y].matches, w, y == 180)).collect();
    let timed: Vec<(&AnchorLine, usize)> = lines.iter().map(|l| (l, w)).collect();
    interpolator_trace(design, &timed, w + SEGMENT_LAG + PIXEL_LAG).expect("records")
}

fn committed(name: &str, fresh: &Trace) -> Trace {
    cosim::committed_trace(&vectors().join(name), fresh).unwrap_or_else(|e| panic!("{e}"))
}

fn count(t: &Trace, port: &str) -> usize {
    let i = t.outputs.iter().position(|p| p.name == port).unwrap_or_else(|| panic!("{port}"));
    t.cycles.iter().filter(|c| c.outputs[i] == 1).count()
}

#[test]
fn cosim_interpolator_vectors_are_current_and_carry_pixels() {
    let d = design();
    let corner = committed("corner.trace", &corner_trace(&d));
    let real = committed("real.trace", &real_trace(&d));
    // Pixels of every admitted line, one dropped line, and lines' ends:
    // the comparison below is not about an idle bus.
    // 30 + 12 + 9 + 12 + 5 + 1 + W_MAX + (40 + 100 + … + 340) pixels,
    // then LINE_QUEUE lines of 300 (the burst has one more, which is dropped).
    assert_eq!(count(&corner, "p_valid"), 69 + W_MAX + 1140 + LINE_QUEUE * 300);
    assert_eq!(count(&corner, "overflow"), 1);
    assert_eq!(count(&real, "p_valid"), 6 * 450);
    assert_eq!(count(&real, "p_last"), 6);
}

/// Both committed vectors replayed by `simulator` against the design.
fn replay(simulator: Simulator) {
    let d = design();
    for (name, fresh) in [("corner.trace", corner_trace(&d)), ("real.trace", real_trace(&d))] {
        let trace = committed(name, &fresh);
        let run = cosim::check(simulator, &d, &trace, &Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        eprintln!("{} {name}: {} cycles, run {:.2} s", simulator.name(), trace.len(), run.run.as_secs_f64());
    }
}

#[test]
fn cosim_interpolator_icarus_matches_rust_on_corner_cases_and_real_rows() {
    replay(Simulator::Icarus);
}

#[test]
fn cosim_interpolator_verilator_matches_rust_on_corner_cases_and_real_rows() {
    replay(Simulator::Verilator);
}


#[test]
fn interpolator_verilog_lints_clean_but_for_the_accepted_warnings() {
    let warnings = cosim::lint_verilator(&design()).unwrap_or_else(|e| panic!("{e}"));
    let counts = cosim::check_accepted(&warnings, sim::hdl::cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("accepted lint warnings: {counts:?}");
}

#[test]
fn interpolator_synthesizes_in_yosys_without_latches() {
    let check = sim::hdl::synth::yosys_latch_check(&design(), "top").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(check.latches, 0, "latches: {:?}", check.latch_cells);
    assert!(check.cells > 300, "the interpolator is not empty: {} cells", check.cells);
}

#[test]
fn interpolator_places_and_routes_on_ecp5_85k_with_two_multipliers() {
    let r = sim::hdl::synth::synthesize(&design(), 125.0).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", sim::hdl::synth::report_table(&r));
    // The weight v·recip and the step t·|Δd|.
    assert_eq!(r.dsps, 2, "DSPs");
    // A small block: well under a twentieth of the device.
    assert!(r.luts < 83_640 / 20, "LUTs {}", r.luts);
    assert!(r.fmax_mhz.is_finite() && r.fmax_mhz > 50.0, "Fmax {}", r.fmax_mhz);
}
