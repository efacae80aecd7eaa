//! Co-simulation traces of the rtl blocks: each block's Rust model driven
//! by its driver's inputs (`crate::drive`), recorded clock by clock at its
//! Verilog's ports for [`crate::hdl::cosim`] to replay.
//!
//! The matcher ([`matcher_trace`]) is driven exactly as [`MatcherSim::run`] drives it (each
//! side's records, then its marker, offered back to back while the side is
//! ready, pairs back to back); this module only watches, through
//! [`MatcherSim::observer`], and records at the sampling point of every
//! clock all input ports (the offered beats, including those not taken
//! while `r_ready`/`o_ready` is low, and `dispmax`) and all output ports of
//! the top. Those are the cycle semantics of [`crate::hdl::cosim`] and of
//! [`detector_trace`]: inputs applied with the clock low,
//! outputs sampled before the rising edge, state from the `initial` values
//! of a freshly built block. Replaying the inputs in the generated Verilog
//! must reproduce the outputs bit for bit; the inputs do not depend on the
//! Verilog's outputs there (the testbench plays them open loop), which is
//! why the offered beats are recorded as they were, back-pressure included.
//!
//! The trace's ports are those of the Verilog's `top` module, in its order,
//! without the clock; the Verilog must be generated for the same cell count
//! and gain rule as the recording ([`crate::hdl::verilog::generate_with`]).

use std::sync::{Arc, Mutex};

use rtl::detector::declivity_detector::DeclivityDetector;
use rtl::matcher::declivity_matcher::{DeclivityMatcher, GainRule};
use rtl::post::interpolator::Interpolator;
use rtl::post::vertical_median::VerticalMedian;

use crate::drive::detector::PixelBeat;
use crate::drive::interpolator::{timed_beats, AnchorLine, Beat};
use crate::drive::matcher::{MatchLine, MatchedLine, MatcherSim};
use crate::drive::vertical_median::MedianBeat;
use crate::hdl::cosim::{data_ports, CosimError, Cycle, PortReader, Trace};

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

/// Records the Rust model of the detector on `beats` (one per clock) as a
/// co-simulation trace with the ports of `verilog`.
pub fn detector_trace(verilog: &str, beats: &[PixelBeat]) -> Result<Trace, CosimError> {
    let (ins, outs) = data_ports(verilog)?;
    let mut reader = PortReader::new(&ins, &outs);
    let in_names: Vec<String> = ins.iter().map(|p| p.name.clone()).collect();
    let stimulus: Vec<Vec<u64>> = beats
        .iter()
        .map(|b| {
            in_names
                .iter()
                .map(|n| match n.as_str() {
                    "s_tdata" => b.tdata as u64,
                    "s_tvalid" => b.tvalid as u64,
                    "s_tuser" => b.tuser as u64,
                    "s_tlast" => b.tlast as u64,
                    "reset" => b.reset as u64,
                    other => panic!("unknown detector input {other}"),
                })
                .collect()
        })
        .collect();
    let mut uut = DeclivityDetector::default();
    crate::hdl::cosim::record(
        &mut uut,
        &ins,
        &outs,
        |u: &mut DeclivityDetector, level| u.clock.next = level.into(),
        |u: &mut DeclivityDetector, v: &[u64]| {
            for (n, &x) in in_names.iter().zip(v) {
                match n.as_str() {
                    "s_tdata" => u.s_tdata.next = x.into(),
                    "s_tvalid" => u.s_tvalid.next = x != 0,
                    "s_tuser" => u.s_tuser.next = x != 0,
                    "s_tlast" => u.s_tlast.next = x != 0,
                    "reset" => u.reset.next = x != 0,
                    _ => {}
                }
            }
        },
        |u: &DeclivityDetector| match reader.read(u, &ins, &outs) {
            Ok(cycle) => cycle.outputs,
            Err(e) => panic!("the detector's ports: {e}"),
        },
        stimulus,
    )
}

/// A co-simulation trace of the interpolator's Rust model (the default
/// mode's, as [`crate::hdl::verilog::Top::Interpolator`] generates it) on
/// `lines`, each offered as [`InterpolatorSim::run`](crate::drive::interpolator::InterpolatorSim::run) offers them with the
/// period beside it, followed by `tail` idle clocks.
pub fn interpolator_trace(verilog: &str, lines: &[(&AnchorLine, usize)], tail: usize) -> Result<Trace, CosimError> {
    let (ins, outs) = data_ports(verilog)?;
    let mut reader = PortReader::new(&ins, &outs);
    let in_names: Vec<String> = ins.iter().map(|p| p.name.clone()).collect();
    let (mut bs, _) = timed_beats(lines);
    bs.extend(std::iter::repeat_n(Beat::default(), tail));
    let value = |b: &Beat, n: &str| match n {
        "a_valid" => b.valid as u64,
        "a_last" => b.last as u64,
        "a_x" => b.x as u64,
        "a_d" => b.d as u64,
        "a_width" => b.width as u64,
        "a_sof" => b.sof as u64,
        // The stimuli never reset the block.
        "reset" => 0,
        other => panic!("unknown interpolator input {other}"),
    };
    let stimulus: Vec<Vec<u64>> = bs.iter().map(|b| in_names.iter().map(|n| value(b, n)).collect()).collect();
    let mut uut = Interpolator::default();
    crate::hdl::cosim::record(
        &mut uut,
        &ins,
        &outs,
        |u: &mut Interpolator, level| u.clock.next = level.into(),
        |u: &mut Interpolator, v: &[u64]| {
            for (n, &x) in in_names.iter().zip(v) {
                match n.as_str() {
                    "a_valid" => u.a_valid.next = x != 0,
                    "a_last" => u.a_last.next = x != 0,
                    "a_x" => u.a_x.next = x.into(),
                    "a_d" => u.a_d.next = x.into(),
                    "a_width" => u.a_width.next = x.into(),
                    "a_sof" => u.a_sof.next = x != 0,
                    "reset" => u.reset.next = x != 0,
                    _ => {}
                }
            }
        },
        |u: &Interpolator| match reader.read(u, &ins, &outs) {
            Ok(cycle) => cycle.outputs,
            Err(e) => panic!("the interpolator's ports: {e}"),
        },
        stimulus,
    )
}

/// The Verilog of a fresh vertical median (top module `top`).
pub fn median_verilog() -> String {
    crate::hdl::cosim::verilog_of(VerticalMedian::new())
}

/// A co-simulation trace of the vertical median's Rust model on `beats`
/// (one per clock), followed by `tail` idle clocks; `verilog` gives the
/// ports (from [`median_verilog`]).
pub fn median_trace(verilog: &str, beats: &[MedianBeat], tail: usize) -> Result<Trace, CosimError> {
    let (ins, outs) = data_ports(verilog)?;
    let mut reader = PortReader::new(&ins, &outs);
    let in_names: Vec<String> = ins.iter().map(|p| p.name.clone()).collect();
    let value = |b: &MedianBeat, n: &str| match n {
        "p_valid" => b.valid as u64,
        "p_d" => b.d,
        "p_last" => b.last as u64,
        "p_sof" => b.sof as u64,
        "p_eof" => b.eof as u64,
        // The stimuli never reset the block.
        "reset" => 0,
        other => panic!("unknown vertical median input {other}"),
    };
    let idle = std::iter::repeat_n(MedianBeat::default(), tail);
    let stimulus: Vec<Vec<u64>> = beats.iter().copied().chain(idle).map(|b| in_names.iter().map(|n| value(&b, n)).collect()).collect();
    let mut uut = VerticalMedian::new();
    crate::hdl::cosim::record(
        &mut uut,
        &ins,
        &outs,
        |u: &mut VerticalMedian, level| u.clock.next = level.into(),
        |u: &mut VerticalMedian, v: &[u64]| {
            for (n, &x) in in_names.iter().zip(v) {
                match n.as_str() {
                    "p_valid" => u.p_valid.next = x != 0,
                    "p_d" => u.p_d.next = x.into(),
                    "p_last" => u.p_last.next = x != 0,
                    "p_sof" => u.p_sof.next = x != 0,
                    "p_eof" => u.p_eof.next = x != 0,
                    "reset" => u.reset.next = x != 0,
                    _ => {}
                }
            }
        },
        |u: &VerticalMedian| match reader.read(u, &ins, &outs) {
            Ok(cycle) => cycle.outputs,
            Err(e) => panic!("the vertical median's ports: {e}"),
        },
        stimulus,
    )
}
