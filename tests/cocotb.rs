//! The cocotb testbench of the generated stereo top (`tests/cocotb/`, its
//! README says how to run it alone): a few real rows of tsukuba streamed
//! through `declivity_stereo` by cocotbext-axi sources with idle clocks and
//! blanking, every output beat checked against golden's hardware parity,
//! the frame structure and the status counters checked, under Icarus and
//! under Verilator; the scoreboard shown to fail on a perturbed beat, and
//! the output contract (no `m_tready`: the sink takes every beat) shown to
//! fail on a sink that stalls.
//! Runs `python3 -m pytest tests/cocotb`, which needs the pinned packages of
//! `tests/cocotb/requirements.txt` and the release `declivity` binary
//! (`cargo test --workspace --release` builds it for the cli's tests).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root.
fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The release `declivity` binary of this workspace.
fn declivity() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| repo().join("target"));
    let bin = if target.is_absolute() { target } else { repo().join(target) }.join("release").join("declivity");
    assert!(bin.is_file(), "{}: no release declivity binary (cargo build --release -p cli)", bin.display());
    bin
}

/// `PATH` with pip's user scripts folder first (where `pip install --user` puts them).
fn path_with_user_scripts() -> std::ffi::OsString {
    let user_base = Command::new("python3").args(["-m", "site", "--user-base"]).output().expect("python3 runs (apt-get install -y python3)");
    let mut paths = vec![PathBuf::from(String::from_utf8_lossy(&user_base.stdout).trim()).join("bin")];
    paths.extend(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()));
    std::env::join_paths(paths).expect("a PATH")
}

#[test]
fn cocotb_testbench_passes_a_band_of_tsukuba_under_icarus_and_verilator_and_fails_on_a_perturbed_beat_or_a_stalling_sink() {
    let out = Command::new("python3")
        .args(["-m", "pytest", "tests/cocotb", "-q", "-p", "no:cacheprovider"])
        .current_dir(repo())
        .env("DECLIVITY_BIN", declivity())
        .env("PATH", path_with_user_scripts())
        .output()
        .expect("python3 runs");
    let log = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(
        !log.contains("No module named pytest") && !log.contains("No module named 'cocotb"),
        "the testbench's packages are missing (python3 -m pip install --user -r tests/cocotb/requirements.txt):\n{log}"
    );
    assert!(out.status.success(), "the cocotb testbench failed:\n{log}");
    // Two simulators × (the band against golden, the band after a reset in mid-frame, the
    // perturbed beat failing), and the stalling sink failing under Icarus: seven tests,
    // none skipped.
    assert!(log.contains("7 passed") && !log.contains("skipped"), "seven tests expected to pass:\n{log}");
}
