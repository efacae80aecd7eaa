//! The sensor's datapath (`DESIGN.md` §3, "top level"): two camera streams
//! in, one disparity per reference (left) pixel out, every scanline
//! pipelined behind the one before.
//!
//! ```text
//! left  ─► SkidBuffer ─► DeclivityDetector ─► RecordFifo ─┐
//!                                                         ├─► DeclivityMatcher ─► RowCheck ─► Interpolator
//! right ─► SkidBuffer ─► DeclivityDetector ─► RecordFifo ─┘                      ─► VerticalMedian ─► DepthStage ─► out
//! ```
//!
//! - Each camera comes in through a [`SkidBuffer`], a register slice, so
//!   that its `tready` is a register.
//! - Each camera has its own [`DeclivityDetector`] (eq. 2–3): line n is
//!   detected while line n − 1 is matched and line n − 2 interpolated.
//! - A [`RecordFifo`] per side holds the records while the matcher is busy
//!   with a heavier line (`declivity budget` gives the worst line's clocks),
//!   so that the cameras are not stalled.
//! - The [`DeclivityMatcher`] (eq. 4–9, the default gain rule
//!   [`GainRule::Robust`] or the paper's) takes a pair when both sides'
//!   markers are in.
//! - The [`RowCheck`] keeps the matches a neighbouring row confirms (the
//!   default mode's consistency check; one line of delay).
//! - The [`Interpolator`] (paper §IV's last step, with the default mode's
//!   edge jump [`EDGE_JUMP_LSB`] or none) gives one disparity per pixel.
//! - The [`VerticalMedian`] takes the median of [`MEDIAN_TAPS`] (nine)
//!   rows (the default mode's; [`MEDIAN_HALF`] (four) lines of delay, the
//!   last [`MEDIAN_HALF`] rows flushed after the frame's last).
//! - The [`DepthStage`] gives each disparity its depth (eq. 1) for the
//!   camera the processor is generated for.
//!
//! ## Ports
//! - `clock`; `reset`, synchronous and active high (see Reset).
//! - In, per camera (`l_` left = reference, `r_` right), AXI4-Stream video:
//!   `tdata` (grey level), `tvalid`, `tuser` (start of frame, on a line's
//!   first pixel), `tlast` (end of line); out `tready` (the register
//!   slice's, a register: it follows the detector's, high except between
//!   lines of widths below the detector's `MIN_LINE_PERIOD`, one clock
//!   later).
//! - `dispmin`, `dispmax`: eq. 6's search area `dispmin < d < dispmax`,
//!   [`POS_FRAC_BITS`] fraction bits (`dispmin` 0: the paper's); the
//!   matcher reads them as it sweeps a line, so change them between frames.
//!   `height`:
//!   the frame's rows (its last row ends the frame for the row check and
//!   the median, which then flush it; registered, so it must hold from two
//!   clocks before a frame's first marker reaches the row check to the
//!   frame's last pixel out of the interpolator: in practice, set it before
//!   the frame and keep it).
//! - Out, AXI4-Stream without back-pressure (`tready` absent, as the
//!   standard allows: the sink takes a beat every clock): `m_tvalid`,
//!   `m_tdata` (bits 15..0 the disparity, [`POS_FRAC_BITS`] fraction bits,
//!   0 = none; bits 31..16 the depth in mm, 0 = none, [`DEPTH_MAX_MM`] =
//!   that far or farther), `m_tuser` (the frame's first pixel), `m_tlast`
//!   (a line's last pixel).
//!   Every line of an output frame has the frame's width: that of the
//!   reference camera's first line of the frame (at most [`W_MAX`]; see
//!   "Frame width").
//! - Status, counters that wrap: `records_dropped` (detector beats that
//!   found a record queue full), `lines_dropped` (lines the row check
//!   had no room for, its rows coming faster than it checks them, or the
//!   interpolator, which the limit on lines in flight below rules out,
//!   and the last row of a frame cut short, which the row check drops when
//!   the next frame begins: their pixels are not sent),
//!   `pixels_dropped` (pixels that came to the median while it flushed a
//!   frame's last rows: the vertical blanking must last the lines
//!   `declivity budget` gives, `vblank_lines`, about [`MEDIAN_HALF`]),
//!   `lines_full` (lines with more than `ROWS_PER_CELL·N` ([`N_MAX`] in the
//!   sensor's [`N_CELLS`] cells) declivities on a side: the first are
//!   matched),
//!   `lines_wide` (line pairs with a side cut: wider than [`W_MAX`], or a
//!   later line of a frame wider than the frame's first: see "Frame
//!   width"), `lines_unpaired` (lines of one camera
//!   dropped because the other camera's line at their place starts a frame
//!   and they do not, or both do more than [`SOF_SKEW_MAX`] clocks apart
//!   and theirs is the older: see the matcher's Pairing). Each counts its event two
//!   clocks after it (the event is registered beside its source).
//!
//! ## Timing
//! Throughput: one pixel per clock per camera while the matcher keeps up on
//! average; a line's matching may take longer than its line time as long as
//! the record queues ([`crate::stream::record_fifo::RECORD_FIFO_DEPTH`] beats)
//! absorb it. Latency from a line's last pixel in to its first disparity
//! out: the register slice's [`crate::stream::skid_buffer::SKID_LAG`], the
//! detector's [`crate::detector::declivity_detector::marker_latency`], the
//! queue's [`crate::stream::record_fifo::RECORD_FIFO_LAG`], the matcher's line
//! (`line_cycles`), one line period in the row check (it waits for the
//! next line's matches), [`CHECK_REGISTER_LAG`] between the row check and
//! the interpolator, the interpolator's `SEGMENT_LAG + PIXEL_LAG`,
//! [`INTERP_REGISTER_LAG`] between the interpolator and the median,
//! [`MEDIAN_HALF`] line periods in the median (it waits for the row
//! [`MEDIAN_HALF`] below),
//! [`MEDIAN_REGISTER_LAG`] between the median and the depth stage, the
//! depth stage's `DEPTH_LAG`, and [`OUTPUT_REGISTER_LAG`] to the output
//! port. The simulation measures it (`declivity rtl depth`:
//! `latency_cycles`, the frame's first line). A later line's
//! latency is more by the largest backlog of the matcher so far in the
//! frame (see "Lines in flight"). After the frame's last line the row check
//! and the median flush their last rows by themselves; the next frame may
//! start once they have: about [`MEDIAN_HALF`] lines of vertical blanking,
//! a line or two more when the row check's first and last rows take longer
//! than the others, fewer when the line period is longer than the line
//! (`declivity budget` gives the number, `vblank_lines`).
//!
//! ## Reset
//! Every block's registers start from their Verilog initial values (queues
//! empty, engines idle, status counters at zero), so the first beat after
//! configuration may start a frame. `reset` (synchronous, active high, one
//! clock or more) returns every register to that value at any clock, in a
//! line or between lines; lines in flight are forgotten and nothing leaves
//! `m_*` until the next frame's. The detectors then clear their histograms:
//! `l_tready` and `r_tready` fall once the input registers are full and stay
//! low until [`RESET_RECOVERY`] clocks after the reset's last clock. The
//! memories are not cleared otherwise: a row, a line or a record is read
//! only after it has been written since the reset. From the next start of
//! frame on, the output is a fresh run's, beat for beat
//! (`tests/rtl_stereo.rs`, `tests/cocotb`). `reset` reaches the blocks
//! through a [`ResetBuffer`]: in the ECP5 a `DCCA` puts it on a global net
//! to every flip-flop (31 000 in `sd`), with no clock of latency.
//!
//! ## Faulty cameras
//! Lines are paired in order within a frame: a line that starts a frame
//! (`tuser`) is paired only with the other camera's line that starts a
//! frame, the other camera's extra lines of the frame before being dropped
//! unpaired (`lines_unpaired`; the matcher's Pairing), and only when the
//! two lines' markers left their detectors at most [`SOF_SKEW_MAX`] clocks
//! apart (each marker carries a time stamp, the upper [`STAMP_BITS`] bits
//! of a clock count, through the record queue's lane 3); further apart,
//! the older is dropped unpaired. A `tuser` inside a
//! line ends that line on the beat before (the detector's Faults). Lines of
//! other widths, and lines run together by a missing `tlast`, take their
//! frame's width (see "Frame width"). Frames cut short, restarted, out of
//! step, paused or of mixed widths: `docs/hardware/datasheet.md`, "Faulty cameras",
//! and the fault campaign, `sim::hdl::faults`.
//!
//! ## Lines in flight
//! The interpolator sends one line per `W` clocks, the cameras' rate, so
//! once its output has fallen behind it never catches up within a frame:
//! after the matcher has been late by `D` clocks (a stretch of lines slower
//! to match than their line time, the backlog waiting in the record
//! queues), the interpolator's output stays `D` later for the rest of the
//! frame, and when the matcher has caught up its queue holds the lines of
//! those `D` clocks besides its usual one or two. Real pairs have such
//! stretches (a busy run of lines puts the matcher several line times
//! behind), so the queue must hold several lines at once. A queue sized
//! for every backlog the record queues allow is large (the figures that
//! follow are `sd`'s): they hold
//! [`RECORD_FIFO_DEPTH`](crate::stream::record_fifo::RECORD_FIFO_DEPTH)
//! (1024) beats per side, the matching of up to eight full
//! lines (`line_period` 845 clocks per 129 beats back to back, 14 for an
//! empty line),
//! and with the three pairs inside the matcher a backlog of about 9 k clocks,
//! 21 lines of 434 px and more of narrower ones: a queue of 32 lines and
//! their 4 k segments (24 `DP16KD` instead of 6).
//!
//! Instead the top keeps at most [`LINES_IN_FLIGHT`] = [`LINE_QUEUE`] (8)
//! lines between the matcher's input and the interpolator's output: a line
//! counts from its reference marker taken by the matcher to its last pixel
//! out of the interpolator (or its drop, by the row check, the interpolator
//! or, unpaired, the matcher; these are counted a clock late, so
//! the hold lasts a clock longer than it must), and while that many are in flight
//! the reference record queue is held (its `r_valid` to the matcher low; the
//! limit is reached only on a marker, so whole lines are held). The rest of
//! a backlog waits in the record queues, where it came from (their
//! overflow is `records_dropped`). The interpolator then never drops a
//! line: when one starts, the other lines in its queue are in flight, at
//! most `LINE_QUEUE - 1`, and their segments, at most `N_MAX - 1` each
//! (889 in `sd`), leave its reserve free (`SEG_RESERVE` = 131 of 1024 in
//! `sd`). Nothing
//! waits on itself: the row check holds back only the last row it got (for
//! the next marker), the matcher and the interpolator finish their lines
//! by themselves, so with two or more lines allowed one always leaves. The
//! limit costs no throughput while fewer than [`LINES_IN_FLIGHT`] lines
//! are in flight. `tests/rtl_stereo.rs` drives it with a synthetic pair
//! (ten rows twice as slow to match as their line, then light ones) on
//! which it holds and no line is lost.
//!
//! ## Frame width
//! A frame's width is the width its reference camera's first line (the one
//! with `tuser`) stores, at most [`W_MAX`]; every output line of the frame
//! has it, as vendor video IP keeps a frame rectangular on early and late
//! ends of line (and as the vertical median needs). Each detector cuts a
//! later line of its frame at its frame's width (the pixels beyond are taken
//! and dropped, `lines_wide` counts the pair: a late end of line, or a
//! `tlast` missing) and stores a shorter one as it is (an early end of
//! line: its matches are interpolated over the frame's width, the last one
//! held to the end). The width travels with the line: the reference
//! detector puts the line's last pixel on its marker's `pos` lane, the
//! matcher and the row check pass it on their markers (`m_x_ref` there),
//! and the row's width is registered beside the interpolator (`k_width`,
//! with the row check's output: [`CHECK_REGISTER_LAG`]). A marker that
//! starts a frame gives the interpolator its own width and sets the frame's
//! (`frame_width`); the frame's other rows get that. So lines of two frames
//! in the pipeline at once each keep their frame's width. (A first row the
//! row check drops, which only a row check overrun does, passes its start
//! of frame to the next row, whose width the frame then takes.)

use crate::primitives::block_ram::DP16KD_WIDTH;
use crate::detector::declivity_detector::DeclivityDetector;
pub use crate::detector::declivity_detector::RESET_RECOVERY;
use crate::matcher::declivity_matcher::{DeclivityMatcher, GainRule};
use crate::post::depth_stage::{DepthCamera, DepthError, DepthStage};
use crate::post::interpolator::{Interpolator, LINE_QUEUE, SEG_RESERVE};
use crate::params::*;
use crate::stream::record_fifo::RecordFifo;
use crate::post::row_check::RowCheck;
use crate::stream::skid_buffer::SkidBuffer;
use crate::post::vertical_median::VerticalMedian;
use crate::primitives::reset_buffer::ResetBuffer;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Bits of the status counters.
pub const STATUS_BITS: usize = 16;
/// Bits of the frame's row count (`height`).
pub const HEIGHT_BITS: usize = W_MAX_BITS + 1;
/// Bits of an output beat: the depth above the disparity, 16 bits each.
pub const OUT_BITS: usize = 2 * DEPTH_BITS;
/// Lines allowed between the matcher's input and the interpolator's output
/// (see "Lines in flight" above): the interpolator's line queue.
pub const LINES_IN_FLIGHT: usize = LINE_QUEUE;
/// Clocks of the register between the row check's output and the
/// interpolator's input (the two blocks are placed apart on the die: their
/// route and the interpolator's first stage do not fit one clock).
pub const CHECK_REGISTER_LAG: usize = 1;
/// Clocks of the register between the vertical median's output and the
/// depth stage's input (placed apart on the die: the route from the
/// median's output register and the depth stage's first stage do not fit
/// one clock).
pub const MEDIAN_REGISTER_LAG: usize = 1;
/// Clocks of the register between the depth stage's output and the output
/// port (`m_*`): no logic drives the flip-flops that feed the port, which
/// nextpnr may place by its pins far from the depth stage, so the depth
/// stage's valid bit does not cross the die into the clear of its output
/// register.
pub const OUTPUT_REGISTER_LAG: usize = 1;
/// Clocks of the register between the interpolator's output and the
/// vertical median's input (placed apart on the die: the route from the
/// interpolator's output register, the row count's comparison for the
/// frame's last row and the median's first logic do not fit one clock).
/// The pixel's end-of-frame flag is computed into it.
pub const INTERP_REGISTER_LAG: usize = 1;
/// Bits of the count of lines in flight `0 ..= LINES_IN_FLIGHT`.
const FLIGHT_BITS: usize = LINE_QUEUE_BITS + 1;
/// Bits of the count of lines that leave the flight on one clock, `0 ..= 5`.
const FLIGHT_LEFT_BITS: usize = 3;
// The interpolator admits every line the limit lets through: at a line's
// admission the other lines in flight, at most `LINES_IN_FLIGHT - 1`, hold
// at most `N_MAX - 1` segments each, and a line is admitted with
// `SEG_RESERVE` places free; no deadlock: the row check holds back at most
// one row (for its successor's marker), so at least one line in flight
// always moves.
const _: () = assert!(LINES_IN_FLIGHT <= LINE_QUEUE && LINES_IN_FLIGHT >= 2);
const _: () = assert!((LINES_IN_FLIGHT - 1) * (N_MAX - 1) + SEG_RESERVE <= 1 << SEG_ADDR_BITS);
const _: () = assert!(LINES_IN_FLIGHT < 1 << FLIGHT_BITS);
const _: () = assert!(POS_BITS <= DEPTH_BITS);
// The matcher's row count flags its frame's last row from registers two
// clocks after a marker (`m_row`, then `m_row_last`), in time for a marker
// two clocks later; the matcher's markers are at least that far apart: the
// traceback starts a line the clock after it sends the previous line's
// marker at the earliest, and takes at least a clock.
const _: () = assert!(crate::matcher::traceback::traceback_cycles(0, 0, 0, 0) >= 1);

/// Where a detector beat's fields sit in the record queue's lanes.
/// Lane 0: `pos`, then the marker's flags.
const SOF_BIT: usize = POS_BITS;
const WIDE_BIT: usize = POS_BITS + 1;
const FULL_BIT: usize = POS_BITS + 2;
/// Lane 1: `amp`, then the marker bit.
const MARKER_BIT: usize = AMP_BITS;
/// Lanes 2–4: two grey levels each (`left0, left1`, `left2, right0`,
/// `right1, right2`); on a marker, lane 2 carries `d_t` and lane 3 the
/// time stamp (the matcher's Pairing).
const _: () = assert!(FULL_BIT < DP16KD_WIDTH && MARKER_BIT < DP16KD_WIDTH && DT_BITS <= DP16KD_WIDTH && 2 * PIXEL_BITS <= DP16KD_WIDTH && STAMP_BITS <= DP16KD_WIDTH);
/// Bits of the clock count whose upper [`STAMP_BITS`] are the time stamp.
const CLOCK_COUNT_BITS: usize = STAMP_BITS + STAMP_SHIFT;


#[derive(LogicBlock)]
pub struct StereoLineProcessor<const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub l_tdata: Signal<In, Bits<PIXEL_BITS>>,
    pub l_tvalid: Signal<In, Bit>,
    pub l_tuser: Signal<In, Bit>,
    pub l_tlast: Signal<In, Bit>,
    pub l_tready: Signal<Out, Bit>,
    pub r_tdata: Signal<In, Bits<PIXEL_BITS>>,
    pub r_tvalid: Signal<In, Bit>,
    pub r_tuser: Signal<In, Bit>,
    pub r_tlast: Signal<In, Bit>,
    pub r_tready: Signal<Out, Bit>,
    pub dispmin: Signal<In, Bits<DISPMAX_BITS>>,
    pub dispmax: Signal<In, Bits<DISPMAX_BITS>>,
    pub height: Signal<In, Bits<HEIGHT_BITS>>,
    pub m_tvalid: Signal<Out, Bit>,
    pub m_tdata: Signal<Out, Bits<OUT_BITS>>,
    pub m_tuser: Signal<Out, Bit>,
    pub m_tlast: Signal<Out, Bit>,
    pub records_dropped: Signal<Out, Bits<STATUS_BITS>>,
    pub lines_dropped: Signal<Out, Bits<STATUS_BITS>>,
    pub pixels_dropped: Signal<Out, Bits<STATUS_BITS>>,
    pub lines_full: Signal<Out, Bits<STATUS_BITS>>,
    pub lines_wide: Signal<Out, Bits<STATUS_BITS>>,
    pub lines_unpaired: Signal<Out, Bits<STATUS_BITS>>,
    /// `reset` on the global network, to every block and register.
    reset_buffer: ResetBuffer,
    // The cameras' register slices (SKID_LAG), then their detectors.
    pub l_skid: SkidBuffer<PIXEL_BITS>,
    pub r_skid: SkidBuffer<PIXEL_BITS>,
    pub left: DeclivityDetector,
    pub right: DeclivityDetector,
    pub l_queue: RecordFifo,
    pub r_queue: RecordFifo,
    pub matcher: DeclivityMatcher<N>,
    pub row_check: RowCheck,
    pub interpolator: Interpolator,
    pub median: VerticalMedian,
    pub depth: DepthStage,
    // The row of the matcher's line and of the interpolator's (so that the
    // frame's last can be marked).
    m_row: ResetDff<Bits<HEIGHT_BITS>>,
    p_row: ResetDff<Bits<HEIGHT_BITS>>,
    m_row_now: Signal<Local, Bits<HEIGHT_BITS>>,
    p_row_now: Signal<Local, Bits<HEIGHT_BITS>>,
    // The frame's last row: `height - 1` and `height == 1` registered (the
    // frame's size is an input that holds during a frame), and whether the
    // matcher's row count is at the last row (from registers, two clocks
    // after the count moved).
    h_m1: ResetDff<Bits<HEIGHT_BITS>>,
    h_one: ResetDff<Bit>,
    m_row_last: ResetDff<Bit>,
    // The interpolator's pixels registered on their way to the median
    // (INTERP_REGISTER_LAG), with their row's end-of-frame flag.
    i_valid: ResetDff<Bit>,
    i_last: ResetDff<Bit>,
    i_d: ResetDff<Bits<POS_BITS>>,
    i_sof: ResetDff<Bit>,
    i_eof: ResetDff<Bit>,
    // The row check's output registered on its way to the interpolator
    // (CHECK_REGISTER_LAG).
    k_valid: ResetDff<Bit>,
    k_last: ResetDff<Bit>,
    k_x: ResetDff<Bits<POS_BITS>>,
    k_d: ResetDff<Bits<POS_BITS>>,
    k_sof: ResetDff<Bit>,
    // The median's output registered on its way to the depth stage
    // (MEDIAN_REGISTER_LAG).
    v_valid: ResetDff<Bit>,
    v_last: ResetDff<Bit>,
    v_d: ResetDff<Bits<POS_BITS>>,
    v_sof: ResetDff<Bit>,
    // The depth stage's output registered on its way to the port
    // (OUTPUT_REGISTER_LAG).
    out_valid: ResetDff<Bit>,
    out_data: ResetDff<Bits<OUT_BITS>>,
    out_user: ResetDff<Bit>,
    out_last: ResetDff<Bit>,
    // The queues' lanes 0-3, built here and then given to each queue in
    // one assignment: a port assigned twice in one evaluation changes twice,
    // and under Icarus the queue's logic and this block then wake each
    // other without end (an event loop, though the logic has no
    // combinational loop: Verilator and Yosys see none).
    l_lane0: Signal<Local, Bits<DP16KD_WIDTH>>,
    l_lane1: Signal<Local, Bits<DP16KD_WIDTH>>,
    l_lane2: Signal<Local, Bits<DP16KD_WIDTH>>,
    l_lane3: Signal<Local, Bits<DP16KD_WIDTH>>,
    r_lane0: Signal<Local, Bits<DP16KD_WIDTH>>,
    r_lane1: Signal<Local, Bits<DP16KD_WIDTH>>,
    r_lane2: Signal<Local, Bits<DP16KD_WIDTH>>,
    r_lane3: Signal<Local, Bits<DP16KD_WIDTH>>,
    // The frame's width for the interpolator (see "Frame width"): the width
    // of the row on the row check's marker (its last pixel + 1, registered
    // with `k_*`), taken on a marker that starts a frame and kept for the
    // frame's other rows.
    k_width: ResetDff<Bits<WIDTH_BITS>>,
    frame_width: ResetDff<Bits<WIDTH_BITS>>,
    width_now: Signal<Local, Bits<WIDTH_BITS>>,
    n_records_dropped: ResetDff<Bits<STATUS_BITS>>,
    n_lines_dropped: ResetDff<Bits<STATUS_BITS>>,
    n_pixels_dropped: ResetDff<Bits<STATUS_BITS>>,
    n_lines_full: ResetDff<Bits<STATUS_BITS>>,
    n_lines_wide: ResetDff<Bits<STATUS_BITS>>,
    n_lines_unpaired: ResetDff<Bits<STATUS_BITS>>,
    // The events the status counters count, registered beside their
    // sources (the counters then count a clock later: the route from a
    // block's output to its counter gets a clock of its own).
    ev_records: ResetDff<Bit>,
    ev_lines: ResetDff<Bit>,
    ev_pixels: ResetDff<Bit>,
    ev_full: ResetDff<Bit>,
    ev_wide: ResetDff<Bit>,
    ev_unpaired: ResetDff<Bit>,
    // Lines in flight: reference markers the matcher took, less the lines
    // the interpolator sent (or the row check or the interpolator dropped);
    // the reference queue held (public for the drivers' diagnostics).
    pub in_flight: ResetDff<Bits<FLIGHT_BITS>>,
    flight_now: Signal<Local, Bits<FLIGHT_BITS>>,
    // The lines that left on the clock before (0–5: one out of the
    // interpolator, one dropped by it, one by the row check for want of
    // room and one as a short frame's last row, one reference line dropped
    // unpaired by the matcher), registered
    // beside their sources, and the count less them: a taken marker then
    // only picks `flight_base` or `flight_base + 1`, and the marker's
    // handshake, the hold and three ± 1 are not in series in one clock.
    flight_left: ResetDff<Bits<FLIGHT_LEFT_BITS>>,
    flight_base: Signal<Local, Bits<FLIGHT_BITS>>,
    flight_left_now: Signal<Local, Bits<FLIGHT_LEFT_BITS>>,
    pub hold: Signal<Local, Bit>,
    // `in_flight >= LINES_IN_FLIGHT` as a register, its next value picked
    // from comparisons of `flight_base` by the taken marker, so that the
    // count's comparison is not behind the marker's handshake.
    hold_q: ResetDff<Bit>,
    // Clocks since configuration or reset, wrapping; the markers' time
    // stamp is its upper bits.
    clock_count: ResetDff<Bits<CLOCK_COUNT_BITS>>,
    stamp: Signal<Local, Bits<STAMP_BITS>>,
    took_last: Signal<Local, Bit>,
    flight_max: Constant<Bits<FLIGHT_BITS>>,
    flight_max_m1: Constant<Bits<FLIGHT_BITS>>,
    sh_level: Constant<Bits<8>>,
    sh_depth: Constant<Bits<8>>,
    sh_stamp: Constant<Bits<8>>,
    sof_mask: Constant<Bits<DP16KD_WIDTH>>,
    wide_mask: Constant<Bits<DP16KD_WIDTH>>,
    full_mask: Constant<Bits<DP16KD_WIDTH>>,
    marker_mask: Constant<Bits<DP16KD_WIDTH>>,
}

impl<const N: usize> StereoLineProcessor<N> {
    /// The datapath with the matcher's gain rule `rule`, the interpolator's
    /// edge jump `jump` ([`POS_FRAC_BITS`] fixed point) and the depth
    /// stage's `camera` (an error if the depth stage cannot hold it).
    pub fn new(rule: GainRule, jump: Option<u64>, camera: DepthCamera) -> Result<Self, DepthError> {
        Ok(StereoLineProcessor {
            clock: Default::default(),
            reset: Default::default(),
            l_tdata: Default::default(),
            l_tvalid: Default::default(),
            l_tuser: Default::default(),
            l_tlast: Default::default(),
            l_tready: Default::default(),
            r_tdata: Default::default(),
            r_tvalid: Default::default(),
            r_tuser: Default::default(),
            r_tlast: Default::default(),
            r_tready: Default::default(),
            dispmin: Default::default(),
            dispmax: Default::default(),
            height: Default::default(),
            m_tvalid: Default::default(),
            m_tdata: Default::default(),
            m_tuser: Default::default(),
            m_tlast: Default::default(),
            records_dropped: Default::default(),
            lines_dropped: Default::default(),
            pixels_dropped: Default::default(),
            lines_full: Default::default(),
            lines_wide: Default::default(),
            lines_unpaired: Default::default(),
            reset_buffer: Default::default(),
            l_skid: Default::default(),
            r_skid: Default::default(),
            left: Default::default(),
            right: Default::default(),
            l_queue: Default::default(),
            r_queue: Default::default(),
            matcher: DeclivityMatcher::new(rule),
            row_check: RowCheck::new(),
            interpolator: Interpolator::new(jump),
            median: VerticalMedian::new(),
            depth: DepthStage::new(camera)?,
            m_row: Default::default(),
            p_row: Default::default(),
            m_row_now: Default::default(),
            l_lane0: Default::default(),
            l_lane1: Default::default(),
            l_lane2: Default::default(),
            l_lane3: Default::default(),
            r_lane0: Default::default(),
            r_lane1: Default::default(),
            r_lane2: Default::default(),
            r_lane3: Default::default(),
            p_row_now: Default::default(),
            h_m1: Default::default(),
            h_one: Default::default(),
            m_row_last: Default::default(),
            i_valid: Default::default(),
            i_last: Default::default(),
            i_d: Default::default(),
            i_sof: Default::default(),
            i_eof: Default::default(),
            k_width: Default::default(),
            frame_width: ResetDff::new((W_MAX as u64).into()),
            width_now: Default::default(),
            n_records_dropped: Default::default(),
            n_lines_dropped: Default::default(),
            n_pixels_dropped: Default::default(),
            n_lines_full: Default::default(),
            n_lines_wide: Default::default(),
            n_lines_unpaired: Default::default(),
            ev_records: Default::default(),
            ev_lines: Default::default(),
            ev_pixels: Default::default(),
            ev_full: Default::default(),
            ev_wide: Default::default(),
            ev_unpaired: Default::default(),
            in_flight: Default::default(),
            k_valid: Default::default(),
            k_last: Default::default(),
            k_x: Default::default(),
            k_d: Default::default(),
            k_sof: Default::default(),
            v_valid: Default::default(),
            v_last: Default::default(),
            v_d: Default::default(),
            v_sof: Default::default(),
            out_valid: Default::default(),
            out_data: Default::default(),
            out_user: Default::default(),
            out_last: Default::default(),
            flight_now: Default::default(),
            flight_left: Default::default(),
            flight_base: Default::default(),
            flight_left_now: Default::default(),
            hold: Default::default(),
            hold_q: Default::default(),
            clock_count: Default::default(),
            stamp: Default::default(),
            took_last: Default::default(),
            flight_max: Constant::new((LINES_IN_FLIGHT as u64).into()),
            flight_max_m1: Constant::new((LINES_IN_FLIGHT as u64 - 1).into()),
            sh_level: Constant::new((PIXEL_BITS as u64).into()),
            sh_depth: Constant::new((DEPTH_BITS as u64).into()),
            sh_stamp: Constant::new((STAMP_SHIFT as u64).into()),
            sof_mask: Constant::new((1u64 << SOF_BIT).into()),
            wide_mask: Constant::new((1u64 << WIDE_BIT).into()),
            full_mask: Constant::new((1u64 << FULL_BIT).into()),
            marker_mask: Constant::new((1u64 << MARKER_BIT).into()),
        })
    }
}

impl<const N: usize> Logic for StereoLineProcessor<N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, m_row, p_row, h_m1, h_one, m_row_last, i_valid, i_last, i_d, i_sof, i_eof, k_width, frame_width, n_records_dropped, n_lines_dropped, n_pixels_dropped, n_lines_full, n_lines_wide, n_lines_unpaired, ev_records, ev_lines, ev_pixels, ev_full, ev_wide, ev_unpaired, in_flight, flight_left, hold_q, clock_count, k_valid, k_last, k_x, k_d, k_sof, v_valid, v_last, v_d, v_sof, out_valid, out_data, out_user, out_last);
        self.reset_buffer.reset_in.next = self.reset.val();
        self.m_row.reset.next = self.reset_buffer.reset.val();
        self.p_row.reset.next = self.reset_buffer.reset.val();
        self.h_m1.reset.next = self.reset_buffer.reset.val();
        self.h_one.reset.next = self.reset_buffer.reset.val();
        self.m_row_last.reset.next = self.reset_buffer.reset.val();
        self.i_valid.reset.next = self.reset_buffer.reset.val();
        self.i_last.reset.next = self.reset_buffer.reset.val();
        self.i_d.reset.next = self.reset_buffer.reset.val();
        self.i_sof.reset.next = self.reset_buffer.reset.val();
        self.i_eof.reset.next = self.reset_buffer.reset.val();
        self.k_width.reset.next = self.reset_buffer.reset.val();
        self.frame_width.reset.next = self.reset_buffer.reset.val();
        self.n_records_dropped.reset.next = self.reset_buffer.reset.val();
        self.n_lines_dropped.reset.next = self.reset_buffer.reset.val();
        self.n_pixels_dropped.reset.next = self.reset_buffer.reset.val();
        self.n_lines_full.reset.next = self.reset_buffer.reset.val();
        self.n_lines_wide.reset.next = self.reset_buffer.reset.val();
        self.n_lines_unpaired.reset.next = self.reset_buffer.reset.val();
        self.ev_records.reset.next = self.reset_buffer.reset.val();
        self.ev_lines.reset.next = self.reset_buffer.reset.val();
        self.ev_pixels.reset.next = self.reset_buffer.reset.val();
        self.ev_full.reset.next = self.reset_buffer.reset.val();
        self.ev_wide.reset.next = self.reset_buffer.reset.val();
        self.ev_unpaired.reset.next = self.reset_buffer.reset.val();
        self.in_flight.reset.next = self.reset_buffer.reset.val();
        self.flight_left.reset.next = self.reset_buffer.reset.val();
        self.hold_q.reset.next = self.reset_buffer.reset.val();
        self.clock_count.reset.next = self.reset_buffer.reset.val();
        self.k_valid.reset.next = self.reset_buffer.reset.val();
        self.k_last.reset.next = self.reset_buffer.reset.val();
        self.k_x.reset.next = self.reset_buffer.reset.val();
        self.k_d.reset.next = self.reset_buffer.reset.val();
        self.k_sof.reset.next = self.reset_buffer.reset.val();
        self.v_valid.reset.next = self.reset_buffer.reset.val();
        self.v_last.reset.next = self.reset_buffer.reset.val();
        self.v_d.reset.next = self.reset_buffer.reset.val();
        self.v_sof.reset.next = self.reset_buffer.reset.val();
        self.out_valid.reset.next = self.reset_buffer.reset.val();
        self.out_data.reset.next = self.reset_buffer.reset.val();
        self.out_user.reset.next = self.reset_buffer.reset.val();
        self.out_last.reset.next = self.reset_buffer.reset.val();
        self.l_skid.clock.next = self.clock.val();
        self.l_skid.reset.next = self.reset_buffer.reset.val();
        self.r_skid.clock.next = self.clock.val();
        self.r_skid.reset.next = self.reset_buffer.reset.val();
        self.left.clock.next = self.clock.val();
        self.left.reset.next = self.reset_buffer.reset.val();
        self.right.clock.next = self.clock.val();
        self.right.reset.next = self.reset_buffer.reset.val();
        self.l_queue.clock.next = self.clock.val();
        self.l_queue.reset.next = self.reset_buffer.reset.val();
        self.r_queue.clock.next = self.clock.val();
        self.r_queue.reset.next = self.reset_buffer.reset.val();
        self.matcher.clock.next = self.clock.val();
        self.matcher.reset.next = self.reset_buffer.reset.val();
        self.row_check.clock.next = self.clock.val();
        self.row_check.reset.next = self.reset_buffer.reset.val();
        self.interpolator.clock.next = self.clock.val();
        self.interpolator.reset.next = self.reset_buffer.reset.val();
        self.median.clock.next = self.clock.val();
        self.median.reset.next = self.reset_buffer.reset.val();
        self.depth.clock.next = self.clock.val();
        self.depth.reset.next = self.reset_buffer.reset.val();

        // ---- The cameras through their register slices into their
        // detectors.
        self.l_skid.s_tdata.next = self.l_tdata.val();
        self.l_skid.s_tvalid.next = self.l_tvalid.val();
        self.l_skid.s_tuser.next = self.l_tuser.val();
        self.l_skid.s_tlast.next = self.l_tlast.val();
        self.l_tready.next = self.l_skid.s_tready.val();
        self.left.s_tdata.next = self.l_skid.m_tdata.val();
        self.left.s_tvalid.next = self.l_skid.m_tvalid.val();
        self.left.s_tuser.next = self.l_skid.m_tuser.val();
        self.left.s_tlast.next = self.l_skid.m_tlast.val();
        self.l_skid.m_tready.next = self.left.s_tready.val();
        self.r_skid.s_tdata.next = self.r_tdata.val();
        self.r_skid.s_tvalid.next = self.r_tvalid.val();
        self.r_skid.s_tuser.next = self.r_tuser.val();
        self.r_skid.s_tlast.next = self.r_tlast.val();
        self.r_tready.next = self.r_skid.s_tready.val();
        self.right.s_tdata.next = self.r_skid.m_tdata.val();
        self.right.s_tvalid.next = self.r_skid.m_tvalid.val();
        self.right.s_tuser.next = self.r_skid.m_tuser.val();
        self.right.s_tlast.next = self.r_skid.m_tlast.val();
        self.r_skid.m_tready.next = self.right.s_tready.val();
        // ---- Detector beats into the record queues (lanes: see the
        // constants above).
        self.clock_count.d.next = self.clock_count.q.val() + 1;
        self.stamp.next = self.clock_count.q.val().get_bits::<STAMP_BITS>(self.sh_stamp.val().index());
        self.l_queue.w_valid.next = self.left.m_valid.val();
        self.l_queue.w_marker.next = self.left.m_last.val();
        self.l_lane0.next = bit_cast::<DP16KD_WIDTH, POS_BITS>(self.left.m_pos.val());
        if self.left.m_last.val() {
            // The marker's `pos`: the line's last pixel.
            self.l_lane0.next = bit_cast::<DP16KD_WIDTH, X_BITS>(self.left.m_end.val());
        }
        self.l_lane1.next = bit_cast::<DP16KD_WIDTH, AMP_BITS>(self.left.m_amp.val());
        self.l_lane2.next =
            (bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.left.m_left1.val()) << self.sh_level.val()) | bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.left.m_left0.val());
        if self.left.m_last.val() {
            self.l_lane1.next = self.l_lane1.val() | self.marker_mask.val();
            self.l_lane2.next = bit_cast::<DP16KD_WIDTH, DT_BITS>(self.left.m_dt.val());
            if self.left.m_sof.val() {
                self.l_lane0.next = self.l_lane0.val() | self.sof_mask.val();
            }
            if self.left.m_wide.val() {
                self.l_lane0.next = self.l_lane0.val() | self.wide_mask.val();
            }
            if self.left.m_full.val() {
                self.l_lane0.next = self.l_lane0.val() | self.full_mask.val();
            }
        }
        self.l_queue.w_lane0.next = self.l_lane0.val();
        self.l_queue.w_lane1.next = self.l_lane1.val();
        self.l_queue.w_lane2.next = self.l_lane2.val();
        self.l_lane3.next =
            (bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.left.m_right0.val()) << self.sh_level.val()) | bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.left.m_left2.val());
        if self.left.m_last.val() {
            self.l_lane3.next = bit_cast::<DP16KD_WIDTH, STAMP_BITS>(self.stamp.val());
        }
        self.l_queue.w_lane3.next = self.l_lane3.val();
        self.l_queue.w_lane4.next =
            (bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.left.m_right2.val()) << self.sh_level.val()) | bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.left.m_right1.val());
        self.r_queue.w_valid.next = self.right.m_valid.val();
        self.r_queue.w_marker.next = self.right.m_last.val();
        self.r_lane0.next = bit_cast::<DP16KD_WIDTH, POS_BITS>(self.right.m_pos.val());
        self.r_lane1.next = bit_cast::<DP16KD_WIDTH, AMP_BITS>(self.right.m_amp.val());
        self.r_lane2.next =
            (bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.right.m_left1.val()) << self.sh_level.val()) | bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.right.m_left0.val());
        if self.right.m_last.val() {
            self.r_lane1.next = self.r_lane1.val() | self.marker_mask.val();
            self.r_lane2.next = bit_cast::<DP16KD_WIDTH, DT_BITS>(self.right.m_dt.val());
            if self.right.m_sof.val() {
                self.r_lane0.next = self.r_lane0.val() | self.sof_mask.val();
            }
            if self.right.m_wide.val() {
                self.r_lane0.next = self.r_lane0.val() | self.wide_mask.val();
            }
            if self.right.m_full.val() {
                self.r_lane0.next = self.r_lane0.val() | self.full_mask.val();
            }
        }
        self.r_queue.w_lane0.next = self.r_lane0.val();
        self.r_queue.w_lane1.next = self.r_lane1.val();
        self.r_queue.w_lane2.next = self.r_lane2.val();
        self.r_lane3.next =
            (bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.right.m_right0.val()) << self.sh_level.val()) | bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.right.m_left2.val());
        if self.right.m_last.val() {
            self.r_lane3.next = bit_cast::<DP16KD_WIDTH, STAMP_BITS>(self.stamp.val());
        }
        self.r_queue.w_lane3.next = self.r_lane3.val();
        self.r_queue.w_lane4.next =
            (bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.right.m_right2.val()) << self.sh_level.val()) | bit_cast::<DP16KD_WIDTH, PIXEL_BITS>(self.right.m_right1.val());

        // ---- The queues into the matcher, the reference side held while
        // `LINES_IN_FLIGHT` lines are in flight (it can then rise only on the
        // clock after a reference marker is taken, so lines are held whole).
        self.hold.next = self.hold_q.q.val();
        self.matcher.dispmin.next = self.dispmin.val();
        self.matcher.dispmax.next = self.dispmax.val();
        self.matcher.r_valid.next = self.l_queue.r_valid.val() & !self.hold.val();
        self.l_queue.r_ready.next = self.matcher.r_ready.val() & !self.hold.val();
        self.matcher.r_last.next = (self.l_queue.r_lane1.val() & self.marker_mask.val()).any();
        self.matcher.r_pos.next = bit_cast::<POS_BITS, DP16KD_WIDTH>(self.l_queue.r_lane0.val());
        self.matcher.r_sof.next = (self.l_queue.r_lane0.val() & self.sof_mask.val()).any();
        self.matcher.r_stamp.next = bit_cast::<STAMP_BITS, DP16KD_WIDTH>(self.l_queue.r_lane3.val());
        self.matcher.r_wide.next = (self.l_queue.r_lane0.val() & self.wide_mask.val()).any();
        self.matcher.r_full.next = (self.l_queue.r_lane0.val() & self.full_mask.val()).any();
        self.matcher.r_amp.next = bit_cast::<AMP_BITS, DP16KD_WIDTH>(self.l_queue.r_lane1.val());
        self.matcher.r_dt.next = bit_cast::<DT_BITS, DP16KD_WIDTH>(self.l_queue.r_lane2.val());
        self.matcher.r_left0.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.l_queue.r_lane2.val());
        self.matcher.r_left1.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.l_queue.r_lane2.val() >> self.sh_level.val());
        self.matcher.r_left2.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.l_queue.r_lane3.val());
        self.matcher.r_right0.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.l_queue.r_lane3.val() >> self.sh_level.val());
        self.matcher.r_right1.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.l_queue.r_lane4.val());
        self.matcher.r_right2.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.l_queue.r_lane4.val() >> self.sh_level.val());
        self.matcher.o_valid.next = self.r_queue.r_valid.val();
        self.r_queue.r_ready.next = self.matcher.o_ready.val();
        self.matcher.o_last.next = (self.r_queue.r_lane1.val() & self.marker_mask.val()).any();
        self.matcher.o_pos.next = bit_cast::<POS_BITS, DP16KD_WIDTH>(self.r_queue.r_lane0.val());
        self.matcher.o_wide.next = (self.r_queue.r_lane0.val() & self.wide_mask.val()).any();
        self.matcher.o_full.next = (self.r_queue.r_lane0.val() & self.full_mask.val()).any();
        self.matcher.o_sof.next = (self.r_queue.r_lane0.val() & self.sof_mask.val()).any();
        self.matcher.o_stamp.next = bit_cast::<STAMP_BITS, DP16KD_WIDTH>(self.r_queue.r_lane3.val());
        self.matcher.o_amp.next = bit_cast::<AMP_BITS, DP16KD_WIDTH>(self.r_queue.r_lane1.val());
        self.matcher.o_dt.next = bit_cast::<DT_BITS, DP16KD_WIDTH>(self.r_queue.r_lane2.val());
        self.matcher.o_left0.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.r_queue.r_lane2.val());
        self.matcher.o_left1.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.r_queue.r_lane2.val() >> self.sh_level.val());
        self.matcher.o_left2.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.r_queue.r_lane3.val());
        self.matcher.o_right0.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.r_queue.r_lane3.val() >> self.sh_level.val());
        self.matcher.o_right1.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.r_queue.r_lane4.val());
        self.matcher.o_right2.next = bit_cast::<PIXEL_BITS, DP16KD_WIDTH>(self.r_queue.r_lane4.val() >> self.sh_level.val());

        // ---- The matches through the row check (the frame's last row
        // marked from the row count) into the interpolator.
        self.m_row_now.next = self.m_row.q.val();
        if self.matcher.m_sof.val() {
            self.m_row_now.next = 0.into();
        }
        if self.matcher.m_valid.val() & self.matcher.m_last.val() {
            self.m_row.d.next = self.m_row_now.val() + 1;
        }
        self.row_check.m_valid.next = self.matcher.m_valid.val();
        self.row_check.m_last.next = self.matcher.m_last.val();
        self.row_check.m_x_ref.next = self.matcher.m_x_ref.val();
        self.row_check.m_disp.next = self.matcher.m_disp.val();
        self.row_check.m_sof.next = self.matcher.m_sof.val();
        // The row's end-of-frame flag, read on its marker: the frame's first
        // row is row 0, the last of a one-row frame; a later row is the last
        // when the count (moved on the previous marker) is at `height - 1`.
        self.h_m1.d.next = self.height.val() - 1;
        self.h_one.d.next = self.height.val() == 1;
        self.m_row_last.d.next = self.m_row.q.val() == self.h_m1.q.val();
        self.row_check.m_eof.next = self.m_row_last.q.val();
        if self.matcher.m_sof.val() {
            self.row_check.m_eof.next = self.h_one.q.val();
        }
        self.k_valid.d.next = self.row_check.c_valid.val();
        self.k_last.d.next = self.row_check.c_last.val();
        self.k_x.d.next = self.row_check.c_x_ref.val();
        self.k_d.d.next = self.row_check.c_disp.val();
        self.k_sof.d.next = self.row_check.c_sof.val();
        self.k_width.d.next = bit_cast::<WIDTH_BITS, POS_BITS>(self.row_check.c_x_ref.val()) + 1;
        self.interpolator.a_valid.next = self.k_valid.q.val();
        self.interpolator.a_last.next = self.k_last.q.val();
        self.interpolator.a_x.next = self.k_x.q.val();
        self.interpolator.a_d.next = self.k_d.q.val();
        self.interpolator.a_sof.next = self.k_sof.q.val();
        self.width_now.next = self.frame_width.q.val();
        if self.k_sof.q.val() {
            self.width_now.next = self.k_width.q.val();
        }
        if self.k_valid.q.val() & self.k_last.q.val() {
            self.frame_width.d.next = self.width_now.val();
        }
        self.interpolator.a_width.next = self.width_now.val();

        // ---- Pixels through the median (the frame's last row marked from
        // the row count) and the depth stage.
        self.p_row_now.next = self.p_row.q.val();
        if self.interpolator.p_sof.val() {
            self.p_row_now.next = 0.into();
        }
        if self.interpolator.p_valid.val() {
            self.p_row.d.next = self.p_row_now.val();
            if self.interpolator.p_last.val() {
                self.p_row.d.next = self.p_row_now.val() + 1;
            }
        }
        self.i_valid.d.next = self.interpolator.p_valid.val();
        self.i_d.d.next = self.interpolator.p_d.val();
        self.i_last.d.next = self.interpolator.p_last.val();
        self.i_sof.d.next = self.interpolator.p_sof.val();
        self.i_eof.d.next = self.p_row_now.val() == self.h_m1.q.val();
        self.median.p_valid.next = self.i_valid.q.val();
        self.median.p_d.next = self.i_d.q.val();
        self.median.p_last.next = self.i_last.q.val();
        self.median.p_sof.next = self.i_sof.q.val();
        self.median.p_eof.next = self.i_eof.q.val();
        self.v_valid.d.next = self.median.v_valid.val();
        self.v_last.d.next = self.median.v_last.val();
        self.v_d.d.next = self.median.v_d.val();
        self.v_sof.d.next = self.median.v_sof.val();
        self.depth.p_valid.next = self.v_valid.q.val();
        self.depth.p_d.next = self.v_d.q.val();
        self.depth.p_last.next = self.v_last.q.val();
        self.depth.p_sof.next = self.v_sof.q.val();

        // ---- Out.
        self.out_valid.d.next = self.depth.z_valid.val();
        self.out_data.d.next = (bit_cast::<OUT_BITS, DEPTH_BITS>(self.depth.z_mm.val()) << self.sh_depth.val()) | bit_cast::<OUT_BITS, POS_BITS>(self.depth.z_d.val());
        self.out_user.d.next = self.depth.z_sof.val();
        self.out_last.d.next = self.depth.z_last.val();
        self.m_tvalid.next = self.out_valid.q.val();
        self.m_tdata.next = self.out_data.q.val();
        self.m_tuser.next = self.out_user.q.val();
        self.m_tlast.next = self.out_last.q.val();

        // ---- Lines in flight: one more on a reference marker taken, one
        // less, a clock later, on a line's last pixel out of the
        // interpolator and on a line dropped (all three registered outputs:
        // no loop).
        self.flight_left_now.next = 0.into();
        if self.interpolator.p_valid.val() & self.interpolator.p_last.val() {
            self.flight_left_now.next = self.flight_left_now.val() + 1;
        }
        if self.interpolator.overflow.val() {
            self.flight_left_now.next = self.flight_left_now.val() + 1;
        }
        if self.row_check.overflow.val() {
            self.flight_left_now.next = self.flight_left_now.val() + 1;
        }
        if self.row_check.cut.val() {
            self.flight_left_now.next = self.flight_left_now.val() + 1;
        }
        if self.matcher.r_unpaired.val() {
            self.flight_left_now.next = self.flight_left_now.val() + 1;
        }
        self.flight_left.d.next = self.flight_left_now.val();
        self.flight_base.next = self.in_flight.q.val() - bit_cast::<FLIGHT_BITS, FLIGHT_LEFT_BITS>(self.flight_left.q.val());
        self.took_last.next = self.l_queue.r_valid.val() & self.matcher.r_ready.val() & !self.hold.val() & self.matcher.r_last.val();
        self.flight_now.next = self.flight_base.val();
        self.hold_q.d.next = self.flight_base.val() >= self.flight_max.val();
        if self.took_last.val() {
            self.flight_now.next = self.flight_base.val() + 1;
            self.hold_q.d.next = self.flight_base.val() >= self.flight_max_m1.val();
        }
        self.in_flight.d.next = self.flight_now.val();

        // ---- Status: each event registered, then counted.
        self.ev_records.d.next = self.l_queue.dropped.val() | self.r_queue.dropped.val();
        self.ev_lines.d.next = self.interpolator.overflow.val() | self.row_check.overflow.val() | self.row_check.cut.val();
        self.ev_pixels.d.next = self.median.overflow.val();
        self.ev_full.d.next = self.matcher.m_valid.val() & self.matcher.m_last.val() & self.matcher.m_full.val();
        self.ev_wide.d.next = self.matcher.m_valid.val() & self.matcher.m_last.val() & self.matcher.m_wide.val();
        self.ev_unpaired.d.next = self.matcher.r_unpaired.val() | self.matcher.o_unpaired.val();
        if self.ev_records.q.val() {
            self.n_records_dropped.d.next = self.n_records_dropped.q.val() + 1;
        }
        if self.ev_lines.q.val() {
            self.n_lines_dropped.d.next = self.n_lines_dropped.q.val() + 1;
        }
        if self.ev_pixels.q.val() {
            self.n_pixels_dropped.d.next = self.n_pixels_dropped.q.val() + 1;
        }
        if self.ev_full.q.val() {
            self.n_lines_full.d.next = self.n_lines_full.q.val() + 1;
        }
        if self.ev_wide.q.val() {
            self.n_lines_wide.d.next = self.n_lines_wide.q.val() + 1;
        }
        if self.ev_unpaired.q.val() {
            self.n_lines_unpaired.d.next = self.n_lines_unpaired.q.val() + 1;
        }
        self.records_dropped.next = self.n_records_dropped.q.val();
        self.lines_dropped.next = self.n_lines_dropped.q.val();
        self.pixels_dropped.next = self.n_pixels_dropped.q.val();
        self.lines_full.next = self.n_lines_full.q.val();
        self.lines_wide.next = self.n_lines_wide.q.val();
        self.lines_unpaired.next = self.n_lines_unpaired.q.val();
    }
}
