//! Direct drive of the rtl row check (`rtl::post::row_check`) and its comparison
//! with golden's hardware-parity row check (`golden::hardware::row_check`,
//! the check against neighbouring rows of `golden::frame::confirmed_matches`
//! on the matcher's fixed-point matches).
//!
//! A row's matches are the matcher's outputs: `(x, d)`, the reference
//! position and the disparity, both with `POS_FRAC_BITS` fraction bits.
//! golden checks the same matches, so the two must keep exactly the same
//! matches.

use golden::hardware::row_check::{row_check, FixedMatch as GoldenMatch};
use rtl::post::row_check::RowCheck;
use rtl::rust_hdl::prelude::*;

/// One fixed-point match: `(x, d)`, `POS_FRAC_BITS` fraction bits each.
pub type FixedMatch = (u64, u64);

/// A row as offered to the row check, with its timing.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TimedRow {
    /// Matches by strictly increasing `x`.
    pub matches: Vec<FixedMatch>,
    /// The row starts a frame (`m_sof` on its marker).
    pub sof: bool,
    /// The row ends a frame (`m_eof` on its marker).
    pub eof: bool,
    /// Clocks from the row's first beat to the next row's first beat, at
    /// least the row's beats.
    pub period: usize,
    /// Idle clocks after each match (`m_valid` low).
    pub gap: usize,
    /// The row's last pixel, on its marker's `m_x_ref` (the line
    /// processor's frame width).
    pub last_x: u64,
}

/// A row as the row check sent it.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct CheckedRow {
    /// The kept matches, in order.
    pub kept: Vec<FixedMatch>,
    /// Clock of each kept match on `c_*`.
    pub match_cycles: Vec<u64>,
    /// `c_count` on the marker.
    pub count: usize,
    /// `c_sof`, `c_eof` on the marker.
    pub sof: bool,
    pub eof: bool,
    /// `c_x_ref` on the marker: the row's last pixel.
    pub last_x: u64,
    /// Clock of the marker on `c_*`.
    pub marker_cycle: u64,
}

/// What a run returns: the rows out, and the clock of each offered row's
/// marker on `m_*`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RowRun {
    pub rows: Vec<CheckedRow>,
    pub markers: Vec<u64>,
    /// Indices of the offered rows that were dropped (`overflow` on the
    /// clock after their marker).
    pub dropped: Vec<usize>,
    /// Rows dropped as the last of a frame cut short (`cut`).
    pub cut: usize,
}

/// The row check under direct drive.
pub struct RowCheckSim {
    uut: Box<RowCheck>,
    /// Clocks simulated.
    pub cycle: u64,
    /// Clocks on which `overflow` was high (rows dropped).
    pub overflows: u64,
    /// Clocks on which `crowded` was high.
    pub crowded: u64,
    /// Clocks on which `cut` was high (a short frame's last row dropped).
    pub cuts: u64,
}

/// One clock's input beat (the row check's `m_*` ports).
#[derive(Debug, Clone, Copy, Default)]
pub struct Beat {
    pub valid: bool,
    pub last: bool,
    pub x: u64,
    pub d: u64,
    pub sof: bool,
    pub eof: bool,
}

/// The rows as clocks of input: each row's matches (each followed by its
/// `gap` idle clocks), its marker, then idle clocks up to its `period`.
/// Returns the beats and the index of each row's marker among them.
pub fn row_beats(rows: &[TimedRow]) -> (Vec<Beat>, Vec<usize>) {
    let mut beats: Vec<Beat> = Vec::new();
    let mut marker_at = Vec::with_capacity(rows.len());
    for r in rows {
        let first = beats.len();
        for &(x, d) in &r.matches {
            beats.push(Beat { valid: true, x, d, ..Beat::default() });
            beats.extend(std::iter::repeat_n(Beat::default(), r.gap));
        }
        marker_at.push(beats.len());
        beats.push(Beat { valid: true, last: true, sof: r.sof, eof: r.eof, x: r.last_x, ..Beat::default() });
        let end = first + r.period;
        if beats.len() < end {
            beats.resize(end, Beat::default());
        }
    }
    (beats, marker_at)
}

/// One clock's output.
#[derive(Debug, Clone, Copy)]
struct Out {
    last: bool,
    x: u64,
    d: u64,
    sof: bool,
    eof: bool,
    count: usize,
}

impl Default for RowCheckSim {
    fn default() -> Self {
        Self::new()
    }
}

impl RowCheckSim {
    pub fn new() -> Self {
        let mut uut = Box::new(RowCheck::new());
        uut.connect_all();
        RowCheckSim { uut, cycle: 0, overflows: 0, crowded: 0, cuts: 0 }
    }

    fn clock(&mut self, b: Beat) -> Option<Out> {
        let u = &mut *self.uut;
        u.clock.next = false.into();
        u.m_valid.next = b.valid;
        u.m_last.next = b.last;
        u.m_x_ref.next = b.x.into();
        u.m_disp.next = b.d.into();
        u.m_sof.next = b.sof;
        u.m_eof.next = b.eof;
        assert!(simulate(u, 100), "the row check's logic did not settle");
        let out = u.c_valid.val().then(|| Out {
            last: u.c_last.val(),
            x: u.c_x_ref.val().index() as u64,
            d: u.c_disp.val().index() as u64,
            sof: u.c_sof.val(),
            eof: u.c_eof.val(),
            count: u.c_count.val().index(),
        });
        self.overflows += u.overflow.val() as u64;
        self.crowded += u.crowded.val() as u64;
        self.cuts += u.cut.val() as u64;
        u.clock.next = true.into();
        assert!(simulate(u, 100), "the row check's logic did not settle");
        self.cycle += 1;
        out
    }

    /// One frame (a row per entry, `(x, d)` matches), one row per `period`
    /// clocks, matches back to back: see [`RowCheckSim::run_timed`].
    pub fn run(&mut self, frame: &[Vec<FixedMatch>], period: usize) -> RowRun {
        self.run_frames(&[frame], period)
    }

    /// Frames back to back, one row per `period` clocks.
    pub fn run_frames(&mut self, frames: &[&[Vec<FixedMatch>]], period: usize) -> RowRun {
        let rows: Vec<TimedRow> = frames.iter().flat_map(|f| frame_rows(f, period, 0)).collect();
        self.run_timed(&rows)
    }

    /// Offers the rows (matches, then the marker, then idle clocks up to
    /// the row's period) and collects the rows out until every offered row
    /// has come out (dropped rows, counted in `overflows`, do not) or
    /// nothing can come any more.
    pub fn run_timed(&mut self, rows: &[TimedRow]) -> RowRun {
        let (beats, marker_at) = row_beats(rows);
        let start = self.cycle;
        let dropped_before = self.overflows;
        let cuts_before = self.cuts;
        let n: usize = rows.iter().map(|r| r.matches.len()).sum();
        let limit = start + beats.len() as u64 + 8 * (n + rows.len()) as u64 + 64 * rows.len() as u64 + 64;
        let mut out = RowRun { rows: Vec::new(), markers: marker_at.iter().map(|&m| start + m as u64).collect(), dropped: Vec::new(), cut: 0 };
        let mut cur = CheckedRow::default();
        let mut k = 0usize;
        while self.cycle < limit && out.rows.len() + ((self.overflows - dropped_before + self.cuts - cuts_before) as usize) < rows.len() {
            let b = beats.get(k).copied().unwrap_or_default();
            k += 1;
            let now = self.cycle;
            let before = self.overflows;
            let o = self.clock(b);
            if self.overflows > before {
                if let Some(i) = out.markers.iter().position(|&m| m + 1 == now) {
                    out.dropped.push(i);
                }
            }
            if let Some(o) = o {
                if o.last {
                    cur.count = o.count;
                    cur.sof = o.sof;
                    cur.eof = o.eof;
                    cur.last_x = o.x;
                    cur.marker_cycle = now;
                    out.rows.push(std::mem::take(&mut cur));
                } else {
                    cur.kept.push((o.x, o.d));
                    cur.match_cycles.push(now);
                }
            }
        }
        out.cut = (self.cuts - cuts_before) as usize;
        // Every offered beat is in, even after the last row came out.
        while k < beats.len() {
            let b = beats[k];
            k += 1;
            assert!(self.clock(b).is_none(), "a row came out beyond the rows offered");
        }
        out
    }
}

/// A frame's rows as [`TimedRow`]s: the first flagged `sof`, the last
/// `eof`, each taking `period` clocks, `gap` idle clocks after each match.
pub fn frame_rows(frame: &[Vec<FixedMatch>], period: usize, gap: usize) -> Vec<TimedRow> {
    let h = frame.len();
    frame
        .iter()
        .enumerate()
        .map(|(y, m)| TimedRow { matches: m.clone(), sof: y == 0, eof: y + 1 == h, period, gap, last_x: 0 })
        .collect()
}

/// The matches golden's hardware-parity row check keeps of each row.
pub fn golden_kept(frame: &[Vec<FixedMatch>]) -> Vec<Vec<FixedMatch>> {
    let rows: Vec<Vec<GoldenMatch>> = frame.iter().map(|r| r.iter().map(|&(x, d)| GoldenMatch { x: x as u32, d: d as u32 }).collect()).collect();
    let keep = row_check(&rows, crate::config::Config::Sd.limits());
    frame.iter().zip(keep).map(|(row, k)| row.iter().zip(k).filter(|(_, k)| *k).map(|(&m, _)| m).collect()).collect()
}

/// golden's matches of every row of a pair before the check across rows
/// (`process_line` with `params`), quantised as the matcher emits them:
/// `⌊16·x_ref⌋`, `⌊16·d⌋` ([`crate::formats::position_lsb`]).
pub fn unchecked_rows(left: &golden::GreyImage, right: &golden::GreyImage, params: &golden::Params) -> Vec<Vec<FixedMatch>> {
    (0..left.height())
        .map(|y| {
            let l = golden::line::process_line(left.row(y), right.row(y), params);
            l.matches
                .iter()
                .map(|m| (crate::formats::position_lsb(m.x_ref) as u64, crate::formats::position_lsb(m.disparity) as u64))
                .collect()
        })
        .collect()
}
