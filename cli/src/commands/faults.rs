//! `declivity rtl faults`: the fault-injection campaign (`sim::hdl::faults`)
//! on the line processor's Verilog under Verilator.

use std::path::PathBuf;

use clap::Args;
use serde::Serialize;
use sim::hdl::faults::{check_spec, run_campaign, CampaignReport, CampaignSpec, Fault, DEFAULT_SOURCES, INVARIANTS};
use sim::{Config, SimError};

use crate::args::{config_help, CliConfig};
use crate::progress::Progress;

pub(crate) fn faults_about() -> String {
    format!(
        "Play frames from two cameras that break the stream's rules into the line processor's generated \
Verilog under Verilator, and check what it does against the datasheet's \"Faulty cameras\". Each faulty \
frame has one class of fault, or two or three mixed ({classes}); a clean frame follows it after a vertical \
gap of --gap-lines line periods and is checked beat for beat and clock for clock against a fresh run of it. \
The frames are crops of real pairs (--pairs; by default {sources} of data/stereo) and generated textures.

The invariants checked over the whole run: {invariants}. The gap must be longer than SOF_SKEW_MAX \
({skew}) and a tick of the stamp, so that a frame started on one camera only is told from the next frame.

Prints, or with --json as one JSON object: the campaign (config, frames, seed, classes, width, height, \
hblank, gap_lines, dispmax) and the report: faulty_frames, injected (faulty frames per class), \
clean_frames, clean_exact, clean_unchecked, clean_late, output_lines, cycles, hung, status (the status \
counters at the end), violations, violated (per invariant), violated_after (per class of the faulty frame \
before) and sim_seconds. Exits with status 1 when an invariant is broken.",
        classes = Fault::all_names(),
        sources = DEFAULT_SOURCES.join(", "),
        invariants = INVARIANTS.join(", "),
        skew = crate::args::per_config(|s| s.sof_skew_max),
    )
}

#[derive(Args, Debug)]
pub(crate) struct FaultsArgs {
    /// Faulty frames, each followed by a clean frame that is checked (at most 10 000: the
    /// campaign holds its whole script in memory, about 8 000 beats a frame).
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    frames: u32,
    /// Seed of the campaign (its frames, faults and where they fall).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Classes of fault, comma-separated [default: all].
    #[arg(long, value_delimiter = ',', value_parser = parse_fault)]
    classes: Vec<Fault>,
    /// Pixels per line of the frames (1 to W_MAX of --config).
    #[arg(long, default_value_t = 160)]
    width: usize,
    /// Rows per frame (the `height` port).
    #[arg(long, default_value_t = 12)]
    height: usize,
    /// Idle clocks after each line.
    #[arg(long, default_value_t = 160, value_parser = clap::value_parser!(u32).range(..=1 << 16))]
    hblank: u32,
    /// Line periods between a frame's end and the next frame.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u32).range(1..=1 << 12))]
    gap_lines: u32,
    /// Eq. 6's search bound, px (0 < d < dispmax).
    #[arg(long, default_value_t = 40.0)]
    dispmax: f64,
    /// Pair folders to crop the real frames from (each a folder with meta.txt; pairs smaller
    /// than the frames are skipped) [default: data/stereo's pairs above].
    #[arg(long)]
    pairs: Vec<PathBuf>,
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the campaign"))]
    config: CliConfig,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn parse_fault(s: &str) -> Result<Fault, String> {
    Fault::ALL.into_iter().find(|f| f.name() == s).ok_or_else(|| format!("no class of fault `{s}`: one of {}", Fault::all_names()))
}

/// The campaign as run and what it found.
#[derive(Serialize)]
struct FaultsOutcome {
    config: &'static str,
    frames: usize,
    seed: u64,
    classes: Vec<&'static str>,
    width: usize,
    height: usize,
    hblank: u32,
    gap_lines: usize,
    dispmax: f64,
    #[serde(flatten)]
    report: CampaignReport,
}

pub(crate) fn run(a: FaultsArgs) -> Result<(), SimError> {
    let config = a.config.0;
    let spec = CampaignSpec {
        config,
        frames: a.frames as usize,
        seed: a.seed,
        width: a.width,
        height: a.height,
        hblank: a.hblank,
        gap_lines: a.gap_lines as usize,
        classes: a.classes.clone(),
        area: sim::formats::SearchArea::below(sim::formats::dispmax_lsb(a.dispmax, config)?),
    };
    check_spec(&spec)?;
    let dirs = if a.pairs.is_empty() { sim::eval::io::stereo_pair_dirs(&DEFAULT_SOURCES) } else { sim::eval::io::expand_pair_dirs(&a.pairs)? };
    let sources = sim::eval::io::load_image_pairs(&dirs)?;
    let design = sim::hdl::verilog::generate_block(config, sim::hdl::verilog::Top::Stereo, &sim::hdl::verilog::Generation::of(config))?;
    let bar = Progress::spinner(format!("fault campaign ({config}, verilator)"), a.json);
    let report = run_campaign(&spec, &sources, &design, &Default::default(), &mut |p| bar.phase(p))?;
    bar.finish();
    let broken = report.violations.len();
    let outcome = FaultsOutcome {
        config: config.name(),
        frames: spec.frames,
        seed: spec.seed,
        classes: spec.classes().iter().map(|c| c.name()).collect(),
        width: spec.width,
        height: spec.height,
        hblank: spec.hblank,
        gap_lines: spec.gap_lines,
        dispmax: a.dispmax,
        report,
    };
    if a.json {
        super::print_json(&outcome);
    } else {
        let r = &outcome.report;
        println!(
            "{} faulty frames ({}), {}x{} px, hblank {}, gap {} lines, seed {} ({config})",
            r.faulty_frames,
            outcome.classes.join(", "),
            spec.width,
            spec.height,
            spec.hblank,
            spec.gap_lines,
            spec.seed
        );
        let injected: Vec<String> = r.injected.iter().map(|(k, v)| format!("{k} {v}")).collect();
        println!("  injected            {}", injected.join(", "));
        println!(
            "  clean frames exact  {} of {} ({} a clock late; {} more sent unchecked after a frame that ended only at their tuser)",
            r.clean_exact, r.clean_frames, r.clean_late, r.clean_unchecked
        );
        println!("  output lines        {}", r.output_lines);
        println!("  hung                {}", r.hung);
        let status: Vec<String> = r.status.iter().map(|(k, v)| format!("{k} {v}")).collect();
        println!("  status              {}", status.join(", "));
        for invariant in INVARIANTS {
            println!("  {:<19} {} violations", invariant, r.violated.get(invariant).copied().unwrap_or(0));
        }
        for v in r.violations.iter().take(10) {
            println!("    {}: {}", v.invariant, v.detail);
        }
        println!("  simulation          {} clocks in {:.1} s", r.cycles, r.sim_seconds);
    }
    if broken > 0 {
        return Err(SimError::Check(format!("{broken} invariants broken (see above)")));
    }
    Ok(())
}
