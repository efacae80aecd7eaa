//! `declivity rtl depth` and `eval --rtl`: a pair through the whole line
//! processor, clock by clock, on the fastest engine installed, compared with
//! golden and scored against ground truth.

use golden::GreyImage;
use rtl::params::N_CELLS;

use crate::config::{Config, Sizes};
use crate::drive::stereo::{golden_depth_map, golden_map, StereoSim};
use crate::error::SimError;
use crate::eval::io::PairData;
use crate::eval::scores::{agree_quarter_px, dense_scores, exact_share};
use crate::formats::SearchArea;
use crate::hdl::cosim::{Options, Simulator};
use crate::hdl::frame::run_frame;
use crate::hdl::verilog::{check_camera, generate_block, CameraReport, Generation, Top};
use rtl::post::depth_stage::DepthCamera;

/// What `declivity rtl depth` reports on a pair (one JSON object).
#[derive(Debug, Clone, serde::Serialize)]
pub struct StereoReport {
    /// The left image (or the pair's name).
    pub image: String,
    /// The configuration run, and its sizes (`W_MAX`, `N_MAX`, cells).
    pub config: Config,
    pub hardware: Sizes,
    pub width: usize,
    pub height: usize,
    /// Eq. 6's area `dispmin < d < dispmax`, px.
    pub dispmin: f64,
    pub dispmax: f64,
    /// Idle clocks after each line of the cameras.
    pub hblank: usize,
    /// The camera the depth stage was generated for (eq. 1's `f/p` and `b`).
    pub camera: CameraReport,
    /// Pixels taken from the left camera.
    pub pixels: u64,
    /// Clocks simulated (until the last line left).
    pub cycles: u64,
    /// Left pixels per clock while the cameras sent the frame.
    pub px_per_clk: f64,
    /// Clocks a camera offered a pixel and was not ready.
    pub stall_cycles: u64,
    /// First pixel in to first disparity out.
    pub latency_cycles: Option<u64>,
    /// Share of pixels within 1/4 px of golden (hardware parity, the same
    /// stages).
    pub agree_quarter_px: f64,
    /// Share of pixels whose disparity equals golden hardware parity's
    /// exactly (both in 1/16 px).
    pub exact_px: f64,
    /// Share of pixels whose depth (mm) equals golden hardware parity's
    /// depth of its own disparity exactly (the same camera).
    pub exact_depth_px: f64,
    /// Clocks simulated per second of wall time (the build excluded).
    pub sim_cycles_per_s: f64,
    pub seconds: f64,
    /// What simulated the line processor: `rust-hdl` (the model itself),
    /// `verilator` or `icarus` (its generated Verilog).
    pub engine: &'static str,
    /// Building the simulator (Verilator's build or Icarus's compile; 0 for
    /// the model, and for a cached Verilator build).
    pub build_seconds: f64,
    /// Lines that came out.
    pub lines_out: usize,
    pub records_dropped: u64,
    pub lines_dropped: u64,
    pub pixels_dropped: u64,
    pub lines_full: u64,
    pub lines_wide: u64,
    pub lines_unpaired: u64,
    /// The most lines in flight between the matcher's input and the
    /// interpolator's output (at most `LINES_IN_FLIGHT`), and the clocks
    /// on which that limit held the reference queue back: probed inside the
    /// rust-hdl model, `null` from the Verilog engines.
    pub lines_in_flight_peak: Option<u64>,
    pub held_cycles: Option<u64>,
}

/// What runs the line processor clock by clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// The rust-hdl model under direct drive (no build; slow per clock:
    /// every clock settles the whole model with the 32-cell matcher).
    RustHdl,
    /// Its generated Verilog under Verilator, driven directly by a C++ `main`
    /// holding the same camera model (`sim::hdl::frame::frame_driver`):
    /// the fastest per clock, after a build of minutes, kept for later runs.
    Verilator,
    /// Its generated Verilog under Icarus Verilog (slow; a few lines).
    Icarus,
}

impl Engine {
    /// The fastest engine installed: Verilator when `verilator` is on the
    /// `PATH`, the rust-hdl model otherwise.
    pub fn fastest_installed() -> Engine {
        if crate::hdl::workdir::find_on_path("verilator").is_some() {
            Engine::Verilator
        } else {
            Engine::RustHdl
        }
    }

    /// The engine's name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Engine::RustHdl => "rust-hdl",
            Engine::Verilator => "verilator",
            Engine::Icarus => "icarus",
        }
    }
}

/// Runs a pair through `config`'s line processor (default mode:
/// `GainRule::Robust`, the edge jump; the depth stage generated for
/// `camera`) on `engine` (the
/// rust-hdl model is `sd`'s only) and compares with golden's hardware
/// parity in `config`
/// (with `vcd`, the rust-hdl engine writes a waveform of the frame's rows
/// in the range to the file, as [`StereoSim::trace_lines_to`]); returns the
/// report, the rtl's map and golden's (px, row-major, 0 = none) and the
/// rtl's depths (mm, row-major, 0 = none).
#[allow(clippy::too_many_arguments)]
fn run_pair(
    config: Config,
    name: &str,
    left: &GreyImage,
    right: &GreyImage,
    (dispmin, dispmax): (f64, f64),
    hblank: usize,
    camera: DepthCamera,
    engine: Engine,
    vcd: Option<(&std::path::Path, &std::ops::Range<usize>)>,
    progress: impl FnMut(usize),
) -> Result<(StereoReport, Vec<f64>, Vec<f64>, Vec<u16>), SimError> {
    let area = SearchArea::from_px(dispmin, dispmax, config)?;
    check_camera(config, &camera)?;
    let w_max = config.sizes().w_max;
    if left.width() > w_max {
        let hint = Config::fitting_hint(left.width());
        return Err(SimError::Argument(format!("{name}: lines of {} px are wider than the {config} hardware's W_MAX = {w_max} px; {hint}", left.width())));
    }
    if engine == Engine::RustHdl && config != Config::Sd {
        return Err(SimError::Argument(format!(
            "the rust-hdl engine runs the sd configuration's model only (a whole {config} frame takes hours under it); use --engine verilator or icarus"
        )));
    }
    if (left.width(), left.height()) != (right.width(), right.height()) {
        return Err(golden::GoldenError::SizeMismatch { left_w: left.width(), left_h: left.height(), right_w: right.width(), right_h: right.height() }.into());
    }
    if vcd.is_some() && engine != Engine::RustHdl {
        return Err(SimError::Argument(format!("a waveform (--vcd) is written by the rust-hdl engine only, not by {}", engine.name())));
    }
    let (run, seconds, build_seconds) = match engine {
        Engine::RustHdl => {
            let mut sim = StereoSim::<{ N_CELLS }>::new(rtl::matcher::declivity_matcher::GainRule::Robust, Some(rtl::params::EDGE_JUMP_LSB), camera, area.dispmax)
                .map_err(|e| SimError::Argument(format!("the depth stage's camera: {e}")))?;
            sim.dispmin = area.dispmin;
            if let Some((path, lines)) = vcd {
                sim.trace_lines_to(path, lines.clone()).map_err(|source| SimError::Io { path: path.to_path_buf(), source })?;
            }
            let t0 = std::time::Instant::now();
            let run = sim.run(left, right, hblank, progress);
            (run, t0.elapsed().as_secs_f64(), 0.0)
        }
        Engine::Verilator | Engine::Icarus => {
            let simulator = if engine == Engine::Verilator { Simulator::Verilator } else { Simulator::Icarus };
            let design = generate_block(config, Top::Stereo, &Generation { camera, ..Generation::of(config) })?;
            let frame = run_frame(simulator, config, &design, left, right, hblank, area, &Options::default())?;
            (frame.run, frame.sim.as_secs_f64(), frame.compile.as_secs_f64())
        }
    };
    let rtl = run.disparity_px(left.height());
    let gold = golden_map(left, right, dispmin, dispmax, config)?;
    let depth = run.depth_mm(left.height());
    let gold_depth = golden_depth_map(&gold, &camera, config);
    let report = StereoReport {
        image: name.to_string(),
        config,
        hardware: config.sizes(),
        width: left.width(),
        height: left.height(),
        dispmin,
        dispmax,
        hblank,
        camera: camera.into(),
        pixels: run.pixels_in,
        cycles: run.cycles,
        px_per_clk: run.px_per_clk(),
        stall_cycles: run.stall_cycles,
        latency_cycles: run.latency_cycles(),
        agree_quarter_px: agree_quarter_px(&rtl, &gold),
        exact_px: exact_share(&rtl, &gold),
        exact_depth_px: exact_share(&depth, &gold_depth),
        sim_cycles_per_s: run.cycles as f64 / seconds.max(1e-9),
        seconds,
        engine: engine.name(),
        build_seconds,
        lines_out: run.rows.len(),
        records_dropped: run.records_dropped,
        lines_dropped: run.lines_dropped,
        pixels_dropped: run.pixels_dropped,
        lines_full: run.lines_full,
        lines_wide: run.lines_wide,
        lines_unpaired: run.lines_unpaired,
        lines_in_flight_peak: (engine == Engine::RustHdl).then_some(run.probe.peak.in_flight),
        held_cycles: (engine == Engine::RustHdl).then_some(run.probe.peak.held_clocks),
    };
    Ok((report, rtl, gold, depth))
}

/// One pair through the line processor, scored against its ground truth:
/// the `eval --rtl --json` object.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RtlEvalReport {
    /// Pair folder name.
    pub pair: String,
    #[serde(flatten)]
    pub run: StereoReport,
    /// Dense scores of the rtl's map, all pixels with ground truth (as
    /// `eval`'s).
    pub bad1: f64,
    pub bad2: f64,
    pub bad2v: f64,
    pub density: f64,
    /// `bad2` on `nonocc.png > 127`; `null` without a mask.
    pub nonocc_bad2: Option<f64>,
    /// golden's `bad2` with the same stages, for comparison.
    pub golden_bad2: f64,
}

/// Runs a pair folder through `config`'s line processor with the search
/// area `dispmin < d < dispmax + 1` (the upper bound as `eval`'s) and scores
/// the map against the left ground truth.
pub fn evaluate_pair_rtl(config: Config, pair: &PairData, dispmin: f64, hblank: usize, engine: Engine, progress: impl FnMut(usize)) -> Result<RtlEvalReport, SimError> {
    let (run, rtl, gold, _) = run_pair(config, &pair.name, &pair.left, &pair.right, (dispmin, pair.dispmax + 1.0), hblank, DepthCamera::default(), engine, None, progress)?;
    let gt = &pair.gt_left;
    let all = dense_scores(&rtl, gt, None);
    Ok(RtlEvalReport {
        pair: pair.name.clone(),
        run,
        bad1: all.bad1,
        bad2: all.bad2,
        bad2v: all.bad2v,
        density: all.density,
        nonocc_bad2: pair.nonocc.as_deref().map(|m| dense_scores(&rtl, gt, Some(m)).bad2),
        golden_bad2: dense_scores(&gold, gt, None).bad2,
    })
}

/// The `eval --rtl` table.
pub fn rtl_markdown_table(reports: &[RtlEvalReport]) -> String {
    let mut s = String::from(
        "| pair | exact_px | exact_depth_px | agree_quarter_px | px_per_clk | stall_cycles | latency_cycles | bad2 | golden bad2 | nonocc_bad2 | lines dropped | sim clocks/s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in reports {
        s.push_str(&format!(
            "| {} | {:.4} | {:.4} | {:.4} | {:.4} | {} | {} | {:.1} | {:.1} | {} | {} | {:.0} |\n",
            r.pair,
            r.run.exact_px,
            r.run.exact_depth_px,
            r.run.agree_quarter_px,
            r.run.px_per_clk,
            r.run.stall_cycles,
            r.run.latency_cycles.map_or("-".into(), |c| c.to_string()),
            r.bad2,
            r.golden_bad2,
            r.nonocc_bad2.map_or("-".into(), |v| format!("{v:.1}")),
            r.run.lines_dropped,
            r.run.sim_cycles_per_s
        ));
    }
    s
}

/// What `rtl depth` was asked for besides the pair.
#[derive(Debug, Clone)]
pub struct RtlDepthJob {
    /// The line processor's configuration.
    pub config: Config,
    /// Eq. 6's area `dispmin < d < dispmax`, px.
    pub dispmin: f64,
    pub dispmax: f64,
    /// Idle clocks after each line of the cameras.
    pub hblank: usize,
    /// The camera the depth stage is generated for.
    pub camera: DepthCamera,
    /// The band of rows run, as a frame of its own.
    pub rows: std::ops::Range<usize>,
    pub engine: Engine,
    /// A waveform of these rows of the band (rust-hdl engine).
    pub vcd: Option<crate::jobs::rtl_detect::Waveform>,
    /// Folder for the pictures (created before the simulation).
    pub out: std::path::PathBuf,
}

/// Runs the band `job.rows` of a pair through the line processor and
/// writes into `job.out`: `disparity_rtl.png` and `disparity_golden.png`
/// (near is bright, one scale), `disparity16_rtl.png` (the output word's
/// disparity, 16-bit, value = d × 16, 0 = none) and `depth_mm_rtl.png` (its
/// depth, 16-bit millimetres, 0 = none). Returns the report and the files
/// with what each shows.
pub fn rtl_depth(
    name: &str,
    left: &GreyImage,
    right: &GreyImage,
    job: &RtlDepthJob,
    progress: impl FnMut(usize),
) -> Result<(StereoReport, Vec<(std::path::PathBuf, &'static str)>), SimError> {
    let height = left.height();
    let rows = &job.rows;
    if rows.end > height || rows.is_empty() {
        return Err(SimError::Argument(format!("--rows {}..{}: not a band of the image ({name} has {height} rows)", rows.start, rows.end)));
    }
    let band = |img: &GreyImage| {
        let w = img.width();
        GreyImage::new(w, rows.len(), img.pixels()[rows.start * w..rows.end * w].to_vec())
    };
    let (l, r) = (band(left)?, band(right)?);
    if let Some(v) = &job.vcd {
        if v.rows.is_empty() || v.rows.end > l.height() {
            return Err(SimError::Argument(format!("--lines {}..{}: not rows of the frame run ({} rows)", v.rows.start, v.rows.end, l.height())));
        }
    }
    std::fs::create_dir_all(&job.out).map_err(|source| SimError::Io { path: job.out.clone(), source })?;
    let vcd = job.vcd.as_ref().map(|v| (v.path.as_path(), &v.rows));
    let (report, rtl, gold, depth) = run_pair(job.config, name, &l, &r, (job.dispmin, job.dispmax), job.hblank, job.camera, job.engine, vcd, progress)?;

    let (w, h) = (l.width(), l.height());
    let files = vec![
        (job.out.join("disparity_rtl.png"), "rtl disparity, near is bright"),
        (job.out.join("disparity_golden.png"), "golden's disparity, same scale"),
        (job.out.join("disparity16_rtl.png"), "rtl output word, 16-bit, value = d x 16, 0 = none"),
        (job.out.join("depth_mm_rtl.png"), "rtl depth (eq. 1, the generated camera), 16-bit millimetres, 0 = none"),
    ];
    use crate::eval::pictures::{disparity_visual_of, save_png};
    save_png(&disparity_visual_of(&rtl, w, h, job.dispmax), &files[0].0)?;
    save_png(&disparity_visual_of(&gold, w, h, job.dispmax), &files[1].0)?;
    let word: Vec<u16> = rtl.iter().map(|&d| crate::formats::disparity_lsb(d, job.config) as u16).collect();
    let png16 = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w as u32, h as u32, word).expect("one word per pixel");
    save_png(&png16, &files[2].0)?;
    let depth16 = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w as u32, h as u32, depth).expect("one depth per pixel");
    save_png(&depth16, &files[3].0)?;
    Ok((report, files))
}
