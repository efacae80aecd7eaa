//! The declivity detector's generated Verilog against its Rust model:
//! bit-exact co-simulation under Icarus and Verilator on committed vectors
//! (`vectors/detector/`), Verilator lint with a short accepted list, and
//! Yosys without latches.
//!
//! The vectors are recorded from the Rust model; a test fails when the
//! committed files differ from a fresh recording. Regenerate them with
//! `COSIM_BLESS=1 cargo test --release -p sim --test cosim_detector`.

use std::path::{Path, PathBuf};

use rtl::detector::declivity_detector::{MIN_LINE_PERIOD, RESET_RECOVERY};
use rtl::params::W_MAX;
use sim::hdl::cosim::{self, Options, Simulator, Trace};
use sim::rng::VectorRng;
use sim::drive::detector::{frame_beats, PixelBeat};
use sim::hdl::traces::detector_trace;

fn vectors() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/detector")
}

fn design() -> String {
    sim::hdl::verilog::generate(sim::Config::Sd, sim::hdl::verilog::Top::Detector)
}


fn walk(rng: &mut VectorRng, n: usize, step: i64) -> Vec<u8> {
    let mut v = 128i64;
    (0..n)
        .map(|_| {
            v = (v + (rng.next() % (2 * step as u64 + 1)) as i64 - step).clamp(0, 255);
            v as u8
        })
        .collect()
}

fn row(pair: &str, y: usize) -> Vec<u8> {
    let dir = sim::eval::io::stereo_data_dir().join(pair);
    let img = sim::eval::io::load_grey(&dir.join("left_gray.png"))
        .unwrap_or_else(|e| panic!("{}: {e} (the pairs are in data/stereo)", dir.display()))
        .image;
    img.row(y).to_vec()
}

/// Widths 1, 2, 3, flat, 0/255 extremes, more than N_MAX declivities, wider
/// than W_MAX, random walks with tvalid gaps, and real rows, each line a
/// frame of its own.
fn corner_trace(design: &str) -> Trace {
    let mut rng = VectorRng(0x5eed_0001);
    let mut zigzag: Vec<u8> = vec![150; 40];
    zigzag.extend((0..300).map(|x| if x % 2 == 0 { 60 } else { 160 }));
    let lines: Vec<Vec<u8>> = vec![
        vec![7],
        vec![0, 255],
        vec![255, 0, 255],
        vec![77; 50],
        (0..40).map(|x| if x % 2 == 0 { 0 } else { 255 }).collect(),
        (0..40).map(|x| if x < 20 { 0 } else { 255 }).collect(),
        zigzag,
        walk(&mut rng, W_MAX + 3, 6),
        walk(&mut rng, 200, 3),
        walk(&mut rng, 200, 20),
        row("tsukuba", 100),
        row("tsukuba", 101),
    ];
    let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
    // Each line followed by enough idle clocks that the input never stalls,
    // and one pixel in eight with tvalid low. Each line starts a frame (its
    // own width: a later line of a frame is cut at the first one's).
    let mut gaps = VectorRng(0x5eed_0002);
    // (After a wide line, as many idle clocks as its width: the reader is
    // that long on it, and the lines behind it wait for its bank.)
    let beats: Vec<_> = refs.iter().flat_map(|line| frame_beats(&[line], MIN_LINE_PERIOD.max(line.len()), || gaps.next() % 8 == 0)).collect();
    detector_trace(design, &beats).expect("records")
}

/// Twelve real rows of two pairs back to back at one pixel per clock.
fn real_trace(design: &str) -> Trace {
    let lines: Vec<Vec<u8>> = (150..156).map(|y| row("cones", y)).chain((200..206).map(|y| row("teddy", y))).collect();
    let refs: Vec<&[u8]> = lines.iter().map(|l| l.as_slice()).collect();
    let mut beats = frame_beats(&refs, 0, || false);
    beats.extend(std::iter::repeat_n(sim::drive::detector::PixelBeat::default(), 2 * MIN_LINE_PERIOD + 512));
    detector_trace(design, &beats).expect("records")
}

/// Tsukuba rows with two resets: one of two clocks inside a line while the
/// line before is being read (its records leaving), one of a clock while the
/// threshold scans a line's histogram; after each, the detector's recovery
/// (the histograms cleared) with `tvalid` low, then the next lines.
fn reset_trace(design: &str) -> Trace {
    let rows: Vec<Vec<u8>> = (100..107).map(|y| row("tsukuba", y)).collect();
    let w = rows[0].len();
    let part = |ys: std::ops::Range<usize>| {
        let refs: Vec<&[u8]> = rows[ys].iter().map(|l| l.as_slice()).collect();
        frame_beats(&refs, MIN_LINE_PERIOD, || false)
    };
    let reset = |clocks: usize| std::iter::repeat_n(PixelBeat { reset: true, ..PixelBeat::default() }, clocks);
    let idle = |clocks: usize| std::iter::repeat_n(PixelBeat::default(), clocks);
    let mut beats = part(0..2);
    beats.truncate(w + MIN_LINE_PERIOD + w / 2);
    beats.extend(reset(2));
    beats.extend(idle(RESET_RECOVERY + 2));
    let mut second = part(2..5);
    // The third line's last pixel, then 40 clocks of its threshold's scan.
    second.truncate(3 * w + 2 * MIN_LINE_PERIOD + 40);
    beats.extend(second);
    beats.extend(reset(1));
    beats.extend(idle(RESET_RECOVERY + 2));
    beats.extend(part(5..7));
    beats.extend(idle(2 * MIN_LINE_PERIOD + 512));
    detector_trace(design, &beats).expect("records")
}

fn committed(name: &str, fresh: &Trace) -> Trace {
    cosim::committed_trace(&vectors().join(name), fresh).unwrap_or_else(|e| panic!("{e}"))
}

/// Clocks on which a beat was offered (`s_tvalid`) and not taken: the
/// trace offers each beat on one clock only, so such a beat is lost.
fn refused_beats(t: &Trace) -> usize {
    let v = t.inputs.iter().position(|p| p.name == "s_tvalid").expect("s_tvalid");
    let r = t.outputs.iter().position(|p| p.name == "s_tready").expect("s_tready");
    t.cycles.iter().filter(|c| c.inputs[v] == 1 && c.outputs[r] == 0).count()
}

fn valid_beats(t: &Trace) -> usize {
    let i = t.outputs.iter().position(|p| p.name == "m_valid").expect("m_valid");
    t.cycles.iter().filter(|c| c.outputs[i] == 1).count()
}

#[test]
fn cosim_detector_vectors_are_current_and_carry_records() {
    let d = design();
    let corner = committed("corner.trace", &corner_trace(&d));
    let real = committed("real.trace", &real_trace(&d));
    let reset = committed("reset.trace", &reset_trace(&d));
    assert!(valid_beats(&reset) > 100, "{}", valid_beats(&reset));
    // Every line's marker and a fair number of records, so the comparison
    // below is not about an idle bus.
    assert!(valid_beats(&corner) > 60, "{}", valid_beats(&corner));
    assert_eq!(refused_beats(&corner), 0, "the corner cases' lines are offered when the detector takes them");
    assert!(valid_beats(&real) > 300, "{}", valid_beats(&real));
}

#[test]
fn cosim_detector_icarus_matches_rust_on_corner_cases() {
    let d = design();
    let trace = committed("corner.trace", &corner_trace(&d));
    let run = cosim::check(Simulator::Icarus, &d, &trace, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("icarus: {} cycles, compile {:.2} s, run {:.2} s", trace.len(), run.compile.as_secs_f64(), run.run.as_secs_f64());
}

#[test]
fn cosim_detector_verilator_matches_rust_on_corner_cases_and_real_rows() {
    let d = design();
    for (name, fresh) in [("corner.trace", corner_trace(&d)), ("real.trace", real_trace(&d)), ("reset.trace", reset_trace(&d))] {
        let trace = committed(name, &fresh);
        let run = cosim::check(Simulator::Verilator, &d, &trace, &Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        eprintln!(
            "verilator {name}: {} cycles, compile {:.2} s, run {:.2} s",
            trace.len(),
            run.compile.as_secs_f64(),
            run.run.as_secs_f64()
        );
    }
}


#[test]
fn detector_verilog_lints_clean_but_for_the_accepted_warnings() {
    let warnings = cosim::lint_verilator(&design()).unwrap_or_else(|e| panic!("{e}"));
    let counts = cosim::check_accepted(&warnings, sim::hdl::cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("accepted lint warnings: {counts:?}");
}

#[test]
fn detector_synthesizes_in_yosys_without_latches() {
    let check = sim::hdl::synth::yosys_latch_check(&design(), "top").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(check.latches, 0, "latches: {:?}", check.latch_cells);
    assert!(check.cells > 1000, "the detector is not empty: {} cells", check.cells);
}

#[test]
fn detector_places_and_routes_on_ecp5_85k_with_its_memories_in_block_ram() {
    let r = sim::hdl::synth::synthesize(&design(), 125.0).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", sim::hdl::synth::report_table(&r));
    // One DP16KD (its 1024 × 18-bit mode, `BlockRam`) per bank of the
    // 2 × 1024 × 8-bit line buffer, one each of the two 256 × 12-bit
    // histogram banks.
    assert_eq!(r.brams, 4, "block RAMs");
    // Three products: g², g²·(2x + 1) and the median fraction × K.
    assert_eq!(r.dsps, 3, "DSPs");
    // A small block: well under a tenth of the device.
    assert!(r.luts < 83_640 / 10 && r.ffs < 83_640 / 10, "LUTs {} FFs {}", r.luts, r.ffs);
    assert!(r.fmax_mhz.is_finite() && r.fmax_mhz > 50.0, "Fmax {}", r.fmax_mhz);
}
