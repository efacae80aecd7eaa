//! Verilator's lint and the warnings the project accepts.

use std::collections::BTreeMap;
use std::process::Command;

use crate::hdl::primitives::MODELS_FILE;

use super::error::*;
use super::run::*;

/// The warnings in a Verilator log (`%Warning-CODE: file:line:col: message`).
pub fn parse_lint(log: &str) -> Vec<LintWarning> {
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

/// The accepted-list entry for the `DP16KD` instances of `rtl::primitives::block_ram`:
/// their read-port-A outputs (`DOA*`, the port only writes) and port B's
/// outputs above the data width are left unconnected. [`check_accepted`]
/// accepts a `PINMISSING` only on such a pin.
pub const DP16KD_UNUSED_OUTPUTS: (&str, &str) =
    ("PINMISSING", "a DP16KD instance (rtl::primitives::block_ram) leaves its port A outputs DOA* and port B's outputs DOB* above the data width unconnected; other missing pins are not accepted");

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
