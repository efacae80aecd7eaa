//! Cycle-accurate direct drive of the rtl [`DeclivityMatcher`] and its
//! comparison with golden's matcher (eq. 4–9).
//!
//! The matcher takes declivity records in the detector's fixed-point
//! formats: positions with `POS_FRAC_BITS` fraction bits, `d_t` with
//! `DT_FRAC_BITS`. Golden's declivities are brought to those formats the way
//! the detector makes them ([`quantize_line`]: positions rounded down, `d_t`
//! to the nearest LSB), and golden's matcher run on the same values, `d_t`
//! rounded down to the matcher's `MATCH_DT_FRAC_BITS` as the matcher does,
//! is the reference ([`golden_match`]). With those inputs every local gain is an
//! integer number of `2^-GAIN_FRAC_BITS` grey levels in both models, golden's
//! f64 arithmetic on them is exact, and the fixed-point gain tolerance is
//! zero: the rtl path must be golden's, node for node.

use golden::declivity::Declivity;
use golden::dp::{prefix_max_dp, Choice, GainTable};
use golden::gain::{gmax, node_gain};
use golden::line::LineFeatures;
use golden::params::{Mode, RefView};
use rtl::matcher::declivity_matcher::{DeclivityMatcher, EngineLine, GainRule};
use rtl::params::{DT_FRAC_BITS, MATCH_DT_BITS, MATCH_DT_FRAC_BITS, POS_FRAC_BITS};
use rust_hdl::prelude::*;
use serde::Serialize;

use crate::config::Config;
use crate::formats::{position_lsb, SearchArea};

// The record and `d_t` formats the driver speaks are the same in every
// configuration (only the position's integer bits and the counts grow).
const _: () = assert!(
    rtl_hd::params::POS_FRAC_BITS == POS_FRAC_BITS
        && rtl_hd::params::DT_FRAC_BITS == DT_FRAC_BITS
        && rtl_hd::params::MATCH_DT_FRAC_BITS == MATCH_DT_FRAC_BITS
        && rtl_hd::params::MATCH_DT_BITS == MATCH_DT_BITS
);

/// A matcher of one configuration's crate (`rtl` is `sd`, `rtl-hd` is
/// `hd`: the same source with other widths) and cell count, as the driver
/// drives its ports, with its crate's timing formulas.
pub trait MatcherDut: Block + Send + Sized + 'static {
    /// The configuration the matcher is built in.
    const CONFIG: Config;
    /// Its gain cells.
    const CELLS: usize;
    /// The matcher for `rule`, built and connected.
    fn build(rule: GainRule) -> Box<Self>;
    /// Sets the clock input, the search area and both sides' inputs.
    fn drive(&mut self, clock: bool, area: SearchArea, r: &SideBeat, o: &SideBeat);
    /// Raises the clock.
    fn rise(&mut self);
    /// `r_ready`, `o_ready`.
    fn ready(&self) -> (bool, bool);
    /// The output beat, when `m_valid`.
    fn beat(&self) -> Option<MatchBeat>;
    /// `r_unpaired`, `o_unpaired`.
    fn unpaired(&self) -> (bool, bool);
    /// Clocks of the sweep of an `n × m` line pair.
    fn sweep_cycles(n: usize, m: usize) -> u64;
    /// Clocks of the traceback of an `n × m` pair that stops at diagonal
    /// `stop_diag` after `nodes` matches.
    fn traceback_cycles(n: usize, m: usize, stop_diag: usize, nodes: usize) -> u64;
    /// `(take, start, marker)` of each line by the engine's documented
    /// timing (`schedule` of the block's crate).
    fn schedule(lines: &[EngineLine]) -> Vec<(u64, u64, u64)>;
}

macro_rules! matcher_dut {
    ($k:ident, $config:expr) => {
        impl<const N: usize> MatcherDut for $k::matcher::declivity_matcher::DeclivityMatcher<N> {
            const CONFIG: Config = $config;
            const CELLS: usize = N;
            fn build(rule: GainRule) -> Box<Self> {
                let rule = match rule {
                    GainRule::Paper => $k::matcher::declivity_matcher::GainRule::Paper,
                    GainRule::Robust => $k::matcher::declivity_matcher::GainRule::Robust,
                };
                crate::blocks::build_block("building the matcher", move || Self::new(rule))
            }
            fn drive(&mut self, clock: bool, area: SearchArea, r: &SideBeat, o: &SideBeat) {
                let u = self;
                u.clock.next = clock.into();
                u.dispmin.next = (area.dispmin as u64).into();
                u.dispmax.next = (area.dispmax as u64).into();
                u.r_valid.next = r.valid;
                u.r_last.next = r.last;
                u.r_pos.next = (r.record.pos as u64).into();
                u.r_amp.next = ((r.record.amplitude as i64 as u64) & AMP_MASK).into();
                u.r_left0.next = (r.record.left[0] as u64).into();
                u.r_left1.next = (r.record.left[1] as u64).into();
                u.r_left2.next = (r.record.left[2] as u64).into();
                u.r_right0.next = (r.record.right[0] as u64).into();
                u.r_right1.next = (r.record.right[1] as u64).into();
                u.r_right2.next = (r.record.right[2] as u64).into();
                u.r_dt.next = (r.dt as u64).into();
                u.r_wide.next = r.wide;
                u.r_full.next = r.full;
                u.r_sof.next = r.sof;
                u.r_stamp.next = (r.stamp as u64).into();
                u.o_valid.next = o.valid;
                u.o_last.next = o.last;
                u.o_pos.next = (o.record.pos as u64).into();
                u.o_amp.next = ((o.record.amplitude as i64 as u64) & AMP_MASK).into();
                u.o_left0.next = (o.record.left[0] as u64).into();
                u.o_left1.next = (o.record.left[1] as u64).into();
                u.o_left2.next = (o.record.left[2] as u64).into();
                u.o_right0.next = (o.record.right[0] as u64).into();
                u.o_right1.next = (o.record.right[1] as u64).into();
                u.o_right2.next = (o.record.right[2] as u64).into();
                u.o_dt.next = (o.dt as u64).into();
                u.o_wide.next = o.wide;
                u.o_full.next = o.full;
                u.o_sof.next = o.sof;
                u.o_stamp.next = (o.stamp as u64).into();
            }
            fn rise(&mut self) {
                self.clock.next = true.into();
            }
            fn ready(&self) -> (bool, bool) {
                (self.r_ready.val(), self.o_ready.val())
            }
            fn unpaired(&self) -> (bool, bool) {
                (self.r_unpaired.val(), self.o_unpaired.val())
            }
            fn beat(&self) -> Option<MatchBeat> {
                let u = self;
                u.m_valid.val().then(|| MatchBeat {
                    marker: u.m_last.val(),
                    ref_index: u.m_ref.val().to_u64() as u32,
                    other_index: u.m_other.val().to_u64() as u32,
                    x_ref: u.m_x_ref.val().to_u64() as u32,
                    disp: u.m_disp.val().to_u64() as u32,
                    count: u.m_count.val().to_u64() as u32,
                    n: u.m_n.val().to_u64() as u32,
                    m: u.m_m.val().to_u64() as u32,
                    wide: u.m_wide.val(),
                    full: u.m_full.val(),
                    sof: u.m_sof.val(),
                })
            }
            fn sweep_cycles(n: usize, m: usize) -> u64 {
                $k::matcher::declivity_matcher::sweep_cycles(n, m, N) as u64
            }
            fn traceback_cycles(n: usize, m: usize, stop_diag: usize, nodes: usize) -> u64 {
                $k::matcher::traceback::traceback_cycles(n, m, stop_diag, nodes) as u64
            }
            fn schedule(lines: &[EngineLine]) -> Vec<(u64, u64, u64)> {
                let lines: Vec<_> = lines
                    .iter()
                    .map(|l| $k::matcher::declivity_matcher::EngineLine { input_done: l.input_done, sweep: l.sweep, traceback: l.traceback })
                    .collect();
                $k::matcher::declivity_matcher::schedule(&lines).into_iter().map(|t| (t.take, t.start, t.marker)).collect()
            }
        }
    };
}

/// The record amplitude's bits (`PIXEL_BITS + 1`, two's complement).
const AMP_MASK: u64 = (1 << (rtl::params::PIXEL_BITS + 1)) - 1;

matcher_dut!(rtl, Config::Sd);
matcher_dut!(rtl_hd, Config::Hd);

/// The `hd` configuration's matcher of `N` cells (`rtl-hd`).
pub type HdMatcher<const N: usize> = rtl_hd::matcher::declivity_matcher::DeclivityMatcher<N>;

/// One declivity record as the matcher takes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MatchRecord {
    /// `X_i · 2^POS_FRAC_BITS`.
    pub pos: u32,
    /// `a_i` (its sign is the polarity).
    pub amplitude: i32,
    pub left: [u8; 3],
    pub right: [u8; 3],
}

/// One line of one view as the matcher takes it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MatchLine {
    /// `d_t · 2^DT_FRAC_BITS`.
    pub dt: u32,
    pub records: Vec<MatchRecord>,
    pub wide: bool,
    pub full: bool,
    pub sof: bool,
    /// The line's last stored pixel (its stored width − 1), which the
    /// marker carries in `pos` (the reference side's reaches the output
    /// marker's `x_ref`).
    pub last_x: u32,
    /// The time stamp the marker carries (`r_stamp`, `o_stamp`: ticks of
    /// `2^STAMP_SHIFT` clocks); two lines that start a frame are paired
    /// only when their stamps are close (the matcher's Pairing).
    pub stamp: u32,
}

/// One output beat: a match, or a line's marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct MatchBeat {
    pub marker: bool,
    pub ref_index: u32,
    pub other_index: u32,
    /// `X_i · 2^POS_FRAC_BITS`.
    pub x_ref: u32,
    /// `(X_i - X_j) · 2^POS_FRAC_BITS`.
    pub disp: u32,
    pub count: u32,
    pub n: u32,
    pub m: u32,
    pub wide: bool,
    pub full: bool,
    pub sof: bool,
}

/// What one line pair came out as.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MatchedLine {
    pub matches: Vec<MatchBeat>,
    pub marker: MatchBeat,
    /// Clock of the marker.
    pub marker_cycle: u64,
    /// Clock at which the line's second input marker was taken.
    pub input_done_cycle: u64,
}

impl MatchedLine {
    /// The matched pairs `(i, j)`.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        self.matches.iter().map(|b| (b.ref_index as usize, b.other_index as usize)).collect()
    }
}

/// The inputs of one side for one clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SideBeat {
    pub valid: bool,
    pub last: bool,
    pub record: MatchRecord,
    pub dt: u32,
    pub wide: bool,
    pub full: bool,
    pub sof: bool,
    pub stamp: u32,
}

/// The matcher under direct drive, with `N` cells: `sd`'s by default,
/// [`HdMatcher`] for `hd`.
pub struct MatcherSim<const N: usize, D: MatcherDut = DeclivityMatcher<N>> {
    pub uut: Box<D>,
    /// Clocks so far.
    pub cycle: u64,
    /// Eq. 6's bound, `dispmax · 2^POS_FRAC_BITS`.
    pub dispmax: u32,
    /// Eq. 6's lower bound (`dispmin < d`), same unit; 0 from [`Self::new`].
    pub dispmin: u32,
    /// Called every clock at the sampling point (inputs applied and settled,
    /// before the rising edge): sees that clock's input and output ports
    /// (`sim::hdl::traces` records co-simulation traces with it).
    pub observer: Option<Box<dyn FnMut(&D) + Send>>,
}

impl<const N: usize> MatcherSim<N> {
    /// The `sd` matcher of `N` cells for `rule`, with the search bound
    /// `dispmax · 2^POS_FRAC_BITS`.
    pub fn new(rule: GainRule, dispmax: u32) -> Self {
        Self::in_area(rule, SearchArea::below(dispmax))
    }

    /// The `sd` matcher of `N` cells for `rule`, with eq. 6's search area
    /// `area`.
    pub fn in_area(rule: GainRule, area: SearchArea) -> Self {
        Self::build(rule, area)
    }
}

impl<const N: usize, D: MatcherDut> MatcherSim<N, D> {
    /// The matcher `D` for `rule`, with eq. 6's search area `area`.
    pub fn build(rule: GainRule, area: SearchArea) -> Self {
        assert_eq!(D::CELLS, N, "the matcher type has N cells");
        MatcherSim { uut: D::build(rule), cycle: 0, dispmax: area.dispmax, dispmin: area.dispmin, observer: None }
    }

    /// One clock: apply the two sides' beats, settle, sample; returns whether
    /// each side's beat was taken and the output beat, if any.
    fn cycle(&mut self, r: SideBeat, o: SideBeat) -> (bool, bool, Option<MatchBeat>) {
        let u = &mut *self.uut;
        let area = SearchArea { dispmin: self.dispmin, dispmax: self.dispmax };
        u.drive(false, area, &r, &o);
        settle(u, SETTLE_LOW);
        let (r_ready, o_ready) = u.ready();
        let r_taken = r.valid && r_ready;
        let o_taken = o.valid && o_ready;
        let out = u.beat();
        if let Some(observe) = self.observer.as_mut() {
            observe(u);
        }
        u.rise();
        settle(u, SETTLE_HIGH);
        self.cycle += 1;
        (r_taken, o_taken, out)
    }

    /// Runs line pairs `(reference, other)` through the matcher, offering
    /// each side's records back to back as soon as the side is ready, and
    /// returns what came out for each pair. `after_each` is called after
    /// every line's marker (a progress bar). `one_at_a_time` offers a pair
    /// only once the previous one's marker is out (the engine then takes it
    /// idle, as the cycle formulas assume).
    pub fn run(
        &mut self,
        pairs: &[(MatchLine, MatchLine)],
        one_at_a_time: bool,
        mut after_each: impl FnMut(),
    ) -> Vec<MatchedLine> {
        let mut out: Vec<MatchedLine> = Vec::with_capacity(pairs.len());
        let mut current = MatchedLine::default();
        // Per side: the pair being offered and the beat within it.
        let (mut rp, mut rk, mut op, mut ok) = (0usize, 0usize, 0usize, 0usize);
        let mut done_cycles = vec![0u64; pairs.len()];
        let mut markers_in = vec![0u8; pairs.len()];
        let limit = self.cycle + 10_000 + 2_000 * pairs.len() as u64;
        while out.len() < pairs.len() {
            assert!(self.cycle < limit, "the matcher stopped producing lines");
            let gate = |p: usize| !one_at_a_time || p == out.len();
            let r = if rp < pairs.len() && gate(rp) { side_beat(&pairs[rp].0, rk) } else { SideBeat::default() };
            let o = if op < pairs.len() && gate(op) { side_beat(&pairs[op].1, ok) } else { SideBeat::default() };
            let (rt, ot, beat) = self.cycle(r, o);
            let now = self.cycle - 1;
            for (taken, beat, p, k) in [(rt, r, &mut rp, &mut rk), (ot, o, &mut op, &mut ok)] {
                if !taken {
                    continue;
                }
                if beat.last {
                    markers_in[*p] += 1;
                    if markers_in[*p] == 2 {
                        done_cycles[*p] = now;
                    }
                    *p += 1;
                    *k = 0;
                } else {
                    *k += 1;
                }
            }
            if let Some(b) = beat {
                if b.marker {
                    current.marker = b;
                    current.marker_cycle = now;
                    current.input_done_cycle = done_cycles[out.len()];
                    out.push(std::mem::take(&mut current));
                    after_each();
                } else {
                    current.matches.push(b);
                }
            }
        }
        out
    }
}

impl<const N: usize, D: MatcherDut> MatcherSim<N, D> {
    /// Runs each side's lines through the matcher as its own stream (the
    /// two sides may have different numbers of lines: a camera's frame with
    /// a line more or less), each side's records offered back to back as
    /// soon as it is ready, until both are taken and `quiet` clocks pass
    /// without output. Returns the lines that came out and the clocks
    /// `r_unpaired` and `o_unpaired` were high on.
    pub fn run_sides(&mut self, refs: &[MatchLine], others: &[MatchLine], quiet: u64) -> (Vec<MatchedLine>, u64, u64) {
        let mut out = Vec::new();
        let mut current = MatchedLine::default();
        let (mut rp, mut rk, mut op, mut ok) = (0usize, 0usize, 0usize, 0usize);
        let (mut r_unpaired, mut o_unpaired, mut last_activity) = (0u64, 0u64, self.cycle);
        let limit = self.cycle + 10_000 + 2_000 * (refs.len() + others.len()) as u64;
        while rp < refs.len() || op < others.len() || self.cycle - last_activity <= quiet {
            assert!(self.cycle < limit, "the matcher stopped producing lines");
            let r = if rp < refs.len() { side_beat(&refs[rp], rk) } else { SideBeat::default() };
            let o = if op < others.len() { side_beat(&others[op], ok) } else { SideBeat::default() };
            let (ur, uo) = self.uut.unpaired();
            r_unpaired += ur as u64;
            o_unpaired += uo as u64;
            let (rt, ot, beat) = self.cycle(r, o);
            let now = self.cycle - 1;
            for (taken, beat, p, k) in [(rt, r, &mut rp, &mut rk), (ot, o, &mut op, &mut ok)] {
                if taken {
                    last_activity = now;
                    if beat.last {
                        *p += 1;
                        *k = 0;
                    } else {
                        *k += 1;
                    }
                }
            }
            if let Some(b) = beat {
                last_activity = now;
                if b.marker {
                    current.marker = b;
                    current.marker_cycle = now;
                    out.push(std::mem::take(&mut current));
                } else {
                    current.matches.push(b);
                }
            }
        }
        (out, r_unpaired, o_unpaired)
    }
}

/// Passes over the matcher made before `simulate` checks that the logic
/// settled, after the inputs (clock low) and after a clock edge: one fewer
/// than the least the matcher's logic needs, so that `simulate`'s own
/// checking pass is never wasted; any further pass is `simulate`'s.
const SETTLE_LOW: usize = 4;
const SETTLE_HIGH: usize = 8;

fn settle<D: MatcherDut>(u: &mut D, passes: usize) {
    crate::drive::settle_block(u, passes, 200, "the matcher");
}

/// Beat `k` of a line: its records, then its marker.
fn side_beat(line: &MatchLine, k: usize) -> SideBeat {
    match line.records.get(k) {
        Some(&record) => SideBeat { valid: true, record, ..SideBeat::default() },
        None => SideBeat {
            valid: true,
            last: true,
            record: MatchRecord { pos: line.last_x, ..MatchRecord::default() },
            dt: line.dt,
            wide: line.wide,
            full: line.full,
            sof: line.sof,
            stamp: line.stamp,
            ..SideBeat::default()
        },
    }
}

/// The golden mode whose gain rule the matcher was generated for.
pub(crate) fn golden_mode(rule: GainRule) -> Mode {
    match rule {
        GainRule::Paper => Mode::Paper,
        GainRule::Robust => Mode::Robust,
    }
}

/// A line's declivities and `d_t` in the detector's formats: positions
/// rounded down to `POS_FRAC_BITS` fraction bits (as the eq. 3 divider
/// does), `d_t` rounded to `DT_FRAC_BITS`; at most `n_max` records (the
/// detector's limit, `N_MAX`).
fn quantize_line(f: &LineFeatures, n_max: usize) -> MatchLine {
    let records = f
        .declivities
        .iter()
        .take(n_max)
        .map(|d| MatchRecord {
            pos: position_lsb(d.position),
            amplitude: d.amplitude,
            left: d.left,
            right: d.right,
        })
        .collect();
    MatchLine {
        dt: (f.dt * (1u32 << DT_FRAC_BITS) as f64).round() as u32,
        records,
        full: f.declivities.len() > n_max,
        ..MatchLine::default()
    }
}

/// The declivities of a [`MatchLine`] as golden's, with their fixed-point
/// positions, and its `d_t` in grey levels as the matcher uses it: rounded
/// down to `MATCH_DT_FRAC_BITS` fraction bits and saturated at
/// `MATCH_DT_BITS` (255.5: a line whose `d_t` reaches 255 has no
/// declivity, so real lines never meet the saturation).
pub(crate) fn dequantize(line: &MatchLine) -> (Vec<Declivity>, f64) {
    let decls = line
        .records
        .iter()
        .map(|r| Declivity {
            start: 0,
            end: 1,
            amplitude: r.amplitude,
            position: r.pos as f64 / (1u32 << POS_FRAC_BITS) as f64,
            left: r.left,
            right: r.right,
        })
        .collect();
    let dt = (line.dt >> (DT_FRAC_BITS - MATCH_DT_FRAC_BITS)).min((1 << MATCH_DT_BITS) - 1);
    (decls, dt as f64 / (1u32 << MATCH_DT_FRAC_BITS) as f64)
}

/// Golden's matching of one quantized line pair: the gain table of eq. 4–8
/// (left reference, `dispmax` in grey-level pixels), the best path of eq. 9
/// with golden's tie order, and where its traceback stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct GoldenMatch {
    pub table: GainTable,
    pub gain: f64,
    pub nodes: Vec<(usize, usize)>,
    /// `i + j` (0-based) of the last cell the traceback decided on; 0 for
    /// an empty table.
    pub stop_diag: usize,
}

impl GoldenMatch {
    /// The gain of a path by golden's table (`None` when it takes a pair
    /// that is no node, or is not increasing in both indices).
    pub fn path_gain(&self, nodes: &[(usize, usize)]) -> Option<f64> {
        let increasing = nodes.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1);
        if !increasing {
            return None;
        }
        nodes.iter().map(|&(i, j)| self.table.get(i, j)).sum()
    }
}

/// Golden's matcher on the quantized pair (see [`GoldenMatch`]), eq. 6's
/// area `0 < d < dispmax`.
pub fn golden_match(reference: &MatchLine, other: &MatchLine, dispmax: u32, rule: GainRule) -> GoldenMatch {
    golden_match_in(reference, other, SearchArea::below(dispmax), rule)
}

/// Golden's matcher on the quantized pair (see [`GoldenMatch`]), eq. 6's
/// area `area`.
pub fn golden_match_in(reference: &MatchLine, other: &MatchLine, area: SearchArea, rule: GainRule) -> GoldenMatch {
    let (r, dt_r) = dequantize(reference);
    let (o, dt_o) = dequantize(other);
    let g = gmax(dt_r, dt_o);
    let px = |lsb: u32| lsb as f64 / (1u32 << POS_FRAC_BITS) as f64;
    let mode = golden_mode(rule);
    let table = GainTable::from_fn(r.len(), o.len(), |i, j| node_gain(&r[i], &o[j], g, (px(area.dispmin), px(area.dispmax)), RefView::Left, mode));
    let tables = prefix_max_dp(&table);
    // golden::dp::traceback, keeping the last cell it decides on.
    let (mut i, mut j) = (r.len(), o.len());
    let mut nodes = Vec::new();
    let mut stop_diag = 0;
    while i > 0 && j > 0 {
        stop_diag = i + j - 2;
        match tables.choice_at(i, j) {
            Choice::Start => break,
            Choice::Node => {
                nodes.push((i - 1, j - 1));
                i -= 1;
                j -= 1;
            }
            Choice::Up => i -= 1,
            Choice::Left => j -= 1,
        }
    }
    nodes.reverse();
    GoldenMatch { gain: tables.best_gain(), table, nodes, stop_diag }
}

/// How a line's rtl matches compare with golden's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Agreement {
    /// The same pairs.
    Identical,
    /// Other pairs, with golden's optimal gain by golden's gains (within the
    /// gain tolerance, here zero: the fixed-point gains are exact).
    EqualGain,
    /// Neither.
    Mismatch,
}

/// Compares the rtl pairs of a line with golden's.
pub fn agreement(golden: &GoldenMatch, rtl_pairs: &[(usize, usize)]) -> Agreement {
    if golden.nodes == rtl_pairs {
        Agreement::Identical
    } else if golden.path_gain(rtl_pairs) == Some(golden.gain) {
        Agreement::EqualGain
    } else {
        Agreement::Mismatch
    }
}

/// Checks one line's beats against its inputs and golden's matching of
/// them ([`golden_match`]): the pairs' positions and disparities, the
/// marker's counts, and the path's gain by golden's gains (golden's
/// optimum, exactly). Returns the first difference found.
pub fn check_line(reference: &MatchLine, other: &MatchLine, got: &MatchedLine, golden: &GoldenMatch) -> Result<(), String> {
    let (n, m) = (reference.records.len(), other.records.len());
    if got.marker.n as usize != n || got.marker.m as usize != m {
        return Err(format!("marker counts {}×{}, sent {n}×{m}", got.marker.n, got.marker.m));
    }
    if got.marker.count as usize != got.matches.len() {
        return Err(format!("marker count {} with {} matches", got.marker.count, got.matches.len()));
    }
    for b in &got.matches {
        let (i, j) = (b.ref_index as usize, b.other_index as usize);
        let (Some(r), Some(o)) = (reference.records.get(i), other.records.get(j)) else {
            return Err(format!("match ({i}, {j}) outside the line"));
        };
        if b.x_ref != r.pos || b.disp != r.pos.wrapping_sub(o.pos) {
            return Err(format!("match ({i}, {j}): x_ref {} disp {}, want {} {}", b.x_ref, b.disp, r.pos, r.pos - o.pos));
        }
    }
    match golden.path_gain(&got.pairs()) {
        Some(g) if g == golden.gain => {}
        g => return Err(format!("the rtl path's gain by golden's gains is {g:?}, golden's optimum {}", golden.gain)),
    }
    Ok(())
}

/// The line pairs of two images as the `sd` matcher takes them
/// ([`image_lines_in`]).
pub fn image_lines(left: &golden::GreyImage, right: &golden::GreyImage) -> Vec<(MatchLine, MatchLine)> {
    image_lines_in(left, right, Config::Sd)
}

/// The line pairs of two images as `config`'s matcher takes them: golden's
/// declivities of each row in hardware-parity mode in `config`'s limits,
/// quantized ([`quantize_line`]); the first row carries the start of frame.
pub fn image_lines_in(left: &golden::GreyImage, right: &golden::GreyImage, config: Config) -> Vec<(MatchLine, MatchLine)> {
    use rayon::prelude::*;
    let limits = config.limits();
    let sizes = config.sizes();
    (0..left.height())
        .into_par_iter()
        .map(|y| {
            // A line wider than W_MAX is its first W_MAX pixels, flagged
            // wide, as the detector sends it.
            // (The detector's own outputs, `d_t` at its 1/32 grey level:
            // `line_features_with` would give the matcher's 1/2.)
            let f = |img: &golden::GreyImage| {
                let d = golden::hardware::detect_line(img.row(y), limits);
                let features = LineFeatures { sigma: d.dt / golden::noise::THRESHOLD_FACTOR, dt: d.dt, declivities: d.declivities };
                MatchLine { wide: img.width() > sizes.w_max, last_x: (img.width().min(sizes.w_max) - 1) as u32, ..quantize_line(&features, sizes.n_max) }
            };
            let (mut l, mut r) = (f(left), f(right));
            (l.sof, r.sof) = (y == 0, y == 0);
            (l, r)
        })
        .collect()
}

/// What `declivity rtl match` reports for one pair of images.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MatchReport {
    /// The configuration the matcher was generated in, and its cells.
    pub config: Config,
    pub cells: usize,
    pub image: String,
    /// The gain rule the matcher was generated for.
    pub rule: &'static str,
    /// Eq. 6's area `dispmin < d < dispmax`, px.
    pub dispmin: f64,
    pub dispmax: f64,
    pub lines: usize,
    pub declivities_ref: usize,
    pub declivities_other: usize,
    pub matches_rtl: usize,
    pub matches_golden: usize,
    pub identical_lines: usize,
    pub equal_gain_lines: usize,
    pub mismatch_lines: usize,
    /// Lines whose beats disagree with their inputs (positions, counts).
    pub malformed_lines: usize,
    /// Lines whose marker left on another clock than the engine's
    /// documented timing gives (`rtl::matcher::declivity_matcher::schedule`).
    pub off_schedule_lines: usize,
    /// The most clocks the engine spent on one line pair (taking it to its
    /// marker).
    pub max_cycles_per_line: u64,
    /// The most clocks a line pair kept the engine from taking the next: from
    /// its take to the clock after its traceback starts (its sweep, and any
    /// wait for the traceback of the pair before). At most the line time of
    /// a `W_MAX` line means the engine keeps up with lines back to back.
    pub max_engine_period: u64,
    /// The line of `max_cycles_per_line`.
    pub max_cycles_line: usize,
    pub cycles: u64,
    pub sim_cycles_per_s: f64,
}

/// Per line: the rtl result, golden's and their agreement.
#[derive(Debug, Clone)]
pub struct LineOutcome {
    pub rtl: MatchedLine,
    pub golden: GoldenMatch,
    pub agreement: Agreement,
    /// Clocks from the engine taking the pair to its marker.
    pub engine_cycles: u64,
}

/// Runs every line pair through the matcher and golden and compares them.
fn match_lines<const N: usize, D: MatcherDut>(
    sim: &mut MatcherSim<N, D>,
    rule: GainRule,
    name: &str,
    pairs: &[(MatchLine, MatchLine)],
    mut progress: impl FnMut(),
) -> (MatchReport, Vec<LineOutcome>) {
    use rayon::prelude::*;
    let c0 = sim.cycle;
    let t0 = std::time::Instant::now();
    let got = sim.run(pairs, false, &mut progress);
    let secs = t0.elapsed().as_secs_f64();
    let cycles = sim.cycle - c0;
    let area = SearchArea { dispmin: sim.dispmin, dispmax: sim.dispmax };
    let golden: Vec<GoldenMatch> = pairs.par_iter().map(|(r, o)| golden_match_in(r, o, area, rule)).collect();
    let mut report = MatchReport {
        config: D::CONFIG,
        cells: N,
        image: name.to_string(),
        rule: golden_mode(rule).name(),
        dispmin: area.dispmin_px(),
        dispmax: area.dispmax as f64 / (1u32 << POS_FRAC_BITS) as f64,
        lines: pairs.len(),
        declivities_ref: pairs.iter().map(|p| p.0.records.len()).sum(),
        declivities_other: pairs.iter().map(|p| p.1.records.len()).sum(),
        matches_rtl: got.iter().map(|l| l.matches.len()).sum(),
        matches_golden: golden.iter().map(|g| g.nodes.len()).sum(),
        identical_lines: 0,
        equal_gain_lines: 0,
        mismatch_lines: 0,
        malformed_lines: 0,
        off_schedule_lines: 0,
        max_cycles_per_line: 0,
        max_engine_period: 0,
        max_cycles_line: 0,
        cycles,
        sim_cycles_per_s: cycles as f64 / secs.max(1e-9),
    };
    // The engine's takes by its documented timing (`rtl::matcher::declivity_matcher::
    // schedule`, checked against the measured markers by `tests/rtl_matcher.rs`).
    let times = D::schedule(
        &got.iter()
            .zip(&golden)
            .map(|(rtl, g)| {
                let (n, m) = (rtl.marker.n as usize, rtl.marker.m as usize);
                EngineLine {
                    input_done: rtl.input_done_cycle,
                    sweep: D::sweep_cycles(n, m),
                    traceback: D::traceback_cycles(n, m, g.stop_diag, g.nodes.len()),
                }
            })
            .collect::<Vec<_>>(),
    );
    let mut outcomes = Vec::with_capacity(pairs.len());
    for (k, (((rtl, golden), (r, o)), t)) in got.into_iter().zip(golden).zip(pairs).zip(times).enumerate() {
        let agreement = agreement(&golden, &rtl.pairs());
        match agreement {
            Agreement::Identical => report.identical_lines += 1,
            Agreement::EqualGain => report.equal_gain_lines += 1,
            Agreement::Mismatch => report.mismatch_lines += 1,
        }
        report.malformed_lines += check_line(r, o, &rtl, &golden).is_err() as usize;
        let (take, start, marker) = t;
        report.off_schedule_lines += usize::from(rtl.marker_cycle != marker);
        let engine_cycles = rtl.marker_cycle - take;
        if engine_cycles > report.max_cycles_per_line {
            report.max_cycles_per_line = engine_cycles;
            report.max_cycles_line = k;
        }
        report.max_engine_period = report.max_engine_period.max(start + 1 - take);
        outcomes.push(LineOutcome { rtl, golden, agreement, engine_cycles });
    }
    (report, outcomes)
}

/// [`match_image_on`] with the `sd` matcher of `N` cells.
pub fn match_image<const N: usize>(
    name: &str,
    pairs: &[(MatchLine, MatchLine)],
    rule: GainRule,
    area: SearchArea,
    chunks: usize,
    progress: &(dyn Fn() + Sync),
) -> (MatchReport, Vec<LineOutcome>) {
    match_image_on::<N, DeclivityMatcher<N>>(name, pairs, rule, area, chunks, progress)
}

/// [`match_lines`] on every row of an image pair, the rows cut into
/// `chunks` runs of consecutive rows, each on a matcher of its own on a
/// thread of its own (rust-hdl simulates one block on one core; line pairs
/// are independent, so the matches are those of one run; only the clocks
/// at the seams differ). `progress` is called after every line, from any
/// thread. The report's `cycles` is the sum over the runs and
/// `sim_cycles_per_s` the clocks simulated per second of wall time.
pub fn match_image_on<const N: usize, D: MatcherDut>(
    name: &str,
    pairs: &[(MatchLine, MatchLine)],
    rule: GainRule,
    area: SearchArea,
    chunks: usize,
    progress: &(dyn Fn() + Sync),
) -> (MatchReport, Vec<LineOutcome>) {
    let t0 = std::time::Instant::now();
    let chunks = chunks.clamp(1, pairs.len().max(1));
    let size = pairs.len().div_ceil(chunks).max(1);
    let parts: Vec<(MatchReport, Vec<LineOutcome>)> = std::thread::scope(|s| {
        let handles: Vec<_> = pairs
            .chunks(size)
            .map(|part| {
                s.spawn(move || {
                    let mut sim = MatcherSim::<N, D>::build(rule, area);
                    match_lines(&mut sim, rule, name, part, progress)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("a matcher thread panicked")).collect()
    });
    let secs = t0.elapsed().as_secs_f64();
    let mut iter = parts.into_iter();
    let (mut report, mut outcomes) = iter.next().unwrap_or_else(|| {
        let mut sim = MatcherSim::<N, D>::build(rule, area);
        match_lines(&mut sim, rule, name, &[], progress)
    });
    let mut offset = outcomes.len();
    for (r, o) in iter {
        report.declivities_ref += r.declivities_ref;
        report.declivities_other += r.declivities_other;
        report.matches_rtl += r.matches_rtl;
        report.matches_golden += r.matches_golden;
        report.identical_lines += r.identical_lines;
        report.equal_gain_lines += r.equal_gain_lines;
        report.mismatch_lines += r.mismatch_lines;
        report.malformed_lines += r.malformed_lines;
        report.off_schedule_lines += r.off_schedule_lines;
        report.max_engine_period = report.max_engine_period.max(r.max_engine_period);
        if r.max_cycles_per_line > report.max_cycles_per_line {
            report.max_cycles_per_line = r.max_cycles_per_line;
            report.max_cycles_line = r.max_cycles_line + offset;
        }
        report.cycles += r.cycles;
        offset += o.len();
        outcomes.extend(o);
    }
    report.lines = pairs.len();
    report.sim_cycles_per_s = report.cycles as f64 / secs.max(1e-9);
    (report, outcomes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(seed: u64) -> impl FnMut() -> u64 {
        let mut r = crate::rng::VectorRng(seed);
        move || r.next()
    }

    fn line(next: &mut impl FnMut() -> u64, n: usize, dt: u32) -> MatchLine {
        let mut pos = 0u32;
        let records = (0..n)
            .map(|_| {
                pos += 16 + (next() % 200) as u32;
                let amplitude = if next() % 2 == 0 { 30 } else { -30 };
                let mut lv = || (next() % 40) as u8 + 100;
                MatchRecord { pos, amplitude, left: [lv(), lv(), lv()], right: [lv(), lv(), lv()] }
            })
            .collect();
        MatchLine { dt, records, ..MatchLine::default() }
    }

    #[test]
    fn smoke_small_lines_match_golden() {
        let mut next = rng(7);
        let pairs: Vec<_> = (0..6)
            .map(|k| {
                let r = line(&mut next, 3 + k * 2, 300 + (k as u32) * 50);
                let o = line(&mut next, 4 + k * 2, 280);
                (r, o)
            })
            .collect();
        let mut sim = MatcherSim::<16>::new(GainRule::Robust, 40 << POS_FRAC_BITS);
        let got = sim.run(&pairs, false, || {});
        for ((r, o), g) in pairs.iter().zip(&got) {
            let want = golden_match(r, o, sim.dispmax, GainRule::Robust);
            check_line(r, o, g, &want).unwrap();
            assert_eq!(agreement(&want, &g.pairs()), Agreement::Identical);
        }
    }
}
