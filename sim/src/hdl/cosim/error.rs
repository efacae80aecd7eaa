//! What can go wrong in a co-simulation.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use thiserror::Error;



/// The command that installs the simulators, named by [`CosimError::ToolMissing`].
const INSTALL_COMMAND: &str = "apt-get install -y iverilog verilator";

/// Iterations [`record`] allows rust-hdl's `simulate` to settle one half cycle.
pub(crate) const MAX_SETTLE_ITERS: usize = 1000;

/// Environment variable that makes [`committed_trace`] (re)write the vector
/// file from the fresh trace: `COSIM_BLESS=1 cargo test ...`.
pub(crate) const BLESS_ENV: &str = "COSIM_BLESS";

/// The name of the top module and of its clock input in generated Verilog.
pub(crate) const TOP_MODULE: &str = "top";
/// The clock input of the top module; it is not part of a trace's inputs.
pub(crate) const CLOCK_PORT: &str = "clock";
/// The synchronous, active-high reset input of every block.
pub(crate) const RESET_PORT: &str = "reset";

/// What can go wrong in a co-simulation.
#[derive(Debug, Error)]
pub enum CosimError {
    /// A simulator is not installed.
    #[error("`{tool}` is not installed or not on PATH ({source}); install the simulators with: {INSTALL_COMMAND} (Verilator's builds also need make and g++)")]
    ToolMissing {
        tool: String,
        #[source]
        source: io::Error,
    },
    /// A tool ran but failed (compile error, simulation error, ...).
    #[error("{tool} failed ({status}); work directory kept at {}\n{log}", dir.display())]
    ToolFailed {
        tool: String,
        status: String,
        log: String,
        dir: PathBuf,
    },
    /// A file or directory could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
    /// A vector file (or a simulator's output file) is malformed.
    #[error("{what}, line {line}: {msg}")]
    Parse {
        what: String,
        line: usize,
        msg: String,
    },
    /// A port description or a value that does not fit its port.
    #[error("{0}")]
    Port(String),
    /// The trace's ports are not the design's ports.
    #[error("the trace's ports do not match the design's `top` module: {0}")]
    PortsDiffer(String),
    /// rust-hdl's simulation did not settle (a combinational loop?).
    #[error(
        "rust-hdl simulation did not settle within {MAX_SETTLE_ITERS} iterations in cycle {cycle}"
    )]
    NotSettled { cycle: usize },
    /// A simulator produced X or Z on an output: the Verilog has state or
    /// logic without a defined value where the Rust model has one.
    #[error("{tool}: output `{port}` is `{text}` (X/Z) in cycle {cycle}; {cycles} of {total} cycles have X/Z outputs (an uninitialised register or RAM output?); work directory kept at {}", dir.display())]
    Unknown {
        tool: String,
        cycle: usize,
        port: String,
        text: String,
        cycles: usize,
        total: usize,
        dir: PathBuf,
    },
    /// The outputs differ from the expected ones.
    #[error("{tool}: {mismatch}\n  (work directory kept at {})", dir.display())]
    Mismatch {
        tool: String,
        mismatch: Box<Mismatch>,
        dir: PathBuf,
    },
    /// Verilator lint found errors (not only warnings).
    #[error("verilator --lint-only reported errors; work directory kept at {}\n{log}", dir.display())]
    LintErrors { log: String, dir: PathBuf },
    /// Lint warnings whose codes are not accepted.
    #[error("{} Verilator warning(s) not in the accepted list:\n{}", .0.len(), .0.iter().map(|w| format!("  {w}")).collect::<Vec<_>>().join("\n"))]
    Unaccepted(Vec<LintWarning>),
    /// A committed vector file is absent or no longer matches the model.
    #[error("{}: {msg} (rerun with {BLESS_ENV}=1 to rewrite the vectors if the change is intended)", path.display())]
    Committed { path: PathBuf, msg: String },
}

pub(crate) fn io_err(path: &Path) -> impl FnOnce(io::Error) -> CosimError + '_ {
    move |source| CosimError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The first differing value of a comparison.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Difference {
    pub cycle: usize,
    pub port: String,
    pub expected: u64,
    pub got: u64,
}

/// Outputs that differ from the expected ones.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mismatch {
    /// The first differing value (in the cycles both have); `None` when only
    /// the number of cycles differs.
    pub first: Option<Difference>,
    /// The number of cycles (among those both have) with any difference.
    pub differing_cycles: usize,
    /// The number of expected cycles.
    pub expected_cycles: usize,
    /// The number of cycles obtained.
    pub got_cycles: usize,
    /// The inputs and all outputs (expected/got) of the first differing cycle.
    pub context: String,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.first {
            Some(d) => write!(
                f,
                "first difference in cycle {}, output `{}`: expected {:#x}, got {:#x}; {} of {} cycles differ",
                d.cycle, d.port, d.expected, d.got, self.differing_cycles, self.expected_cycles
            )?,
            None => write!(f, "no value differs in the common cycles")?,
        }
        if self.got_cycles != self.expected_cycles {
            write!(
                f,
                "; {} cycles expected, {} obtained",
                self.expected_cycles, self.got_cycles
            )?;
        }
        if !self.context.is_empty() {
            write!(f, "\n{}", self.context)?;
        }
        Ok(())
    }
}

impl std::error::Error for Mismatch {}

/// One Verilator warning.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LintWarning {
    /// The warning code: `WIDTH`, `UNUSED`, `DECLFILENAME`, ...
    pub code: String,
    /// The file (`top.v` for the design) and position; empty/0 if not given.
    pub file: String,
    pub line: u32,
    pub column: u32,
    pub message: String,
}

impl fmt::Display for LintWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "%Warning-{} {}:{}:{}: {}",
            self.code, self.file, self.line, self.column, self.message
        )
    }
}
