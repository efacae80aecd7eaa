//! Co-simulation traces of the rtl matcher ([`DeclivityMatcher`]): the Rust
//! model driven by line pairs, recorded clock by clock for `sim::cosim`.
//!
//! The matcher is driven exactly as [`MatcherSim::run`] drives it (each
//! side's records, then its marker, offered back to back while the side is
//! ready, pairs back to back); this module only watches, through
//! [`MatcherSim::observer`], and records at the sampling point of every
//! clock all input ports (the offered beats, including those not taken
//! while `r_ready`/`o_ready` is low, and `dispmax`) and all output ports of
//! the top. Those are the cycle semantics of [`crate::cosim`] and of
//! [`crate::detector::detector_trace`]: inputs applied with the clock low,
//! outputs sampled before the rising edge, state from the `initial` values
//! of a freshly built block. Replaying the inputs in the generated Verilog
//! must reproduce the outputs bit for bit; the inputs do not depend on the
//! Verilog's outputs there (the testbench plays them open loop), which is
//! why the offered beats are recorded as they were, back-pressure included.
//!
//! The trace's ports are those of the Verilog's `top` module, in its order,
//! without the clock; the Verilog must be generated for the same cell count
//! and gain rule as the recording ([`crate::verilog::generate_with`]).

use std::sync::{Arc, Mutex};

use rtl::declivity_matcher::{DeclivityMatcher, GainRule};
use rust_hdl::core::atom::{Atom, AtomKind};
use rust_hdl::core::block::Block;
use rust_hdl::core::probe::Probe;
use rust_hdl::core::synth::VCDValue;

use crate::cosim::{CosimError, Cycle, Port, Trace};
use crate::matcher::{MatchLine, MatchedLine, MatcherSim};

/// The matcher's input ports in the order of the generated Verilog (without
/// the clock) and its output ports likewise.
pub fn matcher_ports(verilog: &str) -> Result<(Vec<Port>, Vec<Port>), CosimError> {
    let (ins, outs) = crate::cosim::top_ports(verilog)?;
    Ok((ins.into_iter().filter(|p| p.name != crate::cosim::CLOCK_PORT).collect(), outs))
}

/// Reads the values of the top's ports from the block, whatever they are:
/// rust-hdl's probe visits every signal of the design, and the top's own
/// input and output signals are those visited in the outermost scope. The
/// port list therefore follows the rtl without an edit here.
struct PortReader {
    /// For each top-level port name: input (`true`) or output, and its
    /// place in the trace's list.
    places: std::collections::HashMap<String, (bool, usize)>,
    inputs: Vec<Option<u64>>,
    outputs: Vec<Option<u64>>,
    depth: usize,
    /// A port wider than 64 bits or with an X/Z bit.
    bad: Option<String>,
}

impl PortReader {
    fn new(ins: &[Port], outs: &[Port]) -> Self {
        let mut places = std::collections::HashMap::new();
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
    fn read<B: Block>(&mut self, uut: &B, ins: &[Port], outs: &[Port]) -> Result<Cycle, String> {
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

/// Records the Rust model of an `N`-cell matcher for `rule` with the search
/// bound `dispmax` (`dispmax · 2^POS_FRAC_BITS`) on `pairs` (reference,
/// other), driven by [`MatcherSim::run`] with the pairs back to back, as a
/// co-simulation trace with the ports of `verilog`. The trace runs from the
/// first clock to the clock of the last pair's marker. Also returns what
/// came out for each pair.
pub fn matcher_trace<const N: usize>(
    verilog: &str,
    rule: GainRule,
    dispmax: u32,
    pairs: &[(MatchLine, MatchLine)],
) -> Result<(Trace, Vec<MatchedLine>), CosimError> {
    let (ins, outs) = matcher_ports(verilog)?;
    let recorded = Arc::new(Mutex::new((Vec::<Cycle>::new(), None::<String>)));
    let mut sim = MatcherSim::<N>::new(rule, dispmax);
    let sink = Arc::clone(&recorded);
    let mut reader = PortReader::new(&ins, &outs);
    let (i, o) = (ins.clone(), outs.clone());
    sim.observer = Some(Box::new(move |u: &DeclivityMatcher<N>| {
        let mut rec = sink.lock().expect("the trace");
        if rec.1.is_none() {
            match reader.read(u, &i, &o) {
                Ok(c) => rec.0.push(c),
                Err(e) => rec.1 = Some(e),
            }
        }
    }));
    let lines = sim.run(pairs, false, || {});
    drop(sim);
    let (cycles, error) = std::mem::take(&mut *recorded.lock().expect("the trace"));
    if let Some(e) = error {
        return Err(CosimError::PortsDiffer(e));
    }
    let mut trace = Trace::new(ins, outs)?;
    for c in cycles {
        trace.push(c.inputs, c.outputs)?;
    }
    Ok((trace, lines))
}
