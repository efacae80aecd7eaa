//! `declivity verilog`: the Verilog of a block.

use std::path::PathBuf;

use clap::Args;
use rtl::params::ROWS_PER_CELL;
use sim::{Config, SimError};

use sim::hdl::verilog::{generate_block, CameraReport, Generation};

use crate::args::{cells_per_config, config_help, per_config, CameraArgs, CliConfig, CliRule, CliTarget, CliTop};

/// Write the Verilog of a hardware block.
#[derive(Args, Debug)]
#[command(long_about = long_about())]
pub(crate) struct VerilogArgs {
    /// The block.
    #[arg(long, value_enum)]
    top: CliTop,
    #[command(flatten)]
    gen: GenerationArgs,
    /// What the Verilog is written for.
    #[arg(long, value_enum, default_value_t = CliTarget::Ecp5)]
    target: CliTarget,
    /// The IP folder to write (created if missing).
    #[arg(long, default_value = "declivity-out/verilog")]
    out: PathBuf,
}

fn long_about() -> String {
    format!(
        "Write a hardware block as a self-contained IP folder in --out: the Verilog that rust-hdl \
         generates for it (DIR/declivity_<block>.v, module declivity_<block>, submodules \
         declivity_<block>$..., one clock input `clock`, one synchronous active-high `reset`; registers also start from \
         the values reset gives them, as Verilog initial values); for --target ecp5, the \
         behavioural models of the ECP5 primitives it instantiates (DP16KD, MULT18X18D, \
         TRELLIS_DPR16X4; for --top stereo the DCCA that puts reset on a global net) in DIR/{}/, one module \
         a file, for simulation only (--target generic puts those models, renamed, inside the \
         block instead, as behavioural Verilog any synthesis tool infers); a simulation file list DIR/declivity_<block>.f (paths under \
         ${{DECLIVITY_<BLOCK>_DIR}}; iverilog -c, verilator -f); a FuseSoC CAPI2 core \
         DIR/declivity_<block>.core (targets default, sim, lint); and DIR/README.md with the \
         generation parameters and the ports. Any two blocks' folders compile together in one \
         project. The same Verilog is linted by Verilator, checked for latches by Yosys and \
         co-simulated bit-exactly against the Rust model by the tests.",
        sim::hdl::ip::SIM_MODELS_DIR
    )
}

/// The configuration and the generation parameters: the matcher's (`--top
/// matcher` and `stereo`), the depth stage's camera (`--top stereo`).
#[derive(Args, Debug)]
pub(crate) struct GenerationArgs {
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("the block"))]
    pub config: CliConfig,
    #[arg(long, help = cells_help())]
    pub cells: Option<usize>,
    /// Gain rule the matcher is generated for (--top matcher and stereo only).
    #[arg(long, value_enum, default_value_t = CliRule::Robust)]
    pub rule: CliRule,
    #[command(flatten)]
    pub camera: CameraArgs,
}

fn cells_help() -> String {
    format!(
        "Gain cells of the matcher's systolic array ({}; each holds up to {ROWS_PER_CELL} reference \
         declivities; --top matcher and stereo only) [default: the configuration's sensor: {}]",
        cells_per_config(),
        per_config(|s| s.cells)
    )
}

impl GenerationArgs {
    /// The generation parameters of `top`, refusing those that do not apply to it.
    pub(crate) fn generation(&self, top: CliTop) -> Result<Generation, SimError> {
        let has_matcher = matches!(top, CliTop::Matcher | CliTop::Stereo);
        if !has_matcher && (self.cells.is_some() || self.rule != CliRule::Robust) {
            return Err(SimError::Argument("--cells and --rule apply to --top matcher and --top stereo only".into()));
        }
        if top != CliTop::Stereo && self.camera.given() {
            return Err(SimError::Argument("--focal-px and --baseline-m apply to --top stereo only (the depth stage)".into()));
        }
        let config = self.config.0;
        Ok(Generation { cells: self.cells.unwrap_or(config.sizes().cells), rule: self.rule.rule(), camera: self.camera.camera() })
    }
}

/// The Verilog of a block as the command line asks for it, and its generation parameters.
pub(crate) fn block_verilog(top: CliTop, m: &GenerationArgs) -> Result<(String, Generation), SimError> {
    let g = m.generation(top)?;
    Ok((generate_block(m.config.0, top.top(), &g)?, g))
}

pub(crate) fn run(a: VerilogArgs) -> Result<(), SimError> {
    // The folder first: a path that cannot be written fails before the generation.
    std::fs::create_dir_all(&a.out).map_err(|source| SimError::Io { path: a.out.clone(), source })?;
    let (v, generation) = block_verilog(a.top, &a.gen)?;
    let target = a.target.target();
    let spec = sim::hdl::ip::IpSpec { config: a.gen.config.0, top: a.top.top(), generation, target };
    let ip = sim::hdl::ip::write_ip_folder(&a.out, &spec, &target.retarget(v))?;
    println!("{}: IP folder of module `{}` ({} lines of Verilog)", ip.dir.display(), ip.module, ip.verilog_lines);
    if a.top == CliTop::Stereo {
        println!("  depth stage generated for a camera of {}", CameraReport::from(generation.camera));
    }
    for f in &ip.files {
        println!("  {f}");
    }
    Ok(())
}
