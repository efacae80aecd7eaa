//! Direct drive of a rust-hdl block: the Rust model run on a stimulus and recorded as a [`Trace`].

use std::collections::HashMap;

use rust_hdl::core::atom::{Atom, AtomKind};
use rust_hdl::core::block::Block;
use rust_hdl::core::module_defines::generate_verilog;
use rust_hdl::core::probe::Probe;
use rust_hdl::core::simulate::simulate;
use rust_hdl::core::synth::VCDValue;

use super::error::*;
use super::ports::*;
use super::trace::*;

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
