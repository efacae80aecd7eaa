//! # ip — a generated block as a self-contained IP folder
//!
//! What a hardware engineer drops into a project (`declivity verilog --top T
//! --out DIR`), in the form of open IP cores such as `verilog-axis`:
//!
//! | file | what it is |
//! |---|---|
//! | `declivity_<block>.v` | the block; its module and every submodule renamed from rust-hdl's `top`, `top$…` to `declivity_<block>`, `declivity_<block>$…`, so that two blocks compile together in one project |
//! | `sim_models/<PRIMITIVE>.v` | the behavioural model of each ECP5 primitive the block instantiates, one module a file, for a simulator's library search (`-y`); synthesis for the ECP5 takes the primitive itself (the `generic` target has none: its block holds the models, renamed) |
//! | `declivity_<block>.f` | the simulation file list, paths under `${DECLIVITY_<BLOCK>_DIR}` (Icarus `-c`, Verilator `-f`) |
//! | `declivity_<block>.core` | a FuseSoC CAPI2 core: `default` (the block alone), `sim` (Icarus, with the models) and `lint` (Verilator) targets |
//! | `README.md` | the generation parameters, the files and the ports (direction, width) |
//!
//! The block's logic is the one [`crate::hdl::verilog`] generates: the
//! renaming changes names only (tested by compiling it and by the
//! co-simulation of the renamed detector).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};


use crate::config::Config;
use crate::hdl::cosim::{top_ports, TOP_MODULE};
use crate::hdl::primitives::models_used;
use crate::drive::matcher::golden_mode;
use crate::hdl::verilog::{CameraReport, Generation, Target, Top};
use crate::SimError;

/// The folder of the primitives' simulation models inside an IP folder.
pub const SIM_MODELS_DIR: &str = "sim_models";

/// What a block was generated from: the parameters its README and core
/// record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IpSpec {
    pub config: Config,
    pub top: Top,
    /// The matcher's cells and rule (`--top matcher` and `stereo`), the
    /// depth stage's camera (`stereo`).
    pub generation: Generation,
    /// What the Verilog is written for (the design passed is already
    /// written for it: [`Target::retarget`]).
    pub target: Target,
}

impl IpSpec {
    /// The block's module name: `declivity_<block>`.
    pub fn module(&self) -> String {
        module_name(self.top)
    }

    /// Whether the block holds the matcher (its cells and rule apply).
    fn has_matcher(&self) -> bool {
        matches!(self.top, Top::Matcher | Top::Stereo)
    }
}

/// The module name of a block in its IP folder: `declivity_<block>`.
pub fn module_name(top: Top) -> String {
    format!("declivity_{}", top.name())
}

/// The environment variable the file list's paths start from:
/// `DECLIVITY_<BLOCK>_DIR`.
pub fn dir_variable(top: Top) -> String {
    format!("{}_DIR", module_name(top).to_uppercase())
}

/// An IP folder as written: its folder, module and files (paths relative
/// to the folder, in the order written).
#[derive(Debug, Clone)]
pub struct IpFolder {
    pub dir: PathBuf,
    pub module: String,
    pub files: Vec<String>,
    /// The lines of the block's Verilog.
    pub verilog_lines: usize,
}

/// `design` with rust-hdl's top module `top` and its submodules `top$…`
/// renamed to `module` and `module$…` ([`rename_module`] from `top`).
pub fn rename_top(design: &str, module: &str) -> String {
    rename_module(design, TOP_MODULE, module)
}

/// `design` with the module `from` and its submodules `from$…` renamed to
/// `to` and `to$…`: every identifier that is `from` or starts with
/// `from$` (module names, instantiations and the comments after
/// `endmodule`), and nothing else (for `top`: not `stop`, `top_x`,
/// `laptop$1`, a system task `$top` or the inside of a string).
pub fn rename_module(design: &str, from: &str, to: &str) -> String {
    let mut out = String::with_capacity(design.len() + design.len() / 8);
    let mut chars = design.char_indices().peekable();
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
    while let Some((i, c)) = chars.next() {
        if c == '"' {
            // A string, copied as it is (with its escapes).
            out.push(c);
            let mut escaped = false;
            for (_, c) in chars.by_ref() {
                out.push(c);
                if escaped {
                    escaped = false;
                } else if c == '\\' {
                    escaped = true;
                } else if c == '"' {
                    break;
                }
            }
        } else if ident(c) {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek() {
                if !ident(d) {
                    break;
                }
                end = j + d.len_utf8();
                chars.next();
            }
            let token = &design[i..end];
            let renamed = c != '$' && !c.is_ascii_digit() && (token == from || token.strip_prefix(from).is_some_and(|r| r.starts_with('$')));
            if renamed {
                out.push_str(to);
                out.push_str(&token[from.len()..]);
            } else {
                out.push_str(token);
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// Writes the IP folder of `design` (the Verilog [`crate::hdl::verilog`]
/// generated for `spec`, top module `top`) into `dir`, created if missing.
pub fn write_ip_folder(dir: &Path, spec: &IpSpec, design: &str) -> Result<IpFolder, SimError> {
    let module = spec.module();
    let (ins, outs) = top_ports(design).map_err(|e| SimError::Argument(format!("the generated Verilog: {e}")))?;
    let renamed = rename_top(design, &module);
    let models = models_used(design);
    let io = |path: PathBuf| move |source| SimError::Io { path, source };
    let models_dir = if models.is_empty() { dir.to_path_buf() } else { dir.join(SIM_MODELS_DIR) };
    std::fs::create_dir_all(&models_dir).map_err(io(models_dir.clone()))?;

    let mut files = Vec::new();
    let mut write = |name: String, text: &str| -> Result<(), SimError> {
        let path = dir.join(&name);
        std::fs::write(&path, text).map_err(io(path))?;
        files.push(name);
        Ok(())
    };
    let verilog = format!("{module}.v");
    write(verilog.clone(), &renamed)?;
    let model_files: Vec<String> = models.iter().map(|(name, _)| format!("{SIM_MODELS_DIR}/{name}.v")).collect();
    for ((_, text), file) in models.iter().zip(&model_files) {
        write(file.clone(), text)?;
    }
    write(format!("{module}.f"), &file_list(spec, &verilog, !models.is_empty()))?;
    write(format!("{module}.core"), &fusesoc_core(spec, &verilog, &model_files))?;
    let ports: Vec<(&str, &str, u32)> = ins
        .iter()
        .map(|p| (p.name.as_str(), "input", p.width))
        .chain(outs.iter().map(|p| (p.name.as_str(), "output", p.width)))
        .collect();
    write("README.md".into(), &readme(spec, &verilog, &model_files, &ports))?;
    Ok(IpFolder { dir: dir.to_path_buf(), module, files, verilog_lines: renamed.lines().count() })
}

/// One line of generation parameters, as the README and the core give them.
fn parameters(spec: &IpSpec) -> String {
    let s = spec.config.sizes();
    let mut p = format!("target `{}`, configuration `{}` (lines up to W_MAX = {} px, N_MAX = {} declivities a line)", spec.target.name(), s.config, s.w_max, s.n_max);
    let g = &spec.generation;
    if spec.has_matcher() {
        let _ = write!(p, ", {} gain cells of {} rows, gain rule `{}`", g.cells, s.rows_per_cell, golden_mode(g.rule).name());
    }
    if spec.top == Top::Stereo {
        let _ = write!(p, ", depth for a camera of {}", CameraReport::from(g.camera));
    }
    p
}

/// The command that generated the block.
fn command(spec: &IpSpec) -> String {
    let mut c = format!("declivity verilog --top {} --config {} --target {}", spec.top.name(), spec.config.name(), spec.target.name());
    let g = &spec.generation;
    if spec.has_matcher() {
        let _ = write!(c, " --cells {} --rule {}", g.cells, golden_mode(g.rule).name());
    }
    if spec.top == Top::Stereo {
        let _ = write!(c, " --focal-px {} --baseline-m {}", g.camera.focal_px, g.camera.baseline_mm / 1000.0);
    }
    c
}

/// The simulation file list: the block and the models' library, under the
/// folder's variable (Icarus `-c` and Verilator `-f` both expand
/// `${NAME}` from the environment).
fn file_list(spec: &IpSpec, verilog: &str, models: bool) -> String {
    let var = dir_variable(spec.top);
    let mut f = format!(
        "// {module}: simulation file list (Icarus: iverilog -c FILE; Verilator: verilator -f FILE).\n\
         // Set {var} to this folder.\n",
        module = spec.module()
    );
    if models {
        let _ = write!(
            f,
            "// The ECP5 primitives' behavioural models are a library (-y): each is read only if\n\
             // the design instantiates it, and only once when several blocks' lists are given.\n\
             // Synthesis for the ECP5 reads {verilog} alone.\n"
        );
    }
    let _ = writeln!(f, "${{{var}}}/{verilog}");
    if models {
        let _ = write!(f, "-y ${{{var}}}/{SIM_MODELS_DIR}\n+libext+.v\n");
    }
    f
}

/// The FuseSoC CAPI2 core.
fn fusesoc_core(spec: &IpSpec, verilog: &str, model_files: &[String]) -> String {
    let module = spec.module();
    let mut c = String::new();
    let _ = writeln!(c, "CAPI=2:");
    let _ = writeln!(c, "# Generated by `{}`.", command(spec));
    let _ = writeln!(c, "name: declivity:ip:{module}:{}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(c, "description: \"Declivity stereo, {}: {}\"", spec.top.name(), parameters(spec).replace('`', ""));
    let _ = writeln!(c, "\nfilesets:\n  rtl:\n    files:\n      - {verilog}\n    file_type: verilogSource");
    let sim_sets = if model_files.is_empty() {
        "[rtl]"
    } else {
        let _ = writeln!(c, "  ecp5_sim_models:\n    files:");
        for f in model_files {
            let _ = writeln!(c, "      - {f}");
        }
        let _ = writeln!(c, "    file_type: verilogSource");
        "[rtl, ecp5_sim_models]"
    };
    let _ = writeln!(c, "\ntargets:\n  default:\n    filesets: [rtl]\n    toplevel: {module}");
    let _ = writeln!(c, "  sim:\n    default_tool: icarus\n    filesets: {sim_sets}\n    toplevel: {module}\n    tools:\n      icarus:\n        iverilog_options: [-g2012]");
    let _ = writeln!(
        c,
        "  lint:\n    default_tool: verilator\n    filesets: {sim_sets}\n    toplevel: {module}\n    tools:\n      verilator:\n        mode: lint-only\n        verilator_options: [-Wall, -Wno-fatal, -Wno-DECLFILENAME]"
    );
    c
}

/// The folder's README: parameters, files, how to simulate, ports.
fn readme(spec: &IpSpec, verilog: &str, model_files: &[String], ports: &[(&str, &str, u32)]) -> String {
    let module = spec.module();
    let var = dir_variable(spec.top);
    let mut r = String::new();
    let _ = writeln!(r, "# `{module}`\n");
    let _ = writeln!(r, "The declivity stereo {} as Verilog, generated by `{}`: {}.\n", spec.top.name(), command(spec), parameters(spec));
    let _ = writeln!(r, "One clock input, `clock`; every register changes on its rising edge. One reset input, `reset`: synchronous, active high, it returns every register to its value after configuration. Timing, latency and the meaning of each port: the datasheet, `docs/hardware/datasheet.md`.\n");
    let _ = writeln!(r, "## Files\n\n| file | what it is |\n|---|---|");
    let _ = writeln!(r, "| `{verilog}` | the block: module `{module}`, its submodules `{module}$…` |");
    for f in model_files {
        let _ = writeln!(r, "| `{f}` | behavioural model of the ECP5 primitive, for simulation only |");
    }
    let _ = writeln!(r, "| `{module}.f` | simulation file list, paths under `${{{var}}}` |");
    let _ = writeln!(r, "| `{module}.core` | FuseSoC CAPI2 core: targets `default`, `sim` (Icarus), `lint` (Verilator) |\n");
    let _ = writeln!(r, "## Use\n\n```sh\nexport {var}=$PWD        # this folder\niverilog -g2012 -c ${var}/{module}.f your_tb.v\nverilator --lint-only -Wall -f ${var}/{module}.f --top-module {module}\nfusesoc --cores-root . run --target lint declivity:ip:{module}\n```\n");
    let _ = match spec.target {
        Target::Ecp5 => writeln!(r, "Synthesis for the ECP5 reads `{verilog}` alone: Yosys's `synth_ecp5` and the vendor's tools map the primitives it instantiates.\n"),
        Target::Generic => writeln!(r, "`{verilog}` is the whole block, for simulation and for any synthesis flow: its memories and products are behavioural Verilog (registered reads, `*`), inferred by the tools.\n"),
    };
    let _ = writeln!(r, "## Ports\n\n| port | direction | width |\n|---|---|--:|");
    for (name, dir, width) in ports {
        let _ = writeln!(r, "| `{name}` | {dir} | {width} |");
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renaming_touches_top_and_its_submodules_only() {
        let v = "module top(clock);\n  top$a$b a_b(.clock(clock));\n  wire stop, top_x, laptop$1; // top$a$b\n  initial $top(\"top$q\");\nendmodule // top\n";
        let r = rename_top(v, "declivity_x");
        assert_eq!(
            r,
            "module declivity_x(clock);\n  declivity_x$a$b a_b(.clock(clock));\n  wire stop, top_x, laptop$1; // declivity_x$a$b\n  initial $top(\"top$q\");\nendmodule // declivity_x\n"
        );
    }

    #[test]
    fn names_follow_the_block() {
        assert_eq!(module_name(Top::Stereo), "declivity_stereo");
        assert_eq!(dir_variable(Top::Detector), "DECLIVITY_DETECTOR_DIR");
    }
}
