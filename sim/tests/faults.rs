//! The fault-injection campaign (`sim::hdl::faults`) on the `sd` line
//! processor's Verilog under Verilator: cameras that cut frames short, mix
//! line widths, drop `tlast`, restart frames, run out of step and pause,
//! each faulty frame followed by a clean one.

use sim::hdl::cosim::Options;
use sim::hdl::faults::{run_campaign, CampaignSpec, Fault};

fn sources() -> Vec<(golden::GreyImage, golden::GreyImage)> {
    ["cones", "teddy", "venus", "tsukuba"]
        .iter()
        .map(|name| {
            let d = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join(name)).expect("the pair loads");
            (d.left, d.right)
        })
        .collect()
}

fn spec(frames: usize, seed: u64, classes: Vec<Fault>) -> CampaignSpec {
    let config = sim::Config::Sd;
    CampaignSpec {
        config,
        frames,
        seed,
        width: 160,
        height: 12,
        hblank: 160,
        gap_lines: 12,
        classes,
        area: sim::formats::SearchArea::below(sim::formats::dispmax_lsb(40.0, config).expect("dispmax")),
    }
}

fn design() -> String {
    sim::hdl::verilog::generate_with(sim::Config::Sd, sim::hdl::verilog::Top::Stereo, rtl::params::N_CELLS, rtl::matcher::declivity_matcher::GainRule::Robust).expect("the design")
}

#[test]
fn every_fault_class_leaves_no_hang_no_misaligned_line_and_exact_clean_frames() {
    let frames: usize = std::env::var("DECLIVITY_FAULT_FRAMES").ok().and_then(|s| s.parse().ok()).unwrap_or(60);
    let seed: u64 = std::env::var("DECLIVITY_FAULT_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(1);
    let classes: Vec<Fault> = match std::env::var("DECLIVITY_FAULT_CLASS") {
        Ok(name) => Fault::ALL.into_iter().filter(|f| f.name() == name).collect(),
        Err(_) => Vec::new(),
    };
    let report = run_campaign(&spec(frames, seed, classes), &sources(), &design(), &Options::default(), &mut |p| eprintln!("{p}")).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("injected {:?}", report.injected);
    eprintln!("{} output lines, {} clocks in {:.1} s, hung {}, status {:?}", report.output_lines, report.cycles, report.sim_seconds, report.hung, report.status);
    eprintln!("clean frames exact: {} of {}", report.clean_exact, report.clean_frames);
    eprintln!("violated {:?}; after {:?}", report.violated, report.violated_after);
    for v in report.violations.iter().take(20) {
        eprintln!("  {}: {}", v.invariant, v.detail);
    }
    assert!(report.violations.is_empty(), "{} invariants broken", report.violations.len());
}
