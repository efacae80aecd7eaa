//! The whole line processor's Verilog (`declivity verilog --top stereo`):
//! Verilator lint with the accepted list of the blocks, Yosys without
//! latches. (Generated with a 16-cell matcher, the size `cosim_matcher`
//! co-simulates: the cells are the matcher's; the joins are what is new.)

use sim::cosim;

fn design() -> String {
    sim::verilog::generate_with(sim::verilog::Top::Stereo, CELLS, rtl::declivity_matcher::GainRule::Robust).expect("a supported size")
}

/// Cells of the matcher in the checked Verilog.
const CELLS: usize = 16;

/// Verilator `-Wall` warnings accepted in the line processor's Verilog,
/// with why.
const ACCEPTED: &[(&str, &str)] = &[
    sim::cosim::ACCEPTED_LINT[0],
    sim::cosim::ACCEPTED_LINT[1],
    sim::cosim::DP16KD_UNUSED_OUTPUTS,
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
fn stereo_verilog_lints_clean_but_for_the_accepted_warnings() {
    let warnings = cosim::lint_verilator(&design()).unwrap_or_else(|e| panic!("{e}"));
    let counts = cosim::check_accepted(&warnings, ACCEPTED).unwrap_or_else(|e| panic!("{e}"));
    for w in warnings.iter().filter(|w| w.code == "UNUSEDSIGNAL") {
        assert!(UNUSED_OUTPUTS.iter().any(|name| w.message.ends_with(&format!("'{name}'"))), "an unused signal not in the list: {}", w.message);
    }
    eprintln!("accepted lint warnings: {counts:?}");
}

#[test]
fn stereo_synthesizes_in_yosys_without_latches() {
    let check = sim::synth::yosys_latch_check(&design(), "top").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(check.latches, 0, "latches: {:?}", check.latch_cells);
    assert!(check.cells > 3000, "the line processor is not empty: {} cells", check.cells);
}
