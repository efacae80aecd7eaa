//! Blocks as IP folders (`sim::hdl::ip`, `declivity verilog --out DIR`):
//! two blocks' folders compile together in one Icarus run and in one
//! Verilator lint through their file lists, which the raw rust-hdl Verilog
//! (every block's module called `top`) cannot; the renaming changes names
//! only; the FuseSoC core runs its lint target; the camera set at
//! generation reaches the depth stage and nothing else.

use std::path::Path;
use std::process::Command;

use sim::hdl::cosim::{self, LintWarning};
use sim::hdl::ip::{self, IpSpec};
use sim::hdl::verilog::{self, Top};
use sim::Config;

fn spec(top: Top) -> IpSpec {
    IpSpec { config: Config::Sd, top, generation: verilog::Generation::of(Config::Sd), target: verilog::Target::Ecp5 }
}

/// Writes the IP folder of `top` into `dir/<block>` and returns the path of its file list.
fn folder(dir: &Path, top: Top) -> (std::path::PathBuf, String) {
    let d = dir.join(top.name());
    let f = ip::write_ip_folder(&d, &spec(top), &verilog::generate(Config::Sd, top)).expect("IP folder written");
    (d.join(format!("{}.f", f.module)), d.to_str().unwrap().to_string())
}

/// Runs `cmd`; a missing tool fails the test with its install command.
fn run(cmd: &mut Command) -> (bool, String) {
    let install = if cmd.get_program() == "fusesoc" { "python3 -m pip install --user fusesoc==2.4.3" } else { "apt-get install -y iverilog verilator" };
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e} ({install})"));
    (out.status.success(), format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr)))
}

#[test]
fn two_blocks_ip_folders_compile_together_in_one_icarus_run_and_one_verilator_lint() {
    let dir = tempfile::tempdir().unwrap();
    // The detector and the interpolator both instantiate DP16KD: its model is in both folders.
    let (det_f, det_dir) = folder(dir.path(), Top::Detector);
    let (int_f, int_dir) = folder(dir.path(), Top::Interpolator);
    assert!(Path::new(&det_dir).join("sim_models/DP16KD.v").is_file() && Path::new(&int_dir).join("sim_models/DP16KD.v").is_file());
    let env = [(ip::dir_variable(Top::Detector), det_dir.as_str()), (ip::dir_variable(Top::Interpolator), int_dir.as_str())];

    let (ok, log) = run(Command::new("iverilog").args(["-g2012", "-o"]).arg(dir.path().join("both.vvp")).arg("-c").arg(&det_f).arg("-c").arg(&int_f).envs(env.clone()).current_dir(dir.path()));
    assert!(ok, "Icarus on both folders' file lists:\n{log}");

    let (ok, log) = run(Command::new("verilator")
        .args(["--lint-only", "-Wall", "-Wno-fatal", "-Wno-DECLFILENAME"])
        .arg("-f")
        .arg(&det_f)
        .arg("-f")
        .arg(&int_f)
        .envs(env)
        .current_dir(dir.path()));
    assert!(ok && !log.contains("%Error"), "Verilator on both folders' file lists:\n{log}");
    let warnings: Vec<LintWarning> = cosim::parse_lint(&log);
    // Two top modules in one lint is what this test does on purpose.
    let mut accepted = cosim::ACCEPTED_LINT.to_vec();
    accepted.push(("MULTITOP", "two blocks linted together, each its own top"));
    let counts = cosim::check_accepted(&warnings, &accepted).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(counts.get("MULTITOP"), Some(&1), "both blocks are tops: {counts:?}");

    // The same two blocks as rust-hdl writes them cannot: both are `module top`.
    let raw = dir.path().join("raw");
    std::fs::create_dir_all(&raw).unwrap();
    std::fs::write(raw.join("detector.v"), verilog::generate(Config::Sd, Top::Detector)).unwrap();
    std::fs::write(raw.join("interpolator.v"), verilog::generate(Config::Sd, Top::Interpolator)).unwrap();
    let (ok, log) = run(Command::new("iverilog")
        .args(["-g2012", "-o", "raw.vvp", "-y", &format!("{det_dir}/sim_models"), "+libext+.v", "detector.v", "interpolator.v"])
        .current_dir(&raw));
    assert!(!ok && log.contains("top"), "the raw blocks were expected to collide on `module top`:\n{log}");
}

/// The generic target's folders hold no models beside the block (each block holds its own,
/// renamed into it), and two of them compile together too.
#[test]
fn two_blocks_generic_ip_folders_compile_together_without_a_model_library() {
    let dir = tempfile::tempdir().unwrap();
    let mut lists = Vec::new();
    let mut env = Vec::new();
    for top in [Top::Detector, Top::Interpolator] {
        let d = dir.path().join(top.name());
        let spec = IpSpec { target: verilog::Target::Generic, ..spec(top) };
        let f = ip::write_ip_folder(&d, &spec, &verilog::Target::Generic.retarget(verilog::generate(Config::Sd, top))).expect("IP folder written");
        assert!(!d.join(ip::SIM_MODELS_DIR).exists(), "{}: no model library", f.module);
        let v = std::fs::read_to_string(d.join(format!("{}.v", f.module))).unwrap();
        assert!(v.contains(&format!("module {}$DP16KD(", f.module)), "{}: its own block RAM", f.module);
        lists.push(d.join(format!("{}.f", f.module)));
        env.push((ip::dir_variable(top), d.to_str().unwrap().to_string()));
    }
    let (ok, log) = run(Command::new("iverilog").args(["-g2012", "-o", "both.vvp", "-c"]).arg(&lists[0]).arg("-c").arg(&lists[1]).envs(env).current_dir(dir.path()));
    assert!(ok, "Icarus on both generic folders:\n{log}");
}

#[test]
fn renaming_a_block_changes_its_module_names_and_nothing_else() {
    for top in [Top::Detector, Top::Interpolator, Top::Stereo] {
        let v = verilog::generate(Config::Sd, top);
        let module = ip::module_name(top);
        assert!(!v.contains(&module), "{module} already named in the raw Verilog");
        let renamed = ip::rename_top(&v, &module);
        assert!(renamed.contains(&format!("module {module}(")) && !renamed.contains("module top"));
        // Named back, it is the generated text byte for byte: the renaming is one-to-one and
        // touched names only.
        assert_eq!(ip::rename_module(&renamed, &module, "top"), v, "{module}");
    }
}

#[test]
fn the_fusesoc_core_runs_its_lint_target_under_verilator() {
    let dir = tempfile::tempdir().unwrap();
    let (_, det_dir) = folder(dir.path(), Top::Detector);
    let (ok, log) = run(Command::new("fusesoc")
        .args(["--cores-root", &det_dir, "run", "--target", "lint", "declivity:ip:declivity_detector"])
        .current_dir(dir.path()));
    assert!(ok, "fusesoc:\n{log}");
    // The target really runs Verilator: the same core on a block with a syntax error fails.
    let v = Path::new(&det_dir).join("declivity_detector.v");
    let text = std::fs::read_to_string(&v).unwrap();
    std::fs::write(&v, text.replacen("endmodule", "endmodule_", 1)).unwrap();
    let broken = dir.path().join("broken");
    std::fs::create_dir_all(&broken).unwrap();
    let (ok, log) = run(Command::new("fusesoc")
        .args(["--cores-root", &det_dir, "run", "--target", "lint", "declivity:ip:declivity_detector"])
        .current_dir(&broken));
    assert!(!ok, "the lint target passed a broken block:\n{log}");
}

/// The modules of a generated Verilog text, by name.
fn modules(v: &str) -> std::collections::BTreeMap<String, String> {
    let mut out = std::collections::BTreeMap::new();
    let mut current: Option<(String, String)> = None;
    for line in v.lines() {
        if let Some(rest) = line.strip_prefix("module ") {
            let name = rest.split('(').next().unwrap_or(rest).to_string();
            current = Some((name, String::new()));
        }
        if let Some((_, text)) = current.as_mut() {
            text.push_str(line);
            text.push('\n');
        }
        if line.starts_with("endmodule") {
            let (name, text) = current.take().expect("endmodule after module");
            out.insert(name, text);
        }
    }
    out
}

#[test]
fn the_camera_set_at_generation_changes_the_depth_stage_and_nothing_else() {
    let with = |camera| {
        let g = verilog::Generation { cells: 2, camera, ..verilog::Generation::of(Config::Sd) };
        verilog::generate_block(Config::Sd, Top::Stereo, &g).expect("a camera the depth stage holds")
    };
    let default = modules(&with(rtl::post::depth_stage::DepthCamera::default()));
    let other = modules(&with(rtl::post::depth_stage::DepthCamera { focal_px: 500.0, baseline_mm: 100.0 }));
    assert_eq!(default.keys().collect::<Vec<_>>(), other.keys().collect::<Vec<_>>(), "the same modules");
    let changed: Vec<&String> = default.keys().filter(|m| default[*m] != other[*m]).collect();
    assert!(!changed.is_empty(), "the camera changed nothing");
    assert!(changed.iter().all(|m| m.starts_with("top$depth")), "modules outside the depth stage changed: {changed:?}");
    // A camera whose farthest depth would round under 1 mm is refused, with the reason.
    let g = verilog::Generation { camera: rtl::post::depth_stage::DepthCamera { focal_px: 1.0, baseline_mm: 1.0 }, ..verilog::Generation::of(Config::Sd) };
    let e = verilog::generate_block(Config::Sd, Top::Stereo, &g).expect_err("f·b = 1 px·mm is refused").to_string();
    assert!(e.contains("depth stage's camera") && e.contains("1 mm"), "{e}");
}
