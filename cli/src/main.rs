//! `declivity`: the declivity stereo method of Bensrhair, Miché and Debrie
//! as a golden model and as streaming hardware. A thin layer over the `sim`
//! library: parse the arguments, call a job, print its report.

// golden allocates many small per-line vectors; mimalloc serves them faster
// than the system allocator.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod args;
mod commands;
mod progress;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

const ABOUT: &str = "Declivity stereo: depth maps by the method of Bensrhair, Miché and Debrie \
(self-adaptive declivity segmentation + dynamic-programming matching of scanlines), and the same \
method as streaming hardware";

const LONG_ABOUT: &str = "Declivity stereo: depth maps by the method of Bensrhair, Miché and Debrie \
(\"High Speed Self-Adaptive Algorithms for Implementation in a 3-D Vision Sensor\").

Each scanline of a rectified pair is cut into declivities (runs between extrema); those whose \
amplitude exceeds a threshold estimated from the line's own noise (d_t = 5.6 sigma, eq. 2) are \
matched between the views by dynamic programming (eq. 4-9), and the disparities are interpolated \
along the line and turned into depth (eq. 1). The `rtl` commands run the same method as \
cycle-accurate hardware; `verilog`, `synth` and `budget` give its Verilog, its size and speed on an \
FPGA, and its clocks per line.

Run without a command to compute the depth map of a bundled pair (Middlebury Tsukuba) and write \
its pictures into ./declivity-out/tsukuba.";

#[derive(Parser, Debug)]
#[command(name = "declivity", version, about = ABOUT, long_about = LONG_ABOUT)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    Depth(commands::depth::DepthArgs),
    Eval(commands::eval::EvalArgs),
    #[command(subcommand)]
    Rtl(commands::rtl::RtlCommand),
    Verilog(commands::verilog::VerilogArgs),
    Synth(commands::synth::SynthArgs),
    Budget(commands::budget::BudgetArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => commands::depth::main_job(),
        Some(Command::Depth(a)) => commands::depth::run(a),
        Some(Command::Eval(a)) => commands::eval::run(a),
        Some(Command::Rtl(c)) => commands::rtl::run(c),
        Some(Command::Verilog(a)) => commands::verilog::run(a),
        Some(Command::Synth(a)) => commands::synth::run(a),
        Some(Command::Budget(a)) => commands::budget::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            let mut src = std::error::Error::source(&e);
            while let Some(s) = src {
                eprintln!("  caused by: {s}");
                src = s.source();
            }
            ExitCode::FAILURE
        }
    }
}
