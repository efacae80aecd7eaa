//! Ports and traces: a trace is, per clock, the input values and the sampled output values of a block; its vector file format is in the module doc of [`super`].

use std::fmt::Write as _;
use std::fmt;
use std::path::Path;

use super::error::*;

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
    fn new(name: &str, width: u32) -> Port {
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
    fn max(&self) -> u64 {
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

pub(super) fn check_values(
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

    /// The output values of every cycle (what a simulator must reproduce).
    pub fn expected(&self) -> Vec<Vec<u64>> {
        self.cycles.iter().map(|c| c.outputs.clone()).collect()
    }

    /// Checks port lists and every value's width (for traces built by hand).
    pub(crate) fn validate(&self) -> Result<(), CosimError> {
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
