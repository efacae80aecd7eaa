//! The whole line processor (`rtl::stereo_line_processor`) under direct
//! drive: a rectified pair in as two camera streams, the disparity map out,
//! with the clocks it took.

use golden::GreyImage;
use rtl::matcher::declivity_matcher::GainRule;
use rtl::post::depth_stage::DepthCamera;
use rtl::params::{DEPTH_BITS, POS_FRAC_BITS};
use rtl::stereo_line_processor::StereoLineProcessor;
use rust_hdl::prelude::*;

use crate::blocks::build_stereo;
use crate::config::Config;

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
    pub lines_unpaired: u64,
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
pub(crate) struct PendingLine {
    disparities: Vec<u32>,
    depths: Vec<u16>,
}

impl StereoRun {
    /// Takes an output beat (`m_tdata` = `word`, with `m_tuser`, `m_tlast`)
    /// sampled on clock `clock` into `pending`, and the line into the run at
    /// its `tlast`; returns whether a line was completed.
    pub(crate) fn push_beat(&mut self, clock: u64, word: u64, tuser: bool, tlast: bool, pending: &mut PendingLine) -> bool {
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

    /// The run with its clocks counted from `start` (the clock its frame
    /// began, as after [`StereoSim::reset`]), to compare with a run that
    /// began on clock 0. The probe keeps its own clocks; a clock before
    /// `start` (`first_in` and `last_in` of a run that took no pixel) counts
    /// as 0.
    pub fn counted_from(&self, start: u64) -> StereoRun {
        let from = |c: u64| c.saturating_sub(start);
        StereoRun {
            line_cycles: self.line_cycles.iter().map(|&(a, b)| (from(a), from(b))).collect(),
            cycles: from(self.cycles),
            first_in: from(self.first_in),
            first_out: self.first_out.map(from),
            last_in: from(self.last_in),
            last_out: self.last_out.map(from),
            ..self.clone()
        }
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

    /// The depths (mm, row-major, 0 = none) of a frame of `height` rows;
    /// rows that did not come out stay 0.
    pub fn depth_mm(&self, height: usize) -> Vec<u16> {
        let mut out = vec![0; self.width * height];
        for (row, dst) in self.depth_rows.iter().zip(out.chunks_mut(self.width)) {
            dst.copy_from_slice(row);
        }
        out
    }
}

/// A run ends when nothing has come in or out for this many clocks after
/// the last pixel in (or when every line is out).
pub(crate) const QUIET_CLOCKS: u64 = 20_000;

/// The line processor under direct drive.
pub struct StereoSim<const N: usize> {
    pub uut: Box<StereoLineProcessor<N>>,
    /// Clocks so far.
    pub cycle: u64,
    /// Eq. 6's bound, `1/2^POS_FRAC_BITS` px.
    pub dispmax: u32,
    /// Eq. 6's lower bound (`dispmin < d`), same unit; 0 from [`Self::new`].
    pub dispmin: u32,
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
/// (as `sim::drive::matcher`'s).
const SETTLE_LOW: usize = 4;
const SETTLE_HIGH: usize = 8;

fn settle<const N: usize>(u: &mut StereoLineProcessor<N>, passes: usize) {
    crate::drive::settle_block(u, passes, 300, "the line processor");
}

/// Sets both cameras' inputs: `(tdata, tuser, tlast)` of the pixel each
/// offers (left, right), or `tvalid` low with the rest 0.
fn offer_pixels<const N: usize>(u: &mut StereoLineProcessor<N>, offers: [Option<(u8, bool, bool)>; 2]) {
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
    pub fn new(rule: GainRule, jump: Option<u64>, camera: DepthCamera, dispmax: u32) -> Result<Self, rtl::post::depth_stage::DepthError> {
        Ok(StereoSim { uut: build_stereo::<N>(rule, jump, camera)?, cycle: 0, dispmax, dispmin: 0, vcd: None })
    }

    /// The default mode's line processor: [`GainRule::Robust`], the edge jump
    /// `EDGE_JUMP_LSB`, the default camera.
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
    pub(crate) fn trace_lines_to(&mut self, path: &std::path::Path, lines: std::ops::Range<usize>) -> std::io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let probe = write_vcd_header(file, &*self.uut);
        self.vcd = Some(StereoVcd { probe: Some(probe), lines });
        Ok(())
    }

    pub fn run(&mut self, left: &GreyImage, right: &GreyImage, hblank: usize, progress: impl FnMut(usize)) -> StereoRun {
        self.run_until(left, right, hblank, None, progress)
    }

    /// As [`run`](Self::run), but stops after `clocks` clocks whatever has
    /// come out: a frame cut short (by a reset, [`Self::reset`]).
    pub fn run_cut(&mut self, left: &GreyImage, right: &GreyImage, hblank: usize, clocks: u64) -> StereoRun {
        self.run_until(left, right, hblank, Some(clocks), |_| {})
    }

    /// Holds `reset` high for `clocks` clocks, with both cameras idle and
    /// the parameters of the last run, then low for `idle` clocks. Output
    /// beats during these clocks are ignored.
    pub fn reset(&mut self, clocks: u64, idle: u64) {
        for k in 0..clocks + idle {
            let u = &mut *self.uut;
            u.clock.next = false.into();
            u.reset.next = k < clocks;
            offer_pixels(u, [None, None]);
            settle(u, SETTLE_LOW);
            u.clock.next = true.into();
            settle(u, SETTLE_HIGH);
            self.cycle += 1;
        }
        self.uut.reset.next = false;
    }

    fn run_until(&mut self, left: &GreyImage, right: &GreyImage, hblank: usize, cut: Option<u64>, mut progress: impl FnMut(usize)) -> StereoRun {
        let quiet = QUIET_CLOCKS;
        let start = self.cycle;
        let mut run = StereoRun { width: left.width().min(rtl::params::W_MAX), ..StereoRun::default() };
        let mut cams = [Camera { image: left, x: 0, y: 0, idle: 0 }, Camera { image: right, x: 0, y: 0, idle: 0 }];
        let mut row = PendingLine::default();
        let mut first_in = None;
        let mut last_activity = start;
        let height = left.height();
        let mut state = QueueState::default();
        loop {
            let u = &mut *self.uut;
            u.clock.next = false.into();
            u.dispmin.next = (self.dispmin as u64).into();
            u.dispmax.next = (self.dispmax as u64).into();
            u.height.next = (height as u64).into();
            let offers = [cams[0].offer(), cams[1].offer()];
            offer_pixels(u, offers);
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
            if run.rows.len() >= height || (inputs_done && self.cycle - last_activity > quiet) || cut.is_some_and(|c| self.cycle - start >= c) {
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
        run.lines_unpaired = u.lines_unpaired.val().to_u64();
        run
    }
}

/// golden's disparity map of the pair for what the line processor of
/// `config` computes: the default mode (its row check, edge jump and
/// vertical median) in hardware parity, left reference, eq. 6's area
/// `dispmin < d < dispmax` (px). Its values are multiples of
/// `1/2^POS_FRAC_BITS` px: the line processor's output must equal it.
pub fn golden_map(left: &GreyImage, right: &GreyImage, dispmin: f64, dispmax: f64, config: Config) -> Result<Vec<f64>, golden::GoldenError> {
    let params = golden::Params { dispmin, hardware: Some(config.limits()), ..golden::Params::new(dispmax)? };
    params.validate()?;
    Ok(golden::process_frame(left, right, &params, golden::Threads::All)?.disparity)
}

/// golden's hardware-parity depths (mm, 0 = none) of a map from
/// [`golden_map`] for the depth stage's `camera` in `config`
/// (`golden::hardware::depth::DepthStage::depth_map_mm`).
///
/// # Panics
/// If the camera is outside the depth stage's range (no line processor is
/// built for it).
pub fn golden_depth_map(disparity: &[f64], camera: &DepthCamera, config: Config) -> Vec<u16> {
    let limits = config.limits();
    let stage = golden::hardware::depth::DepthStage::new(&crate::drive::depth_stage::golden_camera(camera), limits).expect("a camera in the depth stage's range");
    stage.depth_map_mm(disparity, limits)
}

/// What [`blocks_one_after_the_other`] gives: the matcher's matches before
/// the row check, and the output rows.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct BlocksRun {
    /// The matcher's matches of each row, `(X, d)` in `1/2^POS_FRAC_BITS` px.
    pub matches: Vec<Vec<crate::drive::row_check::FixedMatch>>,
    /// The disparity rows out of the median, `1/2^POS_FRAC_BITS` px.
    pub disparity: Vec<Vec<u32>>,
    /// The depth rows, mm.
    pub depth: Vec<Vec<u16>>,
}

/// The line processor's blocks run one after the other, each under its own
/// driver: both detectors over the pair, the matcher over their records
/// (with `N` cells, gain rule `rule`), the row check over the matches, the
/// interpolator over the kept ones (edge jump `jump`), the median over the
/// map and the depth stage (`camera`) over that. The line processor joins
/// exactly these blocks, so its output must equal this, line for line and
/// pixel for pixel; timing differs (here each block waits for the one
/// before).
pub fn blocks_one_after_the_other<const N: usize>(
    left: &GreyImage,
    right: &GreyImage,
    rule: GainRule,
    jump: Option<u64>,
    camera: DepthCamera,
    dispmax: u32,
) -> BlocksRun {
    use crate::drive::detector::{run_lines, DetectorSim};
    use crate::drive::interpolator::{AnchorLine, FixedAnchor, InterpolatorSim};
    use crate::drive::matcher::{MatchLine, MatchRecord, MatcherSim};
    let detect = |img: &GreyImage| {
        let rows: Vec<&[u8]> = (0..img.height()).map(|y| img.row(y)).collect();
        let mut sim = DetectorSim::new();
        run_lines(&mut sim, &rows, |_| false, |_| {}).expect("the detector runs").lines
    };
    let as_match_line = |l: &crate::drive::detector::HwLine| MatchLine {
        dt: l.marker.dt,
        records: l.records.iter().map(|r| MatchRecord { pos: r.pos, amplitude: r.amplitude, left: r.left, right: r.right }).collect(),
        wide: l.marker.wide,
        full: l.marker.full,
        sof: l.marker.sof,
        last_x: l.marker.end,
        stamp: 0,
    };
    let (l, r) = (detect(left), detect(right));
    let pairs: Vec<(MatchLine, MatchLine)> = l.iter().zip(&r).map(|(a, b)| (as_match_line(a), as_match_line(b))).collect();
    let mut matcher = MatcherSim::<N>::new(rule, dispmax);
    let matched = matcher.run(&pairs, false, || {});
    let width = left.width().min(rtl::params::W_MAX);
    let frame: Vec<Vec<crate::drive::row_check::FixedMatch>> =
        matched.iter().map(|m| m.matches.iter().map(|b| (b.x_ref as u64, b.disp as u64)).collect()).collect();
    let checked = crate::drive::row_check::RowCheckSim::new().run(&frame, width.max(rtl::post::row_check::row_check_period()));
    let lines: Vec<AnchorLine> = checked
        .rows
        .iter()
        .enumerate()
        .map(|(y, c)| AnchorLine { anchors: c.kept.iter().map(|&(x, d)| FixedAnchor { x: x as u32, d: d as u32 }).collect(), width, sof: y == 0 })
        .collect();
    let (pixels, _) = InterpolatorSim::new(jump).run(&lines, width);
    let map: Vec<Vec<u64>> = pixels.into_iter().map(|p| p.d.into_iter().map(u64::from).collect()).collect();
    let (medianed, _) = crate::drive::vertical_median::VerticalMedianSim::new().run(&map, width).expect("a map of one width");
    let depth = crate::drive::depth_stage::DepthStageSim::new(camera).expect("the camera fits").run(&medianed, width);
    BlocksRun { matches: frame, disparity: medianed.into_iter().map(|r| r.into_iter().map(|d| d as u32).collect()).collect(), depth: depth.z }
}

/// golden's steps after the matcher in hardware parity (the default mode's
/// row check, edge jump and median: `golden::frame::finish_frame`, and the
/// depth of `camera`) on the matcher's matches of each row (`(X, d)` in
/// `1/2^POS_FRAC_BITS` px), for rows of `width` pixels: the disparity map
/// in px and the depths in mm, row-major. Given the rtl matcher's matches,
/// this is what the line processor must output whatever golden's detector
/// does.
pub fn golden_after_matcher(matches: &[Vec<crate::drive::row_check::FixedMatch>], width: usize, camera: &DepthCamera) -> (Vec<f64>, Vec<u16>) {
    use golden::line::{LineFeatures, LineResult, Match};
    let limits = Config::Sd.limits();
    let unit = (1u64 << POS_FRAC_BITS) as f64;
    let empty = LineFeatures { sigma: 0.0, dt: 0.0, declivities: Vec::new() };
    let lines: Vec<LineResult> = matches
        .iter()
        .map(|row| LineResult {
            reference: empty.clone(),
            other: empty.clone(),
            matches: row
                .iter()
                .enumerate()
                .map(|(i, &(x, d))| {
                    let (x, d) = (x as f64 / unit, d as f64 / unit);
                    Match { ref_index: i, other_index: i, x_ref: x, x_other: x - d, disparity: d, gain: 0.0, edge: false }
                })
                .collect(),
            path_gain: 0.0,
        })
        .collect();
    // dispmax is not read after the matcher.
    let params = golden::Params { hardware: Some(limits), ..golden::Params::new(2.0).expect("a valid bound") };
    let frame = golden::frame::finish_frame(lines, width, matches.len(), &params, golden::Threads::All);
    let depth = golden_depth_map(&frame.disparity, camera, Config::Sd);
    (frame.disparity, depth)
}
