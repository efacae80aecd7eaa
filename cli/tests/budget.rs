//! `declivity budget` as a user meets it: bad sizes refused with a message
//! that names them, the JSON object's keys, the text's stages, the help.

use std::process::{Command, Output};

fn declivity(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_declivity")).args(args).output().expect("the binary runs")
}

const GOOD: [&str; 11] =
    ["budget", "--width", "512", "--height", "512", "--n-max", "128", "--dispmax", "64", "--clock-mhz", "125"];

/// `GOOD` with `flag` set to `value`.
fn with(flag: &str, value: &str) -> Vec<String> {
    let mut a: Vec<String> = GOOD.iter().map(|s| s.to_string()).collect();
    match a.iter().position(|s| s == flag) {
        Some(i) => a[i + 1] = value.to_string(),
        None => a.extend([flag.to_string(), value.to_string()]),
    }
    a
}

#[test]
fn cli_bad_sizes_exit_non_zero_with_a_message_naming_the_problem() {
    let cases = [
        ("--width", "0", "--width 0"),
        ("--height", "0", "--height 0"),
        ("--height", "3", "at least 6 rows"),
        ("--n-max", "0", "--n-max 0"),
        ("--n-max", "129", "N_MAX = 128"),
        ("--cells", "5", "--cells 5"),
        ("--cells", "16", "need at least 32 cells"),
        ("--cells", "16", "(4 per cell)"),
        ("--cells", "64", "--cells 64"),
        ("--clock-mhz", "0", "--clock-mhz 0"),
        ("--clock-mhz", "-125", "--clock-mhz -125"),
        ("--dispmax", "0.5", "greater than 1"),
        ("--dispmax", "5000", "W_MAX = 1024"),
        ("--width", "wide", "--width"),
        ("--width", "1025", "W_MAX = 1024"),
        ("--width", "4294967295", "W_MAX = 1024"),
        ("--height", "300000000", "at most 2047 rows"),
        ("--height", "4294967295", "at most 2047 rows"),
    ];
    for (flag, value, says) in cases {
        let args = with(flag, value);
        let o = Command::new(env!("CARGO_BIN_EXE_declivity")).args(&args).output().expect("runs");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(err.contains(says), "{args:?}: stderr does not say `{says}`: {err}");
    }
}

#[test]
fn cli_json_is_one_object_with_the_budget_keys() {
    let o = declivity(&[&GOOD[..], &["--hblank", "100", "--json"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    for key in [
        "width",
        "height",
        "n_max",
        "dispmax",
        "clock_mhz",
        "hblank",
        "cells",
        "line_period_cycles",
        "stall_cycles_per_line",
        "min_hblank_cycles",
        "latency_cycles",
        "latency_us",
        "frame_time_ms",
        "fps",
        "latency_last_pixel_cycles",
        "output_span_cycles",
        "last_out_cycles",
        "flush_cycles",
        "vblank_lines",
        "vblank_lines_any_rows",
        "frame_cycles",
        "load",
        "stages",
        "resources",
    ] {
        assert!(v.get(key).is_some(), "no key {key} in {v}");
    }
    let stages = v["stages"].as_array().expect("stages");
    let names: Vec<&str> = stages.iter().filter_map(|s| s["name"].as_str()).collect();
    assert_eq!(
        names,
        ["declivity detector", "record queues", "matcher", "row check", "interpolator", "vertical median", "depth stage"]
    );
    for s in stages {
        for key in ["name", "cycles_per_line", "formula", "latency_cycles", "latency_formula", "dsp_blocks", "memories"] {
            assert!(s.get(key).is_some(), "no key {key} in {s}");
        }
    }
    for key in [
        "line_buffer_bits",
        "histogram_banks",
        "pe_count",
        "rows_per_cell",
        "choice_memory_bits",
        "record_memory_bits",
        "record_queue_bits",
        "row_memory_bits",
        "median_line_buffers",
        "depth_table_bits",
        "dp16kd_instances",
        "dsp_blocks",
    ] {
        assert!(v["resources"].get(key).is_some(), "no resources.{key}");
    }
    // The frame time is (H + vertical blanking) × period / F, and the
    // latency the sum of the stages', by the numbers the object gives.
    let (h, p, f) = (v["height"].as_f64().unwrap(), v["line_period_cycles"].as_f64().unwrap(), v["clock_mhz"].as_f64().unwrap());
    let vb = v["vblank_lines"].as_f64().unwrap();
    assert!((v["frame_time_ms"].as_f64().unwrap() - (h + vb) * p / (f * 1e3)).abs() < 1e-9);
    let sum: u64 = stages.iter().map(|s| s["latency_cycles"].as_u64().unwrap()).sum();
    assert_eq!(v["latency_cycles"].as_u64(), Some(sum));
    assert_eq!(v["hblank"].as_u64(), Some(100));
    assert!(v.get("not_included").is_none(), "every stage is in");
}

#[test]
fn cli_text_names_every_stage_and_the_frame_end() {
    let o = declivity(&with("--width", "1024").iter().map(|s| s.as_str()).collect::<Vec<_>>());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for says in [
        "declivity detector",
        "record queues",
        "matcher",
        "row check",
        "interpolator",
        "vertical median",
        "depth stage",
        "line period",
        "latency",
        "flush",
        "vertical blanking",
        "frames/s",
        "DP16KD",
        "MULT18X18D",
        "W_MAX = 1024",
    ] {
        assert!(out.contains(says), "does not say `{says}`:\n{out}");
    }
}

#[test]
fn cli_help_explains_every_option() {
    let o = declivity(&["budget", "--help"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    for opt in ["--width", "--height", "--n-max", "--dispmax", "--clock-mhz", "--hblank", "--cells", "--json"] {
        assert!(out.contains(opt), "--help does not explain {opt}");
    }
    for says in ["line period", "latency", "record queues", "row check", "interpolator", "vertical median", "depth stage", "vertical blanking", "worst line"] {
        assert!(out.contains(says), "--help does not say `{says}`");
    }
}

