//! Cycle-accurate direct drive of the rtl [`DeclivityDetector`] and its
//! comparison with golden's detector in hardware-parity mode.
//!
//! Direct drive (`RUST-HDL-NOTES.md`): the driver sets the inputs, lets the
//! logic settle, samples the outputs, then raises the clock; no threads and
//! no testbench, so whole images run in seconds. One [`DetectorSim::cycle`]
//! is exactly one clock, with the co-simulation harness's cycle semantics
//! (inputs applied with the clock low, outputs sampled before the edge).

use golden::declivity::Declivity;
use golden::hardware::{detect_line, LimitedLine};

use rtl::detector::declivity_detector::DeclivityDetector;
use rtl::params::{DT_FRAC_BITS, POS_FRAC_BITS};
use rust_hdl::core::vcd_probe::VCDProbe;
use rust_hdl::prelude::*;
use serde::Serialize;

use crate::config::Config;

// The record formats the driver reads are the same in every configuration
// (only the position's integer bits grow); the driver's fixed-point units
// are `rtl`'s.
const _: () = assert!(
    rtl_hd::params::POS_FRAC_BITS == POS_FRAC_BITS
        && rtl_hd::params::DT_FRAC_BITS == DT_FRAC_BITS
        && rtl_hd::params::PIXEL_BITS == rtl::params::PIXEL_BITS
);

/// A declivity detector of one configuration's crate (`rtl` is `sd`,
/// `rtl-hd` is `hd`: the same source with other widths), as the driver
/// drives its ports.
pub trait DetectorDut: Block + Sized {
    /// The configuration the detector is built in.
    const CONFIG: Config;
    /// Clocks from a line's last pixel in to its marker out, for a line of
    /// `width` pixels (`camera_marker_latency` of the block's crate).
    fn marker_latency(width: usize) -> usize;
    /// A detector with its ports connected.
    fn build() -> Self;
    /// Sets the clock input and the pixel port's inputs.
    fn drive(&mut self, clock: bool, beat: PixelBeat);
    /// Raises the clock.
    fn rise(&mut self);
    /// `s_tready`.
    fn tready(&self) -> bool;
    /// The output beat, when `m_valid`.
    fn beat(&self) -> Option<RecordBeat>;
}

macro_rules! detector_dut {
    ($krate:ident, $config:expr) => {
        impl DetectorDut for $krate::detector::declivity_detector::DeclivityDetector {
            const CONFIG: Config = $config;
            fn marker_latency(width: usize) -> usize {
                $krate::detector::declivity_detector::camera_marker_latency(width)
            }
            fn build() -> Self {
                let mut uut = Self::default();
                uut.connect_all();
                uut
            }
            fn drive(&mut self, clock: bool, b: PixelBeat) {
                self.clock.next = clock.into();
                self.s_tdata.next = (b.tdata as u64).into();
                self.s_tvalid.next = b.tvalid;
                self.s_tuser.next = b.tuser;
                self.s_tlast.next = b.tlast;
            }
            fn rise(&mut self) {
                self.clock.next = true.into();
            }
            fn tready(&self) -> bool {
                self.s_tready.val()
            }
            fn beat(&self) -> Option<RecordBeat> {
                // The amplitude is PIXEL_BITS + 1 bits, two's complement.
                let amp_bits = 1u64 << (rtl::params::PIXEL_BITS + 1);
                let amp = self.m_amp.val().to_u64();
                self.m_valid.val().then(|| RecordBeat {
                    marker: self.m_last.val(),
                    start: self.m_start.val().to_u64() as u32,
                    end: self.m_end.val().to_u64() as u32,
                    amplitude: if 2 * amp >= amp_bits { amp as i32 - amp_bits as i32 } else { amp as i32 },
                    pos: self.m_pos.val().to_u64() as u32,
                    left: [self.m_left0.val(), self.m_left1.val(), self.m_left2.val()].map(|v| v.to_u64() as u8),
                    right: [self.m_right0.val(), self.m_right1.val(), self.m_right2.val()].map(|v| v.to_u64() as u8),
                    dt: self.m_dt.val().to_u64() as u32,
                    count: self.m_count.val().to_u64() as u32,
                    wide: self.m_wide.val(),
                    full: self.m_full.val(),
                    sof: self.m_sof.val(),
                })
            }
        }
    };
}

detector_dut!(rtl, Config::Sd);
detector_dut!(rtl_hd, Config::Hd);

/// The `hd` configuration's detector (`rtl-hd`).
pub type HdDetector = rtl_hd::detector::declivity_detector::DeclivityDetector;

/// One input beat of the AXI4-Stream video port.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PixelBeat {
    pub tdata: u8,
    pub tvalid: bool,
    pub tuser: bool,
    pub tlast: bool,
    /// The block's synchronous reset on this clock.
    pub reset: bool,
}

/// One output beat: a declivity record, or a line's end marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RecordBeat {
    pub marker: bool,
    pub start: u32,
    pub end: u32,
    /// `a_i`, sign-extended.
    pub amplitude: i32,
    /// `X_i · 2^POS_FRAC_BITS`.
    pub pos: u32,
    pub left: [u8; 3],
    pub right: [u8; 3],
    /// `d_t · 2^DT_FRAC_BITS`.
    pub dt: u32,
    pub count: u32,
    pub wide: bool,
    pub full: bool,
    pub sof: bool,
}

/// What one line came out as.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HwLine {
    pub records: Vec<RecordBeat>,
    /// Clock of each record.
    pub record_cycles: Vec<u64>,
    /// The marker.
    pub marker: RecordBeat,
    /// Clock of the marker.
    pub marker_cycle: u64,
}

impl HwLine {
    /// Adds the output beat `out` of clock `cycle` to `current`, the line
    /// being collected; on its marker, returns the finished line (and
    /// `current` starts afresh).
    fn collect(current: &mut HwLine, out: RecordBeat, cycle: u64) -> Option<HwLine> {
        if out.marker {
            current.marker = out;
            current.marker_cycle = cycle;
            Some(std::mem::take(current))
        } else {
            current.records.push(out);
            current.record_cycles.push(cycle);
            None
        }
    }

    /// `d_t` in grey levels.
    pub fn dt(&self) -> f64 {
        self.marker.dt as f64 / (1u64 << DT_FRAC_BITS) as f64
    }
}

/// The detector under direct drive: `sd`'s by default, [`HdDetector`] for
/// `hd`.
pub struct DetectorSim<D: DetectorDut = DeclivityDetector> {
    pub uut: D,
    /// Clocks so far.
    pub cycle: u64,
    vcd: Option<VcdState>,
}

struct VcdState {
    probe: Option<VCDProbe<std::io::BufWriter<std::fs::File>>>,
    /// Record clocks in this range only.
    range: std::ops::Range<u64>,
}

impl Default for DetectorSim {
    fn default() -> Self {
        Self::new()
    }
}

impl DetectorSim {
    /// The `sd` configuration's detector.
    pub fn new() -> Self {
        Self::build()
    }
}

impl<D: DetectorDut> DetectorSim<D> {
    /// The detector of `D`'s configuration.
    pub fn build() -> Self {
        DetectorSim { uut: D::build(), cycle: 0, vcd: None }
    }

    /// Writes a VCD of the clocks in `range` to `path`.
    pub(crate) fn trace_to(&mut self, path: &std::path::Path, range: std::ops::Range<u64>) -> std::io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let probe = write_vcd_header(file, &self.uut);
        self.vcd = Some(VcdState { probe: Some(probe), range });
        Ok(())
    }

    /// Ends the VCD: dropping the probe flushes and closes the file.
    pub(crate) fn finish_trace(&mut self) {
        self.vcd = None;
    }

    /// One clock: apply `input`, settle, sample; returns whether the pixel
    /// was accepted (`tvalid && tready`) and the output beat, if any.
    fn cycle(&mut self, input: PixelBeat) -> (bool, Option<RecordBeat>) {
        let u = &mut self.uut;
        u.drive(false, input);
        settle(u, SETTLE_LOW);
        let accepted = input.tvalid && u.tready();
        let out = u.beat();
        if let Some(state) = &mut self.vcd {
            if state.range.contains(&self.cycle) {
                if let Some(mut probe) = state.probe.take() {
                    let _ = probe.timestamp(self.cycle * 10);
                    probe = write_vcd_change(probe, &self.uut);
                    state.probe = Some(probe);
                }
            }
        }
        let u = &mut self.uut;
        u.rise();
        settle(u, SETTLE_HIGH);
        if let Some(state) = &mut self.vcd {
            if state.range.contains(&self.cycle) {
                if let Some(mut probe) = state.probe.take() {
                    let _ = probe.timestamp(self.cycle * 10 + 5);
                    probe = write_vcd_change(probe, &self.uut);
                    state.probe = Some(probe);
                }
            }
        }
        self.cycle += 1;
        (accepted, out)
    }
}

/// Passes over the detector made before `simulate` checks that the logic
/// settled, after the inputs (clock low) and after a clock edge: one fewer
/// than the least the detector's logic needs, so that `simulate`'s own
/// checking pass is never wasted; any further pass is `simulate`'s.
const SETTLE_LOW: usize = 3;
const SETTLE_HIGH: usize = 5;

fn settle<D: DetectorDut>(u: &mut D, passes: usize) {
    crate::drive::settle_block(u, passes, 200, "the detector");
}

/// The result of streaming lines through the detector.
#[derive(Debug, Clone, Default)]
pub struct DetectorRun {
    pub lines: Vec<HwLine>,
    /// Clocks until the last marker left.
    pub cycles: u64,
    /// Clocks from the first pixel accepted to the last, inclusive.
    pub input_cycles: u64,
    /// Pixels accepted.
    pub pixels: u64,
    /// Clocks with `tvalid` high and `tready` low.
    pub stall_cycles: u64,
    /// Of those, the clocks on a line's second or later pixel (the detector
    /// documents that it never stalls inside a line).
    pub stalls_inside_lines: u64,
    /// Clock at which each line's first pixel was accepted.
    pub first_pixel_cycle: Vec<u64>,
    /// Clock at which each line's last pixel was accepted.
    pub last_pixel_cycle: Vec<u64>,
    /// Clock at which each line's last stored pixel was accepted: its
    /// `W_MAX`-th in a wider line, where the line is cut (for lines that
    /// start frames, or of the first line's width at most).
    pub last_stored_cycle: Vec<u64>,
}

impl DetectorRun {
    /// Pixels per clock while the image streamed in.
    pub fn px_per_clk(&self) -> f64 {
        if self.input_cycles == 0 {
            0.0
        } else {
            self.pixels as f64 / self.input_cycles as f64
        }
    }
}

/// The detector hung: no marker for too long.
#[derive(Debug, thiserror::Error)]
#[error("the detector produced no line marker for {idle} clocks (line {line} of {lines}); it hangs")]
pub struct DetectorHang {
    pub idle: u64,
    pub line: usize,
    pub lines: usize,
}

/// Streams `lines` through `sim` back to back as one frame (the first pixel
/// carries `tuser`), with `tvalid` low on the clocks `c` where `gap(c)` says
/// so, and collects each line's records with their clocks; `progress` is
/// called with the number of lines done. (A later line of the frame wider
/// than the first is cut at the first's width: [`run_lines_as_frames`]
/// streams lines of any widths.)
pub fn run_lines<D: DetectorDut>(
    sim: &mut DetectorSim<D>,
    lines: &[&[u8]],
    gap: impl FnMut(u64) -> bool,
    progress: impl FnMut(usize),
) -> Result<DetectorRun, DetectorHang> {
    stream_lines(sim, lines, false, gap, progress)
}

/// [`run_lines`] with every line a frame of its own (`tuser` on each line's
/// first pixel), so that lines of any widths up to `W_MAX` are stored whole.
pub fn run_lines_as_frames<D: DetectorDut>(
    sim: &mut DetectorSim<D>,
    lines: &[&[u8]],
    gap: impl FnMut(u64) -> bool,
    progress: impl FnMut(usize),
) -> Result<DetectorRun, DetectorHang> {
    stream_lines(sim, lines, true, gap, progress)
}

fn stream_lines<D: DetectorDut>(
    sim: &mut DetectorSim<D>,
    lines: &[&[u8]],
    each_a_frame: bool,
    mut gap: impl FnMut(u64) -> bool,
    mut progress: impl FnMut(usize),
) -> Result<DetectorRun, DetectorHang> {
    let mut run = DetectorRun::default();
    let mut current = HwLine::default();
    let (mut li, mut xi) = (0usize, 0usize);
    let mut first_accept = None;
    let mut last_accept = 0u64;
    let mut idle = 0u64;
    // Generous: a line's own length plus the pipeline, for the longest line.
    let max_idle = 4 * (lines.iter().map(|l| l.len()).max().unwrap_or(0) as u64) + 4096;
    while run.lines.len() < lines.len() {
        let mut beat = PixelBeat::default();
        if li < lines.len() && !gap(sim.cycle) {
            let line = lines[li];
            beat = PixelBeat { tdata: line[xi], tvalid: true, tuser: (li == 0 || each_a_frame) && xi == 0, tlast: xi + 1 == line.len(), reset: false };
        }
        let cycle = sim.cycle;
        let (accepted, out) = sim.cycle(beat);
        if beat.tvalid && !accepted {
            run.stall_cycles += 1;
            run.stalls_inside_lines += (xi > 0) as u64;
        }
        if accepted {
            first_accept.get_or_insert(cycle);
            if xi == 0 {
                run.first_pixel_cycle.push(cycle);
            }
            last_accept = cycle;
            run.pixels += 1;
            if xi + 1 == lines[li].len().min(D::CONFIG.sizes().w_max) {
                run.last_stored_cycle.push(cycle);
            }
            xi += 1;
            if xi == lines[li].len() {
                run.last_pixel_cycle.push(cycle);
                li += 1;
                xi = 0;
            }
        }
        idle += 1;
        if let Some(line) = out.and_then(|out| HwLine::collect(&mut current, out, cycle)) {
            run.lines.push(line);
            progress(run.lines.len());
            idle = 0;
        }
        if idle > max_idle {
            return Err(DetectorHang { idle, line: run.lines.len(), lines: lines.len() });
        }
    }
    run.cycles = sim.cycle;
    run.input_cycles = first_accept.map_or(0, |f| last_accept - f + 1);
    Ok(run)
}

/// How one line of rtl records compares with golden in parity mode, which
/// computes the detector's values exactly (`golden::hardware`): every
/// field of every record must be equal.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct LineComparison {
    /// Declivities both found, identical in every field.
    pub common: usize,
    /// Of the mismatches, the declivities found by one side only whose
    /// `|a|` is one of the two integers either side of golden's threshold,
    /// `⌊d_t⌋` or `⌊d_t⌋ + 1` (a disagreement on the threshold test).
    pub borderline: usize,
    /// Every difference: a declivity found by one side only, different
    /// bounds, amplitude, levels or position, a record's `d_t` not its
    /// line's, the line's `d_t`, flags or count.
    pub mismatches: usize,
    /// Largest `|X_rtl - X_golden|` in position LSBs over the declivities
    /// both found.
    pub max_pos_err_lsb: f64,
    /// `|d_t,rtl - d_t,golden|` in `d_t` LSBs.
    pub dt_err_lsb: f64,
}

/// Compares `hw` with golden's parity-mode result `gold` for one line.
pub fn compare_line(hw: &HwLine, gold: &LimitedLine) -> LineComparison {
    let pos_unit = (1u64 << POS_FRAC_BITS) as f64;
    let mut c = LineComparison { dt_err_lsb: hw.marker.dt.abs_diff(gold.dt_lsb) as f64, ..Default::default() };
    if hw.marker.dt != gold.dt_lsb {
        c.mismatches += 1;
    }
    if hw.marker.wide != gold.wide || hw.marker.full != gold.full || hw.marker.count as usize != hw.records.len() {
        c.mismatches += 1;
    }
    let threshold = gold.dt_lsb >> DT_FRAC_BITS;
    let borderline = |a: i32| a.unsigned_abs() == threshold || a.unsigned_abs() == threshold + 1;
    let (mut i, mut j) = (0, 0);
    let (h, g) = (&hw.records, &gold.declivities);
    while i < h.len() || j < g.len() {
        let hk = h.get(i).map(|r| (r.start as usize, r.end as usize));
        let gk = g.get(j).map(|d| (d.start, d.end));
        match (hk, gk) {
            (Some(a), Some(b)) if a == b => {
                let (r, d) = (&h[i], &g[j]);
                // Both are multiples of 1/2^POS_FRAC_BITS: the difference is
                // exact, and any golden position off that grid shows.
                let err = (r.pos as f64 - d.position * pos_unit).abs();
                c.max_pos_err_lsb = c.max_pos_err_lsb.max(err);
                if r.amplitude != d.amplitude || r.left != d.left || r.right != d.right || err != 0.0 || r.dt != hw.marker.dt {
                    c.mismatches += 1;
                } else {
                    c.common += 1;
                }
                i += 1;
                j += 1;
            }
            (Some(a), b) if b.is_none_or(|b| a < b) => {
                c.mismatches += 1;
                c.borderline += borderline(h[i].amplitude) as usize;
                i += 1;
            }
            _ => {
                c.mismatches += 1;
                c.borderline += borderline(g[j].amplitude) as usize;
                j += 1;
            }
        }
    }
    c
}

/// golden's declivities of every line in parity mode, in the `sd`
/// configuration's limits.
pub fn golden_lines(lines: &[&[u8]]) -> Vec<LimitedLine> {
    golden_lines_in(lines, Config::Sd)
}

/// golden's declivities of every line in parity mode, in `config`'s limits
/// (`W_MAX`, `N_MAX`).
pub fn golden_lines_in(lines: &[&[u8]], config: Config) -> Vec<LimitedLine> {
    let limits = config.limits();
    lines.iter().map(|l| detect_line(l, limits)).collect()
}

/// A record as golden's [`Declivity`] (position from the fixed point).
fn to_declivity(r: &RecordBeat) -> Declivity {
    Declivity {
        start: r.start as usize,
        end: r.end as usize,
        amplitude: r.amplitude,
        position: r.pos as f64 / (1u64 << POS_FRAC_BITS) as f64,
        left: r.left,
        right: r.right,
    }
}

/// The report of `declivity rtl detect` (its JSON object).
#[derive(Debug, Clone, Serialize)]
pub struct DetectReport {
    /// The configuration the detector was generated in.
    pub config: Config,
    pub image: String,
    pub width: usize,
    pub lines: usize,
    pub pixels: u64,
    /// Clocks until the last line's marker left the detector.
    pub cycles: u64,
    /// Pixels per clock while the image streamed in (first to last pixel).
    pub px_per_clk: f64,
    pub stall_cycles: u64,
    pub declivities_rtl: usize,
    pub declivities_golden: usize,
    /// Of the mismatches, declivities found by one side only with `|a|`
    /// at `⌊d_t⌋` or `⌊d_t⌋ + 1` (see [`LineComparison`]); 0 when golden
    /// and the detector agree.
    pub borderline: usize,
    /// Every difference (see [`LineComparison`]); 0 when they agree.
    pub mismatches: usize,
    /// Largest position difference, 1/2^POS_FRAC_BITS px LSBs; 0 when they
    /// agree.
    pub max_pos_err_lsb: f64,
    /// Largest `d_t` difference, 1/2^DT_FRAC_BITS LSBs; 0 when they agree.
    pub max_dt_err_lsb: f64,
    /// Lines longer than `W_MAX` / with more than `N_MAX` declivities.
    pub wide_lines: usize,
    pub full_lines: usize,
    /// Clocks from the first line's last stored pixel to its marker.
    pub first_line_latency: u64,
    pub sim_cycles_per_s: f64,
}

/// Runs every row of `image` through the detector (back to back, no gaps)
/// and compares each with golden in parity mode. Returns the report and the
/// per-line records.
pub(crate) fn detect_image<D: DetectorDut>(
    sim: &mut DetectorSim<D>,
    name: &str,
    image: &golden::GreyImage,
    progress: impl FnMut(usize),
) -> Result<(DetectReport, Vec<HwLine>), DetectorHang> {
    let lines: Vec<&[u8]> = (0..image.height()).map(|y| image.row(y)).collect();
    let t0 = std::time::Instant::now();
    let run = run_lines(sim, &lines, |_| false, progress)?;
    let secs = t0.elapsed().as_secs_f64();
    let gold = golden_lines_in(&lines, D::CONFIG);
    let mut report = DetectReport {
        config: D::CONFIG,
        image: name.to_string(),
        width: image.width(),
        lines: lines.len(),
        pixels: run.pixels,
        cycles: run.cycles,
        px_per_clk: run.px_per_clk(),
        stall_cycles: run.stall_cycles,
        declivities_rtl: run.lines.iter().map(|l| l.records.len()).sum(),
        declivities_golden: gold.iter().map(|g| g.declivities.len()).sum(),
        borderline: 0,
        mismatches: 0,
        max_pos_err_lsb: 0.0,
        max_dt_err_lsb: 0.0,
        wide_lines: run.lines.iter().filter(|l| l.marker.wide).count(),
        full_lines: run.lines.iter().filter(|l| l.marker.full).count(),
        first_line_latency: run.lines.first().map_or(0, |l| l.marker_cycle - run.last_stored_cycle[0]),
        sim_cycles_per_s: run.cycles as f64 / secs.max(1e-9),
    };
    for (h, g) in run.lines.iter().zip(&gold) {
        let c = compare_line(h, g);
        report.borderline += c.borderline;
        report.mismatches += c.mismatches;
        report.max_pos_err_lsb = report.max_pos_err_lsb.max(c.max_pos_err_lsb);
        report.max_dt_err_lsb = report.max_dt_err_lsb.max(c.dt_err_lsb);
    }
    Ok((report, run.lines))
}

/// The records of each line as golden's line features (for the overlay
/// picture).
pub(crate) fn as_features(lines: &[HwLine]) -> Vec<golden::line::LineFeatures> {
    lines
        .iter()
        .map(|l| golden::line::LineFeatures {
            sigma: l.dt() / golden::noise::THRESHOLD_FACTOR,
            dt: l.dt(),
            declivities: l.records.iter().map(to_declivity).collect(),
        })
        .collect()
}

/// Streams `beats` through `sim` as a camera that may break the rules
/// would (each beat offered until taken, `tvalid` high throughout; its
/// `tuser` and `tlast` as given), then runs until no line's marker has come
/// for `quiet` clocks: the lines whose markers came, in order.
pub fn run_stream<D: DetectorDut>(sim: &mut DetectorSim<D>, beats: &[PixelBeat], quiet: u64) -> Vec<HwLine> {
    let mut lines = Vec::new();
    let mut current = HwLine::default();
    let (mut k, mut idle) = (0usize, 0u64);
    while k < beats.len() || idle <= quiet {
        let beat = beats.get(k).map_or(PixelBeat::default(), |b| PixelBeat { tvalid: true, ..*b });
        let cycle = sim.cycle;
        let (accepted, out) = sim.cycle(beat);
        k += accepted as usize;
        idle += 1;
        if let Some(line) = out.and_then(|out| HwLine::collect(&mut current, out, cycle)) {
            lines.push(line);
            idle = 0;
        }
    }
    lines
}

/// The beats of `lines` streamed as one frame (`tuser` on the first pixel,
/// `tlast` on each line's last), `idle` clocks of `tvalid` low after each
/// line, and `tvalid` low wherever `gap()` says so.
pub fn frame_beats(lines: &[&[u8]], idle: usize, mut gap: impl FnMut() -> bool) -> Vec<PixelBeat> {
    let mut beats = Vec::new();
    for (y, line) in lines.iter().enumerate() {
        for (x, &p) in line.iter().enumerate() {
            while gap() {
                beats.push(PixelBeat::default());
            }
            beats.push(PixelBeat { tdata: p, tvalid: true, tuser: y == 0 && x == 0, tlast: x + 1 == line.len(), reset: false });
        }
        beats.extend(std::iter::repeat_n(PixelBeat::default(), idle));
    }
    beats
}
