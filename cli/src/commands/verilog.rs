//! `declivity verilog`: the Verilog of a block.

use std::path::PathBuf;

use clap::Args;
use rtl::params::ROWS_PER_CELL;
use sim::{Config, SimError};

use crate::args::{cells_per_config, config_help, per_config, CliConfig, CliRule, CliTop};

/// Write the Verilog of a hardware block.
#[derive(Args, Debug)]
#[command(long_about = long_about())]
pub(crate) struct VerilogArgs {
    /// The block.
    #[arg(long, value_enum)]
    top: CliTop,
    #[command(flatten)]
    matcher: MatcherArgs,
    /// The IP folder to write (created if missing).
    #[arg(long, default_value = "declivity-out/verilog")]
    out: PathBuf,
}

fn long_about() -> String {
    format!(
        "Write a hardware block as a self-contained IP folder in --out: the Verilog that rust-hdl \
         generates for it (DIR/declivity_<block>.v, module declivity_<block>, submodules \
         declivity_<block>$..., one clock input `clock`, no reset: registers start from their \
         Verilog initial values); the behavioural models of the ECP5 primitives it instantiates \
         (DP16KD, MULT18X18D, TRELLIS_DPR16X4) in DIR/{}/, one module a file, for simulation \
         only; a simulation file list DIR/declivity_<block>.f (paths under \
         ${{DECLIVITY_<BLOCK>_DIR}}; iverilog -c, verilator -f); a FuseSoC CAPI2 core \
         DIR/declivity_<block>.core (targets default, sim, lint); and DIR/README.md with the \
         generation parameters and the ports. Any two blocks' folders compile together in one \
         project. The same Verilog is linted by Verilator, checked for latches by Yosys and \
         co-simulated bit-exactly against the Rust model by the tests.",
        sim::hdl::ip::SIM_MODELS_DIR
    )
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
    let v = block_verilog(a.top, &a.matcher)?;
    let config = a.matcher.config.0;
    let spec = sim::hdl::ip::IpSpec {
        config,
        top: a.top.top(),
        cells: a.matcher.cells.unwrap_or(config.sizes().cells),
        rule: a.matcher.rule.rule(),
    };
    let ip = sim::hdl::ip::write_ip_folder(&a.out, &spec, &v)?;
    println!("{}: IP folder of module `{}` ({} lines of Verilog)", ip.dir.display(), ip.module, ip.verilog_lines);
    for f in &ip.files {
        println!("  {f}");
    }
    Ok(())
}
