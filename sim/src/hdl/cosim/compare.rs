//! Comparison of a simulator's outputs with a trace, naming the first difference.

use std::fmt::Write as _;

use super::error::*;
use super::trace::*;

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
