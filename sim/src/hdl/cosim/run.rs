//! Running the simulators: Icarus Verilog and Verilator, each in a work directory of its own.

use std::io;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use crate::hdl::primitives::{models_for, MODELS_FILE};

use super::compare::*;
use super::error::*;
use super::ports::*;
use super::testbench::*;
use super::trace::*;

/// The simulators a design is run under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simulator {
    /// Icarus Verilog: `iverilog -g2012` and `vvp`.
    Icarus,
    /// Verilator: for a trace, what `verilator --binary` does (`--cc --exe
    /// --main --timing`, then `make`/`g++`) with the Verilog testbench; for
    /// a frame (`sim::hdl::frame`), `--cc --exe` with a C++ driver of
    /// ours; the runtime objects cached.
    Verilator,
}

impl Simulator {
    /// A short name for messages.
    pub fn name(self) -> &'static str {
        match self {
            Simulator::Icarus => "icarus",
            Simulator::Verilator => "verilator",
        }
    }
}

/// How [`run`] works.
#[derive(Clone, Debug)]
pub struct Options {
    /// The directory under which a unique work directory is made
    /// (default: `std::env::temp_dir()`).
    pub work_root: Option<PathBuf>,
    /// Keep the work directory after success too (it is always kept after a
    /// failure, and its path is in the error).
    pub keep: bool,
    /// The C++ optimisation flag for Verilator's build (`-O0` … `-O3`, `-Os`).
    pub verilator_cxx_opt: String,
    /// Parallel jobs for Verilator's build (`-j`).
    pub build_jobs: usize,
    /// Keep the object files of Verilator's C++ runtime (about 3 s of
    /// compilation, the same for every design) in
    /// `<work root>/cosim-verilator-runtime-<hash>/` and reuse them.
    pub verilator_runtime_cache: bool,
    /// The commands run (names on `PATH` or paths): `iverilog`, `vvp`, `verilator`.
    pub iverilog: String,
    pub vvp: String,
    pub verilator: String,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            work_root: None,
            keep: false,
            verilator_cxx_opt: "-O1".to_string(),
            build_jobs: 2,
            verilator_runtime_cache: true,
            iverilog: "iverilog".to_string(),
            vvp: "vvp".to_string(),
            verilator: "verilator".to_string(),
        }
    }
}

/// The result of [`run`]: the sampled outputs per cycle and the times taken.
#[derive(Clone, Debug)]
pub struct Run {
    pub simulator: Simulator,
    pub outputs: Vec<Vec<u64>>,
    /// Compiling the design and testbench (`iverilog`; `verilator` + C++ build).
    pub compile: Duration,
    /// Running the simulation (`vvp`; the Verilator binary).
    pub run: Duration,
    /// The work directory if it was kept.
    pub work_dir: Option<PathBuf>,
}

/// A unique work directory; removed on drop unless `keep` was set.
pub(crate) struct WorkDir {
    pub(crate) path: PathBuf,
    pub(crate) keep: bool,
}

impl WorkDir {
    pub(crate) fn new(root: Option<&Path>, tag: &str) -> Result<WorkDir, CosimError> {
        let root = root.map(Path::to_path_buf).unwrap_or_else(std::env::temp_dir);
        let path = crate::hdl::workdir::unique_dir(&root, &format!("cosim-{tag}")).map_err(io_err(&root))?;
        Ok(WorkDir { path, keep: false })
    }

    pub(crate) fn write(&self, name: &str, text: &str) -> Result<(), CosimError> {
        let p = self.path.join(name);
        std::fs::write(&p, text).map_err(io_err(&p))
    }

    /// The design as `top.v`, and beside it, as [`MODELS_FILE`], the models
    /// of the vendor primitives it instantiates (every tool here reads both).
    pub(crate) fn write_design(&self, design: &str) -> Result<(), CosimError> {
        self.write("top.v", design)?;
        self.write(MODELS_FILE, &models_for(design))
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        if !self.keep {
            let _ = std::fs::remove_dir_all(&self.path);
        }
    }
}

pub(super) fn spawn(tool: &str, cmd: &mut Command) -> Result<Output, CosimError> {
    cmd.output().map_err(|source| {
        if source.kind() == io::ErrorKind::NotFound {
            CosimError::ToolMissing {
                tool: tool.to_string(),
                source,
            }
        } else {
            CosimError::Io {
                path: PathBuf::from(tool),
                source,
            }
        }
    })
}

pub(crate) fn log_of(out: &Output) -> String {
    const MAX: usize = 8000;
    let mut log = String::from_utf8_lossy(&out.stdout).into_owned();
    log.push_str(&String::from_utf8_lossy(&out.stderr));
    if log.len() > MAX {
        let mut cut = log.len() - MAX;
        while !log.is_char_boundary(cut) {
            cut += 1;
        }
        log = format!("[... {cut} bytes cut ...]\n{}", &log[cut..]);
    }
    log
}

/// Runs a tool in `dir`; a non-zero exit is [`CosimError::ToolFailed`]
/// (the caller marks the work directory kept).
pub(crate) fn run_tool(tool: &str, cmd: &mut Command, dir: &WorkDir) -> Result<Output, CosimError> {
    let out = spawn(tool, cmd.current_dir(&dir.path))?;
    if out.status.success() {
        Ok(out)
    } else {
        Err(CosimError::ToolFailed {
            tool: tool.to_string(),
            status: out.status.to_string(),
            log: log_of(&out),
            dir: dir.path.clone(),
        })
    }
}

/// Runs `design` (Verilog text with module `top`) on the trace's inputs
/// under `sim` and returns the sampled outputs (one `Vec` per cycle, in the
/// trace's output order) and the times. The trace's expected outputs are
/// not used (see [`check`]). The design's ports must be the trace's ports
/// plus the clock ([`check_design_ports`]).
///
/// Everything happens in a new directory `cosim-<simulator>-<unique>` under
/// [`Options::work_root`] (default `std::env::temp_dir()`): `top.v`, `tb.v`,
/// the testbench's input and output files and the build. It is removed
/// after success (unless [`Options::keep`]) and kept after a failure its
/// files explain (tool failure, mismatch, X/Z, unreadable output); the
/// error gives its path.
pub fn run(sim: Simulator, design: &str, trace: &Trace, opts: &Options) -> Result<Run, CosimError> {
    run_and_compare(sim, design, trace, opts, false)
}

fn run_and_compare(
    sim: Simulator,
    design: &str,
    trace: &Trace,
    opts: &Options,
    compare_outputs: bool,
) -> Result<Run, CosimError> {
    trace.validate()?;
    if trace.outputs.is_empty() {
        return Err(CosimError::Port(
            "the trace has no outputs to compare".into(),
        ));
    }
    check_design_ports(design, trace)?;
    let mut dir = WorkDir::new(opts.work_root.as_deref(), sim.name())?;
    let result = run_in(sim, design, trace, opts, &dir).and_then(|r| {
        if compare_outputs {
            compare(trace, &r.outputs).map_err(|m| CosimError::Mismatch {
                tool: sim.name().to_string(),
                mismatch: Box::new(m),
                dir: dir.path.clone(),
            })?;
        }
        Ok(r)
    });
    // Kept after a failure that its files help to understand.
    dir.keep = opts.keep
        || matches!(
            result,
            Err(CosimError::ToolFailed { .. }
                | CosimError::Mismatch { .. }
                | CosimError::Unknown { .. }
                | CosimError::Parse { .. })
        );
    let mut run = result?;
    if dir.keep {
        run.work_dir = Some(dir.path.clone());
    }
    Ok(run)
}

fn run_in(
    sim: Simulator,
    design: &str,
    trace: &Trace,
    opts: &Options,
    dir: &WorkDir,
) -> Result<Run, CosimError> {
    dir.write_design(design)?;
    dir.write("tb.v", &testbench(&trace.inputs, &trace.outputs))?;
    dir.write(TB_INPUT_FILE, &tb_input_text(trace))?;
    let t0 = Instant::now();
    let (compile, out) = match sim {
        Simulator::Icarus => {
            run_tool(
                &opts.iverilog,
                Command::new(&opts.iverilog)
                    .args(["-g2012", "-s", "tb", "-o", "tb.vvp", "tb.v", "top.v", MODELS_FILE]),
                dir,
            )?;
            let compile = t0.elapsed();
            let t1 = Instant::now();
            let out = run_tool(
                &opts.vvp,
                Command::new(&opts.vvp).args(["-n", "tb.vvp"]),
                dir,
            )?;
            (compile, (out, t1.elapsed()))
        }
        Simulator::Verilator => {
            verilator_build(opts, dir, &TB_BUILD)?;
            let compile = t0.elapsed();
            let t1 = Instant::now();
            let out = run_tool(
                "Vtb",
                &mut Command::new(dir.path.join("obj").join("Vtb")),
                dir,
            )?;
            (compile, (out, t1.elapsed()))
        }
    };
    let (out, run_time) = out;
    let log = log_of(&out);
    let tool = sim.name();
    let done = format!("COSIM-DONE {}", trace.len());
    if log.contains("COSIM-ERROR") || !log.contains(&done) {
        return Err(CosimError::ToolFailed {
            tool: tool.to_string(),
            status: format!("testbench did not print `{done}`"),
            log,
            dir: dir.path.clone(),
        });
    }
    let out_path = dir.path.join(TB_OUTPUT_FILE);
    let text = std::fs::read_to_string(&out_path).map_err(io_err(&out_path))?;
    let outputs = parse_tb_outputs(&text, trace, tool, &dir.path)?;
    if outputs.len() != trace.len() {
        return Err(CosimError::ToolFailed {
            tool: tool.to_string(),
            status: format!("{} output lines for {} cycles", outputs.len(), trace.len()),
            log,
            dir: dir.path.clone(),
        });
    }
    Ok(Run {
        simulator: sim,
        outputs,
        compile,
        run: run_time,
        work_dir: None,
    })
}

/// The object files of Verilator's C++ runtime, the same for every design
/// built with the same options; compiling them is most of a small design's
/// build time, so they are kept between runs. `verilated_timing.o` only
/// with `--timing`.
const VERILATOR_RUNTIME: [&str; 3] = ["verilated.o", "verilated_threads.o", "verilated_timing.o"];

/// What [`verilator_build`] builds in `<dir>/obj`.
pub(crate) struct VerilatorBuild<'a> {
    /// The module Verilated (`--top-module`); its class and makefile are
    /// `V<top>`.
    pub top: &'a str,
    /// Verilator's arguments besides the common ones (`--cc --exe`,
    /// warnings, top module, `-Mdir obj`, `-o`): `--main --timing` for a
    /// Verilog testbench, none for a C++ `main` of ours.
    pub args: &'a [&'a str],
    /// Whether `args` hold `--timing` (the runtime then has a timing object).
    pub timing: bool,
    /// The input files in the work directory: Verilog and C++ sources.
    pub files: &'a [&'a str],
    /// The binary's name in `obj`.
    pub binary: &'a str,
}

/// The Verilog testbench build of [`run`]: `verilator --binary` (`--cc
/// --exe --main --timing`) of module `tb` in `tb.v`, `top.v` and the
/// primitives' models.
const TB_BUILD: VerilatorBuild<'static> = VerilatorBuild {
    top: "tb",
    args: &["--main", "--timing"],
    timing: true,
    files: &["tb.v", "top.v", MODELS_FILE],
    binary: "Vtb",
};

/// `verilator --build` split in two: Verilate (`--cc --exe` and
/// `build.args`), then `make` with the runtime objects taken from the cache
/// when present.
pub(crate) fn verilator_build(opts: &Options, dir: &WorkDir, build: &VerilatorBuild) -> Result<(), CosimError> {
    let opt = &opts.verilator_cxx_opt;
    let runtime: &[&str] = if build.timing { &VERILATOR_RUNTIME } else { &VERILATOR_RUNTIME[..2] };
    run_tool(
        &opts.verilator,
        Command::new(&opts.verilator)
            .args(["--cc", "--exe"])
            .args(build.args)
            .args(["-Wno-fatal", "-Wno-lint", "-Wno-style"])
            .args(["--top-module", build.top, "-Mdir", "obj", "-o", build.binary])
            .args(build.files),
        dir,
    )?;
    let obj = dir.path.join("obj");
    let cache = if opts.verilator_runtime_cache {
        verilator_cache_dir(opts, build.timing)
    } else {
        None
    };
    let cached = cache
        .as_ref()
        .is_some_and(|c| runtime.iter().all(|f| c.join(f).is_file()));
    if let (true, Some(c)) = (cached, &cache) {
        for f in runtime {
            // A fresh copy is newer than the runtime sources: make keeps it.
            std::fs::copy(c.join(f), obj.join(f)).map_err(io_err(&c.join(f)))?;
        }
    }
    run_tool(
        "make",
        Command::new("make")
            .args(["-s", "-C", "obj", "-f", &format!("V{}.mk", build.top)])
            .args(["-j", &opts.build_jobs.max(1).to_string()])
            .arg(format!("OPT_FAST={opt}"))
            .arg(format!("OPT_SLOW={opt}"))
            .arg(format!("OPT_GLOBAL={opt}")),
        dir,
    )?;
    if let (false, Some(c)) = (cached, &cache) {
        // Best effort: a failure only costs the next run the full build.
        if std::fs::create_dir_all(c).is_ok() {
            for f in runtime {
                let tmp = c.join(format!("{f}.{}.tmp", std::process::id()));
                if std::fs::copy(obj.join(f), &tmp).is_ok() {
                    let _ = std::fs::rename(&tmp, c.join(f));
                }
                let _ = std::fs::remove_file(&tmp);
            }
        }
    }
    Ok(())
}

/// The cache directory of Verilator's runtime objects for this Verilator
/// (its `--version` and command), C++ compiler (`CXX`), `-O` flag (the
/// runtime is compiled with `OPT_GLOBAL`) and `--timing` or not.
pub(crate) fn verilator_cache_dir(opts: &Options, timing: bool) -> Option<PathBuf> {
    use std::hash::{Hash, Hasher};
    let version = Command::new(&opts.verilator)
        .arg("--version")
        .output()
        .ok()?;
    let mut h = std::collections::hash_map::DefaultHasher::new();
    version.stdout.hash(&mut h);
    opts.verilator.hash(&mut h);
    opts.verilator_cxx_opt.hash(&mut h);
    std::env::var("CXX").ok().hash(&mut h);
    let tag = if timing { "" } else { "-notiming" };
    let root = opts.work_root.clone().unwrap_or_else(std::env::temp_dir);
    Some(root.join(format!("cosim-verilator-runtime{tag}-{:016x}", h.finish())))
}

/// Runs the design under `sim` and [`compare`]s its outputs with the
/// trace's; a difference is [`CosimError::Mismatch`].
/// The work directory is kept on a mismatch (its path is in the error).
pub fn check(
    sim: Simulator,
    design: &str,
    trace: &Trace,
    opts: &Options,
) -> Result<Run, CosimError> {
    run_and_compare(sim, design, trace, opts, true)
}
