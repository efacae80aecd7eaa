//! The `declivity` binary as a user meets it: the main job, `depth`, `eval`,
//! `rtl detect`, `rtl match`, `verilog`, and clear errors with a non-zero
//! exit on bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use image::{GrayImage, Luma, Rgb, RgbImage};

fn declivity(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_declivity")).args(args).current_dir(cwd).output().expect("the binary runs")
}

fn text(o: &Output) -> (String, String) {
    (String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
}

fn stereo() -> PathBuf {
    sim::eval::io::stereo_data_dir()
}

/// A textured grey image and the same shifted left by `d` pixels (so the
/// disparity is `d` everywhere away from the border).
fn shifted_pair(w: u32, h: u32, d: u32) -> (GrayImage, GrayImage) {
    let tex = |x: u32, y: u32| -> u8 {
        let v = ((x / 5) * 37 + (y / 7) * 11) % 7;
        (40 + v * 30) as u8
    };
    let left = GrayImage::from_fn(w, h, |x, y| Luma([tex(x, y)]));
    let right = GrayImage::from_fn(w, h, |x, y| Luma([tex(x + d, y)]));
    (left, right)
}

/// A temporary folder holding `l.png` and `r.png`, the [`shifted_pair`] of these sizes.
fn pair_dir(w: u32, h: u32, d: u32) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = shifted_pair(w, h, d);
    l.save(dir.path().join("l.png")).unwrap();
    r.save(dir.path().join("r.png")).unwrap();
    dir
}

#[test]
fn main_job_without_arguments_writes_the_bundled_pair_pictures_and_cites_it() {
    let dir = tempfile::tempdir().unwrap();
    let o = declivity(&[], dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    assert!(out.contains("Scharstein") && out.contains("Tsukuba"), "citation printed: {out}");
    let folder = dir.path().join("declivity-out/tsukuba");
    assert!(out.contains("declivity-out/tsukuba"), "names its folder: {out}");
    for f in ["disparity16.png", "disparity.png", "declivities_left.png", "declivities_right.png", "graph_line_144.png"] {
        assert!(folder.join(f).is_file(), "{f} written");
    }
    let d16 = image::open(folder.join("disparity16.png")).unwrap().into_luma16();
    assert_eq!(d16.dimensions(), (384, 288));
    // Tsukuba's ground truth lies in 5..14 px: most pixels of the paper
    // mode's map (more than 65 %) hold d x 16 with d in 5..=15.
    let in_range = d16.pixels().filter(|p| (5 * 16..=15 * 16).contains(&p[0])).count();
    assert!(in_range as f64 > 0.65 * (384.0 * 288.0), "{in_range} pixels in range");
}

#[test]
fn depth_on_a_shifted_pair_recovers_the_shift_and_writes_depth_and_point_cloud() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = shifted_pair(120, 16, 6);
    l.save(dir.path().join("l.png")).unwrap();
    r.save(dir.path().join("r.png")).unwrap();
    let o = declivity(
        &["depth", "l.png", "r.png", "--dispmax", "10", "--out", "out", "--focal-px", "500", "--baseline-m", "0.1", "--graph-line", "3"],
        dir.path(),
    );
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    let d16 = image::open(dir.path().join("out/disparity16.png")).unwrap().into_luma16();
    // d = 6 px -> 96 in the 16-bit map, at every pixel away from the right border.
    let centre = d16.get_pixel(60, 8)[0];
    assert_eq!(centre, 96);
    let depth = image::open(dir.path().join("out/depth_mm.png")).unwrap().into_luma16();
    // Z = f b / d = 500 * 0.1 / 6 m = 8333 mm.
    assert_eq!(depth.get_pixel(60, 8)[0], 8333);
    let ply = std::fs::read_to_string(dir.path().join("out/points.ply")).unwrap();
    assert!(ply.starts_with("ply\nformat ascii 1.0"), "PLY header");
    assert!(dir.path().join("out/graph_line_3.png").is_file());
}

#[test]
fn colour_input_is_converted_with_a_note_not_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = shifted_pair(80, 8, 4);
    let colour = RgbImage::from_fn(80, 8, |x, y| {
        let v = l.get_pixel(x, y)[0];
        Rgb([v, v, v])
    });
    colour.save(dir.path().join("l.png")).unwrap();
    r.save(dir.path().join("r.png")).unwrap();
    let o = declivity(&["depth", "l.png", "r.png", "--dispmax", "8", "--out", "o"], dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    assert!(err.contains("note:") && err.contains("converted to grey"), "stderr {err}");
}

#[test]
fn bad_inputs_fail_with_a_clear_message_and_a_nonzero_exit() {
    let dir = pair_dir(60, 10, 3);
    let p = dir.path();
    GrayImage::new(50, 10).save(p.join("small.png")).unwrap();
    std::fs::write(p.join("junk.png"), b"not an image").unwrap();
    std::fs::create_dir(p.join("empty")).unwrap();
    let (wl, wr) = shifted_pair(1100, 10, 3);
    wl.save(p.join("wide_l.png")).unwrap();
    wr.save(p.join("wide_r.png")).unwrap();
    let cases: &[(&[&str], &str)] = &[
        // Lines wider than the configuration's W_MAX: refused, the one that takes them named.
        (&["budget", "--width", "1920", "--height", "1080", "--n-max", "128", "--dispmax", "64", "--clock-mhz", "148.5"], "--config hd"),
        (&["budget", "--config", "hd", "--width", "2100", "--height", "1080", "--n-max", "128", "--dispmax", "64", "--clock-mhz", "148.5"], "no configuration takes lines this wide"),
        (&["rtl", "depth", "wide_l.png", "wide_r.png", "--dispmax", "8", "--engine", "icarus"], "--config hd"),
        (&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--config", "hd", "--engine", "rust-hdl"], "sd configuration's model only"),
        (&["verilog", "--config", "hd", "--top", "matcher", "--cells", "128"], "hd matcher is generated with [2, 4, 8, 16, 32, 64] cells"),
        (&["synth", "--top", "detector", "--speed", "5"], "not an ECP5 speed grade"),
        (&["depth", "missing.png", "r.png", "--dispmax", "8"], "missing.png"),
        (&["depth", "junk.png", "r.png", "--dispmax", "8"], "cannot read image"),
        (&["depth", "l.png", "small.png", "--dispmax", "8"], "differ in size"),
        (&["depth", "l.png", "r.png", "--dispmax", "1"], "dispmax must be greater than 1"),
        (&["eval", "empty"], "nothing to evaluate"),
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--graph-line", "10"], "outside the image"),
        // The sensor's array is 32 cells of four rows; 64 is not generated.
        (&["verilog", "--top", "matcher", "--cells", "64"], "generated with [2, 4, 8, 16, 32] cells"),
        // A camera of no size, or of a NaN baseline, has no depth.
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--focal-px", "0", "--baseline-m", "0.16"], "finite number greater than 0"),
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--focal-px=-5", "--baseline-m", "0.16"], "finite number greater than 0"),
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--focal-px", "500", "--baseline-m", "nan"], "finite number greater than 0"),
        // Eq. 6's lower bound below the upper one, and on the positions' grid
        // where the line processor takes it.
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--dispmin", "7.5"], "dispmin must be at least 0 and less than dispmax"),
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--dispmin", "2.03", "--hardware-parity"], "multiple of 1/16"),
        (&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--dispmin", "2.03"], "multiple of 1/16"),
        (&["rtl", "match", "l.png", "r.png", "--dispmax", "8", "--dispmin", "7"], "dispmin must be at least 0 and less than dispmax"),
        (&["depth", "l.png", "r.png", "--dispmax", "8", "--dispmin=-1"], "0 or more"),
        // No silent defaults: zero runs, and options --rtl does not use.
        (&["eval", "--runs", "0", "empty"], "--runs"),
        (&["eval", "--rtl", "--out", "o", "empty"], "cannot be used with"),
        (&["eval", "--rtl", "--mode", "paper", "empty"], "cannot be used with"),
        (&["eval", "--rtl", "--diagnose", "empty"], "cannot be used with"),
        // Blanking the simulation could never run through.
        (&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--hblank", "4000000000"], "--hblank"),
        // An output folder that cannot be made, refused before the simulation.
        (&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--engine", "rust-hdl", "--out", "/proc/x"], "/proc/x"),
        (&["verilog", "--top", "stereo", "--out", "/proc/x"], "/proc/x"),
    ];
    for &(args, needle) in cases {
        let o = declivity(args, p);
        let (_, err) = text(&o);
        assert!(!o.status.success(), "{args:?} must fail");
        assert!(err.contains("error:") && err.contains(needle), "{args:?}: stderr {err:?} lacks {needle:?}");
    }
}

/// A pair folder in `dir/name`: `left` and `right`, a ground truth of `d`
/// px everywhere (scale 16) and `meta.txt` with `dispmax`.
fn pair_folder(dir: &Path, name: &str, left: &GrayImage, right: &GrayImage, d: u8, dispmax: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::create_dir_all(&p).unwrap();
    left.save(p.join("left_gray.png")).unwrap();
    right.save(p.join("right_gray.png")).unwrap();
    GrayImage::from_pixel(left.width(), left.height(), Luma([d * 16])).save(p.join("disp_gt.png")).unwrap();
    std::fs::write(p.join("meta.txt"), format!("scale: 16\ndispmax: {dispmax}\n")).unwrap();
    p
}

/// `meta.txt` numbers keep their sign: a negative `dispmax` is refused, not
/// read as positive.
#[test]
fn eval_refuses_a_negative_dispmax_in_meta_txt_and_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = shifted_pair(60, 10, 3);
    pair_folder(dir.path(), "neg", &l, &r, 3, "-3");
    let o = declivity(&["eval", "neg"], dir.path());
    let (_, err) = text(&o);
    assert!(!o.status.success(), "accepted: {err}");
    assert!(err.contains("meta.txt") && err.contains("must be positive (got -3)"), "stderr {err}");
}

/// A folder with one bad pair: the good pairs are still scored and printed,
/// the bad one is named, and the exit is non-zero.
#[test]
fn eval_scores_the_good_pairs_of_a_folder_and_names_the_bad_one() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = shifted_pair(120, 12, 4);
    pair_folder(&dir.path().join("all"), "a_good", &l, &r, 4, "8");
    pair_folder(&dir.path().join("all"), "c_good", &l, &r, 4, "8");
    let bad = dir.path().join("all/b_bad");
    std::fs::create_dir_all(&bad).unwrap();
    std::fs::write(bad.join("meta.txt"), "scale: 16\ndispmax: 8\n").unwrap();
    for json in [false, true] {
        let args: &[&str] = if json { &["eval", "--runs", "1", "--json", "all"] } else { &["eval", "--runs", "1", "all"] };
        let o = declivity(args, dir.path());
        let (out, err) = text(&o);
        assert!(!o.status.success(), "{args:?}: a bad pair must fail the run");
        assert!(out.contains("a_good") && out.contains("c_good"), "{args:?}: the good pairs are reported: {out}");
        assert!(err.contains("b_bad") && err.contains("has no left_gray.png") && err.contains("1 of 3 pairs"), "{args:?}: stderr {err}");
    }
}

/// `sparse_acc1` is undefined without a match: `null` in JSON, a dash in
/// the table, never 0.
#[test]
fn eval_gives_no_sparse_accuracy_for_a_pair_without_matches() {
    let dir = tempfile::tempdir().unwrap();
    let flat = GrayImage::from_pixel(60, 10, Luma([120]));
    pair_folder(dir.path(), "flat", &flat, &flat, 3, "8");
    let o = declivity(&["eval", "--runs", "1", "--json", "flat"], dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "stderr {err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["matches"], 0, "{v}");
    assert!(v["sparse_acc1"].is_null(), "{v}");
    let o = declivity(&["eval", "--runs", "1", "flat"], dir.path());
    let (out, _) = text(&o);
    let row = out.lines().find(|l| l.starts_with("| flat")).expect("a row for the pair");
    assert_eq!(row.split('|').nth(7).map(str::trim), Some("—"), "sparse_acc1 column: {row}");
}

#[test]
fn eval_json_has_the_documented_keys_per_pair() {
    let o = declivity(&["eval", "--json", "--runs", "1", stereo().join("tsukuba").to_str().unwrap()], Path::new("."));
    let (out, err) = text(&o);
    assert!(o.status.success(), "stderr {err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1, "one object per pair: {out}");
    let v: serde_json::Value = serde_json::from_str(lines[0]).unwrap();
    for k in [
        "pair", "mode", "width", "height", "declivities", "matches", "match_frac", "sparse_acc1", "bad1", "bad2", "bad1v", "bad2v", "density",
        "nonocc_bad2", "ms",
    ] {
        assert!(v.get(k).is_some(), "key {k} in {v}");
    }
    assert_eq!(v["pair"], "tsukuba");
    assert_eq!(v["mode"], "robust", "the default mode");
    assert!(v["nonocc_bad2"].is_number(), "tsukuba has a mask");
}

#[test]
fn eval_json_gives_null_nonocc_without_a_mask() {
    let o = declivity(&["eval", "--json", "--runs", "1", "--mode", "paper", stereo().join("map").to_str().unwrap()], Path::new("."));
    let (out, err) = text(&o);
    assert!(o.status.success(), "stderr {err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert!(v["nonocc_bad2"].is_null(), "{v}");
    assert_eq!(v["mode"], "paper");
}

#[test]
fn every_subcommand_explains_itself_in_help() {
    for args in [
        &["--help"][..],
        &["depth", "--help"],
        &["eval", "--help"],
        &["rtl", "detect", "--help"],
        &["rtl", "match", "--help"],
        &["rtl", "faults", "--help"],
        &["verilog", "--help"],
        &["synth", "--help"],
    ] {
        let o = declivity(args, Path::new("."));
        let (out, _) = text(&o);
        assert!(o.status.success());
        assert!(out.contains("Usage:") && out.len() > 400, "{args:?}: {out}");
    }
}

fn bundled_left() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/stereo/tsukuba/left_gray.png")
}

#[test]
fn rtl_detect_json_reports_agreement_throughput_and_writes_the_overlay_and_waveform() {
    let dir = tempfile::tempdir().unwrap();
    let left = bundled_left();
    let o = declivity(
        &["rtl", "detect", left.to_str().unwrap(), "--json", "--out", "o", "--vcd", "w.vcd", "--lines", "10..11"],
        dir.path(),
    );
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    for key in [
        "lines",
        "pixels",
        "cycles",
        "px_per_clk",
        "declivities_rtl",
        "declivities_golden",
        "borderline",
        "mismatches",
        "max_pos_err_lsb",
        "sim_cycles_per_s",
    ] {
        assert!(v.get(key).is_some(), "{key} in {out}");
    }
    assert_eq!(v["lines"], 288);
    assert_eq!(v["pixels"], 384 * 288);
    assert_eq!(v["mismatches"], 0, "{out}");
    assert_eq!(v["px_per_clk"], 1.0, "{out}");
    // The records are golden's hardware parity's, every one.
    let (rtl, gold) = (v["declivities_rtl"].as_u64().unwrap(), v["declivities_golden"].as_u64().unwrap());
    assert!(rtl > 10_000 && rtl == gold, "{out}");
    assert_eq!(v["borderline"], 0, "{out}");
    assert_eq!(v["max_pos_err_lsb"].as_f64(), Some(0.0), "{out}");
    assert_eq!(v["max_dt_err_lsb"].as_f64(), Some(0.0), "{out}");
    // The image streams in `pixels` clocks; the last line's records follow
    // within one marker latency.
    let cycles = v["cycles"].as_u64().unwrap();
    assert!(cycles > 384 * 288 && cycles < 384 * 288 + 2000, "{cycles}");
    let overlay = image::open(dir.path().join("o/declivities_rtl.png")).unwrap();
    assert_eq!((overlay.width(), overlay.height()), (384, 288));
    let vcd = std::fs::read_to_string(dir.path().join("w.vcd")).unwrap();
    assert!(vcd.contains("$var") && vcd.contains("s_tdata") && vcd.contains("#"), "a VCD with the ports");
}

/// `--config hd` runs `rtl-hd`'s detector: a line wider than `sd`'s W_MAX
/// (1 024 px) comes out whole there, while `sd` keeps its first 1 024 pixels,
/// marks it wide and says which configuration takes it.
#[test]
fn rtl_detect_config_hd_takes_lines_sd_cuts_and_sd_says_so() {
    let dir = tempfile::tempdir().unwrap();
    // Tsukuba's rows three times side by side: 1 152 px.
    let t = image::open(bundled_left()).unwrap().to_luma8();
    let wide = image::GrayImage::from_fn(3 * t.width(), 40, |x, y| *t.get_pixel(x % t.width(), y + 100));
    let path = dir.path().join("wide.png");
    wide.save(&path).unwrap();
    let run = |config: &str| {
        let o = declivity(&["rtl", "detect", path.to_str().unwrap(), "--json", "--out", "o", "--config", config], dir.path());
        let (out, err) = text(&o);
        assert!(o.status.success(), "stdout {out}\nstderr {err}");
        (serde_json::from_str::<serde_json::Value>(out.trim()).expect("one JSON object"), err)
    };
    let (hd, hd_err) = run("hd");
    assert_eq!(hd["config"], "hd", "{hd}");
    assert_eq!((hd["mismatches"].as_u64(), hd["wide_lines"].as_u64()), (Some(0), Some(0)), "{hd}");
    assert!(!hd_err.contains("wider"), "{hd_err}");
    let (sd, sd_err) = run("sd");
    assert_eq!(sd["config"], "sd", "{sd}");
    assert_eq!((sd["mismatches"].as_u64(), sd["wide_lines"].as_u64()), (Some(0), Some(40)), "{sd}");
    assert!(sd_err.contains("wider than the sd detector's W_MAX = 1024") && sd_err.contains("--config hd"), "{sd_err}");
    // The first 1 024 pixels hold fewer declivities than the whole lines.
    assert!(sd["declivities_rtl"].as_u64() < hd["declivities_rtl"].as_u64(), "{sd}\n{hd}");
}

#[test]
fn rtl_detect_rejects_rows_outside_the_image_and_unreadable_files() {
    let dir = tempfile::tempdir().unwrap();
    let left = bundled_left();
    let o = declivity(&["rtl", "detect", left.to_str().unwrap(), "--vcd", "w.vcd", "--lines", "280..300"], dir.path());
    let (_, err) = text(&o);
    assert!(!o.status.success());
    assert!(err.contains("280..300") && err.contains("288 rows"), "{err}");
    std::fs::write(dir.path().join("bad.png"), b"not a png").unwrap();
    let o = declivity(&["rtl", "detect", "bad.png"], dir.path());
    let (_, err) = text(&o);
    assert!(!o.status.success());
    assert!(err.contains("bad.png"), "{err}");
    let o = declivity(&["rtl", "detect", left.to_str().unwrap(), "--lines", "5..2", "--vcd", "w.vcd"], dir.path());
    assert!(!o.status.success());
    assert!(text(&o).1.contains("empty"), "{}", text(&o).1);
}

/// The depth stage is generated for the camera asked for: `rtl depth` reports it, its depths
/// equal golden's for that camera, and each is eq. 1's `f·b/d` of its own disparity within the
/// datasheet's bound (½ + Z·2⁻¹⁵ mm).
#[test]
fn rtl_depth_runs_the_depth_stage_generated_for_the_camera_asked_and_reports_it() {
    let dir = pair_dir(40, 3, 4);
    let p = dir.path();
    let (focal_px, baseline_m) = (500.0, 0.1);
    let o = declivity(
        &["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--engine", "rust-hdl", "--focal-px", "500", "--baseline-m", "0.1", "--json", "--out", "o"],
        p,
    );
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    assert_eq!((v["camera"]["focal_px"].as_f64(), v["camera"]["baseline_mm"].as_f64()), (Some(focal_px), Some(baseline_m * 1000.0)), "{out}");
    assert_eq!(v["exact_depth_px"].as_f64(), Some(1.0), "{out}");
    let word = image::open(p.join("o/disparity16_rtl.png")).unwrap().into_luma16();
    let depth = image::open(p.join("o/depth_mm_rtl.png")).unwrap().into_luma16();
    let mut checked = 0;
    for (w, z) in word.pixels().zip(depth.pixels()) {
        if w[0] == 0 {
            assert_eq!(z[0], 0, "no disparity, no depth");
            continue;
        }
        let eq1 = focal_px * baseline_m * 1000.0 / (w[0] as f64 / 16.0);
        assert!((z[0] as f64 - eq1).abs() <= 0.5 + eq1 / 32768.0, "d = {} px: depth {} mm, eq. 1 gives {eq1:.1}", w[0] as f64 / 16.0, z[0]);
        checked += 1;
    }
    assert!(checked > 40, "only {checked} pixels with a disparity");
    // The text report names the camera.
    let o = declivity(&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--engine", "rust-hdl", "--rows", "0..1", "--focal-px", "500", "--baseline-m", "0.1", "--out", "o"], p);
    let (out, err) = text(&o);
    assert!(o.status.success() && out.contains("focal length 500 px, baseline 100 mm"), "stdout {out}\nstderr {err}");
}

/// `verilog --top stereo` generates the depth stage for the camera asked for and records it;
/// other blocks, and a camera whose depths 16 bits cannot hold, are refused before generation.
#[test]
fn verilog_generates_the_stereo_top_for_the_camera_asked_and_refuses_what_does_not_apply() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let o = declivity(&["verilog", "--top", "stereo", "--cells", "2", "--focal-px", "500", "--baseline-m", "0.1", "--out", "st"], p);
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    assert!(out.contains("focal length 500 px, baseline 100 mm"), "{out}");
    let readme = std::fs::read_to_string(p.join("st/README.md")).unwrap();
    assert!(readme.contains("--focal-px 500 --baseline-m 0.1") && readme.contains("focal length 500 px, baseline 100 mm"), "{readme}");
    for (args, needle) in [
        (&["verilog", "--top", "detector", "--focal-px", "500", "--baseline-m", "0.1"][..], "apply to --top stereo only"),
        (&["verilog", "--top", "stereo", "--focal-px", "500"], "--baseline-m"),
        // f·b = 1 px·mm: the farthest depths would round under 1 mm.
        (&["verilog", "--top", "stereo", "--focal-px", "1", "--baseline-m", "0.001"], "depth stage's camera"),
        (&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--focal-px", "1", "--baseline-m", "0.001"], "depth stage's camera"),
    ] {
        let o = declivity(args, p);
        let (_, err) = text(&o);
        assert!(!o.status.success() && err.contains(needle), "{args:?}: stderr {err:?} lacks {needle:?}");
    }
}

#[test]
fn verilog_command_writes_the_detectors_ip_folder_with_its_ports_and_models() {
    let dir = tempfile::tempdir().unwrap();
    // A position has 4 fraction bits below the line's index: 14 bits in sd (W_MAX 1024), 15 in hd (2048).
    for (config, pos) in [("sd", "output reg  [13:0] m_pos"), ("hd", "output reg  [14:0] m_pos")] {
        let out_dir = format!("v-{config}");
        let o = declivity(&["verilog", "--top", "detector", "--config", config, "--out", &out_dir], dir.path());
        let (out, err) = text(&o);
        assert!(o.status.success(), "stdout {out}\nstderr {err}");
        let ip = dir.path().join(&out_dir);
        let v = std::fs::read_to_string(ip.join("declivity_detector.v")).unwrap();
        assert!(v.contains("module declivity_detector(") && !v.contains("module top"));
        // The primitives it instantiates have their models beside it, and the lists name them.
        for f in ["sim_models/DP16KD.v", "sim_models/MULT18X18D.v", "declivity_detector.f", "declivity_detector.core", "README.md"] {
            assert!(ip.join(f).is_file(), "{config}: {f}");
            assert!(out.contains(f), "{config}: {f} not reported in {out}");
        }
        assert!(!ip.join("sim_models/TRELLIS_DPR16X4.v").exists(), "{config}: the detector has no LUT RAM");
        let readme = std::fs::read_to_string(ip.join("README.md")).unwrap();
        assert!(readme.contains(&format!("--config {config}")), "{readme}");
        for port in ["s_tdata", "s_tvalid", "s_tuser", "s_tlast", "s_tready", "m_valid", "m_last", "m_pos", "m_dt"] {
            assert!(v.contains(port), "{config}: {port}");
        }
        assert!(v.contains(pos), "{config}: {pos}");
    }
}

#[test]
fn budget_json_names_the_configuration_and_its_sizes() {
    let dir = tempfile::tempdir().unwrap();
    for (config, w_max, n_max, cells) in [("sd", 1024, 128, 32), ("hd", 2048, 256, 64)] {
        let o = declivity(&["budget", "--config", config, "--width", "1000", "--height", "720", "--n-max", "100", "--dispmax", "64", "--clock-mhz", "125", "--json"], dir.path());
        let (out, err) = text(&o);
        assert!(o.status.success(), "stdout {out}\nstderr {err}");
        let j: serde_json::Value = serde_json::from_str(&out).expect("one JSON object");
        assert_eq!(j["config"], config);
        assert_eq!((j["hardware"]["w_max"].as_u64(), j["hardware"]["n_max"].as_u64(), j["hardware"]["cells"].as_u64()), (Some(w_max), Some(n_max), Some(cells)));
        assert_eq!(j["cells"].as_u64(), Some(cells), "{config}: the sensor's array by default");
    }
}

/// Left and right images of the Tsukuba pair in data/stereo.
fn tsukuba_pair() -> (String, String) {
    let dir = stereo().join("tsukuba");
    let path = |f: &str| dir.join(f).to_str().unwrap().to_string();
    (path("left_gray.png"), path("right_gray.png"))
}

#[test]
fn rtl_match_json_on_a_few_rows_agrees_with_golden_and_draws_the_graph() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = tsukuba_pair();
    let o = declivity(&["rtl", "match", &l, &r, "--dispmax", "16", "--rows", "140..144", "--json", "--out", "o"], dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    for key in [
        "lines",
        "matches_rtl",
        "matches_golden",
        "identical_lines",
        "equal_gain_lines",
        "mismatch_lines",
        "malformed_lines",
        "off_schedule_lines",
        "max_cycles_per_line",
        "max_cycles_line",
        "max_engine_period",
        "cycles",
        "sim_cycles_per_s",
        "rule",
        "dispmax",
        "rows",
        "graph",
    ] {
        assert!(v.get(key).is_some(), "{key} in {out}");
    }
    assert_eq!(v["lines"], 4);
    assert_eq!(v["identical_lines"], 4, "{out}");
    assert_eq!(v["mismatch_lines"], 0, "{out}");
    assert_eq!(v["malformed_lines"], 0, "{out}");
    assert_eq!(v["off_schedule_lines"], 0, "every marker on rtl::matcher::declivity_matcher::schedule: {out}");
    assert!(v["max_engine_period"].as_u64().unwrap() > 0, "{out}");
    assert_eq!(v["rule"], "robust", "the default rule");
    assert_eq!(v["dispmax"], 16.0);
    assert_eq!(v["rows"], serde_json::json!([140, 144]));
    assert_eq!(v["matches_rtl"], v["matches_golden"]);
    assert!(v["matches_rtl"].as_u64().unwrap() > 40, "tsukuba's rows have tens of matches: {out}");
    let row = v["max_cycles_line"].as_u64().unwrap();
    assert!((140..144).contains(&row), "an image row: {out}");
    assert!(v["max_cycles_per_line"].as_u64().unwrap() > 0 && v["sim_cycles_per_s"].as_f64().unwrap() > 0.0);
    // The default graph line is the middle of the rows run.
    let graph = dir.path().join("o/graph_rtl_line_142.png");
    assert!(v["graph"].as_str().unwrap().ends_with("graph_rtl_line_142.png"), "{out}");
    let img = image::open(&graph).expect("the matching graph is written").into_rgb8();
    assert!(img.width() > 200 && img.height() > 200);
    // Both paths are drawn: golden's rings (green) and the rtl boxes (orange).
    assert!(img.pixels().any(|p| p.0 == [0, 255, 0]) && img.pixels().any(|p| p.0 == [255, 150, 0]));

    // The same rows on the hd configuration's matcher: its 64 cells, the
    // same paths (no tsukuba row has more than sd's 128 declivities).
    let o = declivity(&["rtl", "match", &l, &r, "--dispmax", "16", "--rows", "140..142", "--json", "--out", "o", "--config", "hd"], dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    let h: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    assert_eq!((h["config"].as_str(), h["cells"].as_u64()), (Some("hd"), Some(64)), "{out}");
    assert_eq!(v["config"], "sd", "the default configuration");
    assert_eq!((h["identical_lines"].as_u64(), h["off_schedule_lines"].as_u64()), (Some(2), Some(0)), "{out}");
}

#[test]
fn rtl_match_text_summary_and_graph_line() {
    let dir = tempfile::tempdir().unwrap();
    let (l, r) = tsukuba_pair();
    let o = declivity(&["rtl", "match", &l, &r, "--dispmax", "15.5", "--rows", "10..12", "--graph-line", "10", "--rule", "paper"], dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    assert!(out.contains("identical lines     2 of 2") && out.contains("paper rule"), "{out}");
    assert!(out.contains("off-schedule lines  0") && out.contains("max engine period"), "{out}");
    assert!(dir.path().join("declivity-out/rtl-match-left_gray/graph_rtl_line_10.png").is_file(), "{out}");
}

#[test]
fn rtl_match_rejects_bad_inputs_with_a_clear_message() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let (l, r) = tsukuba_pair();
    std::fs::write(p.join("bad.png"), b"not a png").unwrap();
    GrayImage::new(50, 10).save(p.join("small.png")).unwrap();
    let cases: [(&[&str], &str); 10] = [
        (&["rtl", "match", &l, &r, "--dispmax", "16", "--rows", "280..300"], "280..300"),
        (&["rtl", "match", &l, &r, "--dispmax", "16", "--rows", "5..2"], "empty"),
        (&["rtl", "match", &l, &r, "--dispmax", "16", "--rows", "5..8", "--graph-line", "9"], "outside the rows run"),
        (&["rtl", "match", &l, &r, "--dispmax", "1"], "greater than 1"),
        (&["rtl", "match", &l, &r, "--dispmax", "nan"], "greater than 1"),
        (&["rtl", "match", &l, &r, "--dispmax", "inf"], "greater than 1"),
        (&["rtl", "match", &l, &r, "--dispmax", "2000"], "at most W_MAX"),
        (&["rtl", "match", &l, &r, "--dispmax", "10.3"], "multiple of 1/16"),
        (&["rtl", "match", "bad.png", &r, "--dispmax", "16"], "bad.png"),
        (&["rtl", "match", &l, "small.png", "--dispmax", "16"], "differ in size"),
    ];
    for (args, needle) in cases {
        let o = declivity(args, p);
        let (_, err) = text(&o);
        assert!(!o.status.success(), "{args:?} must fail");
        assert!(err.contains(needle), "{args:?}: stderr {err:?} lacks {needle:?}");
    }
}

#[test]
fn rtl_depth_writes_a_waveform_from_the_first_pixel_in_to_the_traced_row_out() {
    let dir = pair_dir(40, 3, 4);
    let p = dir.path();
    let o = declivity(&["rtl", "depth", "l.png", "r.png", "--dispmax", "8", "--vcd", "w.vcd", "--lines", "0..1", "--json", "--out", "o"], p);
    let (out, err) = text(&o);
    assert!(o.status.success(), "stdout {out}\nstderr {err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    assert_eq!(v["lines_out"], 3, "{out}");
    let vcd = std::fs::read_to_string(p.join("w.vcd")).expect("the waveform");
    let times: Vec<u64> = vcd.lines().filter_map(|l| l.strip_prefix('#')).map(|t| t.parse().expect("a timestamp")).collect();
    assert_eq!(times.first(), Some(&0), "row 0's first pixel enters on clock 0");
    let first_out = v["latency_cycles"].as_u64().expect("a disparity came out");
    let last = *times.last().expect("clocks were recorded");
    assert!(last / 10 >= first_out + 39, "the trace ends at clock {} before row 0's 40 outputs from clock {first_out} left", last / 10);
    let m_tvalid = vcd.lines().find(|l| l.ends_with(" m_tvalid $end")).and_then(|l| l.split_whitespace().nth(3)).expect("m_tvalid is traced").to_string();
    assert!(vcd.lines().any(|l| l == format!("1{m_tvalid}")), "m_tvalid rises in the trace");
}

#[test]
fn rtl_depth_rejects_a_waveform_outside_the_rows_or_from_verilator() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let (l, r) = tsukuba_pair();
    let cases: [(&[&str], &str); 3] = [
        (&["rtl", "depth", &l, &r, "--dispmax", "16", "--rows", "100..104", "--vcd", "w.vcd", "--lines", "3..6"], "not rows of the frame run"),
        (&["rtl", "depth", &l, &r, "--dispmax", "16", "--rows", "100..104", "--vcd", "w.vcd", "--lines", "0..1", "--engine", "verilator"], "rust-hdl engine only"),
        (&["rtl", "depth", &l, &r, "--dispmax", "16", "--vcd", "w.vcd"], "--lines"),
    ];
    for (args, needle) in cases {
        let o = declivity(args, p);
        let (_, err) = text(&o);
        assert!(!o.status.success(), "{args:?} must fail");
        assert!(err.contains(needle), "{args:?}: stderr {err:?} lacks {needle:?}");
    }
}

/// `rtl faults` refuses what it cannot run before it simulates: an unknown
/// class, frames wider than `W_MAX`, a vertical gap within the skew at which
/// the core pairs frame starts, an unreadable pair folder; and a short
/// campaign reports, in JSON, every class it injected and no invariant
/// broken (the full one: the datasheet's Verification).
#[test]
fn rtl_faults_refuses_bad_campaigns_and_a_short_one_keeps_every_invariant() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    let cases: [(&[&str], &str); 5] = [
        (&["rtl", "faults", "--classes", "short_frame,late_frame"], "no class of fault `late_frame`"),
        (&["rtl", "faults", "--width", "1025"], "1 to 1024 px wide"),
        (&["rtl", "faults", "--height", "1"], "2 to 2047 rows"),
        (&["rtl", "faults", "--gap-lines", "6"], "SOF_SKEW_MAX = 2048"),
        (&["rtl", "faults", "--pairs", "nowhere"], "nowhere"),
    ];
    for (args, needle) in cases {
        let o = declivity(args, p);
        let (_, err) = text(&o);
        assert!(!o.status.success(), "{args:?} must fail");
        assert!(err.contains(needle), "{args:?}: stderr {err:?} lacks {needle:?}");
    }
    let o = declivity(&["rtl", "faults", "--frames", "12", "--seed", "3", "--json"], p);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    assert_eq!(v["faulty_frames"], 12);
    let injected = v["injected"].as_object().expect("injected per class");
    assert!(!injected.is_empty() && injected.values().all(|n| n.as_u64().unwrap_or(0) > 0), "{injected:?}");
    assert_eq!(v["violations"].as_array().map(Vec::len), Some(0), "{out}");
    assert_eq!(v["clean_exact"], v["clean_frames"], "{out}");
    assert!(v["clean_frames"].as_u64().unwrap_or(0) >= 12, "{out}");
}
