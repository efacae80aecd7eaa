//! Committed vectors: a fresh trace against its file in `vectors/`, re-blessed on request.

use std::path::Path;

use super::compare::*;
use super::error::*;
use super::trace::*;

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
