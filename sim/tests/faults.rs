//! The fault-injection campaign (`sim::hdl::faults`) on the `sd` line
//! processor's Verilog under Verilator: cameras that cut frames short,
//! restart frames inside a frame or a line, run out of step, pause, mix
//! line widths and drop `tlast`, each faulty frame followed by a clean
//! one. `DECLIVITY_FAULT_FRAMES` and `DECLIVITY_FAULT_SEED` set the size and
//! the seed (the full campaign: 1000 frames).

use sim::hdl::cosim::Options;
use sim::hdl::faults::{run_campaign, CampaignReport, CampaignSpec, Fault};

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}

fn campaign(frames: u64, classes: Vec<Fault>) -> CampaignReport {
    let config = sim::Config::Sd;
    let spec = CampaignSpec {
        config,
        frames: env("DECLIVITY_FAULT_FRAMES", frames) as usize,
        seed: env("DECLIVITY_FAULT_SEED", 1),
        width: 160,
        height: 12,
        hblank: 160,
        gap_lines: 12,
        classes,
        area: sim::formats::SearchArea::below(sim::formats::dispmax_lsb(40.0, config).expect("dispmax")),
    };
    let design = sim::hdl::verilog::generate_with(config, sim::hdl::verilog::Top::Stereo, rtl::params::N_CELLS, rtl::matcher::declivity_matcher::GainRule::Robust).expect("the design");
    let report = run_campaign(&spec, &sim::eval::io::load_image_pairs(&sim::eval::io::stereo_pair_dirs(&sim::hdl::faults::DEFAULT_SOURCES)).expect("the pairs load"), &design, &Options::default(), &mut |p| eprintln!("{p}")).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("injected {:?}", report.injected);
    eprintln!("{} output lines, {} clocks in {:.1} s, hung {}, status {:?}", report.output_lines, report.cycles, report.sim_seconds, report.hung, report.status);
    eprintln!(
        "clean frames exact: {} of {} ({} of them a clock late; {} more sent unchecked after a frame whose last line ended only at their tuser)",
        report.clean_exact, report.clean_frames, report.clean_late, report.clean_unchecked
    );
    eprintln!("violated {:?}; after {:?}", report.violated, report.violated_after);
    for invariant in sim::hdl::faults::INVARIANTS {
        for v in report.violations.iter().filter(|v| v.invariant == invariant).take(5) {
            eprintln!("  {}: {}", v.invariant, v.detail);
        }
    }
    report
}

/// The classes whose behaviour is defined in full (datasheet, "Faulty
/// cameras"), mixed: every invariant holds.
#[test]
fn short_restarted_out_of_step_and_paused_frames_never_hang_or_misalign_and_the_next_clean_frame_is_exact() {
    let report = campaign(120, vec![Fault::ShortFrame, Fault::SofMidFrame, Fault::OutOfStep, Fault::IdleClocks]);
    for class in ["short_frame", "sof_mid_frame", "out_of_step", "idle_clocks"] {
        assert!(report.injected.get(class).copied().unwrap_or(0) > 0, "{class} injected");
    }
    assert!(report.status.iter().any(|(n, v)| n == "lines_unpaired" && *v > 0), "lines out of step were dropped unpaired and counted");
    assert!(report.violations.is_empty(), "{} invariants broken", report.violations.len());
    assert_eq!(report.clean_exact, report.clean_frames);
}

/// Lines of other widths and missing `tlast`s: every output line has its
/// frame's width (the frame's first reference line's, as stored), and the
/// next clean frame is exact.
#[test]
fn lines_of_other_widths_and_missing_tlasts_keep_every_output_line_at_its_frames_width_and_the_next_clean_frame_exact() {
    let report = campaign(60, vec![Fault::MixedWidths, Fault::MissingTlast]);
    for class in ["mixed_widths", "missing_tlast"] {
        assert!(report.injected.get(class).copied().unwrap_or(0) > 0, "{class} injected");
    }
    assert!(report.status.iter().any(|(n, v)| n == "lines_wide" && *v > 0), "lines cut at their frame's width were counted");
    assert!(report.violations.is_empty(), "{} invariants broken", report.violations.len());
    assert_eq!(report.clean_exact, report.clean_frames);
}

/// All six classes, mixed in one frame as they come: every invariant
/// holds.
#[test]
fn every_class_of_fault_mixed_never_hangs_or_misaligns_and_the_next_clean_frame_is_exact() {
    let report = campaign(120, Fault::ALL.to_vec());
    for class in Fault::ALL {
        assert!(report.injected.get(class.name()).copied().unwrap_or(0) > 0, "{} injected", class.name());
    }
    assert!(report.violations.is_empty(), "{} invariants broken", report.violations.len());
    assert_eq!(report.clean_exact, report.clean_frames);
}
