//! Co-simulation of rust-hdl blocks against their generated Verilog.
//!
//! Every `rtl` block must simulate bit-exactly like the Verilog that
//! `generate_verilog` writes for it (`DESIGN.md` §4). This module is the
//! block-independent machinery for that check:
//!
//! 1. [`record`] drives a rust-hdl block directly (no threaded testbench) with
//!    a stimulus and records a [`Trace`]: per cycle, the input values and the
//!    sampled output values.
//! 2. Traces are written to and read from compact text vector files
//!    ([`Trace::write`], [`Trace::read`]; format below) that are committed in
//!    `vectors/`.
//! 3. [`run_icarus`] and [`run_verilator`] generate a Verilog testbench
//!    ([`testbench`]), run the design on the trace's inputs under Icarus
//!    Verilog or Verilator and return the outputs they sampled;
//!    [`compare`] checks them against the trace and names the first
//!    difference. [`check`] does both.
//! 4. [`lint_verilator`] runs `verilator --lint-only -Wall` and returns the
//!    parsed warnings; [`check_accepted`] fails on any warning whose code is
//!    not in an accepted list.
//!
//! # Cycle semantics
//!
//! The same in the Rust driver and in the testbench. Cycle `k`:
//! apply the inputs of cycle `k` while the clock is low, let the
//! combinational logic settle, **sample the outputs** (they are cycle `k`'s
//! outputs), raise the clock (state `k` → `k + 1`), lower it. So an output
//! that is a register shows in cycle `k` the value registered at the end of
//! cycle `k − 1`, and a combinational output shows its function of cycle
//! `k`'s inputs and state. State starts from the Verilog `initial` values
//! (rust-hdl's `DFF` initial values), so the block passed to [`record`] must
//! be freshly constructed, and the Verilog must come from another fresh
//! block ([`verilog_of`]). Nothing may be triggered by the falling edge.
//!
//! # Vector file format (version 1)
//!
//! Plain text, one line per cycle, diff-friendly:
//!
//! ```text
//! # cosim trace v1
//! inputs enable:1 data:8 threshold:8
//! outputs sum:8 above:1
//! cycles 5
//! 1 5 10 | 0 0
//! 1 7 10 | 5 0
//! 0 0 10 | c 0
//! *2
//! ```
//!
//! * Lines starting with `#` and blank lines are ignored (anywhere).
//! * `inputs` / `outputs` list the ports as `name:width` (width 1–64 bits),
//!   in the order of the values. `cycles N` gives the number of cycles after
//!   expansion; a truncated file is therefore detected.
//! * A data line holds the values in lowercase hexadecimal without leading
//!   zeros or `0x`, separated by single spaces, inputs then ` | ` then
//!   outputs. A file with only an `inputs` header (written by
//!   [`Trace::write_inputs`]) or only an `outputs` header
//!   ([`Trace::write_expected`]) has no `|`; [`Trace::read_split`] joins
//!   such a pair. One file per block trace is the normal case; the split form
//!   serves stimulus shared by several blocks or expected outputs kept apart.
//! * `*N` repeats the previous data line `N` more times (run-length coding of
//!   idle stretches, where neither inputs nor outputs change). Lines that
//!   differ are written plainly; typical traces take 20–40 bytes per cycle,
//!   so about 30 000 cycles (some image lines) fit in 1 MB.
//!
//! The testbench reads its own, simpler file (the number of cycles, then the
//! input values of one cycle per line) and writes the sampled outputs as
//! zero-padded hex, one cycle per line; both are internal to this module.
//!
//! # Tools
//!
//! Icarus Verilog 11 (`iverilog -g2012`, `vvp`) and Verilator 5.006
//! (`verilator --binary`, which needs `make` and `g++`). A missing tool is
//! the error [`CosimError::ToolMissing`], whose message gives the install
//! command; callers' tests therefore fail instead of passing silently.
//!
//! Verilator 5.006 does not re-evaluate combinational logic that reads a
//! variable written only by `$fscanf`; the testbench therefore scans into
//! temporaries and assigns the ports from them with blocking assignments.

use crate::primitives::{models_for, MODELS_FILE};
use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use rust_hdl::core::atom::{Atom, AtomKind};
use rust_hdl::core::block::Block;
use rust_hdl::core::module_defines::generate_verilog;
use rust_hdl::core::probe::Probe;
use rust_hdl::core::simulate::simulate;
use rust_hdl::core::synth::VCDValue;
use thiserror::Error;

/// The command that installs the simulators, named by [`CosimError::ToolMissing`].
pub const INSTALL_COMMAND: &str = "apt-get install -y iverilog verilator";

/// Iterations [`record`] allows rust-hdl's `simulate` to settle one half cycle.
pub const MAX_SETTLE_ITERS: usize = 1000;

/// Environment variable that makes [`committed_trace`] (re)write the vector
/// file from the fresh trace: `COSIM_BLESS=1 cargo test ...`.
pub const BLESS_ENV: &str = "COSIM_BLESS";

/// The name of the top module and of its clock input in generated Verilog.
pub const TOP_MODULE: &str = "top";
/// The clock input of the top module; it is not part of a trace's inputs.
pub const CLOCK_PORT: &str = "clock";

// ---------------------------------------------------------------------------
// Errors

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

// ---------------------------------------------------------------------------
// Ports and traces

/// A port of the top module other than the clock: a name and a width of
/// 1–64 bits.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Port {
    pub name: String,
    pub width: u32,
}

impl Port {
    /// A port; panics on a width outside 1..=64 or a name that is not a
    /// plain Verilog identifier (both are programming errors).
    pub fn new(name: &str, width: u32) -> Port {
        Port::checked(name, width).unwrap_or_else(|e| panic!("{e}"))
    }

    fn checked(name: &str, width: u32) -> Result<Port, CosimError> {
        if !(1..=64).contains(&width) {
            return Err(CosimError::Port(format!(
                "port `{name}`: width {width} is not in 1..=64"
            )));
        }
        let ok = name
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !ok || name.starts_with("cosim_") || name == CLOCK_PORT {
            return Err(CosimError::Port(format!(
                "port name `{name}` is not a plain Verilog identifier, is `{CLOCK_PORT}`, or starts with the testbench's prefix `cosim_`"
            )));
        }
        Ok(Port {
            name: name.to_string(),
            width,
        })
    }

    /// The largest value the port holds.
    pub fn max(&self) -> u64 {
        if self.width == 64 {
            u64::MAX
        } else {
            (1u64 << self.width) - 1
        }
    }

    fn fits(&self, v: u64) -> bool {
        v <= self.max()
    }
}

impl fmt::Display for Port {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.name, self.width)
    }
}

/// Ports from `(name, width)` pairs: `ports(&[("data", 8), ("valid", 1)])`.
pub fn ports(list: &[(&str, u32)]) -> Vec<Port> {
    list.iter().map(|&(n, w)| Port::new(n, w)).collect()
}

/// One clock cycle: the input values applied and the output values sampled,
/// in port order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cycle {
    pub inputs: Vec<u64>,
    pub outputs: Vec<u64>,
}

/// A recorded run of a block: its ports and, per cycle, inputs and outputs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Trace {
    pub inputs: Vec<Port>,
    pub outputs: Vec<Port>,
    pub cycles: Vec<Cycle>,
}

fn check_values(
    ports: &[Port],
    values: &[u64],
    what: &str,
    cycle: usize,
) -> Result<(), CosimError> {
    if values.len() != ports.len() {
        return Err(CosimError::Port(format!(
            "cycle {cycle}: {} {what} values for {} {what} ports",
            values.len(),
            ports.len()
        )));
    }
    for (p, &v) in ports.iter().zip(values) {
        if !p.fits(v) {
            return Err(CosimError::Port(format!(
                "cycle {cycle}: value {v:#x} does not fit {what} `{}` ({} bits)",
                p.name, p.width
            )));
        }
    }
    Ok(())
}

fn check_port_list(inputs: &[Port], outputs: &[Port]) -> Result<(), CosimError> {
    let mut seen = std::collections::HashSet::new();
    for p in inputs.iter().chain(outputs) {
        Port::checked(&p.name, p.width)?;
        if !seen.insert(p.name.as_str()) {
            return Err(CosimError::Port(format!(
                "port `{}` is listed twice",
                p.name
            )));
        }
    }
    Ok(())
}

impl Trace {
    /// An empty trace with these ports.
    pub fn new(inputs: Vec<Port>, outputs: Vec<Port>) -> Result<Trace, CosimError> {
        check_port_list(&inputs, &outputs)?;
        Ok(Trace {
            inputs,
            outputs,
            cycles: Vec::new(),
        })
    }

    /// Appends a cycle after checking the number of values and their widths.
    pub fn push(&mut self, inputs: Vec<u64>, outputs: Vec<u64>) -> Result<(), CosimError> {
        let k = self.cycles.len();
        check_values(&self.inputs, &inputs, "input", k)?;
        check_values(&self.outputs, &outputs, "output", k)?;
        self.cycles.push(Cycle { inputs, outputs });
        Ok(())
    }

    /// The number of cycles.
    pub fn len(&self) -> usize {
        self.cycles.len()
    }

    /// Whether the trace has no cycles.
    pub fn is_empty(&self) -> bool {
        self.cycles.is_empty()
    }

    /// The input values of every cycle, as a stimulus for [`record`].
    pub fn stimulus(&self) -> impl Iterator<Item = Vec<u64>> + '_ {
        self.cycles.iter().map(|c| c.inputs.clone())
    }

    /// The output values of every cycle (what a simulator must reproduce).
    pub fn expected(&self) -> Vec<Vec<u64>> {
        self.cycles.iter().map(|c| c.outputs.clone()).collect()
    }

    /// Checks port lists and every value's width (for traces built by hand).
    pub fn validate(&self) -> Result<(), CosimError> {
        check_port_list(&self.inputs, &self.outputs)?;
        for (k, c) in self.cycles.iter().enumerate() {
            check_values(&self.inputs, &c.inputs, "input", k)?;
            check_values(&self.outputs, &c.outputs, "output", k)?;
        }
        Ok(())
    }

    /// The vector file text (format in the module documentation).
    pub fn to_text(&self) -> String {
        self.render(true, true)
    }

    /// Parses a vector file's text; `what` names it in error messages.
    pub fn from_text(text: &str, what: &str) -> Result<Trace, CosimError> {
        parse_trace(text, what)
    }

    /// Writes the trace (inputs and expected outputs) to one vector file.
    pub fn write(&self, path: &Path) -> Result<(), CosimError> {
        write_file(path, &self.to_text())
    }

    /// Writes only the inputs (a stimulus file without `|`).
    pub fn write_inputs(&self, path: &Path) -> Result<(), CosimError> {
        write_file(path, &self.render(true, false))
    }

    /// Writes only the expected outputs (a file without `|`).
    pub fn write_expected(&self, path: &Path) -> Result<(), CosimError> {
        write_file(path, &self.render(false, true))
    }

    /// Reads a vector file written by [`Trace::write`] (or any of the forms).
    pub fn read(path: &Path) -> Result<Trace, CosimError> {
        let text = std::fs::read_to_string(path).map_err(io_err(path))?;
        parse_trace(&text, &path.display().to_string())
    }

    /// Reads an inputs file and an expected-outputs file of the same number
    /// of cycles and joins them into one trace.
    pub fn read_split(inputs: &Path, expected: &Path) -> Result<Trace, CosimError> {
        let a = Trace::read(inputs)?;
        let b = Trace::read(expected)?;
        if a.len() != b.len() {
            return Err(CosimError::Port(format!(
                "{} has {} cycles, {} has {}",
                inputs.display(),
                a.len(),
                expected.display(),
                b.len()
            )));
        }
        let mut t = Trace::new(a.inputs, b.outputs)?;
        t.cycles = a
            .cycles
            .into_iter()
            .zip(b.cycles)
            .map(|(i, o)| Cycle {
                inputs: i.inputs,
                outputs: o.outputs,
            })
            .collect();
        Ok(t)
    }

    fn render(&self, with_inputs: bool, with_outputs: bool) -> String {
        let mut s = String::with_capacity(64 + self.cycles.len() * 24);
        s.push_str("# cosim trace v1\n");
        let header = |s: &mut String, key: &str, ports: &[Port]| {
            s.push_str(key);
            for p in ports {
                let _ = write!(s, " {p}");
            }
            s.push('\n');
        };
        if with_inputs {
            header(&mut s, "inputs", &self.inputs);
        }
        if with_outputs {
            header(&mut s, "outputs", &self.outputs);
        }
        let _ = writeln!(s, "cycles {}", self.cycles.len());
        let mut line = String::new();
        let mut prev = String::new();
        let mut repeats = 0usize;
        let flush = |s: &mut String, repeats: &mut usize| {
            if *repeats > 0 {
                let _ = writeln!(s, "*{repeats}");
                *repeats = 0;
            }
        };
        for c in &self.cycles {
            line.clear();
            let mut first = true;
            let mut put = |line: &mut String, v: u64| {
                if !first {
                    line.push(' ');
                }
                first = false;
                let _ = write!(line, "{v:x}");
            };
            if with_inputs {
                for &v in &c.inputs {
                    put(&mut line, v);
                }
            }
            if with_inputs && with_outputs {
                line.push_str(" |");
            }
            if with_outputs {
                for &v in &c.outputs {
                    put(&mut line, v);
                }
            }
            if line == prev {
                repeats += 1;
            } else {
                flush(&mut s, &mut repeats);
                s.push_str(&line);
                s.push('\n');
                std::mem::swap(&mut line, &mut prev);
            }
        }
        flush(&mut s, &mut repeats);
        s
    }
}

fn write_file(path: &Path, text: &str) -> Result<(), CosimError> {
    if let Some(dir) = path.parent() {
        if !dir.as_os_str().is_empty() {
            std::fs::create_dir_all(dir).map_err(io_err(dir))?;
        }
    }
    std::fs::write(path, text).map_err(io_err(path))
}

fn parse_ports(rest: &str, what: &str, line: usize) -> Result<Vec<Port>, CosimError> {
    rest.split_whitespace()
        .map(|tok| {
            let (name, width) = tok.split_once(':').ok_or_else(|| CosimError::Parse {
                what: what.to_string(),
                line,
                msg: format!("port `{tok}` is not `name:width`"),
            })?;
            let width: u32 = width.parse().map_err(|_| CosimError::Parse {
                what: what.to_string(),
                line,
                msg: format!("port `{tok}`: width is not a number"),
            })?;
            Port::checked(name, width).map_err(|e| CosimError::Parse {
                what: what.to_string(),
                line,
                msg: e.to_string(),
            })
        })
        .collect()
}

fn parse_hex_values(
    text: &str,
    ports: &[Port],
    what: &str,
    line: usize,
) -> Result<Vec<u64>, CosimError> {
    let err = |msg: String| CosimError::Parse {
        what: what.to_string(),
        line,
        msg,
    };
    let mut vals = Vec::with_capacity(ports.len());
    for tok in text.split_whitespace() {
        let p = ports
            .get(vals.len())
            .ok_or_else(|| err(format!("more than {} values", ports.len())))?;
        let v = u64::from_str_radix(tok, 16)
            .map_err(|_| err(format!("`{tok}` is not a hex value (port `{}`)", p.name)))?;
        if !p.fits(v) {
            return Err(err(format!(
                "value {v:#x} does not fit port `{}` ({} bits)",
                p.name, p.width
            )));
        }
        vals.push(v);
    }
    if vals.len() != ports.len() {
        return Err(err(format!(
            "{} values for {} ports",
            vals.len(),
            ports.len()
        )));
    }
    Ok(vals)
}

fn parse_trace(text: &str, what: &str) -> Result<Trace, CosimError> {
    let err = |line: usize, msg: String| CosimError::Parse {
        what: what.to_string(),
        line,
        msg,
    };
    let mut inputs: Option<Vec<Port>> = None;
    let mut outputs: Option<Vec<Port>> = None;
    let mut declared: Option<usize> = None;
    let mut cycles: Vec<Cycle> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if declared.is_none() {
            let (key, rest) = line.split_once(' ').unwrap_or((line, ""));
            match key {
                "inputs" if inputs.is_none() => inputs = Some(parse_ports(rest, what, n)?),
                "outputs" if outputs.is_none() => outputs = Some(parse_ports(rest, what, n)?),
                "cycles" => {
                    declared = Some(rest.trim().parse().map_err(|_| {
                        err(n, format!("`cycles` needs a decimal count, got `{rest}`"))
                    })?);
                    if inputs.is_none() && outputs.is_none() {
                        return Err(err(
                            n,
                            "no `inputs` or `outputs` line before `cycles`".into(),
                        ));
                    }
                }
                _ => return Err(err(n, format!("expected a header line, got `{line}`"))),
            }
            continue;
        }
        if let Some(count) = line.strip_prefix('*') {
            let count: usize = count
                .trim()
                .parse()
                .map_err(|_| err(n, format!("`{line}` is not a repeat count")))?;
            let last = cycles
                .last()
                .cloned()
                .ok_or_else(|| err(n, "repeat before the first data line".into()))?;
            cycles.resize(cycles.len() + count, last);
            continue;
        }
        let (ins, outs) = match (&inputs, &outputs) {
            (Some(ip), Some(op)) => {
                let (a, b) = line
                    .split_once('|')
                    .ok_or_else(|| err(n, "no `|` between inputs and outputs".into()))?;
                (
                    parse_hex_values(a, ip, what, n)?,
                    parse_hex_values(b, op, what, n)?,
                )
            }
            (Some(ip), None) => (parse_hex_values(line, ip, what, n)?, Vec::new()),
            (None, Some(op)) => (Vec::new(), parse_hex_values(line, op, what, n)?),
            (None, None) => unreachable!(),
        };
        cycles.push(Cycle {
            inputs: ins,
            outputs: outs,
        });
    }
    let declared = declared.ok_or_else(|| err(0, "no `cycles` line".into()))?;
    if cycles.len() != declared {
        return Err(err(
            text.lines().count(),
            format!(
                "{} cycles, the header says {declared} (truncated file?)",
                cycles.len()
            ),
        ));
    }
    let mut t = Trace::new(inputs.unwrap_or_default(), outputs.unwrap_or_default())?;
    t.cycles = cycles;
    Ok(t)
}

// ---------------------------------------------------------------------------
// Direct drive of a rust-hdl block

/// The Verilog of a freshly constructed block (`connect_all`, then
/// rust-hdl's `generate_verilog`; top module `top`).
///
/// Take the Verilog from a fresh block, never from one that has been
/// simulated: rust-hdl's `RAM` widget writes its *current* simulated
/// contents as the Verilog `initial` values, so the Verilog of a simulated
/// block starts from a different state than the recording did.
pub fn verilog_of<B: Block>(mut fresh: B) -> String {
    fresh.connect_all();
    generate_verilog(&fresh)
}

/// Runs rust-hdl's `simulate` until the block settles.
fn settle<B: Block>(uut: &mut B, cycle: usize) -> Result<(), CosimError> {
    if simulate(uut, MAX_SETTLE_ITERS) {
        Ok(())
    } else {
        Err(CosimError::NotSettled { cycle })
    }
}

/// Drives a freshly constructed rust-hdl block directly and records a
/// [`Trace`] of one cycle per stimulus item (cycle semantics in the module
/// documentation).
///
/// * `clock(uut, level)` sets the block's clock input: `uut.clock.next = level`;
/// * `set(uut, values)` applies one cycle's input values (in `inputs` order);
/// * `get(uut)` reads the output values (in `outputs` order).
///
/// Calls `connect_all` on the block first. Each cycle costs two rust-hdl
/// `simulate` calls (inputs with the clock low, then the rising edge; the
/// clock is lowered together with the next cycle's inputs, which is the
/// same as long as nothing is triggered by the falling edge).
pub fn record<B: Block>(
    uut: &mut B,
    inputs: &[Port],
    outputs: &[Port],
    mut clock: impl FnMut(&mut B, bool),
    mut set: impl FnMut(&mut B, &[u64]),
    mut get: impl FnMut(&B) -> Vec<u64>,
    stimulus: impl IntoIterator<Item = Vec<u64>>,
) -> Result<Trace, CosimError> {
    let mut trace = Trace::new(inputs.to_vec(), outputs.to_vec())?;
    let stimulus = stimulus.into_iter();
    trace.cycles.reserve(stimulus.size_hint().0);
    uut.connect_all();
    for (k, ins) in stimulus.enumerate() {
        check_values(inputs, &ins, "input", k)?;
        clock(uut, false);
        set(uut, &ins);
        settle(uut, k)?;
        let outs = get(uut);
        check_values(outputs, &outs, "output", k)?;
        clock(uut, true);
        settle(uut, k)?;
        trace.cycles.push(Cycle {
            inputs: ins,
            outputs: outs,
        });
    }
    clock(uut, false);
    settle(uut, trace.len())?;
    Ok(trace)
}

/// A design's input ports in the order of its Verilog, without the clock,
/// and its output ports likewise: the ports a trace records.
pub fn data_ports(verilog: &str) -> Result<(Vec<Port>, Vec<Port>), CosimError> {
    let (ins, outs) = top_ports(verilog)?;
    Ok((ins.into_iter().filter(|p| p.name != CLOCK_PORT).collect(), outs))
}

/// Reads the values of the top's ports from the block, whatever they are:
/// rust-hdl's probe visits every signal of the design, and the top's own
/// input and output signals are those visited in the outermost scope. The
/// port list therefore follows the rtl without an edit here.
pub struct PortReader {
    /// For each top-level port name: input (`true`) or output, and its
    /// place in the trace's list.
    places: HashMap<String, (bool, usize)>,
    inputs: Vec<Option<u64>>,
    outputs: Vec<Option<u64>>,
    depth: usize,
    /// A port wider than 64 bits or with an X/Z bit.
    bad: Option<String>,
}

impl PortReader {
    /// A reader of the ports `ins` and `outs`.
    pub fn new(ins: &[Port], outs: &[Port]) -> Self {
        let mut places = HashMap::new();
        for (k, p) in ins.iter().enumerate() {
            places.insert(p.name.clone(), (true, k));
        }
        for (k, p) in outs.iter().enumerate() {
            places.insert(p.name.clone(), (false, k));
        }
        PortReader { places, inputs: vec![None; ins.len()], outputs: vec![None; outs.len()], depth: 0, bad: None }
    }

    /// One clock's values, in the trace's port order; an error names a
    /// port the block does not have (or cannot give as a number).
    pub fn read<B: Block>(&mut self, uut: &B, ins: &[Port], outs: &[Port]) -> Result<Cycle, String> {
        self.inputs.iter_mut().chain(self.outputs.iter_mut()).for_each(|v| *v = None);
        self.depth = 0;
        uut.accept("top", self);
        if let Some(bad) = self.bad.take() {
            return Err(bad);
        }
        let missing = |ports: &[Port], vals: &[Option<u64>]| {
            ports.iter().zip(vals).find(|(_, v)| v.is_none()).map(|(p, _)| format!("the Rust model has no port `{}`", p.name))
        };
        if let Some(m) = missing(ins, &self.inputs).or_else(|| missing(outs, &self.outputs)) {
            return Err(m);
        }
        Ok(Cycle { inputs: self.inputs.iter().flatten().copied().collect(), outputs: self.outputs.iter().flatten().copied().collect() })
    }
}

impl Probe for PortReader {
    fn visit_start_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.depth += 1;
    }

    fn visit_end_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.depth -= 1;
    }

    fn visit_atom(&mut self, name: &str, signal: &dyn Atom) {
        if self.depth != 1 || !matches!(signal.kind(), AtomKind::InputParameter | AtomKind::OutputParameter) {
            return;
        }
        let Some(&(input, k)) = self.places.get(name) else {
            return;
        };
        let one = match VCDValue::from(true) {
            VCDValue::Single(v) => v,
            _ => unreachable!("a bool is one bit"),
        };
        let zero = match VCDValue::from(false) {
            VCDValue::Single(v) => v,
            _ => unreachable!("a bool is one bit"),
        };
        let bits = match signal.vcd() {
            VCDValue::Single(v) => vec![v],
            VCDValue::Vector(v) => v,
            _ => Vec::new(),
        };
        if bits.is_empty() || bits.len() > 64 || bits.iter().any(|b| *b != one && *b != zero) {
            self.bad = Some(format!("port `{name}` of the Rust model is not a number of 1–64 bits"));
            return;
        }
        // Most significant bit first.
        let v = bits.iter().fold(0u64, |acc, b| (acc << 1) | (*b == one) as u64);
        if input {
            self.inputs[k] = Some(v);
        } else {
            self.outputs[k] = Some(v);
        }
    }
}

// ---------------------------------------------------------------------------
// Comparison

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

/// Compares simulator outputs (one `Vec` per cycle, in the trace's output
/// port order) with the trace's expected outputs.
pub fn compare(expected: &Trace, got: &[Vec<u64>]) -> Result<(), Mismatch> {
    let mut first: Option<Difference> = None;
    let mut first_cycle = 0;
    let mut differing = 0;
    for (k, (c, g)) in expected.cycles.iter().zip(got).enumerate() {
        let mut differs = g.len() != c.outputs.len();
        for (j, p) in expected.outputs.iter().enumerate() {
            let e = c.outputs[j];
            let v = g.get(j).copied();
            if v != Some(e) {
                differs = true;
                if first.is_none() {
                    first_cycle = k;
                    first = Some(Difference {
                        cycle: k,
                        port: p.name.clone(),
                        expected: e,
                        got: v.unwrap_or(u64::MAX),
                    });
                }
            }
        }
        if differs {
            differing += 1;
        }
    }
    if first.is_none() && got.len() == expected.len() {
        return Ok(());
    }
    let mut context = String::new();
    if first.is_some() {
        let c = &expected.cycles[first_cycle];
        let _ = write!(context, "  cycle {first_cycle} inputs:");
        for (p, v) in expected.inputs.iter().zip(&c.inputs) {
            let _ = write!(context, " {}={v:#x}", p.name);
        }
        let _ = write!(context, "\n  cycle {first_cycle} outputs (expected/got):");
        for (j, p) in expected.outputs.iter().enumerate() {
            let e = c.outputs[j];
            match got[first_cycle].get(j) {
                Some(&g) if g == e => {
                    let _ = write!(context, " {}={e:#x}", p.name);
                }
                Some(&g) => {
                    let _ = write!(context, " {}={e:#x}/{g:#x}(!)", p.name);
                }
                None => {
                    let _ = write!(context, " {}={e:#x}/missing(!)", p.name);
                }
            }
        }
    }
    Err(Mismatch {
        first,
        differing_cycles: differing,
        expected_cycles: expected.len(),
        got_cycles: got.len(),
        context,
    })
}

// ---------------------------------------------------------------------------
// Design ports

/// The ports of the design's `top` module, parsed from its Verilog (both
/// rust-hdl's non-ANSI style and ANSI headers). The clock is included.
pub fn top_ports(design: &str) -> Result<(Vec<Port>, Vec<Port>), CosimError> {
    let toks = tokenize(design);
    let start = toks
        .windows(2)
        .position(|w| w[0] == "module" && w[1] == TOP_MODULE)
        .ok_or_else(|| {
            CosimError::PortsDiffer(format!("no `module {TOP_MODULE}` in the design"))
        })?;
    let mut ins = Vec::new();
    let mut outs = Vec::new();
    let mut dir: Option<bool> = None; // Some(true) input, Some(false) output
    let mut width = 1u32;
    let mut i = start + 2;
    while i < toks.len() {
        let t = toks[i].as_str();
        match t {
            "endmodule" => break,
            "input" | "output" => {
                dir = Some(t == "input");
                width = 1;
            }
            "inout" => {
                return Err(CosimError::PortsDiffer(
                    "`inout` ports are not supported".into(),
                ))
            }
            ";" | ")" => dir = None,
            "wire" | "reg" | "logic" | "signed" | "unsigned" | "," | "(" => {}
            _ if t.starts_with('[') => {
                if dir.is_some() {
                    width = range_width(t).ok_or_else(|| {
                        CosimError::PortsDiffer(format!("cannot read the range `{t}`"))
                    })?;
                }
            }
            _ => {
                if let Some(is_in) = dir {
                    let p = Port {
                        name: t.to_string(),
                        width,
                    };
                    if is_in {
                        ins.push(p);
                    } else {
                        outs.push(p);
                    }
                }
            }
        }
        i += 1;
    }
    Ok((ins, outs))
}

fn tokenize(s: &str) -> Vec<String> {
    let mut toks = Vec::new();
    let mut cur = String::new();
    let mut chars = s.chars().peekable();
    let push = |toks: &mut Vec<String>, cur: &mut String| {
        if !cur.is_empty() {
            toks.push(std::mem::take(cur));
        }
    };
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                push(&mut toks, &mut cur);
                for c in chars.by_ref() {
                    if c == '\n' {
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                push(&mut toks, &mut cur);
                chars.next();
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
            }
            '[' => {
                push(&mut toks, &mut cur);
                let mut r = String::from("[");
                for c in chars.by_ref() {
                    if !c.is_whitespace() {
                        r.push(c);
                    }
                    if c == ']' {
                        break;
                    }
                }
                toks.push(r);
            }
            '(' | ')' | ',' | ';' => {
                push(&mut toks, &mut cur);
                toks.push(c.to_string());
            }
            c if c.is_whitespace() => push(&mut toks, &mut cur),
            c => cur.push(c),
        }
    }
    push(&mut toks, &mut cur);
    toks
}

fn range_width(r: &str) -> Option<u32> {
    let inner = r.strip_prefix('[')?.strip_suffix(']')?;
    let (a, b) = inner.split_once(':')?;
    let a: i64 = a.parse().ok()?;
    let b: i64 = b.parse().ok()?;
    u32::try_from((a - b).abs() + 1).ok()
}

/// Checks that the design's `top` has the clock input and exactly the
/// trace's ports (by name and width; order does not matter).
pub fn check_design_ports(design: &str, trace: &Trace) -> Result<(), CosimError> {
    let (ins, outs) = top_ports(design)?;
    let mut problems = Vec::new();
    match ins.iter().find(|p| p.name == CLOCK_PORT) {
        Some(p) if p.width == 1 => {}
        Some(p) => problems.push(format!("`{CLOCK_PORT}` is {} bits wide", p.width)),
        None => problems.push(format!("no `{CLOCK_PORT}` input")),
    }
    let ins: Vec<Port> = ins.into_iter().filter(|p| p.name != CLOCK_PORT).collect();
    for (kind, design_ports, trace_ports) in [
        ("input", &ins, &trace.inputs),
        ("output", &outs, &trace.outputs),
    ] {
        for p in design_ports.iter() {
            match trace_ports.iter().find(|q| q.name == p.name) {
                None => problems.push(format!("design {kind} `{p}` is not in the trace")),
                Some(q) if q.width != p.width => problems.push(format!(
                    "{kind} `{}` is {} bits in the design, {} in the trace",
                    p.name, p.width, q.width
                )),
                Some(_) => {}
            }
        }
        for q in trace_ports.iter() {
            if !design_ports.iter().any(|p| p.name == q.name) {
                problems.push(format!("trace {kind} `{q}` is not a design {kind}"));
            }
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(CosimError::PortsDiffer(problems.join("; ")))
    }
}

// ---------------------------------------------------------------------------
// Testbench

/// The file the testbench reads its inputs from (in its work directory).
pub const TB_INPUT_FILE: &str = "cosim_inputs.txt";
/// The file the testbench writes the sampled outputs to.
pub const TB_OUTPUT_FILE: &str = "cosim_outputs.txt";

/// A Verilog testbench (module `tb`) that instantiates `top`, reads
/// [`TB_INPUT_FILE`] (a decimal cycle count, then one line of hex input
/// values per cycle, in `inputs` order), applies the cycle semantics of the
/// module documentation and writes the sampled outputs to
/// [`TB_OUTPUT_FILE`] (one line of zero-padded hex values per cycle, in
/// `outputs` order). It prints `COSIM-DONE <cycles>` at the end, or a line
/// starting with `COSIM-ERROR`. Works under Icarus 11 and Verilator 5.006.
pub fn testbench(inputs: &[Port], outputs: &[Port]) -> String {
    let mut s = String::new();
    let decl = |w: u32| {
        if w == 1 {
            String::new()
        } else {
            format!("[{}:0] ", w - 1)
        }
    };
    s.push_str("// Generated by sim::cosim::testbench; cycle k: apply inputs (clock low), #1,\n");
    s.push_str("// sample outputs, clock high, #1, clock low.\n");
    s.push_str("module tb;\n");
    s.push_str("  reg clock;\n");
    for (j, p) in inputs.iter().enumerate() {
        let _ = writeln!(s, "  reg {}{};", decl(p.width), p.name);
        let _ = writeln!(s, "  reg {}cosim_in_{j};", decl(p.width));
    }
    for p in outputs {
        let _ = writeln!(s, "  wire {}{};", decl(p.width), p.name);
    }
    s.push_str("  integer cosim_fin, cosim_fout, cosim_r, cosim_count, cosim_k;\n");
    let mut conns = vec![format!(".{CLOCK_PORT}(clock)")];
    conns.extend(
        inputs
            .iter()
            .chain(outputs)
            .map(|p| format!(".{0}({0})", p.name)),
    );
    let _ = writeln!(
        s,
        "  {TOP_MODULE} dut(\n    {}\n  );",
        conns.join(",\n    ")
    );
    let in_fmt = vec!["%h"; inputs.len()].join(" ");
    let in_args: Vec<String> = (0..inputs.len()).map(|j| format!("cosim_in_{j}")).collect();
    let out_fmt = vec!["%h"; outputs.len()].join(" ");
    let out_args: Vec<&str> = outputs.iter().map(|p| p.name.as_str()).collect();
    s.push_str("  initial begin\n");
    s.push_str("    clock = 1'b0;\n");
    let _ = writeln!(s, "    cosim_fin = $fopen(\"{TB_INPUT_FILE}\", \"r\");");
    let _ = writeln!(s, "    cosim_fout = $fopen(\"{TB_OUTPUT_FILE}\", \"w\");");
    s.push_str("    if (cosim_fin == 0 || cosim_fout == 0) begin\n");
    s.push_str("      $display(\"COSIM-ERROR cannot open the vector files\");\n");
    s.push_str("      $finish;\n    end\n");
    s.push_str("    cosim_count = 0;\n");
    s.push_str("    cosim_r = $fscanf(cosim_fin, \"%d\\n\", cosim_count);\n");
    s.push_str("    if (cosim_r != 1) begin\n");
    s.push_str("      $display(\"COSIM-ERROR no cycle count\");\n");
    s.push_str("      $finish;\n    end\n");
    s.push_str("    for (cosim_k = 0; cosim_k < cosim_count; cosim_k = cosim_k + 1) begin\n");
    if !inputs.is_empty() {
        let _ = writeln!(
            s,
            "      cosim_r = $fscanf(cosim_fin, \"{in_fmt}\\n\", {});",
            in_args.join(", ")
        );
        let _ = writeln!(s, "      if (cosim_r != {}) begin", inputs.len());
        s.push_str("        $display(\"COSIM-ERROR bad input line for cycle %0d\", cosim_k);\n");
        s.push_str("        $finish;\n      end\n");
        for (j, p) in inputs.iter().enumerate() {
            let _ = writeln!(s, "      {} = cosim_in_{j};", p.name);
        }
    }
    s.push_str("      #1;\n");
    let _ = writeln!(
        s,
        "      $fwrite(cosim_fout, \"{out_fmt}\\n\", {});",
        out_args.join(", ")
    );
    s.push_str("      clock = 1'b1;\n");
    s.push_str("      #1;\n");
    s.push_str("      clock = 1'b0;\n");
    s.push_str("    end\n");
    s.push_str("    $fclose(cosim_fout);\n");
    s.push_str("    $display(\"COSIM-DONE %0d\", cosim_k);\n");
    s.push_str("    $finish;\n");
    s.push_str("  end\n");
    s.push_str("endmodule\n");
    s
}

fn tb_input_text(trace: &Trace) -> String {
    let mut s = String::with_capacity(16 + trace.len() * (trace.inputs.len() * 4 + 1));
    let _ = writeln!(s, "{}", trace.len());
    for c in &trace.cycles {
        for (j, v) in c.inputs.iter().enumerate() {
            if j > 0 {
                s.push(' ');
            }
            let _ = write!(s, "{v:x}");
        }
        s.push('\n');
    }
    s
}

/// Parses the testbench's output file.
fn parse_tb_outputs(
    text: &str,
    trace: &Trace,
    tool: &str,
    dir: &Path,
) -> Result<Vec<Vec<u64>>, CosimError> {
    let mut out = Vec::with_capacity(trace.len());
    let mut unknown: Option<(usize, String, String)> = None;
    let mut unknown_cycles = 0;
    for (k, line) in text.lines().enumerate() {
        let toks: Vec<&str> = line.split_whitespace().collect();
        if toks.len() != trace.outputs.len() {
            return Err(CosimError::Parse {
                what: format!("{tool} output {}", dir.join(TB_OUTPUT_FILE).display()),
                line: k + 1,
                msg: format!("{} values for {} outputs", toks.len(), trace.outputs.len()),
            });
        }
        let mut vals = Vec::with_capacity(toks.len());
        let mut has_unknown = false;
        for (tok, p) in toks.iter().zip(&trace.outputs) {
            if tok.contains(['x', 'X', 'z', 'Z']) {
                has_unknown = true;
                if unknown.is_none() {
                    unknown = Some((k, p.name.clone(), tok.to_string()));
                }
                vals.push(0);
                continue;
            }
            let v = u64::from_str_radix(tok, 16).map_err(|_| CosimError::Parse {
                what: format!("{tool} output {}", dir.join(TB_OUTPUT_FILE).display()),
                line: k + 1,
                msg: format!("`{tok}` is not hex (output `{}`)", p.name),
            })?;
            vals.push(v);
        }
        if has_unknown {
            unknown_cycles += 1;
        }
        out.push(vals);
    }
    if let Some((cycle, port, text)) = unknown {
        return Err(CosimError::Unknown {
            tool: tool.to_string(),
            cycle,
            port,
            text,
            cycles: unknown_cycles,
            total: out.len(),
            dir: dir.to_path_buf(),
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------
// Running the simulators

/// The simulators a design is run under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simulator {
    /// Icarus Verilog: `iverilog -g2012` and `vvp`.
    Icarus,
    /// Verilator: for a trace, what `verilator --binary` does (`--cc --exe
    /// --main --timing`, then `make`/`g++`) with the Verilog testbench; for
    /// a frame (`sim::stereo_cosim`), `--cc --exe` with a C++ driver of
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
        let path = crate::workdir::unique_dir(&root, &format!("cosim-{tag}")).map_err(io_err(&root))?;
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

fn spawn(tool: &str, cmd: &mut Command) -> Result<Output, CosimError> {
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

/// Runs the design under Icarus Verilog on the trace's inputs and returns
/// the sampled outputs (default [`Options`]).
pub fn run_icarus(design: &str, trace: &Trace) -> Result<Vec<Vec<u64>>, CosimError> {
    run(Simulator::Icarus, design, trace, &Options::default()).map(|r| r.outputs)
}

/// Runs the design under Verilator on the trace's inputs and returns the
/// sampled outputs (default [`Options`]).
pub fn run_verilator(design: &str, trace: &Trace) -> Result<Vec<Vec<u64>>, CosimError> {
    run(Simulator::Verilator, design, trace, &Options::default()).map(|r| r.outputs)
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

// ---------------------------------------------------------------------------
// Committed vectors

/// The committed trace at `path`, checked against a `fresh` recording of
/// the Rust model: same ports, same inputs, same outputs. With
/// `COSIM_BLESS=1` in the environment the file is (re)written from `fresh`
/// first. A missing file or a difference is [`CosimError::Committed`].
pub fn committed_trace(path: &Path, fresh: &Trace) -> Result<Trace, CosimError> {
    if std::env::var(BLESS_ENV).is_ok_and(|v| v == "1") {
        fresh.write(path)?;
    }
    if !path.exists() {
        return Err(CosimError::Committed {
            path: path.to_path_buf(),
            msg: "no committed vector file".into(),
        });
    }
    let committed = Trace::read(path)?;
    let fail = |msg: String| CosimError::Committed {
        path: path.to_path_buf(),
        msg,
    };
    if committed.inputs != fresh.inputs || committed.outputs != fresh.outputs {
        return Err(fail("the ports differ from the model's".into()));
    }
    if committed.len() != fresh.len() {
        return Err(fail(format!(
            "{} cycles committed, the stimulus has {}",
            committed.len(),
            fresh.len()
        )));
    }
    if let Some(k) =
        (0..committed.len()).find(|&k| committed.cycles[k].inputs != fresh.cycles[k].inputs)
    {
        return Err(fail(format!("the stimulus differs from cycle {k}")));
    }
    compare(&committed, &fresh.expected()).map_err(|m| {
        fail(format!(
            "the Rust model no longer reproduces the committed outputs: {m}"
        ))
    })?;
    Ok(committed)
}

/// xorshift64 for the random parts of committed vectors: seeded, and the
/// same on every machine and version, so a recording is reproducible.
pub struct VectorRng(pub u64);

impl VectorRng {
    /// The next 64 random bits (the seed must be non-zero).
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

// ---------------------------------------------------------------------------
// Lint

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

fn parse_lint(log: &str) -> Vec<LintWarning> {
    let mut out = Vec::new();
    for line in log.lines() {
        let Some(rest) = line.strip_prefix("%Warning-") else {
            continue;
        };
        let Some((code, rest)) = rest.split_once(':') else {
            continue;
        };
        let rest = rest.trim_start();
        // "file:line:col: message" (file has no spaces in our work directory)
        let mut parts = rest.splitn(4, ':');
        let (file, l, c, msg) = (parts.next(), parts.next(), parts.next(), parts.next());
        let w = match (
            file,
            l.and_then(|l| l.parse().ok()),
            c.and_then(|c| c.parse().ok()),
            msg,
        ) {
            (Some(f), Some(l), Some(c), Some(m)) if !f.contains(' ') => LintWarning {
                code: code.to_string(),
                file: f.to_string(),
                line: l,
                column: c,
                message: m.trim().to_string(),
            },
            _ => LintWarning {
                code: code.to_string(),
                file: String::new(),
                line: 0,
                column: 0,
                message: rest.trim().to_string(),
            },
        };
        out.push(w);
    }
    out
}

/// Runs `verilator --lint-only -Wall` on the design (as `top.v`, top module
/// `top`) and returns its warnings. Errors are [`CosimError::LintErrors`].
/// `DECLFILENAME` is switched off: `generate_verilog` puts every module in
/// one file, so it would fire once per sub-module.
pub fn lint_verilator(design: &str) -> Result<Vec<LintWarning>, CosimError> {
    lint_verilator_with(design, &Options::default())
}

/// [`lint_verilator`] with the work root and `verilator` command of `opts`.
pub fn lint_verilator_with(design: &str, opts: &Options) -> Result<Vec<LintWarning>, CosimError> {
    let mut dir = WorkDir::new(opts.work_root.as_deref(), "lint")?;
    dir.write_design(design)?;
    let out = spawn(
        &opts.verilator,
        Command::new(&opts.verilator)
            .args(["--lint-only", "-Wall", "-Wno-fatal", "-Wno-DECLFILENAME"])
            .args(["--top-module", TOP_MODULE, "top.v", MODELS_FILE])
            .current_dir(&dir.path),
    )?;
    // The whole log is parsed (a warning early in a long log counts as
    // much as one at its end); `log_of` cuts it for the error message only.
    let full = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let log = log_of(&out);
    let errors = full
        .lines()
        .any(|l| l.starts_with("%Error") && !l.starts_with("%Error: Exiting due to"));
    if !out.status.success() || errors {
        dir.keep = true;
        return Err(CosimError::LintErrors {
            log,
            dir: dir.path.clone(),
        });
    }
    Ok(parse_lint(&full))
}

/// The Verilator `-Wall` warnings every block's lint accepts, with why
/// (`check_accepted`'s list; a block adds its own with their reasons).
pub const ACCEPTED_LINT: &[(&str, &str)] = &[
    ("WIDTH", "rust-hdl writes every literal as 32 or 64 bits; each arithmetic result goes through a signal of its own width (rtl crate doc), so the widths that matter are explicit"),
    ("UNUSEDPARAM", "rust-hdl declares a localparam for every state of an enum in each module that holds it"),
    DP16KD_UNUSED_OUTPUTS,
];

/// The accepted-list entry for the `DP16KD` instances of `rtl::block_ram`:
/// their read-port-A outputs (`DOA*`, the port only writes) and port B's
/// outputs above the data width are left unconnected. [`check_accepted`]
/// accepts a `PINMISSING` only on such a pin.
pub const DP16KD_UNUSED_OUTPUTS: (&str, &str) =
    ("PINMISSING", "a DP16KD instance (rtl::block_ram) leaves its port A outputs DOA* and port B's outputs DOB* above the data width unconnected; other missing pins are not accepted");

/// A `PINMISSING` warning on a `DP16KD` output pin (`DOA*`, `DOB*`).
fn is_dp16kd_output_pin(w: &LintWarning) -> bool {
    let pin = w.message.strip_prefix("Cell has missing pin: '").and_then(|p| p.strip_suffix('\''));
    pin.is_some_and(|p| (p.starts_with("DOA") || p.starts_with("DOB")) && p[3..].parse::<u32>().is_ok_and(|n| n < 18))
}

/// Fails with [`CosimError::Unaccepted`] on every warning whose code is not
/// in `accepted` (`(code, reason)` pairs; the reason documents the choice);
/// a `PINMISSING` is accepted only on a `DP16KD` output pin
/// ([`DP16KD_UNUSED_OUTPUTS`]).
/// Returns the number of warnings per accepted code.
pub fn check_accepted(
    warnings: &[LintWarning],
    accepted: &[(&str, &str)],
) -> Result<BTreeMap<String, usize>, CosimError> {
    let mut counts = BTreeMap::new();
    let mut bad = Vec::new();
    for w in warnings {
        if accepted.iter().any(|(c, _)| *c == w.code) && (w.code != "PINMISSING" || is_dp16kd_output_pin(w)) {
            *counts.entry(w.code.clone()).or_insert(0) += 1;
        } else {
            bad.push(w.clone());
        }
    }
    if bad.is_empty() {
        Ok(counts)
    } else {
        Err(CosimError::Unaccepted(bad))
    }
}
