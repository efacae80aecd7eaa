//! The `generic` target (`declivity verilog --target generic`): the blocks
//! with every ECP5 primitive replaced by its behavioural model inside the
//! block. It holds no vendor primitive, lints clean but for the accepted
//! warnings, maps onto an Artix-7's block RAMs and DSPs under Yosys's
//! `synth_xilinx`, and the line processor in it runs a whole pair under
//! Verilator equal to golden's hardware parity in every disparity and depth.

use sim::hdl::cosim::{self, Options, Simulator};
use sim::hdl::frame::run_frame;
use sim::hdl::primitives::instantiates;
use sim::hdl::verilog::{generate, Target, Top};
use sim::Config;

/// The primitives the `ecp5` target instantiates by name.
const PRIMITIVES: [&str; 4] = ["DP16KD", "MULT18X18D", "TRELLIS_DPR16X4", "DCCA"];

fn generic(top: Top) -> String {
    Target::Generic.retarget(generate(Config::Sd, top))
}

#[test]
fn generic_blocks_instantiate_no_vendor_primitive_and_lint_clean_but_for_the_accepted_warnings() {
    for top in [Top::Detector, Top::Interpolator, Top::Matcher] {
        let ecp5 = generate(Config::Sd, top);
        let v = Target::Generic.retarget(ecp5.clone());
        for p in PRIMITIVES {
            assert!(!instantiates(&v, p), "{}: `{p}` still instantiated", top.name());
            // Each primitive the ecp5 target used has its stand-in inside the block.
            assert_eq!(instantiates(&ecp5, p), v.contains(&format!("module top${p}(")), "{}: {p}", top.name());
        }
        let warnings = cosim::lint_verilator(&v).unwrap_or_else(|e| panic!("{}: {e}", top.name()));
        cosim::check_accepted(&warnings, cosim::ACCEPTED_LINT).unwrap_or_else(|e| panic!("{}: {e}", top.name()));
    }
}

#[test]
fn the_generic_detector_maps_onto_artix7_block_ram_and_dsp_under_synth_xilinx() {
    let e = sim::hdl::synth::xilinx::estimate_xilinx(&generic(Top::Detector), "top").unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", serde_json::to_string(&e).expect("serializes"));
    // No black box is left: every cell is a 7-series one.
    for p in PRIMITIVES {
        assert!(!e.yosys_cells.keys().any(|c| c.contains(p)), "{p} left in the netlist: {:?}", e.yosys_cells);
    }
    // The detector's line buffers (four DP16KD in the ecp5 target) become block RAM, and its
    // products (MULT18X18D) DSP slices.
    assert!(e.ramb18 + e.ramb36 >= 2, "line buffers in block RAM: {e:?}");
    assert!(e.dsps >= 1, "products in DSP48E1: {e:?}");
    assert!(e.luts > 100 && e.ffs > 100, "{e:?}");
}

/// The whole tsukuba pair through the generic line processor under
/// Verilator: every line out, nothing dropped, every disparity and depth
/// equal to golden's hardware parity (which the ecp5 target's Verilog and
/// the rust-hdl model equal too: `cosim_stereo.rs`).
#[test]
fn the_generic_line_processor_under_verilator_equals_golden_hardware_parity_on_a_whole_pair() {
    use rtl::post::depth_stage::DepthCamera;
    use sim::drive::stereo::{golden_depth_map, golden_map};
    let config = Config::Sd;
    let pair = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba")).expect("the pair loads");
    let dispmax = pair.dispmax + 1.0;
    let lsb = sim::formats::dispmax_lsb(dispmax, config).expect("dispmax");
    let ecp5 = generate(config, Top::Stereo);
    let design = Target::Generic.retarget(ecp5.clone());
    for p in PRIMITIVES {
        // The line processor instantiates every primitive, the reset's `DCCA` too, and its
        // generic Verilog none.
        assert!(instantiates(&ecp5, p) && !instantiates(&design, p) && design.contains(&format!("module top${p}(")), "{p}");
    }
    let got = run_frame(Simulator::Verilator, config, &design, &pair.left, &pair.right, 0, sim::formats::SearchArea::below(lsb), &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    let run = &got.run;
    assert_eq!(run.rows.len(), pair.left.height(), "every line out");
    assert_eq!((run.lines_dropped, run.records_dropped, run.pixels_dropped), (0, 0, 0), "nothing dropped");
    let rtl = run.disparity_px(pair.left.height());
    let gold = golden_map(&pair.left, &pair.right, 0.0, dispmax, config).expect("golden runs");
    let matched = rtl.iter().filter(|&&d| d > 0.0).count();
    eprintln!("generic tsukuba: {} clocks, {matched} pixels with a disparity, build {:.1} s, run {:.1} s", run.cycles, got.compile.as_secs_f64(), got.sim.as_secs_f64());
    assert!(matched > rtl.len() / 2, "a dense map ({matched} of {})", rtl.len());
    for (i, (a, b)) in rtl.iter().zip(&gold).enumerate() {
        assert_eq!(a, b, "disparity at ({}, {}) differs from golden's hardware parity", i % pair.left.width(), i / pair.left.width());
    }
    let depth = run.depth_mm(pair.left.height());
    let gold_depth = golden_depth_map(&gold, &DepthCamera::default(), config);
    assert_eq!(depth, gold_depth, "every depth equal to golden's hardware parity");
}
