//! The interpolator (`DESIGN.md` §2.2 and §3, paper §IV's last step,
//! `golden::disparity::interpolate_into`): a line's matches in, one
//! disparity per reference pixel per clock out.
//!
//! Between consecutive matches `a`, `b` (positions `X_a < X_b`, disparities
//! `d_a`, `d_b`) the pixel centres `x` with `⌈X_a⌉ ≤ x < ⌈X_b⌉` take
//! `d_a + t·(d_b - d_a)`, `t = (x - X_a) / (X_b - X_a)`; before the first
//! match the first disparity is held, from the last match's `⌈X⌉` on the
//! last one (golden's `EndRule::Hold`, its default); a line without a match
//! is empty (0, "no disparity"). With an edge jump `J` (golden's `edge_jump`),
//! two matches whose disparities differ by more than `J` are not bridged:
//! their pixels take the smaller disparity.
//!
//! Two engines, a segment memory and a line queue between them:
//! - **Segments**: as matches arrive, each one that starts a new pixel
//!   (`⌈X_b⌉ > ⌈X_a⌉`) closes the segment from the previous match. Its
//!   `1 / (X_b - X_a)` comes from a table: the distance is shifted left until
//!   its top bit is set (`lz` places), and the next [`RECIP_INDEX_BITS`]
//!   bits address a table of `2^RECIP_SHIFT / m` at the middle of the
//!   bucket (a [`BlockRam`] that starts with the table and is never
//!   written, read through its output register, whose word leaves early
//!   enough in the clock for the segment memory's write). The segment (its
//!   last pixel, `X_a`, its base `d_a` (across a jump the smaller
//!   disparity), `|d_b - d_a|` and its sign, the jump flag, `lz` and the
//!   reciprocal) goes into the segment memory; at the line's end marker the line's description (its last pixel, the
//!   held values and where their pixels start, start of frame) goes into
//!   the line queue, and is shown to the pixel engine once the line's last
//!   segment can be in the prefetch registers. The queue (LUT RAM) keeps
//!   each description twice, read at the read pointer and at its successor
//!   from registers: no queue address waits for the pixel engine's end of
//!   line, which picks between the two reads a clock later. The segments
//!   of a line cover the pixels from the first match's `⌈X⌉` to the last
//!   one's without gaps, so the pixel engine needs no count of them.
//! - **Where the pixel is** (in the head, in a segment, at its segment's
//!   last pixel, at the line's last) comes from registers: a line's first
//!   pixel from flags its description brings (computed when it is
//!   written), every later one from comparisons made a clock ahead with
//!   `x + 1` (a register), and the segment's end from one comparison per
//!   prefetch register, picked by the ring's read index. No carry chain
//!   lies between the pixel count and the engine's control (the end of a
//!   segment, of a line; the ring's and the queue's pointers).
//! - **Prefetch**: the segment memory (block RAMs with their output
//!   registers, [`BlockRam`]: two clocks a read) is read in order into four
//!   registers whenever they will have room; the pixel engine works on the
//!   first, so no memory read is in its loop. Four registers sustain a
//!   segment per clock (one-pixel segments in a row).
//! - **Pixels**: while the queue holds a line, its pixels leave one per
//!   clock, lines back to back: the head, then each segment's pixels, then
//!   the tail. A segment's pixel is `d_a ± ⌊(t·|Δd| + ½)⌋` with
//!   `t = ((x - X_a) << lz) · recip >> (POS_BITS - 1)`, two 16×16 products,
//!   [`WEIGHT_FRAC_BITS`] fraction bits; `t` is clamped below 1.
//!
//! Accuracy against golden on the same (fixed-point) matches: the pixels
//! that take a held or jump value are exact; a ramp pixel is within
//! `½ + |Δd|·2^-RECIP_INDEX_BITS` LSB (the reciprocal's relative error is
//! below `2^-(RECIP_INDEX_BITS+1) + 2^-15`, `t`'s truncation adds at most
//! `|Δd|·2^-16`).
//!
//! ## Ports
//! - `clock`; `reset`, synchronous and active high.
//! - In, the match stream (as the matcher emits it, reference order):
//!   `a_valid` with `a_last` low is a match, `a_x` (`X`) and `a_d` (its
//!   disparity), both [`POS_FRAC_BITS`] fraction bits, strictly increasing
//!   `a_x` within a line; `a_valid` with `a_last` high ends the line:
//!   `a_width` (its pixels, `1 ..= W_MAX`), `a_sof` (it starts a frame).
//! - Out, no back-pressure: `p_valid`, `p_d` (disparity, [`POS_FRAC_BITS`]
//!   fraction bits, 0 = none), `p_last` (the line's last pixel), `p_sof`
//!   (the frame's first pixel), `p_empty` (the line had no match).
//! - `overflow`: high for a clock (with the dropped line's marker) when a
//!   line is dropped because the line queue or the segment memory had no
//!   room for it when it started (see Timing).
//!
//! ## Timing
//! A line's description is shown [`SEGMENT_LAG`] clocks after its marker;
//! the pixel engine starts the line on that clock if it is idle, or on the
//! clock after the previous line's last pixel, and the line's first pixel
//! leaves [`PIXEL_LAG`] clocks after the engine starts it.
//! Lines leave back to back at one pixel per clock: a line of `W` pixels
//! takes `W` clocks. The queue holds [`LINE_QUEUE`] lines and the memory
//! `2^SEG_ADDR_BITS` segments; a line is admitted on its first match (or
//! its marker) if the queue has a free place and the memory room for a
//! whole line ([`SEG_RESERVE`]), else it is dropped whole (its marker
//! raises `overflow`, its pixels never leave). A line is counted in the
//! queue from its marker to its last pixel's clock in the pixel engine, so
//! no line is dropped while at most `LINE_QUEUE - 1` lines are in the
//! queue when one starts (their segments, at most `N_MAX - 1` each, then
//! leave room for it: `(LINE_QUEUE - 1)·(N_MAX - 1) + SEG_RESERVE ≤
//! 2^SEG_ADDR_BITS`). Lines arriving on average one per `W` clocks are not
//! enough for that: the queue holds every line that arrives while earlier
//! ones are sent, and lines come in bursts after a late one (the matcher
//! catching up on a backlog). The line processor keeps at most
//! `LINE_QUEUE` lines between the matcher's input and this output
//! (`rtl::stereo_line_processor`, "Lines in flight"). `a_valid` low
//! between matches only delays them. The registers start from their
//! Verilog initial values, with the queue and the segment memory empty and
//! the pixel engine idle; `reset` (synchronous, active high) returns them
//! to these values.

use crate::primitives::block_ram::BlockRam;
use crate::primitives::dsp_multiplier::{DspMultiplier, MUL_OPERAND_BITS};
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from a line's marker on `a_*` to its description in the line
/// queue being shown to the pixel engine: the marker's write, then six
/// clocks, as long as a line's last segment takes from its match through
/// the segment memory into the prefetch registers (the segment register,
/// the normalisation's first half, its second half into the table's
/// address register, the table into its output register beside the
/// segment, the memory's write, its two-clock read).
pub const SEGMENT_LAG: usize = 7;
/// Clocks from the pixel engine's clock of a pixel to the pixel on `p_*`:
/// the selection, the shift, the first product, the weight, the second
/// product, the rounding, the sum (each product registered straight out of
/// its DSP block).
pub const PIXEL_LAG: usize = 7;
/// Lines the line queue holds.
pub const LINE_QUEUE: usize = 1 << LINE_QUEUE_BITS;
/// Free segment places a line needs to be admitted: its at most
/// `N_MAX - 1` segments and the four of the previous line still on
/// their way to the memory (stages 1 to 4).
pub(crate) const SEG_RESERVE: usize = N_MAX - 1 + 4;
// A full queue's other lines leave a line room in the segment memory (see
// Timing).
const _: () = assert!((LINE_QUEUE - 1) * (N_MAX - 1) + SEG_RESERVE <= 1 << SEG_ADDR_BITS);

/// The reciprocal table: entry `i` is `⌊2^RECIP_SHIFT / m⌋` for the middle
/// `m` of the bucket of normalised distances whose bits after the leading
/// one are `i`.
pub fn recip_table() -> Vec<u64> {
    let low = POS_BITS - 1 - RECIP_INDEX_BITS;
    (0..1u64 << RECIP_INDEX_BITS)
        .map(|i| {
            let m = ((i + (1 << RECIP_INDEX_BITS)) << low) + (1 << (low - 1));
            (1u64 << RECIP_SHIFT) / m
        })
        .collect()
}

/// Bits of a segment's shape: `lz` (the distance's normalising shift,
/// 0 ..= POS_BITS - 1), the sign of `d_b - d_a` ([`NEG_BIT`]) and the jump
/// flag ([`JUMP_BIT`]).
const SHAPE_BITS: usize = 6;
/// Bits of the shift `lz` in a shape.
const LZ_BITS: usize = 4;
/// The shape bit of `d_b < d_a`.
const NEG_BIT: usize = 4;
/// The shape bit of a jump (the pixels take the smaller disparity).
const JUMP_BIT: usize = 5;
/// Bits of a segment-memory pointer (one above the address).
const SEG_PTR_BITS: usize = SEG_ADDR_BITS + 1;
/// Bits of a segment in the segment memory: its last pixel, `X_a`, its
/// base, `|Δd|`, its shape and its reciprocal.
pub const SEGMENT_BITS: usize = WIDTH_BITS + 3 * POS_BITS + SHAPE_BITS + RECIP_BITS;
/// Flags of a line's description: start of frame ([`SOF_AT`]), empty line
/// ([`EMPTY_AT`]), and where its first pixel is (in the head, [`HEAD0_AT`];
/// in a segment, [`SEG0_AT`]; the line's last, [`LAST0_AT`]), so that the
/// pixel engine compares no column on a line's first clock.
const FLAG_BITS: usize = 5;
const SOF_AT: usize = 0;
const EMPTY_AT: usize = 1;
const HEAD0_AT: usize = 2;
const SEG0_AT: usize = 3;
const LAST0_AT: usize = 4;
/// Bits of a line's description in the line queue: its last pixel, the
/// held values and their pixels, the flags.
pub const LINE_BITS: usize = 3 * WIDTH_BITS + 2 * POS_BITS + FLAG_BITS;
/// Where the fields of a line's description start in its word (the flags
/// in the bits below).
const LAST_X_AT: usize = FLAG_BITS;
const FIRST_C_AT: usize = LAST_X_AT + WIDTH_BITS;
const LAST_C_AT: usize = FIRST_C_AT + WIDTH_BITS;
const FIRST_D_AT: usize = LAST_C_AT + WIDTH_BITS;
const LAST_D_AT: usize = FIRST_D_AT + POS_BITS;
const _: () = assert!(LAST_D_AT + POS_BITS == LINE_BITS);
/// Segments the prefetch registers hold.
const PREFETCH: usize = 4;
/// Bits of a count `0 ..= PREFETCH`.
const FILL_BITS: usize = 3;
/// Bits of an index of the prefetch ring.
const SLOT_BITS: usize = 2;
/// Bits of a line-queue pointer (one above the address).
const QUEUE_PTR_BITS: usize = LINE_QUEUE_BITS + 1;

#[derive(LogicBlock)]
pub struct Interpolator {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub a_valid: Signal<In, Bit>,
    pub a_last: Signal<In, Bit>,
    pub a_x: Signal<In, Bits<POS_BITS>>,
    pub a_d: Signal<In, Bits<POS_BITS>>,
    pub a_width: Signal<In, Bits<WIDTH_BITS>>,
    pub a_sof: Signal<In, Bit>,
    pub p_valid: Signal<Out, Bit>,
    pub p_d: Signal<Out, Bits<POS_BITS>>,
    pub p_last: Signal<Out, Bit>,
    pub p_sof: Signal<Out, Bit>,
    pub p_empty: Signal<Out, Bit>,
    pub overflow: Signal<Out, Bit>,
    // ---- Segments: the line being received (admission, the previous match).
    in_line: ResetDff<Bit>,
    dropping: ResetDff<Bit>,
    has_prev: ResetDff<Bit>,
    prev_x: ResetDff<Bits<POS_BITS>>,
    prev_d: ResetDff<Bits<POS_BITS>>,
    prev_c: ResetDff<Bits<WIDTH_BITS>>,
    first_d: ResetDff<Bits<POS_BITS>>,
    first_c: ResetDff<Bits<WIDTH_BITS>>,
    // Stage 1: a segment; stage 2: its distance half normalised (`s2_m`);
    // stage 3: the table's address register (in `recip`), the shape with
    // the whole shift; stage 4: the table's word out of its output register
    // (in `recip`) beside the segment, into the memory.
    s1_seg: ResetDff<Bit>,
    s1_last: ResetDff<Bits<WIDTH_BITS>>,
    s1_ax: ResetDff<Bits<POS_BITS>>,
    s1_ad: ResetDff<Bits<POS_BITS>>,
    s1_dx: ResetDff<Bits<POS_BITS>>,
    s1_dd: ResetDff<Bits<POS_BITS>>,
    s1_neg: ResetDff<Bit>,
    s1_min: ResetDff<Bits<POS_BITS>>,
    s2_seg: ResetDff<Bit>,
    s2_last: ResetDff<Bits<WIDTH_BITS>>,
    s2_ax: ResetDff<Bits<POS_BITS>>,
    s2_ad: ResetDff<Bits<POS_BITS>>,
    s2_dd: ResetDff<Bits<POS_BITS>>,
    s2_m: ResetDff<Bits<POS_BITS>>,
    s2_shape: ResetDff<Bits<SHAPE_BITS>>,
    s3_seg: ResetDff<Bit>,
    s3_last: ResetDff<Bits<WIDTH_BITS>>,
    s3_ax: ResetDff<Bits<POS_BITS>>,
    s3_ad: ResetDff<Bits<POS_BITS>>,
    s3_dd: ResetDff<Bits<POS_BITS>>,
    s3_shape: ResetDff<Bits<SHAPE_BITS>>,
    // Stage 4: the segment with its reciprocal, into the memory.
    s4_seg: ResetDff<Bit>,
    s4_last: ResetDff<Bits<WIDTH_BITS>>,
    s4_ax: ResetDff<Bits<POS_BITS>>,
    s4_ad: ResetDff<Bits<POS_BITS>>,
    s4_dd: ResetDff<Bits<POS_BITS>>,
    s4_shape: ResetDff<Bits<SHAPE_BITS>>,
    recip: BlockRam<RECIP_BITS, RECIP_INDEX_BITS>,
    // ---- The segment memory, one RAM per field, and its pointers (one bit
    // above the address, so that full and empty differ).
    seg_last: BlockRam<WIDTH_BITS, SEG_ADDR_BITS>,
    seg_ax: BlockRam<POS_BITS, SEG_ADDR_BITS>,
    seg_ad: BlockRam<POS_BITS, SEG_ADDR_BITS>,
    seg_dd: BlockRam<POS_BITS, SEG_ADDR_BITS>,
    seg_shape: BlockRam<SHAPE_BITS, SEG_ADDR_BITS>,
    seg_recip: BlockRam<RECIP_BITS, SEG_ADDR_BITS>,
    seg_wp: ResetDff<Bits<SEG_PTR_BITS>>,
    // The prefetch: reads in order at `rd_ptr` whenever the registers will
    // have room, two clocks to their data (`rd1`, `rd2`), into four
    // registers `e0..e3` used as a ring (written at `wi`, the pixel
    // engine's segment at `ri`).
    rd_ptr: ResetDff<Bits<SEG_PTR_BITS>>,
    // Segments written and not yet read; lines in the queue (public for
    // the drivers' diagnostics).
    pub seg_used: ResetDff<Bits<SEG_PTR_BITS>>,
    pub q_used: ResetDff<Bits<QUEUE_PTR_BITS>>,
    // `seg_used > seg_limit` and `q_used ≥ LINE_QUEUE` as registers (0 at
    // power-up, as the counts): the admission reads no comparison.
    seg_full: ResetDff<Bit>,
    q_full: ResetDff<Bit>,
    // `seg_used != 0` (the memory holds an unread segment: `seg_used` is
    // `seg_wp - rd_ptr`) as a register, written beside the count.
    seg_any: ResetDff<Bit>,
    rd1: ResetDff<Bit>,
    rd2: ResetDff<Bit>,
    fill: ResetDff<Bits<FILL_BITS>>,
    wi: ResetDff<Bits<SLOT_BITS>>,
    ri: ResetDff<Bits<SLOT_BITS>>,
    e0_last: ResetDff<Bits<WIDTH_BITS>>,
    e0_ax: ResetDff<Bits<POS_BITS>>,
    e0_ad: ResetDff<Bits<POS_BITS>>,
    e0_dd: ResetDff<Bits<POS_BITS>>,
    e0_shape: ResetDff<Bits<SHAPE_BITS>>,
    e0_recip: ResetDff<Bits<RECIP_BITS>>,
    e1_last: ResetDff<Bits<WIDTH_BITS>>,
    e1_ax: ResetDff<Bits<POS_BITS>>,
    e1_ad: ResetDff<Bits<POS_BITS>>,
    e1_dd: ResetDff<Bits<POS_BITS>>,
    e1_shape: ResetDff<Bits<SHAPE_BITS>>,
    e1_recip: ResetDff<Bits<RECIP_BITS>>,
    e2_last: ResetDff<Bits<WIDTH_BITS>>,
    e2_ax: ResetDff<Bits<POS_BITS>>,
    e2_ad: ResetDff<Bits<POS_BITS>>,
    e2_dd: ResetDff<Bits<POS_BITS>>,
    e2_shape: ResetDff<Bits<SHAPE_BITS>>,
    e2_recip: ResetDff<Bits<RECIP_BITS>>,
    e3_last: ResetDff<Bits<WIDTH_BITS>>,
    e3_ax: ResetDff<Bits<POS_BITS>>,
    e3_ad: ResetDff<Bits<POS_BITS>>,
    e3_dd: ResetDff<Bits<POS_BITS>>,
    e3_shape: ResetDff<Bits<SHAPE_BITS>>,
    e3_recip: ResetDff<Bits<RECIP_BITS>>,
    // ---- The line queue: written at the marker, shown to the pixel engine
    // [`SEGMENT_LAG`] clocks after it (the write pointer delayed through
    // `q_wp1..5`).
    // A line's description is one word ([`LINE_BITS`], fields at the
    // `*_AT` offsets), kept twice: read at the read pointer and at its
    // successor; the entry at the pointer's next value is picked after the
    // read registers by `q_next_q` (the line done a clock ago), so no address
    // waits for the pixel's comparison.
    q_line: RAM<Bits<LINE_BITS>, LINE_QUEUE_BITS>,
    q_line_n: RAM<Bits<LINE_BITS>, LINE_QUEUE_BITS>,
    q_wp: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_wp1: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_wp2: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_wp3: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_wp4: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_wp5: ResetDff<Bits<QUEUE_PTR_BITS>>,
    // A line is shown (`q_wp5` a clock ago against the read pointer),
    // computed a clock ahead from registers: the engine's control starts
    // at a register.
    line_ready: ResetDff<Bit>,
    q_rp: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_rp1: ResetDff<Bits<QUEUE_PTR_BITS>>,
    q_next_q: ResetDff<Bit>,
    overflow_q: ResetDff<Bit>,
    // ---- Pixels: the line being sent, then the pixel pipeline.
    x: ResetDff<Bits<WIDTH_BITS>>,
    // `x + 1`, `x == 0`; the pixel's place on the next clock of the same
    // line (in the head, in a segment, the line's last: compared a clock
    // ahead against `x + 1`); `x` against each ring slot's last pixel.
    x1: ResetDff<Bits<WIDTH_BITS>>,
    x_zero: ResetDff<Bit>,
    head_next: ResetDff<Bit>,
    seg_next: ResetDff<Bit>,
    last_next: ResetDff<Bit>,
    at_e0: ResetDff<Bit>,
    at_e1: ResetDff<Bit>,
    at_e2: ResetDff<Bit>,
    at_e3: ResetDff<Bit>,
    p0_valid: ResetDff<Bit>,
    p0_last: ResetDff<Bit>,
    p0_sof: ResetDff<Bit>,
    p0_empty: ResetDff<Bit>,
    p0_ramp: ResetDff<Bit>,
    p0_neg: ResetDff<Bit>,
    p0_base: ResetDff<Bits<POS_BITS>>,
    p0_u: ResetDff<Bits<POS_BITS>>,
    p0_lz: ResetDff<Bits<LZ_BITS>>,
    p0_recip: ResetDff<Bits<RECIP_BITS>>,
    p0_dd: ResetDff<Bits<POS_BITS>>,
    p1_valid: ResetDff<Bit>,
    p1_last: ResetDff<Bit>,
    p1_sof: ResetDff<Bit>,
    p1_empty: ResetDff<Bit>,
    p1_ramp: ResetDff<Bit>,
    p1_neg: ResetDff<Bit>,
    p1_base: ResetDff<Bits<POS_BITS>>,
    p1_dd: ResetDff<Bits<POS_BITS>>,
    p2_valid: ResetDff<Bit>,
    p2_last: ResetDff<Bit>,
    p2_sof: ResetDff<Bit>,
    p2_empty: ResetDff<Bit>,
    p2_ramp: ResetDff<Bit>,
    p2_neg: ResetDff<Bit>,
    p2_base: ResetDff<Bits<POS_BITS>>,
    p2_prod: ResetDff<Bits<32>>,
    p2_dd: ResetDff<Bits<POS_BITS>>,
    p3_valid: ResetDff<Bit>,
    p3_last: ResetDff<Bit>,
    p3_sof: ResetDff<Bit>,
    p3_empty: ResetDff<Bit>,
    p3_ramp: ResetDff<Bit>,
    p3_neg: ResetDff<Bit>,
    p3_base: ResetDff<Bits<POS_BITS>>,
    p4_valid: ResetDff<Bit>,
    p4_last: ResetDff<Bit>,
    p4_sof: ResetDff<Bit>,
    p4_empty: ResetDff<Bit>,
    p4_ramp: ResetDff<Bit>,
    p4_neg: ResetDff<Bit>,
    p4_base: ResetDff<Bits<POS_BITS>>,
    p4_prod: ResetDff<Bits<32>>,
    p5_valid: ResetDff<Bit>,
    p5_last: ResetDff<Bit>,
    p5_sof: ResetDff<Bit>,
    p5_empty: ResetDff<Bit>,
    p5_ramp: ResetDff<Bit>,
    p5_neg: ResetDff<Bit>,
    p5_base: ResetDff<Bits<POS_BITS>>,
    p5_delta: ResetDff<Bits<POS_BITS>>,
    o_valid: ResetDff<Bit>,
    o_last: ResetDff<Bit>,
    o_sof: ResetDff<Bit>,
    o_empty: ResetDff<Bit>,
    o_d: ResetDff<Bits<POS_BITS>>,
    // ---- Locals.
    b_c: Signal<Local, Bits<WIDTH_BITS>>,
    x_up: Signal<Local, Bits<{ POS_BITS + 1 }>>,
    ax_wide: Signal<Local, Bits<{ POS_BITS + 1 }>>,
    prev_c_fix: Signal<Local, Bits<{ POS_BITS + 1 }>>,
    first_event: Signal<Local, Bit>,
    sof_flag: Signal<Local, Bits<FLAG_BITS>>,
    line_write: Signal<Local, Bit>,
    fits: Signal<Local, Bit>,
    drop_now: Signal<Local, Bit>,
    n1: Signal<Local, Bits<POS_BITS>>,
    n2: Signal<Local, Bits<POS_BITS>>,
    n3: Signal<Local, Bits<POS_BITS>>,
    n4: Signal<Local, Bits<POS_BITS>>,
    l1: Signal<Local, Bits<SHAPE_BITS>>,
    l2: Signal<Local, Bits<SHAPE_BITS>>,
    l3: Signal<Local, Bits<SHAPE_BITS>>,
    l4: Signal<Local, Bits<SHAPE_BITS>>,
    jump: Signal<Local, Bit>,
    signed_shape: Signal<Local, Bits<SHAPE_BITS>>,
    empty_line: Signal<Local, Bit>,
    in_head: Signal<Local, Bit>,
    in_seg: Signal<Local, Bit>,
    in_head_now: Signal<Local, Bit>,
    in_seg_now: Signal<Local, Bit>,
    empty_cur: Signal<Local, Bit>,
    empty_succ: Signal<Local, Bit>,
    head_cur: Signal<Local, Bit>,
    head_succ: Signal<Local, Bit>,
    seg_cur: Signal<Local, Bit>,
    seg_succ: Signal<Local, Bit>,
    at_cur_last: Signal<Local, Bit>,
    step: Signal<Local, Bit>,
    at_read: Signal<Local, Bit>,
    head0: Signal<Local, Bit>,
    seg0: Signal<Local, Bit>,
    last0_flag: Signal<Local, Bits<FLAG_BITS>>,
    first_c_cur: Signal<Local, Bits<WIDTH_BITS>>,
    first_c_succ: Signal<Local, Bits<WIDTH_BITS>>,
    last_c_cur: Signal<Local, Bits<WIDTH_BITS>>,
    last_c_succ: Signal<Local, Bits<WIDTH_BITS>>,
    seg_done: Signal<Local, Bit>,
    line_done: Signal<Local, Bit>,
    issue: Signal<Local, Bit>,
    room: Signal<Local, Bit>,
    pop: Signal<Local, Bit>,
    kept: Signal<Local, Bits<FILL_BITS>>,
    cur_ax: Signal<Local, Bits<POS_BITS>>,
    cur_ad: Signal<Local, Bits<POS_BITS>>,
    cur_dd: Signal<Local, Bits<POS_BITS>>,
    cur_shape: Signal<Local, Bits<SHAPE_BITS>>,
    cur_recip: Signal<Local, Bits<RECIP_BITS>>,
    q_rp_next: Signal<Local, Bits<QUEUE_PTR_BITS>>,
    q_last_x_cur: Signal<Local, Bits<WIDTH_BITS>>,
    q_last_x_succ: Signal<Local, Bits<WIDTH_BITS>>,
    at_last_x: Signal<Local, Bit>,
    q_first_d_out: Signal<Local, Bits<POS_BITS>>,
    q_last_d_out: Signal<Local, Bits<POS_BITS>>,
    q_sof_out: Signal<Local, Bit>,
    q_flags_in: Signal<Local, Bits<FLAG_BITS>>,
    q_last_x_in: Signal<Local, Bits<WIDTH_BITS>>,
    q_word_in: Signal<Local, Bits<LINE_BITS>>,
    q_word_out: Signal<Local, Bits<LINE_BITS>>,
    x16: Signal<Local, Bits<POS_BITS>>,
    // The two products in DSP blocks whose input registers are P1's `v`,
    // `recip` and P3's `t`, `|Δd|` (`DspMultiplier`).
    mul_v: DspMultiplier,
    mul_t: DspMultiplier,
    v_in: Signal<Local, Bits<MUL_OPERAND_BITS>>,
    t_in: Signal<Local, Bits<MUL_OPERAND_BITS>>,
    rounded: Signal<Local, Bits<32>>,
    // ---- Constants.
    frac_round: Constant<Bits<{ POS_BITS + 1 }>>,
    frac_bits: Constant<Bits<8>>,
    // The top 8, 4, 2, 1 bits of a distance, as shifts.
    top8: Constant<Bits<8>>,
    top4: Constant<Bits<8>>,
    top2: Constant<Bits<8>>,
    top1: Constant<Bits<8>>,
    sh8: Constant<Bits<8>>,
    sh4: Constant<Bits<8>>,
    sh2: Constant<Bits<8>>,
    sh1: Constant<Bits<8>>,
    lz8: Constant<Bits<SHAPE_BITS>>,
    lz4: Constant<Bits<SHAPE_BITS>>,
    lz2: Constant<Bits<SHAPE_BITS>>,
    lz1: Constant<Bits<SHAPE_BITS>>,
    neg_flag: Constant<Bits<SHAPE_BITS>>,
    jump_flag: Constant<Bits<SHAPE_BITS>>,
    neg_bit: Constant<Bits<8>>,
    jump_bit: Constant<Bits<8>>,
    bit0: Constant<Bits<8>>,
    index_low: Constant<Bits<8>>,
    jump_on: Constant<Bit>,
    jump_lsb: Constant<Bits<POS_BITS>>,
    seg_limit: Constant<Bits<SEG_PTR_BITS>>,
    seg_limit_up: Constant<Bits<SEG_PTR_BITS>>,
    seg_one: Constant<Bits<SEG_PTR_BITS>>,
    prefetch: Constant<Bits<FILL_BITS>>,
    prefetch_m1: Constant<Bits<FILL_BITS>>,
    prefetch_m2: Constant<Bits<FILL_BITS>>,
    slot1: Constant<Bits<SLOT_BITS>>,
    slot2: Constant<Bits<SLOT_BITS>>,
    slot3: Constant<Bits<SLOT_BITS>>,
    queue_size: Constant<Bits<QUEUE_PTR_BITS>>,
    queue_last: Constant<Bits<QUEUE_PTR_BITS>>,
    flag_sof: Constant<Bits<FLAG_BITS>>,
    flag_empty: Constant<Bits<FLAG_BITS>>,
    flag_head0: Constant<Bits<FLAG_BITS>>,
    flag_seg0: Constant<Bits<FLAG_BITS>>,
    flag_last0: Constant<Bits<FLAG_BITS>>,
    empty_at: Constant<Bits<8>>,
    head0_at: Constant<Bits<8>>,
    seg0_at: Constant<Bits<8>>,
    last0_at: Constant<Bits<8>>,
    t_shift: Constant<Bits<8>>,
    t_over: Constant<Bits<8>>,
    t_max: Constant<Bits<16>>,
    half: Constant<Bits<32>>,
    w_shift: Constant<Bits<8>>,
    last_x_at: Constant<Bits<8>>,
    first_c_at: Constant<Bits<8>>,
    last_c_at: Constant<Bits<8>>,
    first_d_at: Constant<Bits<8>>,
    last_d_at: Constant<Bits<8>>,
}

/// A memory whose Verilog starts all zeros, as its Rust model does (an
/// uninitialised Verilog memory reads `x` in Icarus until written).
fn zeroed<const D: usize, const A: usize>() -> RAM<Bits<D>, A> {
    RAM::from(std::iter::repeat_n(Bits::<D>::default(), 1 << A))
}

impl Interpolator {
    /// An interpolator with edge jump `jump` (in [`POS_FRAC_BITS`] fixed
    /// point; `None`: every pair of consecutive matches is bridged).
    pub fn new(jump: Option<u64>) -> Self {
        let cp = |v: u64| Constant::<Bits<POS_BITS>>::new(v.into());
        let c8 = |v: u64| Constant::<Bits<8>>::new(v.into());
        let cs = |v: u64| Constant::<Bits<SHAPE_BITS>>::new(v.into());
        Interpolator {
            clock: Default::default(),
            reset: Default::default(),
            a_valid: Default::default(),
            a_last: Default::default(),
            a_x: Default::default(),
            a_d: Default::default(),
            a_width: Default::default(),
            a_sof: Default::default(),
            p_valid: Default::default(),
            p_d: Default::default(),
            p_last: Default::default(),
            p_sof: Default::default(),
            p_empty: Default::default(),
            overflow: Default::default(),
            in_line: Default::default(),
            dropping: Default::default(),
            has_prev: Default::default(),
            prev_x: Default::default(),
            prev_d: Default::default(),
            prev_c: Default::default(),
            first_d: Default::default(),
            first_c: Default::default(),
            s1_seg: Default::default(),
            s1_last: Default::default(),
            s1_ax: Default::default(),
            s1_ad: Default::default(),
            s1_dx: Default::default(),
            s1_dd: Default::default(),
            s1_neg: Default::default(),
            s1_min: Default::default(),
            s2_seg: Default::default(),
            s2_last: Default::default(),
            s2_ax: Default::default(),
            s2_ad: Default::default(),
            s2_dd: Default::default(),
            s2_m: Default::default(),
            s2_shape: Default::default(),
            s3_seg: Default::default(),
            s3_last: Default::default(),
            s3_ax: Default::default(),
            s3_ad: Default::default(),
            s3_dd: Default::default(),
            s3_shape: Default::default(),
            s4_seg: Default::default(),
            s4_last: Default::default(),
            s4_ax: Default::default(),
            s4_ad: Default::default(),
            s4_dd: Default::default(),
            s4_shape: Default::default(),
            recip: BlockRam::with_words(recip_table()),
            seg_last: Default::default(),
            seg_ax: Default::default(),
            seg_ad: Default::default(),
            seg_dd: Default::default(),
            seg_shape: Default::default(),
            seg_recip: Default::default(),
            seg_wp: Default::default(),
            rd_ptr: Default::default(),
            seg_used: Default::default(),
            q_used: Default::default(),
            seg_full: Default::default(),
            seg_any: Default::default(),
            q_full: Default::default(),
            rd1: Default::default(),
            rd2: Default::default(),
            fill: Default::default(),
            wi: Default::default(),
            ri: Default::default(),
            e0_last: Default::default(),
            e0_ax: Default::default(),
            e0_ad: Default::default(),
            e0_dd: Default::default(),
            e0_shape: Default::default(),
            e0_recip: Default::default(),
            e1_last: Default::default(),
            e1_ax: Default::default(),
            e1_ad: Default::default(),
            e1_dd: Default::default(),
            e1_shape: Default::default(),
            e1_recip: Default::default(),
            e2_last: Default::default(),
            e2_ax: Default::default(),
            e2_ad: Default::default(),
            e2_dd: Default::default(),
            e2_shape: Default::default(),
            e2_recip: Default::default(),
            e3_last: Default::default(),
            e3_ax: Default::default(),
            e3_ad: Default::default(),
            e3_dd: Default::default(),
            e3_shape: Default::default(),
            e3_recip: Default::default(),
            q_line: zeroed(),
            q_line_n: zeroed(),
            q_wp: Default::default(),
            q_wp1: Default::default(),
            q_wp2: Default::default(),
            q_wp3: Default::default(),
            q_wp4: Default::default(),
            q_wp5: Default::default(),
            line_ready: Default::default(),
            q_rp: Default::default(),
            q_rp1: ResetDff::new(1u64.into()),
            q_next_q: Default::default(),
            overflow_q: Default::default(),
            x: Default::default(),
            x1: ResetDff::new(1u64.into()),
            x_zero: ResetDff::new(true),
            head_next: Default::default(),
            seg_next: Default::default(),
            last_next: Default::default(),
            at_e0: ResetDff::new(true),
            at_e1: ResetDff::new(true),
            at_e2: ResetDff::new(true),
            at_e3: ResetDff::new(true),
            p0_valid: Default::default(),
            p0_last: Default::default(),
            p0_sof: Default::default(),
            p0_empty: Default::default(),
            p0_ramp: Default::default(),
            p0_neg: Default::default(),
            p0_base: Default::default(),
            p0_u: Default::default(),
            p0_lz: Default::default(),
            p0_recip: Default::default(),
            p0_dd: Default::default(),
            p1_valid: Default::default(),
            p1_last: Default::default(),
            p1_sof: Default::default(),
            p1_empty: Default::default(),
            p1_ramp: Default::default(),
            p1_neg: Default::default(),
            p1_base: Default::default(),
            p1_dd: Default::default(),
            p2_valid: Default::default(),
            p2_last: Default::default(),
            p2_sof: Default::default(),
            p2_empty: Default::default(),
            p2_ramp: Default::default(),
            p2_neg: Default::default(),
            p2_base: Default::default(),
            p2_prod: Default::default(),
            p2_dd: Default::default(),
            p3_valid: Default::default(),
            p3_last: Default::default(),
            p3_sof: Default::default(),
            p3_empty: Default::default(),
            p3_ramp: Default::default(),
            p3_neg: Default::default(),
            p3_base: Default::default(),
            p4_valid: Default::default(),
            p4_last: Default::default(),
            p4_sof: Default::default(),
            p4_empty: Default::default(),
            p4_ramp: Default::default(),
            p4_neg: Default::default(),
            p4_base: Default::default(),
            p4_prod: Default::default(),
            p5_valid: Default::default(),
            p5_last: Default::default(),
            p5_sof: Default::default(),
            p5_empty: Default::default(),
            p5_ramp: Default::default(),
            p5_neg: Default::default(),
            p5_base: Default::default(),
            p5_delta: Default::default(),
            o_valid: Default::default(),
            o_last: Default::default(),
            o_sof: Default::default(),
            o_empty: Default::default(),
            o_d: Default::default(),
            b_c: Default::default(),
            x_up: Default::default(),
            ax_wide: Default::default(),
            prev_c_fix: Default::default(),
            first_event: Default::default(),
            sof_flag: Default::default(),
            line_write: Default::default(),
            fits: Default::default(),
            drop_now: Default::default(),
            n1: Default::default(),
            n2: Default::default(),
            n3: Default::default(),
            n4: Default::default(),
            l1: Default::default(),
            l2: Default::default(),
            l3: Default::default(),
            l4: Default::default(),
            jump: Default::default(),
            signed_shape: Default::default(),
            empty_line: Default::default(),
            in_head: Default::default(),
            in_seg: Default::default(),
            in_head_now: Default::default(),
            in_seg_now: Default::default(),
            empty_cur: Default::default(),
            empty_succ: Default::default(),
            head_cur: Default::default(),
            head_succ: Default::default(),
            seg_cur: Default::default(),
            seg_succ: Default::default(),
            at_cur_last: Default::default(),
            step: Default::default(),
            at_read: Default::default(),
            head0: Default::default(),
            seg0: Default::default(),
            last0_flag: Default::default(),
            first_c_cur: Default::default(),
            first_c_succ: Default::default(),
            last_c_cur: Default::default(),
            last_c_succ: Default::default(),
            seg_done: Default::default(),
            line_done: Default::default(),
            issue: Default::default(),
            room: Default::default(),
            pop: Default::default(),
            kept: Default::default(),
            cur_ax: Default::default(),
            cur_ad: Default::default(),
            cur_dd: Default::default(),
            cur_shape: Default::default(),
            cur_recip: Default::default(),
            q_rp_next: Default::default(),
            q_last_x_cur: Default::default(),
            q_last_x_succ: Default::default(),
            at_last_x: Default::default(),
            q_first_d_out: Default::default(),
            q_last_d_out: Default::default(),
            q_sof_out: Default::default(),
            q_flags_in: Default::default(),
            q_last_x_in: Default::default(),
            q_word_in: Default::default(),
            q_word_out: Default::default(),
            x16: Default::default(),
            mul_v: Default::default(),
            mul_t: Default::default(),
            v_in: Default::default(),
            t_in: Default::default(),
            rounded: Default::default(),
            frac_round: Constant::new(((1u64 << POS_FRAC_BITS) - 1).into()),
            frac_bits: c8(POS_FRAC_BITS as u64),
            top8: c8((POS_BITS - 8) as u64),
            top4: c8((POS_BITS - 4) as u64),
            top2: c8((POS_BITS - 2) as u64),
            top1: c8((POS_BITS - 1) as u64),
            sh8: c8(8),
            sh4: c8(4),
            sh2: c8(2),
            sh1: c8(1),
            lz8: cs(8),
            lz4: cs(4),
            lz2: cs(2),
            lz1: cs(1),
            neg_flag: cs(1 << NEG_BIT),
            jump_flag: cs(1 << JUMP_BIT),
            neg_bit: c8(NEG_BIT as u64),
            jump_bit: c8(JUMP_BIT as u64),
            bit0: c8(0),
            index_low: c8((POS_BITS - 1 - RECIP_INDEX_BITS) as u64),
            jump_on: Constant::new(jump.is_some()),
            jump_lsb: cp(jump.unwrap_or(0)),
            prefetch: Constant::new((PREFETCH as u64).into()),
            prefetch_m1: Constant::new((PREFETCH as u64 - 1).into()),
            prefetch_m2: Constant::new((PREFETCH as u64 - 2).into()),
            slot1: Constant::new(1u64.into()),
            slot2: Constant::new(2u64.into()),
            slot3: Constant::new(3u64.into()),
            seg_limit: Constant::new((((1usize << SEG_ADDR_BITS) - SEG_RESERVE) as u64).into()),
            seg_limit_up: Constant::new((((1usize << SEG_ADDR_BITS) - SEG_RESERVE + 1) as u64).into()),
            seg_one: Constant::new(1u64.into()),
            queue_size: Constant::new((LINE_QUEUE as u64).into()),
            queue_last: Constant::new(((LINE_QUEUE - 1) as u64).into()),
            flag_sof: Constant::new((1u64 << SOF_AT).into()),
            flag_empty: Constant::new((1u64 << EMPTY_AT).into()),
            flag_head0: Constant::new((1u64 << HEAD0_AT).into()),
            flag_seg0: Constant::new((1u64 << SEG0_AT).into()),
            flag_last0: Constant::new((1u64 << LAST0_AT).into()),
            empty_at: c8(EMPTY_AT as u64),
            head0_at: c8(HEAD0_AT as u64),
            seg0_at: c8(SEG0_AT as u64),
            last0_at: c8(LAST0_AT as u64),
            t_shift: c8((POS_BITS - 1) as u64),
            t_over: c8((POS_BITS - 1 + WEIGHT_FRAC_BITS) as u64),
            t_max: Constant::new(((1u64 << WEIGHT_FRAC_BITS) - 1).into()),
            half: Constant::new((1u64 << (WEIGHT_FRAC_BITS - 1)).into()),
            w_shift: c8(WEIGHT_FRAC_BITS as u64),
            last_x_at: c8(LAST_X_AT as u64),
            first_c_at: c8(FIRST_C_AT as u64),
            last_c_at: c8(LAST_C_AT as u64),
            first_d_at: c8(FIRST_D_AT as u64),
            last_d_at: c8(LAST_D_AT as u64),
        }
    }
}

impl Default for Interpolator {
    /// The default mode's edge jump, [`EDGE_JUMP_LSB`].
    fn default() -> Self {
        Interpolator::new(Some(EDGE_JUMP_LSB))
    }
}

impl Logic for Interpolator {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, in_line, dropping, has_prev, prev_x, prev_d, prev_c, first_d, first_c, s1_seg, s1_last, s1_ax, s1_ad, s1_dx, s1_dd, s1_neg, s1_min, s2_seg, s2_last, s2_ax, s2_ad, s2_dd, s2_m, s2_shape, s3_seg, s3_last, s3_ax, s3_ad, s3_dd, s3_shape, s4_seg, s4_last, s4_ax, s4_ad, s4_dd, s4_shape, seg_wp, rd_ptr, seg_used, q_used, seg_full, seg_any, q_full, rd1, rd2, fill, wi, ri, e0_last, e0_ax, e0_ad, e0_dd, e0_shape, e0_recip, e1_last, e1_ax, e1_ad, e1_dd, e1_shape, e1_recip, e2_last, e2_ax, e2_ad, e2_dd, e2_shape, e2_recip, e3_last, e3_ax, e3_ad, e3_dd, e3_shape, e3_recip, q_wp, q_wp1, q_wp2, q_wp3, q_wp4, q_wp5, line_ready, q_rp, q_rp1, q_next_q, overflow_q, x, x1, x_zero, head_next, seg_next, last_next, at_e0, at_e1, at_e2, at_e3, p0_valid, p0_last, p0_sof, p0_empty, p0_ramp, p0_neg, p0_base, p0_u, p0_lz, p0_recip, p0_dd, p1_valid, p1_last, p1_sof, p1_empty, p1_ramp, p1_neg, p1_base, p1_dd, p2_valid, p2_last, p2_sof, p2_empty, p2_ramp, p2_neg, p2_base, p2_prod, p2_dd, p3_valid, p3_last, p3_sof, p3_empty, p3_ramp, p3_neg, p3_base, p4_valid, p4_last, p4_sof, p4_empty, p4_ramp, p4_neg, p4_base, p4_prod, p5_valid, p5_last, p5_sof, p5_empty, p5_ramp, p5_neg, p5_base, p5_delta, o_valid, o_last, o_sof, o_empty, o_d);
        self.in_line.reset.next = self.reset.val();
        self.dropping.reset.next = self.reset.val();
        self.has_prev.reset.next = self.reset.val();
        self.prev_x.reset.next = self.reset.val();
        self.prev_d.reset.next = self.reset.val();
        self.prev_c.reset.next = self.reset.val();
        self.first_d.reset.next = self.reset.val();
        self.first_c.reset.next = self.reset.val();
        self.s1_seg.reset.next = self.reset.val();
        self.s1_last.reset.next = self.reset.val();
        self.s1_ax.reset.next = self.reset.val();
        self.s1_ad.reset.next = self.reset.val();
        self.s1_dx.reset.next = self.reset.val();
        self.s1_dd.reset.next = self.reset.val();
        self.s1_neg.reset.next = self.reset.val();
        self.s1_min.reset.next = self.reset.val();
        self.s2_seg.reset.next = self.reset.val();
        self.s2_last.reset.next = self.reset.val();
        self.s2_ax.reset.next = self.reset.val();
        self.s2_ad.reset.next = self.reset.val();
        self.s2_dd.reset.next = self.reset.val();
        self.s2_m.reset.next = self.reset.val();
        self.s2_shape.reset.next = self.reset.val();
        self.s3_seg.reset.next = self.reset.val();
        self.s3_last.reset.next = self.reset.val();
        self.s3_ax.reset.next = self.reset.val();
        self.s3_ad.reset.next = self.reset.val();
        self.s3_dd.reset.next = self.reset.val();
        self.s3_shape.reset.next = self.reset.val();
        self.s4_seg.reset.next = self.reset.val();
        self.s4_last.reset.next = self.reset.val();
        self.s4_ax.reset.next = self.reset.val();
        self.s4_ad.reset.next = self.reset.val();
        self.s4_dd.reset.next = self.reset.val();
        self.s4_shape.reset.next = self.reset.val();
        self.seg_wp.reset.next = self.reset.val();
        self.rd_ptr.reset.next = self.reset.val();
        self.seg_used.reset.next = self.reset.val();
        self.q_used.reset.next = self.reset.val();
        self.seg_full.reset.next = self.reset.val();
        self.seg_any.reset.next = self.reset.val();
        self.q_full.reset.next = self.reset.val();
        self.rd1.reset.next = self.reset.val();
        self.rd2.reset.next = self.reset.val();
        self.fill.reset.next = self.reset.val();
        self.wi.reset.next = self.reset.val();
        self.ri.reset.next = self.reset.val();
        self.e0_last.reset.next = self.reset.val();
        self.e0_ax.reset.next = self.reset.val();
        self.e0_ad.reset.next = self.reset.val();
        self.e0_dd.reset.next = self.reset.val();
        self.e0_shape.reset.next = self.reset.val();
        self.e0_recip.reset.next = self.reset.val();
        self.e1_last.reset.next = self.reset.val();
        self.e1_ax.reset.next = self.reset.val();
        self.e1_ad.reset.next = self.reset.val();
        self.e1_dd.reset.next = self.reset.val();
        self.e1_shape.reset.next = self.reset.val();
        self.e1_recip.reset.next = self.reset.val();
        self.e2_last.reset.next = self.reset.val();
        self.e2_ax.reset.next = self.reset.val();
        self.e2_ad.reset.next = self.reset.val();
        self.e2_dd.reset.next = self.reset.val();
        self.e2_shape.reset.next = self.reset.val();
        self.e2_recip.reset.next = self.reset.val();
        self.e3_last.reset.next = self.reset.val();
        self.e3_ax.reset.next = self.reset.val();
        self.e3_ad.reset.next = self.reset.val();
        self.e3_dd.reset.next = self.reset.val();
        self.e3_shape.reset.next = self.reset.val();
        self.e3_recip.reset.next = self.reset.val();
        self.q_wp.reset.next = self.reset.val();
        self.q_wp1.reset.next = self.reset.val();
        self.q_wp2.reset.next = self.reset.val();
        self.q_wp3.reset.next = self.reset.val();
        self.q_wp4.reset.next = self.reset.val();
        self.q_wp5.reset.next = self.reset.val();
        self.line_ready.reset.next = self.reset.val();
        self.q_rp.reset.next = self.reset.val();
        self.q_rp1.reset.next = self.reset.val();
        self.q_next_q.reset.next = self.reset.val();
        self.overflow_q.reset.next = self.reset.val();
        self.x.reset.next = self.reset.val();
        self.x1.reset.next = self.reset.val();
        self.x_zero.reset.next = self.reset.val();
        self.head_next.reset.next = self.reset.val();
        self.seg_next.reset.next = self.reset.val();
        self.last_next.reset.next = self.reset.val();
        self.at_e0.reset.next = self.reset.val();
        self.at_e1.reset.next = self.reset.val();
        self.at_e2.reset.next = self.reset.val();
        self.at_e3.reset.next = self.reset.val();
        self.p0_valid.reset.next = self.reset.val();
        self.p0_last.reset.next = self.reset.val();
        self.p0_sof.reset.next = self.reset.val();
        self.p0_empty.reset.next = self.reset.val();
        self.p0_ramp.reset.next = self.reset.val();
        self.p0_neg.reset.next = self.reset.val();
        self.p0_base.reset.next = self.reset.val();
        self.p0_u.reset.next = self.reset.val();
        self.p0_lz.reset.next = self.reset.val();
        self.p0_recip.reset.next = self.reset.val();
        self.p0_dd.reset.next = self.reset.val();
        self.p1_valid.reset.next = self.reset.val();
        self.p1_last.reset.next = self.reset.val();
        self.p1_sof.reset.next = self.reset.val();
        self.p1_empty.reset.next = self.reset.val();
        self.p1_ramp.reset.next = self.reset.val();
        self.p1_neg.reset.next = self.reset.val();
        self.p1_base.reset.next = self.reset.val();
        self.p1_dd.reset.next = self.reset.val();
        self.p2_valid.reset.next = self.reset.val();
        self.p2_last.reset.next = self.reset.val();
        self.p2_sof.reset.next = self.reset.val();
        self.p2_empty.reset.next = self.reset.val();
        self.p2_ramp.reset.next = self.reset.val();
        self.p2_neg.reset.next = self.reset.val();
        self.p2_base.reset.next = self.reset.val();
        self.p2_prod.reset.next = self.reset.val();
        self.p2_dd.reset.next = self.reset.val();
        self.p3_valid.reset.next = self.reset.val();
        self.p3_last.reset.next = self.reset.val();
        self.p3_sof.reset.next = self.reset.val();
        self.p3_empty.reset.next = self.reset.val();
        self.p3_ramp.reset.next = self.reset.val();
        self.p3_neg.reset.next = self.reset.val();
        self.p3_base.reset.next = self.reset.val();
        self.p4_valid.reset.next = self.reset.val();
        self.p4_last.reset.next = self.reset.val();
        self.p4_sof.reset.next = self.reset.val();
        self.p4_empty.reset.next = self.reset.val();
        self.p4_ramp.reset.next = self.reset.val();
        self.p4_neg.reset.next = self.reset.val();
        self.p4_base.reset.next = self.reset.val();
        self.p4_prod.reset.next = self.reset.val();
        self.p5_valid.reset.next = self.reset.val();
        self.p5_last.reset.next = self.reset.val();
        self.p5_sof.reset.next = self.reset.val();
        self.p5_empty.reset.next = self.reset.val();
        self.p5_ramp.reset.next = self.reset.val();
        self.p5_neg.reset.next = self.reset.val();
        self.p5_base.reset.next = self.reset.val();
        self.p5_delta.reset.next = self.reset.val();
        self.o_valid.reset.next = self.reset.val();
        self.o_last.reset.next = self.reset.val();
        self.o_sof.reset.next = self.reset.val();
        self.o_empty.reset.next = self.reset.val();
        self.o_d.reset.next = self.reset.val();
        self.recip.clock.next = self.clock.val();
        self.seg_last.clock.next = self.clock.val();
        self.seg_ax.clock.next = self.clock.val();
        self.seg_ad.clock.next = self.clock.val();
        self.seg_dd.clock.next = self.clock.val();
        self.seg_shape.clock.next = self.clock.val();
        self.seg_recip.clock.next = self.clock.val();
        self.q_line.read_clock.next = self.clock.val();
        self.q_line_n.read_clock.next = self.clock.val();
        self.q_line.write_clock.next = self.clock.val();
        self.q_line_n.write_clock.next = self.clock.val();

        // ================= Segments =================
        // The first pixel centre at or after the match: ⌈X⌉.
        self.x_up.next = bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.a_x.val()) + self.frac_round.val();
        self.b_c.next = bit_cast::<WIDTH_BITS, { POS_BITS + 1 }>(self.x_up.val() >> self.frac_bits.val());
        self.ax_wide.next = bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.a_x.val());
        self.prev_c_fix.next = bit_cast::<{ POS_BITS + 1 }, WIDTH_BITS>(self.prev_c.q.val()) << self.frac_bits.val();
        // Admission, on a line's first match or its marker: a free place in
        // the queue and room in the memory for a whole line.
        self.first_event.next = self.a_valid.val() & !self.in_line.q.val();
        // (Whether the counts are at their limits is kept as registers,
        // `seg_full` and `q_full`, written beside the counts: no comparison
        // is in the path to the drop, the queue's write and its count.)
        self.fits.next = !self.seg_full.q.val() & !self.q_full.q.val();
        self.drop_now.next = self.dropping.q.val();
        if self.first_event.val() {
            self.drop_now.next = !self.fits.val();
            self.dropping.d.next = !self.fits.val();
        }
        // Stage 1: a match that starts a new pixel closes the segment from
        // the previous match.
        self.s1_seg.d.next = false;
        // (⌈X⌉ - 1 = ⌊(X - 1 LSB) / 2^POS_FRAC_BITS⌋ for X > 0, as every
        // segment's X_b is: one adder, not two.)
        self.s1_last.d.next = bit_cast::<WIDTH_BITS, POS_BITS>((self.a_x.val() - 1) >> self.frac_bits.val());
        self.s1_ax.d.next = self.prev_x.q.val();
        self.s1_ad.d.next = self.prev_d.q.val();
        self.s1_dx.d.next = self.a_x.val() - self.prev_x.q.val();
        self.s1_neg.d.next = self.a_d.val() < self.prev_d.q.val();
        self.s1_min.d.next = self.prev_d.q.val();
        self.s1_dd.d.next = self.a_d.val() - self.prev_d.q.val();
        if self.a_d.val() < self.prev_d.q.val() {
            self.s1_dd.d.next = self.prev_d.q.val() - self.a_d.val();
            self.s1_min.d.next = self.a_d.val();
        }
        if self.a_valid.val() & !self.a_last.val() {
            self.in_line.d.next = true;
            // (⌈X_b⌉ > c ⇔ X_b > c for a whole c: the match compared with
            // the previous one's pixel, not through ⌈X_b⌉'s adder.)
            self.s1_seg.d.next = self.has_prev.q.val() & (self.ax_wide.val() > self.prev_c_fix.val()) & !self.drop_now.val();
            if !self.has_prev.q.val() {
                self.first_d.d.next = self.a_d.val();
                self.first_c.d.next = self.b_c.val();
            }
            self.has_prev.d.next = true;
            self.prev_x.d.next = self.a_x.val();
            self.prev_d.d.next = self.a_d.val();
            self.prev_c.d.next = self.b_c.val();
        }
        // The marker: the line's description into the queue (shown once its
        // last segment is in the memory).
        self.q_line.write_address.next = bit_cast::<LINE_QUEUE_BITS, QUEUE_PTR_BITS>(self.q_wp.q.val());
        self.q_line_n.write_address.next = bit_cast::<LINE_QUEUE_BITS, QUEUE_PTR_BITS>(self.q_wp.q.val());
        self.sof_flag.next = 0.into();
        if self.a_sof.val() {
            self.sof_flag.next = self.flag_sof.val();
        }
        self.q_last_x_in.next = self.a_width.val() - 1;
        // Where the line's first pixel is: in the head (before the first
        // match's ⌈X⌉), in a segment, or the line's last (a line of one pixel).
        self.head0.next = self.first_c.q.val().any();
        self.seg0.next = !self.first_c.q.val().any() & self.prev_c.q.val().any();
        self.q_flags_in.next = self.sof_flag.val();
        if !self.has_prev.q.val() {
            self.q_flags_in.next = self.sof_flag.val() | self.flag_empty.val();
        }
        if self.has_prev.q.val() & self.head0.val() {
            self.q_flags_in.next = self.sof_flag.val() | self.flag_head0.val();
        }
        if self.has_prev.q.val() & self.seg0.val() {
            self.q_flags_in.next = self.sof_flag.val() | self.flag_seg0.val();
        }
        self.last0_flag.next = 0.into();
        if !self.q_last_x_in.val().any() {
            self.last0_flag.next = self.flag_last0.val();
        }
        self.q_word_in.next = bit_cast::<LINE_BITS, FLAG_BITS>(self.q_flags_in.val() | self.last0_flag.val())
            | (bit_cast::<LINE_BITS, WIDTH_BITS>(self.q_last_x_in.val()) << self.last_x_at.val())
            | (bit_cast::<LINE_BITS, WIDTH_BITS>(self.first_c.q.val()) << self.first_c_at.val())
            | (bit_cast::<LINE_BITS, WIDTH_BITS>(self.prev_c.q.val()) << self.last_c_at.val())
            | (bit_cast::<LINE_BITS, POS_BITS>(self.first_d.q.val()) << self.first_d_at.val())
            | (bit_cast::<LINE_BITS, POS_BITS>(self.prev_d.q.val()) << self.last_d_at.val());
        self.q_line.write_data.next = self.q_word_in.val();
        self.q_line_n.write_data.next = self.q_word_in.val();
        self.line_write.next = false;
        self.overflow_q.d.next = false;
        if self.a_valid.val() & self.a_last.val() {
            self.in_line.d.next = false;
            self.has_prev.d.next = false;
            self.line_write.next = !self.drop_now.val();
            self.overflow_q.d.next = self.drop_now.val();
        }
        self.q_line.write_enable.next = self.line_write.val();
        self.q_line_n.write_enable.next = self.line_write.val();
        if self.line_write.val() {
            self.q_wp.d.next = self.q_wp.q.val() + 1;
        }
        self.q_wp1.d.next = self.q_wp.q.val();
        self.q_wp2.d.next = self.q_wp1.q.val();
        self.q_wp3.d.next = self.q_wp2.q.val();
        self.q_wp4.d.next = self.q_wp3.q.val();
        self.q_wp5.d.next = self.q_wp4.q.val();
        self.overflow.next = self.overflow_q.q.val();

        // Stages 2 and 3: the distance shifted left until its top bit is
        // set, the shift counted, in four steps (by 8, 4, 2, 1), two a
        // stage; the jump flag. (Each step tests its top bits for zero, no
        // comparator, and sets its own bit of the count, no adder. Two
        // steps a stage, not four, keep the stage short.)
        self.n1.next = self.s1_dx.q.val();
        self.l1.next = 0.into();
        if !(self.s1_dx.q.val() >> self.top8.val()).any() {
            self.n1.next = self.s1_dx.q.val() << self.sh8.val();
            self.l1.next = self.lz8.val();
        }
        self.n2.next = self.n1.val();
        self.l2.next = self.l1.val();
        if !(self.n1.val() >> self.top4.val()).any() {
            self.n2.next = self.n1.val() << self.sh4.val();
            self.l2.next = self.l1.val() | self.lz4.val();
        }
        self.jump.next = self.jump_on.val() & (self.s1_dd.q.val() > self.jump_lsb.val());
        self.signed_shape.next = self.l2.val();
        if self.s1_neg.q.val() {
            self.signed_shape.next = self.l2.val() | self.neg_flag.val();
        }
        self.s2_shape.d.next = self.signed_shape.val();
        if self.jump.val() {
            self.s2_shape.d.next = self.signed_shape.val() | self.jump_flag.val();
        }
        self.s2_seg.d.next = self.s1_seg.q.val();
        self.s2_m.d.next = self.n2.val();
        self.s2_last.d.next = self.s1_last.q.val();
        self.s2_ax.d.next = self.s1_ax.q.val();
        // A jump's pixels take the smaller disparity: it is stored as the
        // segment's base instead of d_a.
        self.s2_ad.d.next = self.s1_ad.q.val();
        if self.jump.val() {
            self.s2_ad.d.next = self.s1_min.q.val();
        }
        self.s2_dd.d.next = self.s1_dd.q.val();
        // Stage 3: the last two steps, then the table's address (the bits
        // after the leading one); the reciprocal is out a clock later,
        // beside stage 3's registers.
        self.n3.next = self.s2_m.q.val();
        self.l3.next = 0.into();
        if !(self.s2_m.q.val() >> self.top2.val()).any() {
            self.n3.next = self.s2_m.q.val() << self.sh2.val();
            self.l3.next = self.lz2.val();
        }
        self.n4.next = self.n3.val();
        self.l4.next = self.l3.val();
        if !(self.n3.val() >> self.top1.val()).any() {
            self.n4.next = self.n3.val() << self.sh1.val();
            self.l4.next = self.l3.val() | self.lz1.val();
        }
        // (Through a shift and a cast, not `get_bits`: the Verilog then
        // reads all of `n4`, which Verilator's lint wants of a signal.)
        self.recip.write_enable.next = false;
        self.recip.write_address.next = 0.into();
        self.recip.write_data.next = 0.into();
        self.recip.read_address.next = bit_cast::<RECIP_INDEX_BITS, POS_BITS>(self.n4.val() >> self.index_low.val());
        self.s3_seg.d.next = self.s2_seg.q.val();
        self.s3_last.d.next = self.s2_last.q.val();
        self.s3_ax.d.next = self.s2_ax.q.val();
        self.s3_ad.d.next = self.s2_ad.q.val();
        self.s3_dd.d.next = self.s2_dd.q.val();
        self.s3_shape.d.next = self.s2_shape.q.val() | self.l4.val();
        // Stage 4: the segment, and beside it the reciprocal out of the
        // table's output register.
        self.s4_seg.d.next = self.s3_seg.q.val();
        self.s4_last.d.next = self.s3_last.q.val();
        self.s4_ax.d.next = self.s3_ax.q.val();
        self.s4_ad.d.next = self.s3_ad.q.val();
        self.s4_dd.d.next = self.s3_dd.q.val();
        self.s4_shape.d.next = self.s3_shape.q.val();
        // The segment into the memory.
        self.seg_last.write_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.seg_wp.q.val());
        self.seg_ax.write_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.seg_wp.q.val());
        self.seg_ad.write_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.seg_wp.q.val());
        self.seg_dd.write_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.seg_wp.q.val());
        self.seg_shape.write_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.seg_wp.q.val());
        self.seg_recip.write_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.seg_wp.q.val());
        self.seg_last.write_data.next = self.s4_last.q.val();
        self.seg_ax.write_data.next = self.s4_ax.q.val();
        self.seg_ad.write_data.next = self.s4_ad.q.val();
        self.seg_dd.write_data.next = self.s4_dd.q.val();
        self.seg_shape.write_data.next = self.s4_shape.q.val();
        self.seg_recip.write_data.next = self.recip.read_data.val();
        self.seg_last.write_enable.next = self.s4_seg.q.val();
        self.seg_ax.write_enable.next = self.s4_seg.q.val();
        self.seg_ad.write_enable.next = self.s4_seg.q.val();
        self.seg_dd.write_enable.next = self.s4_seg.q.val();
        self.seg_shape.write_enable.next = self.s4_seg.q.val();
        self.seg_recip.write_enable.next = self.s4_seg.q.val();
        if self.s4_seg.q.val() {
            self.seg_wp.d.next = self.seg_wp.q.val() + 1;
        }

        // ================= Pixels =================
        // The queue's and the memory's outputs show the entries at the read
        // pointers (the segments are in the prefetch ring). The queue's
        // entry at the read pointer: its word is read a clock ago at the
        // pointer and at its successor, and after a line done (the pointer
        // moved on) the successor's read is the one shown.
        self.q_word_out.next = self.q_line.read_data.val();
        if self.q_next_q.q.val() {
            self.q_word_out.next = self.q_line_n.read_data.val();
        }
        self.q_sof_out.next = self.q_word_out.val().get_bit(self.bit0.val().index());
        self.q_first_d_out.next = bit_cast::<POS_BITS, LINE_BITS>(self.q_word_out.val() >> self.first_d_at.val());
        self.q_last_d_out.next = bit_cast::<POS_BITS, LINE_BITS>(self.q_word_out.val() >> self.last_d_at.val());
        // (No line: as an empty one. The memories' output registers start
        // undefined in Verilog; nothing reads them before a line is shown.)
        self.empty_line.next = !self.line_ready.q.val() | self.q_word_out.val().get_bit(self.empty_at.val().index());
        // Where the pixel is, from registers only: on a line's first clock
        // (`x == 0`) the flags its description brought, after it the
        // comparisons made a clock ago against `x + 1`: no carry chain
        // between the pixel count and the engine's control (the pixel's
        // comparisons with the queue's columns are not in one clock with
        // `seg_done` and the ring's `fill`).
        self.in_head_now.next = self.head_next.q.val();
        self.in_seg_now.next = self.seg_next.q.val();
        self.at_last_x.next = self.last_next.q.val();
        if self.x_zero.q.val() {
            self.in_head_now.next = self.q_word_out.val().get_bit(self.head0_at.val().index());
            self.in_seg_now.next = self.q_word_out.val().get_bit(self.seg0_at.val().index());
            self.at_last_x.next = self.q_word_out.val().get_bit(self.last0_at.val().index());
        }
        self.in_head.next = self.line_ready.q.val() & self.in_head_now.val();
        self.in_seg.next = self.line_ready.q.val() & self.in_seg_now.val();
        // The engine's segment, out of the ring.
        self.at_cur_last.next = self.at_e0.q.val();
        self.cur_ax.next = self.e0_ax.q.val();
        self.cur_ad.next = self.e0_ad.q.val();
        self.cur_dd.next = self.e0_dd.q.val();
        self.cur_shape.next = self.e0_shape.q.val();
        self.cur_recip.next = self.e0_recip.q.val();
        if self.ri.q.val() == self.slot1.val() {
            self.at_cur_last.next = self.at_e1.q.val();
            self.cur_ax.next = self.e1_ax.q.val();
            self.cur_ad.next = self.e1_ad.q.val();
            self.cur_dd.next = self.e1_dd.q.val();
            self.cur_shape.next = self.e1_shape.q.val();
            self.cur_recip.next = self.e1_recip.q.val();
        }
        if self.ri.q.val() == self.slot2.val() {
            self.at_cur_last.next = self.at_e2.q.val();
            self.cur_ax.next = self.e2_ax.q.val();
            self.cur_ad.next = self.e2_ad.q.val();
            self.cur_dd.next = self.e2_dd.q.val();
            self.cur_shape.next = self.e2_shape.q.val();
            self.cur_recip.next = self.e2_recip.q.val();
        }
        if self.ri.q.val() == self.slot3.val() {
            self.at_cur_last.next = self.at_e3.q.val();
            self.cur_ax.next = self.e3_ax.q.val();
            self.cur_ad.next = self.e3_ad.q.val();
            self.cur_dd.next = self.e3_dd.q.val();
            self.cur_shape.next = self.e3_shape.q.val();
            self.cur_recip.next = self.e3_recip.q.val();
        }
        self.line_done.next = self.line_ready.q.val() & self.at_last_x.val();
        self.seg_done.next = self.in_seg.val() & self.at_cur_last.val();
        // The pixel steps on inside a line; after its last, and while no
        // line is shown (then `x` is 0), it is 0 on the next clock.
        self.step.next = self.line_ready.q.val() & !self.line_done.val();
        self.x.d.next = 0.into();
        self.x1.d.next = 1.into();
        if self.step.val() {
            self.x.d.next = self.x1.q.val();
            self.x1.d.next = self.x1.q.val() + 1;
        }
        self.x_zero.d.next = !self.step.val();
        // The next clock's place in the same line: `x + 1` compared with
        // both queue reads' columns, the shown read's results picked after
        // (used only if the line goes on, so that its description is the
        // one shown now).
        self.first_c_cur.next = bit_cast::<WIDTH_BITS, LINE_BITS>(self.q_line.read_data.val() >> self.first_c_at.val());
        self.first_c_succ.next = bit_cast::<WIDTH_BITS, LINE_BITS>(self.q_line_n.read_data.val() >> self.first_c_at.val());
        self.last_c_cur.next = bit_cast::<WIDTH_BITS, LINE_BITS>(self.q_line.read_data.val() >> self.last_c_at.val());
        self.last_c_succ.next = bit_cast::<WIDTH_BITS, LINE_BITS>(self.q_line_n.read_data.val() >> self.last_c_at.val());
        self.q_last_x_cur.next = bit_cast::<WIDTH_BITS, LINE_BITS>(self.q_line.read_data.val() >> self.last_x_at.val());
        self.q_last_x_succ.next = bit_cast::<WIDTH_BITS, LINE_BITS>(self.q_line_n.read_data.val() >> self.last_x_at.val());
        self.empty_cur.next = self.q_line.read_data.val().get_bit(self.empty_at.val().index());
        self.empty_succ.next = self.q_line_n.read_data.val().get_bit(self.empty_at.val().index());
        self.head_cur.next = !self.empty_cur.val() & (self.x1.q.val() < self.first_c_cur.val());
        self.head_succ.next = !self.empty_succ.val() & (self.x1.q.val() < self.first_c_succ.val());
        self.seg_cur.next = !self.empty_cur.val() & !(self.x1.q.val() < self.first_c_cur.val()) & (self.x1.q.val() < self.last_c_cur.val());
        self.seg_succ.next = !self.empty_succ.val() & !(self.x1.q.val() < self.first_c_succ.val()) & (self.x1.q.val() < self.last_c_succ.val());
        self.head_next.d.next = self.head_cur.val();
        self.seg_next.d.next = self.seg_cur.val();
        self.last_next.d.next = self.x1.q.val() == self.q_last_x_cur.val();
        if self.q_next_q.q.val() {
            self.head_next.d.next = self.head_succ.val();
            self.seg_next.d.next = self.seg_succ.val();
            self.last_next.d.next = self.x1.q.val() == self.q_last_x_succ.val();
        }
        // The next clock's pixel (`x + 1` or 0) against each ring slot's
        // last pixel, and against the prefetch's data for the slot it writes
        // (below, with the slot's fields); the engine's slot is picked by
        // `ri` after the registers.
        self.at_read.next = !self.seg_last.read_data.val().any();
        self.at_e0.d.next = !self.e0_last.q.val().any();
        self.at_e1.d.next = !self.e1_last.q.val().any();
        self.at_e2.d.next = !self.e2_last.q.val().any();
        self.at_e3.d.next = !self.e3_last.q.val().any();
        if self.step.val() {
            self.at_read.next = self.x1.q.val() == self.seg_last.read_data.val();
            self.at_e0.d.next = self.x1.q.val() == self.e0_last.q.val();
            self.at_e1.d.next = self.x1.q.val() == self.e1_last.q.val();
            self.at_e2.d.next = self.x1.q.val() == self.e2_last.q.val();
            self.at_e3.d.next = self.x1.q.val() == self.e3_last.q.val();
        }
        // (The pointers' successors are registers of their own: no adder
        // between the pixel's comparisons and the memories' addresses.)
        self.q_rp_next.next = self.q_rp.q.val();
        if self.line_done.val() {
            self.q_rp_next.next = self.q_rp1.q.val();
        }
        self.q_rp.d.next = self.q_rp_next.val();
        // (A line is shown on the next clock if the queue's write pointer
        // five clocks ago differs from the read pointer's next value: both
        // comparisons from registers, picked by the line's end.)
        self.line_ready.d.next = self.q_wp5.q.val() != self.q_rp.q.val();
        if self.line_done.val() {
            self.line_ready.d.next = self.q_wp5.q.val() != self.q_rp1.q.val();
        }
        // (Both successors from registers, one picked after the line's end.)
        self.q_rp1.d.next = self.q_rp.q.val() + 1;
        if self.line_done.val() {
            self.q_rp1.d.next = self.q_rp1.q.val() + 1;
        }
        self.q_line.read_address.next = bit_cast::<LINE_QUEUE_BITS, QUEUE_PTR_BITS>(self.q_rp.q.val());
        self.q_line_n.read_address.next = bit_cast::<LINE_QUEUE_BITS, QUEUE_PTR_BITS>(self.q_rp1.q.val());
        self.q_next_q.d.next = self.line_done.val();
        // The prefetch: a read whenever the memory holds an unread segment
        // and the registers will have room for it (counting the two reads
        // on their way, not this clock's pop: four registers let one pop
        // and one read per clock go on); its data are pushed behind what
        // the registers keep after this clock's pop.
        // (`fill + rd1 + rd2 < PREFETCH` as `fill` against the bound less
        // the reads on their way, picked by them: no adders in series
        // before the comparison, whose `issue` enables the read pointer and
        // picks `seg_used`'s next value.)
        self.room.next = self.fill.q.val() < self.prefetch.val();
        if self.rd1.q.val() ^ self.rd2.q.val() {
            self.room.next = self.fill.q.val() < self.prefetch_m1.val();
        }
        if self.rd1.q.val() & self.rd2.q.val() {
            self.room.next = self.fill.q.val() < self.prefetch_m2.val();
        }
        self.issue.next = self.seg_any.q.val() & self.room.val();
        if self.issue.val() {
            self.rd_ptr.d.next = self.rd_ptr.q.val() + 1;
        }
        self.rd1.d.next = self.issue.val();
        self.rd2.d.next = self.rd1.q.val();
        self.seg_last.read_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.rd_ptr.q.val());
        self.seg_ax.read_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.rd_ptr.q.val());
        self.seg_ad.read_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.rd_ptr.q.val());
        self.seg_dd.read_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.rd_ptr.q.val());
        self.seg_shape.read_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.rd_ptr.q.val());
        self.seg_recip.read_address.next = bit_cast::<SEG_ADDR_BITS, SEG_PTR_BITS>(self.rd_ptr.q.val());
        // The full flags of the counts' next values, from comparisons of
        // the counts now with the limit and its neighbours, picked by the
        // change (`c ± 1 > L` ⇔ `c > L ∓ 1`): the same decision as the
        // next count's comparison, with no adder before it.
        self.seg_full.d.next = self.seg_used.q.val() > self.seg_limit.val();
        if self.s4_seg.q.val() & !self.issue.val() {
            self.seg_used.d.next = self.seg_used.q.val() + 1;
            self.seg_full.d.next = self.seg_used.q.val() >= self.seg_limit.val();
            self.seg_any.d.next = true;
        }
        if !self.s4_seg.q.val() & self.issue.val() {
            self.seg_used.d.next = self.seg_used.q.val() - 1;
            self.seg_full.d.next = self.seg_used.q.val() > self.seg_limit_up.val();
            self.seg_any.d.next = self.seg_used.q.val() != self.seg_one.val();
        }
        self.q_full.d.next = self.q_used.q.val() >= self.queue_size.val();
        if self.line_write.val() & !self.line_done.val() {
            self.q_used.d.next = self.q_used.q.val() + 1;
            self.q_full.d.next = self.q_used.q.val() >= self.queue_last.val();
        }
        if !self.line_write.val() & self.line_done.val() {
            self.q_used.d.next = self.q_used.q.val() - 1;
            self.q_full.d.next = self.q_used.q.val() > self.queue_size.val();
        }
        // The ring: data pushed at `wi`, the engine's segment at `ri`
        // (registers with enables: no multiplexer on the write side).
        self.pop.next = self.seg_done.val();
        // (fill ± 1 from the register, picked by the pop and the push: no
        // adder after the segment's end.)
        self.kept.next = self.fill.q.val();
        if self.pop.val() & !self.rd2.q.val() {
            self.kept.next = self.fill.q.val() - 1;
        }
        if !self.pop.val() & self.rd2.q.val() {
            self.kept.next = self.fill.q.val() + 1;
        }
        if self.pop.val() {
            self.ri.d.next = self.ri.q.val() + 1;
        }
        self.fill.d.next = self.kept.val();
        if self.rd2.q.val() {
            self.wi.d.next = self.wi.q.val() + 1;
            if !self.wi.q.val().any() {
                self.e0_last.d.next = self.seg_last.read_data.val();
                self.e0_ax.d.next = self.seg_ax.read_data.val();
                self.e0_ad.d.next = self.seg_ad.read_data.val();
                self.e0_dd.d.next = self.seg_dd.read_data.val();
                self.e0_shape.d.next = self.seg_shape.read_data.val();
                self.e0_recip.d.next = self.seg_recip.read_data.val();
                self.at_e0.d.next = self.at_read.val();
            }
            if self.wi.q.val() == self.slot1.val() {
                self.e1_last.d.next = self.seg_last.read_data.val();
                self.e1_ax.d.next = self.seg_ax.read_data.val();
                self.e1_ad.d.next = self.seg_ad.read_data.val();
                self.e1_dd.d.next = self.seg_dd.read_data.val();
                self.e1_shape.d.next = self.seg_shape.read_data.val();
                self.e1_recip.d.next = self.seg_recip.read_data.val();
                self.at_e1.d.next = self.at_read.val();
            }
            if self.wi.q.val() == self.slot2.val() {
                self.e2_last.d.next = self.seg_last.read_data.val();
                self.e2_ax.d.next = self.seg_ax.read_data.val();
                self.e2_ad.d.next = self.seg_ad.read_data.val();
                self.e2_dd.d.next = self.seg_dd.read_data.val();
                self.e2_shape.d.next = self.seg_shape.read_data.val();
                self.e2_recip.d.next = self.seg_recip.read_data.val();
                self.at_e2.d.next = self.at_read.val();
            }
            if self.wi.q.val() == self.slot3.val() {
                self.e3_last.d.next = self.seg_last.read_data.val();
                self.e3_ax.d.next = self.seg_ax.read_data.val();
                self.e3_ad.d.next = self.seg_ad.read_data.val();
                self.e3_dd.d.next = self.seg_dd.read_data.val();
                self.e3_shape.d.next = self.seg_shape.read_data.val();
                self.e3_recip.d.next = self.seg_recip.read_data.val();
                self.at_e3.d.next = self.at_read.val();
            }
        }
        self.p0_valid.d.next = self.line_ready.q.val();
        self.p0_last.d.next = self.line_done.val();
        self.p0_sof.d.next = self.line_ready.q.val() & self.q_sof_out.val() & self.x_zero.q.val();
        self.p0_empty.d.next = self.line_ready.q.val() & self.empty_line.val();
        self.p0_base.d.next = 0.into();
        if !self.empty_line.val() {
            self.p0_base.d.next = self.q_last_d_out.val();
        }
        if self.in_head.val() {
            self.p0_base.d.next = self.q_first_d_out.val();
        }
        if self.in_seg.val() {
            self.p0_base.d.next = self.cur_ad.val();
        }
        self.p0_ramp.d.next = self.in_seg.val() & !self.cur_shape.val().get_bit(self.jump_bit.val().index());
        self.p0_neg.d.next = self.cur_shape.val().get_bit(self.neg_bit.val().index());
        self.x16.next = bit_cast::<POS_BITS, WIDTH_BITS>(self.x.q.val()) << self.frac_bits.val();
        self.p0_u.d.next = self.x16.val() - self.cur_ax.val();
        self.p0_lz.d.next = self.cur_shape.val().get_bits::<LZ_BITS>(self.bit0.val().index());
        self.p0_recip.d.next = self.cur_recip.val();
        self.p0_dd.d.next = self.cur_dd.val();
        // P1: the distance normalised as the segment's length was.
        self.p1_valid.d.next = self.p0_valid.q.val();
        self.p1_last.d.next = self.p0_last.q.val();
        self.p1_sof.d.next = self.p0_sof.q.val();
        self.p1_empty.d.next = self.p0_empty.q.val();
        self.p1_ramp.d.next = self.p0_ramp.q.val();
        self.p1_neg.d.next = self.p0_neg.q.val();
        self.p1_base.d.next = self.p0_base.q.val();
        // P1's v and recip: the input registers of `mul_v`.
        self.v_in.next = bit_cast::<MUL_OPERAND_BITS, POS_BITS>(self.p0_u.q.val()) << self.p0_lz.q.val();
        self.mul_v.clock.next = self.clock.val();
        self.mul_v.a.next = self.v_in.val();
        self.mul_v.b.next = self.p0_recip.q.val();
        self.p1_dd.d.next = self.p0_dd.q.val();
        // P2: v · recip (a DSP block; the product registered).
        self.p2_valid.d.next = self.p1_valid.q.val();
        self.p2_last.d.next = self.p1_last.q.val();
        self.p2_sof.d.next = self.p1_sof.q.val();
        self.p2_empty.d.next = self.p1_empty.q.val();
        self.p2_ramp.d.next = self.p1_ramp.q.val();
        self.p2_neg.d.next = self.p1_neg.q.val();
        self.p2_base.d.next = self.p1_base.q.val();
        self.p2_prod.d.next = self.mul_v.p.val();
        self.p2_dd.d.next = self.p1_dd.q.val();
        // P3: the weight t = v · recip / 2^(POS_BITS - 1), below 1.
        self.p3_valid.d.next = self.p2_valid.q.val();
        self.p3_last.d.next = self.p2_last.q.val();
        self.p3_sof.d.next = self.p2_sof.q.val();
        self.p3_empty.d.next = self.p2_empty.q.val();
        self.p3_ramp.d.next = self.p2_ramp.q.val();
        self.p3_neg.d.next = self.p2_neg.q.val();
        self.p3_base.d.next = self.p2_base.q.val();
        // P3's t and |Δd|: the input registers of `mul_t`.
        self.t_in.next = bit_cast::<MUL_OPERAND_BITS, 32>(self.p2_prod.q.val() >> self.t_shift.val());
        if (self.p2_prod.q.val() >> self.t_over.val()).any() {
            self.t_in.next = self.t_max.val();
        }
        self.mul_t.clock.next = self.clock.val();
        self.mul_t.a.next = self.t_in.val();
        self.mul_t.b.next = bit_cast::<MUL_OPERAND_BITS, POS_BITS>(self.p2_dd.q.val());
        // P4: t · |Δd| (a DSP block; the product registered).
        self.p4_valid.d.next = self.p3_valid.q.val();
        self.p4_last.d.next = self.p3_last.q.val();
        self.p4_sof.d.next = self.p3_sof.q.val();
        self.p4_empty.d.next = self.p3_empty.q.val();
        self.p4_ramp.d.next = self.p3_ramp.q.val();
        self.p4_neg.d.next = self.p3_neg.q.val();
        self.p4_base.d.next = self.p3_base.q.val();
        self.p4_prod.d.next = self.mul_t.p.val();
        // P5: the step, rounded.
        self.p5_valid.d.next = self.p4_valid.q.val();
        self.p5_last.d.next = self.p4_last.q.val();
        self.p5_sof.d.next = self.p4_sof.q.val();
        self.p5_empty.d.next = self.p4_empty.q.val();
        self.p5_ramp.d.next = self.p4_ramp.q.val();
        self.p5_neg.d.next = self.p4_neg.q.val();
        self.p5_base.d.next = self.p4_base.q.val();
        self.rounded.next = self.p4_prod.q.val() + self.half.val();
        self.p5_delta.d.next = bit_cast::<POS_BITS, 32>(self.rounded.val() >> self.w_shift.val());
        // The pixel.
        self.o_d.d.next = self.p5_base.q.val();
        if self.p5_ramp.q.val() {
            self.o_d.d.next = self.p5_base.q.val() + self.p5_delta.q.val();
            if self.p5_neg.q.val() {
                self.o_d.d.next = self.p5_base.q.val() - self.p5_delta.q.val();
            }
        }
        self.o_valid.d.next = self.p5_valid.q.val();
        self.o_last.d.next = self.p5_last.q.val();
        self.o_sof.d.next = self.p5_sof.q.val();
        self.o_empty.d.next = self.p5_empty.q.val();
        self.p_valid.next = self.o_valid.q.val();
        self.p_d.next = self.o_d.q.val();
        self.p_last.next = self.o_last.q.val();
        self.p_sof.next = self.o_sof.q.val();
        self.p_empty.next = self.o_empty.q.val();
    }
}
