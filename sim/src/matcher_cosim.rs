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

use crate::cosim::{data_ports, CosimError, Cycle, PortReader, Trace};
use crate::matcher::{MatchLine, MatchedLine, MatcherSim};

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
    let (ins, outs) = data_ports(verilog)?;
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
