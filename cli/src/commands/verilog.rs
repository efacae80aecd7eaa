//! `declivity verilog`: the Verilog of a block.

use std::path::PathBuf;

use clap::Args;
use rtl::params::ROWS_PER_CELL;
use sim::{Config, SimError};

use crate::args::{cells_per_config, config_help, per_config, CliConfig, CliRule, CliTop};

/// Write the Verilog of a hardware block.
#[derive(Args, Debug)]
#[command(long_about = "Write the Verilog that rust-hdl generates for a hardware block into --out \
(DIR/<top>.v, top module `top`, one clock input `clock`, no reset: registers start from their Verilog \
initial values). The ECP5 primitives it instantiates (DP16KD, MULT18X18D, TRELLIS_DPR16X4) have \
behavioural models for simulation in sim/src/hdl/models/. The same Verilog is linted by Verilator, \
checked for latches by Yosys and co-simulated bit-exactly against the Rust model by the tests.")]
pub(crate) struct VerilogArgs {
    /// The block.
    #[arg(long, value_enum)]
    top: CliTop,
    #[command(flatten)]
    matcher: MatcherArgs,
    /// Output folder (created if missing).
    #[arg(long, default_value = "declivity-out/verilog")]
    out: PathBuf,
}

/// The configuration and the matcher's generation parameters (`--top
/// matcher` and `stereo`).
#[derive(Args, Debug)]
pub(crate) struct MatcherArgs {
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the block"))]
    pub config: CliConfig,
    #[arg(long, help = cells_help())]
    pub cells: Option<usize>,
    /// Gain rule the matcher is generated for (--top matcher and stereo only).
    #[arg(long, value_enum, default_value_t = CliRule::Robust)]
    pub rule: CliRule,
}

fn cells_help() -> String {
    format!(
        "Gain cells of the matcher's systolic array ({}; each holds up to {ROWS_PER_CELL} reference \
         declivities; --top matcher and stereo only) [default: the configuration's sensor: {}]",
        cells_per_config(),
        per_config(|s| s.cells)
    )
}

/// The Verilog of a block as the command line asks for it.
pub(crate) fn block_verilog(top: CliTop, m: &MatcherArgs) -> Result<String, SimError> {
    let has_matcher = matches!(top, CliTop::Matcher | CliTop::Stereo);
    if !has_matcher && (m.cells.is_some() || m.rule != CliRule::Robust) {
        return Err(SimError::Argument("--cells and --rule apply to --top matcher and --top stereo only".into()));
    }
    let config = m.config.0;
    let cells = m.cells.unwrap_or(config.sizes().cells);
    sim::hdl::verilog::generate_with(config, top.top(), cells, m.rule.rule())
        .ok_or_else(|| SimError::Argument(format!("--cells {cells}: the {config} matcher is generated with {:?} cells", config.matcher_cells())))
}

pub(crate) fn run(a: VerilogArgs) -> Result<(), SimError> {
    std::fs::create_dir_all(&a.out).map_err(|source| SimError::Io { path: a.out.clone(), source })?;
    let path = a.out.join(format!("{}.v", a.top.top().name()));
    let v = block_verilog(a.top, &a.matcher)?;
    std::fs::write(&path, &v).map_err(|source| SimError::Io { path: path.clone(), source })?;
    println!("{} ({} lines, top module `top`)", path.display(), v.lines().count());
    Ok(())
}
