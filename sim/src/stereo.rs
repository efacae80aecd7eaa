//! The whole line processor (`rtl::stereo_line_processor`) under direct
//! drive: a rectified pair in as two camera streams, the disparity map out,
//! with the clocks it took.

use golden::GreyImage;
use rtl::declivity_matcher::GainRule;
use rtl::depth_stage::DepthCamera;
use rtl::params::{DEPTH_BITS, POS_FRAC_BITS};
use rtl::stereo_line_processor::StereoLineProcessor;
use rust_hdl::prelude::*;

/// What a frame through the line processor gave.
#[derive(Debug, Clone, Default)]
pub struct StereoRun {
    /// Width of the output lines.
    pub width: usize,
    /// The output lines, disparities in `1/2^POS_FRAC_BITS` px (0 = none).
    pub rows: Vec<Vec<u32>>,
    /// Their depths in mm (0 = none).
    pub depth_rows: Vec<Vec<u16>>,
    /// Whether each output line started a frame (`m_tuser` on its first
    /// pixel).
    pub sof: Vec<bool>,
    /// Clock of each output line's first and last beat.
    pub line_cycles: Vec<(u64, u64)>,
    /// Clocks simulated.
    pub cycles: u64,
    /// Clocks on which a camera offered a pixel and was not ready (either
    /// camera).
    pub stall_cycles: u64,
    /// Pixels taken from the left camera.
    pub pixels_in: u64,
    /// Clock of the first pixel taken and of the first disparity out.
    pub first_in: u64,
    pub first_out: Option<u64>,
    /// Clock of the last pixel taken and of the last disparity out.
    pub last_in: u64,
    pub last_out: Option<u64>,
    /// The status counters at the end.
    pub records_dropped: u64,
    pub lines_dropped: u64,
    pub pixels_dropped: u64,
    pub lines_full: u64,
    pub lines_wide: u64,
    /// The queues between the detectors and the pixels, as seen clock by
    /// clock (diagnostics).
    pub probe: QueueProbe,
}

/// The datapath's line queues as the driver saw them clock by clock, from
/// the blocks' own signals: when each line passed each stage, the peaks of
/// what each queue held, and the state of all of them on every dropped
/// line (diagnostics: which buffer overflowed, and what was behind it).
#[derive(Debug, Clone, Default)]
pub struct QueueProbe {
    /// Clock of each reference line's last pixel taken from the camera.
    pub line_in: Vec<u64>,
    /// Clock of each line's marker out of the matcher.
    pub matched: Vec<u64>,
    /// Clock of each row's marker out of the row check (into the
    /// interpolator).
    pub checked: Vec<u64>,
    /// Clock of each line's last pixel out of the interpolator.
    pub interpolated: Vec<u64>,
    /// The peaks of the state below over the run.
    pub peak: QueueState,
    /// The clock (as [`QueueState::cycle`]) of the peak of the
    /// interpolator's lines.
    pub peak_interp_cycle: u64,
    /// The state on each clock a line was dropped (the interpolator's or
    /// the row check's `overflow`).
    pub drops: Vec<QueueState>,
}

/// What the queues held on one clock.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct QueueState {
    pub cycle: u64,
    /// Which block dropped a line on this clock.
    pub interpolator_overflow: bool,
    pub row_check_overflow: bool,
    /// Lines (markers) taken from the reference camera, out of the matcher,
    /// out of the row check, out of the interpolator, so far.
    pub lines_in: usize,
    pub lines_matched: usize,
    pub lines_checked: usize,
    pub lines_interpolated: usize,
    /// Per side (left, right): beats in the record queue (written, not yet
    /// taken by the matcher) and line markers among them.
    pub record_beats: [u64; 2],
    pub record_lines: [u64; 2],
    /// The interpolator's lines (`q_used`: admitted, last pixel not yet
    /// issued) and segments (`seg_used`: written, not yet read).
    pub interp_lines: u64,
    pub interp_segments: u64,
    /// Rows in the row check: markers in, not yet out (the dropped ones
    /// counted until the end).
    pub row_check_rows: u64,
    /// The line processor's count of lines in flight (reference markers
    /// the matcher took, less lines sent or dropped after it), and the
    /// clocks so far on which its limit held a beat of the reference
    /// queue back.
    pub in_flight: u64,
    pub held_clocks: u64,
}

impl QueueState {
    fn max(&self, o: &QueueState) -> QueueState {
        let m2 = |a: [u64; 2], b: [u64; 2]| [a[0].max(b[0]), a[1].max(b[1])];
        QueueState {
            cycle: self.cycle.max(o.cycle),
            interpolator_overflow: self.interpolator_overflow | o.interpolator_overflow,
            row_check_overflow: self.row_check_overflow | o.row_check_overflow,
            lines_in: self.lines_in.max(o.lines_in),
            lines_matched: self.lines_matched.max(o.lines_matched),
            lines_checked: self.lines_checked.max(o.lines_checked),
            lines_interpolated: self.lines_interpolated.max(o.lines_interpolated),
            record_beats: m2(self.record_beats, o.record_beats),
            record_lines: m2(self.record_lines, o.record_lines),
            interp_lines: self.interp_lines.max(o.interp_lines),
            interp_segments: self.interp_segments.max(o.interp_segments),
            row_check_rows: self.row_check_rows.max(o.row_check_rows),
            in_flight: self.in_flight.max(o.in_flight),
            held_clocks: self.held_clocks.max(o.held_clocks),
        }
    }
}

impl<const N: usize> StereoSim<N> {
    /// Counts this clock's events into `state` and `probe` (after the
    /// clock's inputs settled, before its edge).
    fn probe_clock(&self, state: &mut QueueState, probe: &mut QueueProbe) {
        let u = &*self.uut;
        let cycle = self.cycle;
        state.cycle = cycle;
        // (A beat's marker bit, decoded, is the matcher's `r_last`/`o_last`.)
        let queues = [(&u.l_queue, u.matcher.r_last.val()), (&u.r_queue, u.matcher.o_last.val())];
        for (k, (q, marker_out)) in queues.iter().enumerate() {
            if q.w_valid.val() {
                state.record_beats[k] += 1;
                if q.w_marker.val() {
                    state.record_lines[k] += 1;
                }
            }
            if q.r_valid.val() && q.r_ready.val() {
                state.record_beats[k] -= 1;
                if *marker_out {
                    state.record_lines[k] -= 1;
                }
            }
        }
        if u.l_tvalid.val() && u.l_tready.val() && u.l_tlast.val() {
            state.lines_in += 1;
            probe.line_in.push(cycle);
        }
        if u.matcher.m_valid.val() && u.matcher.m_last.val() {
            state.lines_matched += 1;
            state.row_check_rows += 1;
            probe.matched.push(cycle);
        }
        if u.row_check.c_valid.val() && u.row_check.c_last.val() {
            state.lines_checked += 1;
            state.row_check_rows -= 1;
            probe.checked.push(cycle);
        }
        if u.interpolator.p_valid.val() && u.interpolator.p_last.val() {
            state.lines_interpolated += 1;
            probe.interpolated.push(cycle);
        }
        state.interp_lines = u.interpolator.q_used.q.val().to_u64();
        state.interp_segments = u.interpolator.seg_used.q.val().to_u64();
        state.in_flight = u.in_flight.q.val().to_u64();
        if u.hold.val() && u.l_queue.r_valid.val() {
            state.held_clocks += 1;
        }
        state.interpolator_overflow = u.interpolator.overflow.val();
        state.row_check_overflow = u.row_check.overflow.val();
        if state.interp_lines > probe.peak.interp_lines {
            probe.peak_interp_cycle = cycle;
        }
        probe.peak = probe.peak.max(state);
        if state.interpolator_overflow || state.row_check_overflow {
            probe.drops.push(*state);
        }
    }
}

/// An output line being received: its disparities and depths so far.
#[derive(Debug, Clone, Default)]
pub struct PendingLine {
    disparities: Vec<u32>,
    depths: Vec<u16>,
}

impl StereoRun {
    /// Takes an output beat (`m_tdata` = `word`, with `m_tuser`, `m_tlast`)
    /// sampled on clock `clock` into `pending`, and the line into the run at
    /// its `tlast`; returns whether a line was completed.
    pub fn push_beat(&mut self, clock: u64, word: u64, tuser: bool, tlast: bool, pending: &mut PendingLine) -> bool {
        self.first_out.get_or_insert(clock);
        self.last_out = Some(clock);
        if pending.disparities.is_empty() {
            self.sof.push(tuser);
            self.line_cycles.push((clock, clock));
        }
        if let Some(l) = self.line_cycles.last_mut() {
            l.1 = clock;
        }
        pending.disparities.push((word & ((1 << DEPTH_BITS) - 1)) as u32);
        pending.depths.push((word >> DEPTH_BITS) as u16);
        if tlast {
            self.rows.push(std::mem::take(&mut pending.disparities));
            self.depth_rows.push(std::mem::take(&mut pending.depths));
        }
        tlast
    }

    /// Clocks from the first pixel in to the first disparity out.
    pub fn latency_cycles(&self) -> Option<u64> {
        self.first_out.map(|o| o - self.first_in)
    }

    /// Pixels in per clock from the first pixel in to the last one in.
    pub fn px_per_clk(&self) -> f64 {
        self.pixels_in as f64 / (self.last_in - self.first_in + 1).max(1) as f64
    }

    /// The output as one row-major map in px (`0.0` = none), `height` rows
    /// (missing rows are 0).
    pub fn disparity_px(&self, height: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.width * height];
        for (row, dst) in self.rows.iter().zip(out.chunks_mut(self.width)) {
            for (d, &v) in dst.iter_mut().zip(row) {
                *d = v as f64 / (1u32 << POS_FRAC_BITS) as f64;
            }
        }
        out
    }
}

/// A run ends when nothing has come in or out for this many clocks after
/// the last pixel in (or when every line is out).
pub const QUIET_CLOCKS: u64 = 20_000;

/// The line processor under direct drive.
pub struct StereoSim<const N: usize> {
    pub uut: Box<StereoLineProcessor<N>>,
    /// Clocks so far.
    pub cycle: u64,
    /// Eq. 6's bound, `1/2^POS_FRAC_BITS` px.
    pub dispmax: u32,
    vcd: Option<StereoVcd>,
}

/// A waveform being written ([`StereoSim::trace_lines_to`]).
struct StereoVcd {
    probe: Option<rust_hdl::core::vcd_probe::VCDProbe<std::io::BufWriter<std::fs::File>>>,
    /// The frame's rows whose clocks are recorded.
    lines: std::ops::Range<usize>,
}

impl StereoVcd {
    /// Records the block's signals at `time` (ns, a clock of 10 ns) if
    /// `active`.
    fn sample<const N: usize>(&mut self, active: bool, time: u64, u: &StereoLineProcessor<N>) {
        if !active {
            return;
        }
        if let Some(mut probe) = self.probe.take() {
            let _ = probe.timestamp(time);
            self.probe = Some(write_vcd_change(probe, u));
        }
    }
}

/// Passes over the logic before `simulate` is asked whether it settled
/// (as `sim::matcher`'s).
const SETTLE_LOW: usize = 4;
const SETTLE_HIGH: usize = 8;

fn settle<const N: usize>(u: &mut StereoLineProcessor<N>, passes: usize) {
    crate::settle_block(u, passes, 300, "the line processor");
}

/// Builds and connects the line processor on a thread with a stack large
/// enough for it (as [`crate::matcher::build_matcher`]).
pub fn build_stereo<const N: usize>(rule: GainRule, jump: Option<u64>, camera: DepthCamera) -> Result<Box<StereoLineProcessor<N>>, rtl::depth_stage::DepthError> {
    crate::on_big_stack("building the line processor", move || {
        let mut uut = Box::new(StereoLineProcessor::<N>::new(rule, jump, camera)?);
        uut.connect_all();
        Ok(uut)
    })
}

/// One camera's stream: the pixel offered, and where it is.
struct Camera<'a> {
    image: &'a GreyImage,
    x: usize,
    y: usize,
    /// Idle clocks left before the next line.
    idle: usize,
}

impl Camera<'_> {
    fn done(&self) -> bool {
        self.y >= self.image.height()
    }

    /// `(tdata, tuser, tlast)` of the pixel offered, if any.
    fn offer(&self) -> Option<(u8, bool, bool)> {
        (!self.done() && self.idle == 0).then(|| {
            let w = self.image.width();
            (self.image.row(self.y)[self.x], self.x == 0 && self.y == 0, self.x + 1 == w)
        })
    }

    fn advance(&mut self, taken: bool, hblank: usize) {
        if self.idle > 0 {
            self.idle -= 1;
        } else if taken {
            self.x += 1;
            if self.x == self.image.width() {
                self.x = 0;
                self.y += 1;
                self.idle = hblank;
            }
        }
    }
}

impl<const N: usize> StereoSim<N> {
    /// The line processor with gain rule `rule`, edge jump `jump`
    /// (`1/2^POS_FRAC_BITS` px) and the depth stage's `camera`, eq. 6's
    /// bound `dispmax` in the same unit.
    pub fn new(rule: GainRule, jump: Option<u64>, camera: DepthCamera, dispmax: u32) -> Result<Self, rtl::depth_stage::DepthError> {
        Ok(StereoSim { uut: build_stereo::<N>(rule, jump, camera)?, cycle: 0, dispmax, vcd: None })
    }

    /// The default mode's line processor (as [`StereoLineProcessor::robust`]).
    pub fn robust(dispmax: u32) -> Self {
        Self::new(GainRule::Robust, Some(rtl::params::EDGE_JUMP_LSB), DepthCamera::default(), dispmax).expect("the default camera fits")
    }

    /// Streams the pair through, both cameras from the same clock, a line
    /// every `width + hblank` clocks at best (`tvalid` low for `hblank`
    /// clocks after each line), until `height` lines have left or nothing
    /// has left for `quiet` clocks after the last pixel in. `progress` is
    /// called with the number of lines out after each.
    /// Writes a VCD waveform (every signal of the line processor, a clock
    /// of 10 ns) to `path` during the next [`run`](Self::run): from the clock
    /// the left camera offers the first pixel of row `lines.start` to the
    /// clock the output line `lines.end − 1` leaves, so that the lines'
    /// pixels, records, matches and disparities are all in it.
    pub fn trace_lines_to(&mut self, path: &std::path::Path, lines: std::ops::Range<usize>) -> std::io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let probe = write_vcd_header(file, &*self.uut);
        self.vcd = Some(StereoVcd { probe: Some(probe), lines });
        Ok(())
    }

    pub fn run(&mut self, left: &GreyImage, right: &GreyImage, hblank: usize, mut progress: impl FnMut(usize)) -> StereoRun {
        let quiet = QUIET_CLOCKS;
        let mut run = StereoRun { width: left.width().min(rtl::params::W_MAX), ..StereoRun::default() };
        let mut cams = [Camera { image: left, x: 0, y: 0, idle: 0 }, Camera { image: right, x: 0, y: 0, idle: 0 }];
        let mut row = PendingLine::default();
        let mut first_in = None;
        let mut last_activity = 0u64;
        let height = left.height();
        let mut state = QueueState::default();
        loop {
            let u = &mut *self.uut;
            u.clock.next = false.into();
            u.dispmax.next = (self.dispmax as u64).into();
            u.height.next = (height as u64).into();
            let offers = [cams[0].offer(), cams[1].offer()];
            for (k, offer) in offers.iter().enumerate() {
                let (tdata, tuser, tlast) = offer.unwrap_or((0, false, false));
                let (d, v, us, l) = if k == 0 {
                    (&mut u.l_tdata, &mut u.l_tvalid, &mut u.l_tuser, &mut u.l_tlast)
                } else {
                    (&mut u.r_tdata, &mut u.r_tvalid, &mut u.r_tuser, &mut u.r_tlast)
                };
                d.next = (tdata as u64).into();
                v.next = offer.is_some();
                us.next = tuser;
                l.next = tlast;
            }
            settle(u, SETTLE_LOW);
            let tracing = self.vcd.as_ref().is_some_and(|v| cams[0].y >= v.lines.start && run.rows.len() < v.lines.end);
            if let Some(v) = &mut self.vcd {
                v.sample(tracing, self.cycle * 10, &self.uut);
            }
            self.probe_clock(&mut state, &mut run.probe);
            let u = &mut *self.uut;
            let taken = [offers[0].is_some() && u.l_tready.val(), offers[1].is_some() && u.r_tready.val()];
            if (offers[0].is_some() && !taken[0]) || (offers[1].is_some() && !taken[1]) {
                run.stall_cycles += 1;
            }
            if taken[0] {
                run.pixels_in += 1;
                first_in.get_or_insert(self.cycle);
                run.last_in = self.cycle;
                last_activity = self.cycle;
            }
            if u.m_tvalid.val() {
                last_activity = self.cycle;
                if run.push_beat(self.cycle, u.m_tdata.val().to_u64(), u.m_tuser.val(), u.m_tlast.val(), &mut row) {
                    progress(run.rows.len());
                }
            }
            u.clock.next = true.into();
            settle(u, SETTLE_HIGH);
            if let Some(v) = &mut self.vcd {
                v.sample(tracing, self.cycle * 10 + 5, &self.uut);
            }
            self.cycle += 1;
            for (cam, &t) in cams.iter_mut().zip(&taken) {
                cam.advance(t, hblank);
            }
            let inputs_done = cams.iter().all(Camera::done);
            if run.rows.len() >= height || (inputs_done && self.cycle - last_activity > quiet) {
                break;
            }
        }
        // Dropping the probe flushes and closes the waveform.
        self.vcd = None;
        let u = &*self.uut;
        run.first_in = first_in.unwrap_or(0);
        run.cycles = self.cycle;
        run.records_dropped = u.records_dropped.val().to_u64();
        run.lines_dropped = u.lines_dropped.val().to_u64();
        run.pixels_dropped = u.pixels_dropped.val().to_u64();
        run.lines_full = u.lines_full.val().to_u64();
        run.lines_wide = u.lines_wide.val().to_u64();
        run
    }
}

/// golden's disparity map of the pair for what the line processor computes:
/// the default mode (its row check, edge jump and vertical median) in
/// hardware parity, left reference, `dispmax` px.
pub fn golden_map(left: &GreyImage, right: &GreyImage, dispmax: f64) -> Result<Vec<f64>, golden::GoldenError> {
    let mut params = golden::Params::new(dispmax)?;
    params.hardware = Some(crate::detector::hardware_limits());
    Ok(golden::process_frame(left, right, &params, golden::Threads::All)?.disparity)
}

/// The share of `rtl`'s pixels within a quarter pixel of `golden`'s (both
/// row-major px maps of one size).
pub fn agree_quarter_px(rtl: &[f64], golden: &[f64]) -> f64 {
    let close = rtl.iter().zip(golden).filter(|(a, b)| (*a - *b).abs() <= 0.25).count();
    close as f64 / rtl.len().max(1) as f64
}

/// The line processor's blocks run one after the other, each under its own
/// driver: both detectors over the pair, the matcher over their records
/// (with `N` cells, gain rule `rule`), the row check over the matches, the
/// interpolator over the kept ones (edge jump `jump`), the median over the
/// map and the depth stage (`camera`) over that. The line processor joins
/// exactly these blocks, so its output must equal this, line for line and
/// pixel for pixel; timing differs (here each block waits for the one
/// before). Returns the disparity rows and the depth rows.
pub fn blocks_one_after_the_other<const N: usize>(
    left: &GreyImage,
    right: &GreyImage,
    rule: GainRule,
    jump: Option<u64>,
    camera: DepthCamera,
    dispmax: u32,
) -> (Vec<Vec<u32>>, Vec<Vec<u16>>) {
    use crate::detector::{run_lines, DetectorSim};
    use crate::interpolator::{AnchorLine, FixedAnchor, InterpolatorSim};
    use crate::matcher::{MatchLine, MatchRecord, MatcherSim};
    let detect = |img: &GreyImage| {
        let rows: Vec<&[u8]> = (0..img.height()).map(|y| img.row(y)).collect();
        let mut sim = DetectorSim::new();
        run_lines(&mut sim, &rows, |_| false, |_| {}).expect("the detector runs").lines
    };
    let as_match_line = |l: &crate::detector::HwLine| MatchLine {
        dt: l.marker.dt,
        records: l.records.iter().map(|r| MatchRecord { pos: r.pos, amplitude: r.amplitude, left: r.left, right: r.right }).collect(),
        wide: l.marker.wide,
        full: l.marker.full,
        sof: l.marker.sof,
    };
    let (l, r) = (detect(left), detect(right));
    let pairs: Vec<(MatchLine, MatchLine)> = l.iter().zip(&r).map(|(a, b)| (as_match_line(a), as_match_line(b))).collect();
    let mut matcher = MatcherSim::<N>::new(rule, dispmax);
    let matched = matcher.run(&pairs, false, || {});
    let width = left.width().min(rtl::params::W_MAX);
    let frame: Vec<Vec<crate::row_check::FixedMatch>> =
        matched.iter().map(|m| m.matches.iter().map(|b| (b.x_ref as u64, b.disp as u64)).collect()).collect();
    let checked = crate::row_check::RowCheckSim::new().run(&frame, width.max(rtl::row_check::row_check_period()));
    let lines: Vec<AnchorLine> = checked
        .rows
        .iter()
        .enumerate()
        .map(|(y, c)| AnchorLine { anchors: c.kept.iter().map(|&(x, d)| FixedAnchor { x: x as u32, d: d as u32 }).collect(), width, sof: y == 0 })
        .collect();
    let (pixels, _) = InterpolatorSim::new(jump).run(&lines, width);
    let map: Vec<Vec<u64>> = pixels.into_iter().map(|p| p.d.into_iter().map(u64::from).collect()).collect();
    let (medianed, _) = crate::vertical_median::VerticalMedianSim::new().run(&map, width).expect("a map of one width");
    let depth = crate::depth_stage::DepthStageSim::new(camera).expect("the camera fits").run(&medianed, width);
    (medianed.into_iter().map(|r| r.into_iter().map(|d| d as u32).collect()).collect(), depth.z)
}

/// What `declivity rtl depth` reports on a pair (one JSON object).
#[derive(Debug, Clone, serde::Serialize)]
pub struct StereoReport {
    /// The left image (or the pair's name).
    pub image: String,
    pub width: usize,
    pub height: usize,
    /// Eq. 6's bound, px.
    pub dispmax: f64,
    /// Idle clocks after each line of the cameras.
    pub hblank: usize,
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
    /// The most lines in flight between the matcher's input and the
    /// interpolator's output (at most `LINES_IN_FLIGHT`), and the clocks
    /// on which that limit held the reference queue back: probed inside the
    /// rust-hdl model, `null` from the Verilog engines.
    pub lines_in_flight_peak: Option<u64>,
    pub held_cycles: Option<u64>,
}

/// What runs the line processor clock by clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Engine {
    /// The rust-hdl model under direct drive (about a thousand clocks per
    /// second with the 32-cell matcher).
    #[default]
    #[value(name = "rust-hdl")]
    RustHdl,
    /// Its generated Verilog under Verilator, driven directly by a C++ `main`
    /// holding the same camera model (`sim::stereo_cosim::frame_driver`):
    /// over a hundred thousand clocks per second after a build of a few
    /// minutes, kept for later runs.
    Verilator,
    /// Its generated Verilog under Icarus Verilog (slow; a few lines).
    Icarus,
}

impl Engine {
    /// The engine's name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Engine::RustHdl => "rust-hdl",
            Engine::Verilator => "verilator",
            Engine::Icarus => "icarus",
        }
    }
}

/// Runs a pair through the line processor (default mode: [`GainRule::Robust`],
/// the edge jump, the default camera) on `engine` and compares with golden
/// (with `vcd`, the rust-hdl engine writes a waveform of the frame's rows
/// in the range to the file, as [`StereoSim::trace_lines_to`]); returns the
/// report, the rtl's map and golden's (px, row-major, 0 = none) and the
/// rtl's depths (mm, row-major, 0 = none).
pub fn run_pair(
    name: &str,
    left: &GreyImage,
    right: &GreyImage,
    dispmax: f64,
    hblank: usize,
    engine: Engine,
    vcd: Option<(&std::path::Path, &std::ops::Range<usize>)>,
    progress: impl FnMut(usize),
) -> Result<(StereoReport, Vec<f64>, Vec<f64>, Vec<u16>), crate::SimError> {
    let lsb = crate::budget::dispmax_lsb(dispmax)?;
    if left.width() > rtl::params::W_MAX {
        return Err(crate::SimError::Argument(format!(
            "{name}: lines of {} px are wider than the hardware's W_MAX = {} px",
            left.width(),
            rtl::params::W_MAX
        )));
    }
    if (left.width(), left.height()) != (right.width(), right.height()) {
        return Err(golden::GoldenError::SizeMismatch { left_w: left.width(), left_h: left.height(), right_w: right.width(), right_h: right.height() }.into());
    }
    if vcd.is_some() && engine != Engine::RustHdl {
        return Err(crate::SimError::Argument(format!("a waveform (--vcd) is written by the rust-hdl engine only, not by {}", engine.name())));
    }
    let (run, seconds, build_seconds) = match engine {
        Engine::RustHdl => {
            let mut sim = StereoSim::<{ rtl::params::N_CELLS }>::robust(lsb);
            if let Some((path, lines)) = vcd {
                sim.trace_lines_to(path, lines.clone()).map_err(|source| crate::SimError::Io { path: path.to_path_buf(), source })?;
            }
            let t0 = std::time::Instant::now();
            let run = sim.run(left, right, hblank, progress);
            (run, t0.elapsed().as_secs_f64(), 0.0)
        }
        Engine::Verilator | Engine::Icarus => {
            let simulator = if engine == Engine::Verilator { crate::cosim::Simulator::Verilator } else { crate::cosim::Simulator::Icarus };
            let design = crate::verilog::generate(crate::verilog::Top::Stereo);
            let frame = crate::stereo_cosim::run_frame(simulator, &design, left, right, hblank, lsb, &crate::cosim::Options::default())?;
            (frame.run, frame.sim.as_secs_f64(), frame.compile.as_secs_f64())
        }
    };
    let rtl = run.disparity_px(left.height());
    let gold = golden_map(left, right, dispmax)?;
    let report = StereoReport {
        image: name.to_string(),
        width: left.width(),
        height: left.height(),
        dispmax,
        hblank,
        pixels: run.pixels_in,
        cycles: run.cycles,
        px_per_clk: run.px_per_clk(),
        stall_cycles: run.stall_cycles,
        latency_cycles: run.latency_cycles(),
        agree_quarter_px: agree_quarter_px(&rtl, &gold),
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
        lines_in_flight_peak: (engine == Engine::RustHdl).then_some(run.probe.peak.in_flight),
        held_cycles: (engine == Engine::RustHdl).then_some(run.probe.peak.held_clocks),
    };
    let mut depth = vec![0u16; left.width() * left.height()];
    for (dst, row) in depth.chunks_mut(left.width()).zip(&run.depth_rows) {
        dst.iter_mut().zip(row).for_each(|(d, &z)| *d = z);
    }
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

/// Runs a pair folder through the line processor with the search bound
/// `dispmax + 1` (as `eval`) and scores the map against the left ground
/// truth.
pub fn evaluate_pair_rtl(pair: &crate::io::PairData, hblank: usize, engine: Engine, progress: impl FnMut(usize)) -> Result<RtlEvalReport, crate::SimError> {
    use crate::eval::dense_scores;
    let (run, rtl, gold, _) = run_pair(&pair.name, &pair.left, &pair.right, pair.dispmax + 1.0, hblank, engine, None, progress)?;
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
        "| pair | agree_quarter_px | px_per_clk | stall_cycles | latency_cycles | bad2 | golden bad2 | nonocc_bad2 | lines dropped | sim clocks/s |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in reports {
        s.push_str(&format!(
            "| {} | {:.4} | {:.4} | {} | {} | {:.1} | {:.1} | {} | {} | {:.0} |\n",
            r.pair,
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
