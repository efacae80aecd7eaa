//! The extraction pass of the declivity detector (paper §II, `DESIGN.md`
//! §2.1): tracks the extrema of a line at one pixel per clock, accumulates
//! the two sums of eq. 3, reads the attributes and keeps the characteristic
//! declivities (`|a_i| > d_t`), at most [`N_MAX`] per line.
//!
//! Declivities follow golden's rules exactly (golden `declivity` module doc):
//! a declivity starts at each non-zero gradient `g(x) = I(x+1) - I(x)` whose
//! sign differs from the last non-zero one, and ends one pixel after its own
//! last non-zero gradient (the tight plateau rule).
//!
//! ## Ports
//! - In: a pixel stream `in_valid`, `in_first`, `in_last`, `in_pix`, `in_x`
//!   (the pixel's index in its line) with the line's `in_dt` (`d_t` in fixed
//!   point), `in_thr` (`⌊d_t⌋`), `in_wide` (line cut at `W_MAX`) and
//!   `in_sof` (first line of a frame). A line's pixels must come on
//!   consecutive clocks; lines may be back to back or apart. They pass
//!   through a [`PixelWindow`].
//! - Out: items for the eq. 3 divider ([`crate::detector::position_divider`]):
//!   `item_valid`, `item_dividend` (`Σ g²(2x+1) · 2^(POS_FRAC_BITS-1)`),
//!   `item_divisor` (`Σ g²`) and four tag lanes laid out as [`TagLayout`]
//!   says: a declivity record (start, end, amplitude, the 3+3 neighbour grey
//!   levels, `d_t`) or, after the line's last record, the line's marker
//!   (count, `d_t`, flags, and in the end field the line's last pixel: its
//!   stored width − 1).
//!
//! ## Timing
//! A pixel reaches the centre of a 7-pixel window [`TRACKER_CENTER`] + 1
//! clocks after it enters (the window gives the two pixels after it for the
//! right-hand levels, and two pipeline stages for `g²` and `g²(2x+1)`); a
//! declivity's record leaves one clock after its closing pixel is at the
//! centre, the line's marker one clock after the line's last record slot.
//! At most one item per clock: a declivity closes on a gradient, the last
//! one at the line's last pixel, and the marker takes the next clock, which
//! is a bubble or a line's first pixel (where nothing closes).
//!
//! ## Overflow
//! The (N_MAX + 1)-th and later characteristic declivities of a line are
//! dropped and the marker's `full` flag is set; the line's other records and
//! the stream stay aligned.
//!
//! ## Reset
//! The registers start from their Verilog initial values (zero), as between
//! two lines; `reset` (synchronous, active high) returns them there.

use crate::params::*;
use crate::primitives::dsp_multiplier::{DspMultiplier, MUL_OPERAND_BITS, MUL_PRODUCT_BITS};
use crate::detector::pixel_window::PixelWindow;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// The window tap where a pixel's gradient is examined.
pub(crate) const TRACKER_CENTER: usize = crate::detector::pixel_window::WINDOW_CENTER;
/// Bits of a grey level plus the integer threshold (no overflow).
const CMP_BITS: usize = DT_INT_BITS + 1;

/// Where each field sits in the four 32-bit tag lanes of an item.
pub(crate) struct TagLayout;

impl TagLayout {
    /// Lane 0: `start | end << X_BITS | amplitude << 2·X_BITS`, and the
    /// marker flag above them; a marker's `end` is its line's last pixel.
    pub(crate) const END_SHIFT: usize = X_BITS;
    pub(crate) const AMP_SHIFT: usize = 2 * X_BITS;
    pub(crate) const MARKER_SHIFT: usize = 2 * X_BITS + AMP_BITS;
    /// Lane 1: `I(x_i) | I(x_i - 1) << 8 | I(x_i - 2) << 16` for a record;
    /// the count for a marker. Lane 2: the right levels in the same layout
    /// for a record; for a marker `wide | full << 1 | sof << 2`.
    pub(crate) const LEVEL_SHIFT: usize = PIXEL_BITS;
    /// Lane 3: `d_t`.
    pub(crate) const DT_LANE: usize = 3;
}

#[derive(LogicBlock)]
pub(crate) struct DeclivityTracker {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_first: Signal<In, Bit>,
    pub in_last: Signal<In, Bit>,
    pub in_pix: Signal<In, Bits<PIXEL_BITS>>,
    pub in_x: Signal<In, Bits<X_BITS>>,
    pub in_dt: Signal<In, Bits<DT_BITS>>,
    /// `⌊d_t⌋`, the line's integer threshold.
    pub in_thr: Signal<In, Bits<DT_INT_BITS>>,
    pub in_wide: Signal<In, Bit>,
    pub in_sof: Signal<In, Bit>,
    pub item_valid: Signal<Out, Bit>,
    pub item_dividend: Signal<Out, Bits<DIVIDEND_BITS>>,
    pub item_divisor: Signal<Out, Bits<S0_BITS>>,
    pub item_tag0: Signal<Out, Bits<32>>,
    pub item_tag1: Signal<Out, Bits<32>>,
    pub item_tag2: Signal<Out, Bits<32>>,
    pub item_tag3: Signal<Out, Bits<32>>,
    // The window on the pixel stream.
    window: PixelWindow,
    // g² and g²·(2x + 1) in DSP blocks, each fed a clock ahead of the
    // register it replaces (`DspMultiplier`: its input registers).
    square: DspMultiplier,
    weight: DspMultiplier,
    // Gradient pipeline: g at taps 2–4, g² at taps 3–4, g²(2x+1) at tap 4.
    g2: ResetDff<Bits<AMP_BITS>>,
    g3: ResetDff<Bits<AMP_BITS>>,
    g4: ResetDff<Bits<AMP_BITS>>,
    gsq3: ResetDff<Bits<S0_BITS>>,
    gsq4: ResetDff<Bits<S0_BITS>>,
    w4: ResetDff<Bits<S1_BITS>>,
    // Registered one clock ahead of the centre: the sign tests of g(x) and
    // the amplitude test |I(x) - I(x_i)| > ⌊d_t⌋ of a declivity closing at x.
    nz4: ResetDff<Bit>,
    up4: ResetDff<Bit>,
    char4: ResetDff<Bit>,
    /// `I + ⌊d_t⌋` of the pixels at taps 3 and 4, and of the declivity's
    /// start level.
    at_thr3: ResetDff<Bits<CMP_BITS>>,
    at_thr4: ResetDff<Bits<CMP_BITS>>,
    run_thr: ResetDff<Bits<CMP_BITS>>,
    // The declivity under way.
    seen: ResetDff<Bit>,
    rising: ResetDff<Bit>,
    start: ResetDff<Bits<X_BITS>>,
    start_level: ResetDff<Bits<PIXEL_BITS>>,
    left0: ResetDff<Bits<PIXEL_BITS>>,
    left1: ResetDff<Bits<PIXEL_BITS>>,
    left2: ResetDff<Bits<PIXEL_BITS>>,
    s0: ResetDff<Bits<S0_BITS>>,
    s1: ResetDff<Bits<S1_BITS>>,
    /// `x_{i+1}`: one past the last non-zero gradient so far.
    end_reg: ResetDff<Bits<X_BITS>>,
    /// The gradients at x - 1 and x - 2 updated `end_reg` (so `x_{i+1}` is
    /// x or x - 1).
    upd1: ResetDff<Bit>,
    upd2: ResetDff<Bit>,
    // The line.
    count: ResetDff<Bits<COUNT_BITS>>,
    full: ResetDff<Bit>,
    mk_pending: ResetDff<Bit>,
    mk_count: ResetDff<Bits<COUNT_BITS>>,
    mk_full: ResetDff<Bit>,
    mk_wide: ResetDff<Bit>,
    mk_sof: ResetDff<Bit>,
    mk_dt: ResetDff<Bits<DT_BITS>>,
    /// The line's last pixel (its stored width − 1), for the marker.
    mk_end: ResetDff<Bits<X_BITS>>,
    // The item register.
    o_valid: ResetDff<Bit>,
    o_dividend: ResetDff<Bits<DIVIDEND_BITS>>,
    o_divisor: ResetDff<Bits<S0_BITS>>,
    o_tag0: ResetDff<Bits<32>>,
    o_tag1: ResetDff<Bits<32>>,
    o_tag2: ResetDff<Bits<32>>,
    o_tag3: ResetDff<Bits<32>>,
    // Combinational values of the centre.
    gabs: Signal<Local, Bits<MUL_OPERAND_BITS>>,
    odd_x: Signal<Local, Bits<MUL_OPERAND_BITS>>,
    seen_eff: Signal<Local, Bit>,
    count_eff: Signal<Local, Bits<COUNT_BITS>>,
    count_eff1: Signal<Local, Bits<COUNT_BITS>>,
    count_next: Signal<Local, Bits<COUNT_BITS>>,
    full_eff: Signal<Local, Bit>,
    x_next: Signal<Local, Bits<X_BITS>>,
    lvl_a: Signal<Local, Bits<CMP_BITS>>,
    lvl_run: Signal<Local, Bits<CMP_BITS>>,
    lvl_new: Signal<Local, Bits<CMP_BITS>>,
    thr: Signal<Local, Bits<CMP_BITS>>,
    amp: Signal<Local, Bits<AMP_BITS>>,
    close_run: Signal<Local, Bit>,
    close_line: Signal<Local, Bit>,
    keep: Signal<Local, Bit>,
    drop: Signal<Local, Bit>,
    start_new: Signal<Local, Bit>,
    extend: Signal<Local, Bit>,
    p1: Signal<Local, Bits<PIXEL_BITS>>,
    p2: Signal<Local, Bits<PIXEL_BITS>>,
    pm1: Signal<Local, Bits<PIXEL_BITS>>,
    pm2: Signal<Local, Bits<PIXEL_BITS>>,
    right1: Signal<Local, Bits<PIXEL_BITS>>,
    right2: Signal<Local, Bits<PIXEL_BITS>>,
    // Constants.
    n_max: Constant<Bits<COUNT_BITS>>,
    sign_bit: Constant<Bits<AMP_BITS>>,
    dividend_shift: Constant<Bits<8>>,
    end_shift: Constant<Bits<8>>,
    amp_shift: Constant<Bits<8>>,
    marker_shift: Constant<Bits<8>>,
    level_shift: Constant<Bits<8>>,
}

impl Default for DeclivityTracker {
    fn default() -> Self {
        let c8 = |v: usize| Constant::new((v as u64).into());
        Self {
            clock: Default::default(),
            reset: Default::default(),
            in_valid: Default::default(),
            in_first: Default::default(),
            in_last: Default::default(),
            in_pix: Default::default(),
            in_x: Default::default(),
            in_dt: Default::default(),
            in_thr: Default::default(),
            in_wide: Default::default(),
            in_sof: Default::default(),
            item_valid: Default::default(),
            item_dividend: Default::default(),
            item_divisor: Default::default(),
            item_tag0: Default::default(),
            item_tag1: Default::default(),
            item_tag2: Default::default(),
            item_tag3: Default::default(),
            window: Default::default(),
            square: Default::default(),
            weight: Default::default(),
            g2: Default::default(),
            g3: Default::default(),
            g4: Default::default(),
            gsq3: Default::default(),
            gsq4: Default::default(),
            w4: Default::default(),
            nz4: Default::default(),
            up4: Default::default(),
            char4: Default::default(),
            at_thr3: Default::default(),
            at_thr4: Default::default(),
            run_thr: Default::default(),
            seen: Default::default(),
            rising: Default::default(),
            start: Default::default(),
            start_level: Default::default(),
            left0: Default::default(),
            left1: Default::default(),
            left2: Default::default(),
            s0: Default::default(),
            s1: Default::default(),
            end_reg: Default::default(),
            upd1: Default::default(),
            upd2: Default::default(),
            count: Default::default(),
            full: Default::default(),
            mk_pending: Default::default(),
            mk_count: Default::default(),
            mk_full: Default::default(),
            mk_wide: Default::default(),
            mk_sof: Default::default(),
            mk_dt: Default::default(),
            mk_end: Default::default(),
            o_valid: Default::default(),
            o_dividend: Default::default(),
            o_divisor: Default::default(),
            o_tag0: Default::default(),
            o_tag1: Default::default(),
            o_tag2: Default::default(),
            o_tag3: Default::default(),
            gabs: Default::default(),
            odd_x: Default::default(),
            seen_eff: Default::default(),
            count_eff: Default::default(),
            count_eff1: Default::default(),
            count_next: Default::default(),
            full_eff: Default::default(),
            x_next: Default::default(),
            lvl_a: Default::default(),
            lvl_run: Default::default(),
            lvl_new: Default::default(),
            thr: Default::default(),
            amp: Default::default(),
            close_run: Default::default(),
            close_line: Default::default(),
            keep: Default::default(),
            drop: Default::default(),
            start_new: Default::default(),
            extend: Default::default(),
            p1: Default::default(),
            p2: Default::default(),
            pm1: Default::default(),
            pm2: Default::default(),
            right1: Default::default(),
            right2: Default::default(),
            n_max: Constant::new((N_MAX as u64).into()),
            sign_bit: Constant::new((1u64 << PIXEL_BITS).into()),
            dividend_shift: c8(POS_FRAC_BITS - 1),
            end_shift: c8(TagLayout::END_SHIFT),
            amp_shift: c8(TagLayout::AMP_SHIFT),
            marker_shift: c8(TagLayout::MARKER_SHIFT),
            level_shift: c8(TagLayout::LEVEL_SHIFT),
        }
    }
}

impl Logic for DeclivityTracker {
    #[hdl_gen]
    fn update(&mut self) {
        self.window.clock.next = self.clock.val();
        self.window.reset.next = self.reset.val();
        dff_setup!(
            self, clock, g2, g3, g4, gsq3, gsq4, w4, nz4, up4, char4, at_thr3, at_thr4, run_thr, seen, rising, start, start_level, left0, left1, left2, s0, s1,
            end_reg, upd1, upd2, count, full, mk_pending, mk_count, mk_full, mk_wide, mk_sof, mk_dt, mk_end, o_valid, o_dividend,
            o_divisor, o_tag0, o_tag1, o_tag2, o_tag3
        );
        self.g2.reset.next = self.reset.val();
        self.g3.reset.next = self.reset.val();
        self.g4.reset.next = self.reset.val();
        self.gsq3.reset.next = self.reset.val();
        self.gsq4.reset.next = self.reset.val();
        self.w4.reset.next = self.reset.val();
        self.nz4.reset.next = self.reset.val();
        self.up4.reset.next = self.reset.val();
        self.char4.reset.next = self.reset.val();
        self.at_thr3.reset.next = self.reset.val();
        self.at_thr4.reset.next = self.reset.val();
        self.run_thr.reset.next = self.reset.val();
        self.seen.reset.next = self.reset.val();
        self.rising.reset.next = self.reset.val();
        self.start.reset.next = self.reset.val();
        self.start_level.reset.next = self.reset.val();
        self.left0.reset.next = self.reset.val();
        self.left1.reset.next = self.reset.val();
        self.left2.reset.next = self.reset.val();
        self.s0.reset.next = self.reset.val();
        self.s1.reset.next = self.reset.val();
        self.end_reg.reset.next = self.reset.val();
        self.upd1.reset.next = self.reset.val();
        self.upd2.reset.next = self.reset.val();
        self.count.reset.next = self.reset.val();
        self.full.reset.next = self.reset.val();
        self.mk_pending.reset.next = self.reset.val();
        self.mk_count.reset.next = self.reset.val();
        self.mk_full.reset.next = self.reset.val();
        self.mk_wide.reset.next = self.reset.val();
        self.mk_sof.reset.next = self.reset.val();
        self.mk_dt.reset.next = self.reset.val();
        self.mk_end.reset.next = self.reset.val();
        self.o_valid.reset.next = self.reset.val();
        self.o_dividend.reset.next = self.reset.val();
        self.o_divisor.reset.next = self.reset.val();
        self.o_tag0.reset.next = self.reset.val();
        self.o_tag1.reset.next = self.reset.val();
        self.o_tag2.reset.next = self.reset.val();
        self.o_tag3.reset.next = self.reset.val();
        // ---- The window shifts every clock; bubbles travel as bubbles.
        self.window.in_valid.next = self.in_valid.val();
        self.window.in_first.next = self.in_first.val();
        self.window.in_last.next = self.in_last.val();
        self.window.in_pix.next = self.in_pix.val();
        self.window.in_x.next = self.in_x.val();
        self.window.in_dt.next = self.in_dt.val();
        self.window.in_thr.next = self.in_thr.val();
        self.window.in_wide.next = self.in_wide.val();
        self.window.in_sof.next = self.in_sof.val();
        // ---- Gradient pipeline. g(x) = I(x+1) - I(x) while x is at tap 1
        // (zero at a line's last pixel), g² at tap 2, g²(2x+1) at tap 3.
        self.g2.d.next = 0.into();
        if self.window.valid1.val() & !self.window.last1.val() {
            self.g2.d.next = bit_cast::<AMP_BITS, PIXEL_BITS>(self.window.pix0.val())
                - bit_cast::<AMP_BITS, PIXEL_BITS>(self.window.pix1.val());
        }
        self.g3.d.next = self.g2.q.val();
        self.g4.d.next = self.g3.q.val();
        // |g(x)| (the difference of the larger and the smaller level: no
        // negation in front of the multiplier) into the square's input
        // registers, where g(x) is registered: g² comes out at tap 2.
        self.gabs.next = 0.into();
        if self.window.valid1.val() & !self.window.last1.val() {
            self.gabs.next = bit_cast::<MUL_OPERAND_BITS, PIXEL_BITS>(self.window.pix0.val() - self.window.pix1.val());
            if self.window.pix1.val() > self.window.pix0.val() {
                self.gabs.next = bit_cast::<MUL_OPERAND_BITS, PIXEL_BITS>(self.window.pix1.val() - self.window.pix0.val());
            }
        }
        self.square.clock.next = self.clock.val();
        self.square.a.next = self.gabs.val();
        self.square.b.next = self.gabs.val();
        self.gsq3.d.next = bit_cast::<S0_BITS, MUL_PRODUCT_BITS>(self.square.p.val());
        self.gsq4.d.next = self.gsq3.q.val();
        // g²(x) and 2x + 1 into the weight's input registers where gsq3 and
        // tap 3 take them (x at tap 3 is x at tap 2 one clock earlier: the
        // window shifts on every clock).
        self.odd_x.next = bit_cast::<MUL_OPERAND_BITS, X_BITS>(self.window.x2.val())
            + bit_cast::<MUL_OPERAND_BITS, X_BITS>(self.window.x2.val())
            + 1;
        self.weight.clock.next = self.clock.val();
        self.weight.a.next = bit_cast::<MUL_OPERAND_BITS, MUL_PRODUCT_BITS>(self.square.p.val());
        self.weight.b.next = self.odd_x.val();
        self.w4.d.next = bit_cast::<S1_BITS, MUL_PRODUCT_BITS>(self.weight.p.val());

        // ---- The centre: pixel x at tap 4.
        self.seen_eff.next = self.seen.q.val() & !self.window.first4.val();
        self.count_eff.next = self.count.q.val();
        self.full_eff.next = self.full.q.val();
        // (`count_eff + 1` from the register, picked by `keep` last: no
        // adder after the decision.)
        self.count_eff1.next = self.count.q.val() + 1;
        if self.window.first4.val() {
            self.count_eff.next = 0.into();
            self.count_eff1.next = 1.into();
            self.full_eff.next = false;
        }
        self.x_next.next = self.window.x4.val() + 1;
        self.amp.next = bit_cast::<AMP_BITS, PIXEL_BITS>(self.window.pix4.val())
            - bit_cast::<AMP_BITS, PIXEL_BITS>(self.start_level.q.val());
        self.close_run.next = self.window.valid4.val()
            & !self.window.last4.val()
            & self.nz4.q.val()
            & self.seen_eff.val()
            & (self.up4.q.val() != self.rising.q.val());
        self.close_line.next = self.window.valid4.val() & self.window.last4.val() & self.seen_eff.val();
        self.keep.next = (self.close_run.val() | self.close_line.val()) & self.char4.q.val() & (self.count_eff.val() < self.n_max.val());
        self.drop.next = (self.close_run.val() | self.close_line.val()) & self.char4.q.val() & (self.count_eff.val() >= self.n_max.val());
        self.start_new.next = self.window.valid4.val()
            & !self.window.last4.val()
            & self.nz4.q.val()
            & (!self.seen_eff.val() | (self.up4.q.val() != self.rising.q.val()));
        self.extend.next = self.window.valid4.val()
            & !self.window.last4.val()
            & self.nz4.q.val()
            & self.seen_eff.val()
            & (self.up4.q.val() == self.rising.q.val());
        // One clock ahead: pixel x at tap 3. Its declivity started at
        // x - 1 (now at the centre) or earlier.
        self.nz4.d.next = self.g3.q.val() != 0;
        self.up4.d.next = (self.g3.q.val() != 0) & (self.g3.q.val() < self.sign_bit.val());
        // |I(x) - level| > ⌊d_t⌋ as two comparisons with the threshold added
        // to one side, for both possible start levels (the declivity under
        // way, or one starting at x - 1), chosen last. The sums `I + ⌊d_t⌋`
        // are registered: at taps 3 and 4, and for the declivity's start.
        self.lvl_a.next = bit_cast::<CMP_BITS, PIXEL_BITS>(self.window.pix3.val());
        self.lvl_run.next = bit_cast::<CMP_BITS, PIXEL_BITS>(self.start_level.q.val());
        self.lvl_new.next = bit_cast::<CMP_BITS, PIXEL_BITS>(self.window.pix4.val());
        self.thr.next = bit_cast::<CMP_BITS, DT_INT_BITS>(self.window.thr2.val());
        self.at_thr3.d.next = bit_cast::<CMP_BITS, PIXEL_BITS>(self.window.pix2.val()) + self.thr.val();
        self.at_thr4.d.next = self.at_thr3.q.val();
        self.char4.d.next = (self.lvl_a.val() > self.run_thr.q.val()) | (self.lvl_run.val() > self.at_thr3.q.val());
        if self.start_new.val() {
            self.char4.d.next = (self.lvl_a.val() > self.at_thr4.q.val()) | (self.lvl_new.val() > self.at_thr3.q.val());
        }

        // Neighbour levels: x + 1 and x + 2 clamped at the line's end, x - 1
        // and x - 2 clamped at its start.
        self.p1.next = self.window.pix3.val();
        self.p2.next = self.window.pix2.val();
        if self.window.last3.val() {
            self.p2.next = self.window.pix3.val();
        }
        self.pm1.next = self.window.pix5.val();
        self.pm2.next = self.window.pix6.val();
        if self.window.first5.val() {
            self.pm2.next = self.window.pix5.val();
        }
        if self.window.first4.val() {
            self.pm1.next = self.window.pix4.val();
            self.pm2.next = self.window.pix4.val();
        }
        // I(end + k): the run from end to x is flat, so only end = x and
        // end = x - 1 reach past x.
        self.right1.next = self.window.pix4.val();
        self.right2.next = self.window.pix4.val();
        if self.close_run.val() & self.upd1.q.val() {
            self.right1.next = self.p1.val();
            self.right2.next = self.p2.val();
        }
        if self.close_run.val() & !self.upd1.q.val() & self.upd2.q.val() {
            self.right2.next = self.p1.val();
        }

        // ---- State.
        self.count_next.next = self.count_eff.val();
        if self.keep.val() {
            self.count_next.next = self.count_eff1.val();
        }
        if self.window.valid4.val() {
            self.count.d.next = self.count_next.val();
            self.full.d.next = self.full_eff.val() | self.drop.val();
            self.seen.d.next = self.seen_eff.val();
        }
        self.upd1.d.next = self.start_new.val() | self.extend.val();
        self.upd2.d.next = self.upd1.q.val();
        if self.start_new.val() {
            self.seen.d.next = true;
            self.rising.d.next = self.up4.q.val();
            self.start.d.next = self.window.x4.val();
            self.start_level.d.next = self.window.pix4.val();
            self.run_thr.d.next = self.at_thr4.q.val();
            self.left0.d.next = self.window.pix4.val();
            self.left1.d.next = self.pm1.val();
            self.left2.d.next = self.pm2.val();
            self.s0.d.next = self.gsq4.q.val();
            self.s1.d.next = self.w4.q.val();
            self.end_reg.d.next = self.x_next.val();
        }
        if self.extend.val() {
            self.s0.d.next = self.s0.q.val() + self.gsq4.q.val();
            self.s1.d.next = self.s1.q.val() + self.w4.q.val();
            self.end_reg.d.next = self.x_next.val();
        }
        self.mk_pending.d.next = self.window.valid4.val() & self.window.last4.val();
        if self.window.valid4.val() & self.window.last4.val() {
            self.mk_count.d.next = self.count_next.val();
            self.mk_full.d.next = self.full_eff.val() | self.drop.val();
            self.mk_wide.d.next = self.window.wide4.val();
            self.mk_sof.d.next = self.window.sof4.val();
            self.mk_dt.d.next = self.window.dt4.val();
            self.mk_end.d.next = self.window.x4.val();
        }

        // ---- The item: a kept record, else a pending marker. The fields
        // are the record's or the marker's whatever `keep` says (they mean
        // nothing without `o_valid`): `keep` drives one register, not the
        // clear of every field, so that its fan-out stays small.
        self.o_valid.d.next = self.keep.val() | self.mk_pending.q.val();
        self.o_dividend.d.next = bit_cast::<DIVIDEND_BITS, S1_BITS>(self.s1.q.val()) << self.dividend_shift.val();
        self.o_divisor.d.next = self.s0.q.val();
        self.o_tag0.d.next = bit_cast::<32, X_BITS>(self.start.q.val())
            | (bit_cast::<32, X_BITS>(self.end_reg.q.val()) << self.end_shift.val())
            | (bit_cast::<32, AMP_BITS>(self.amp.val()) << self.amp_shift.val());
        self.o_tag1.d.next = bit_cast::<32, PIXEL_BITS>(self.left0.q.val())
            | (bit_cast::<32, PIXEL_BITS>(self.left1.q.val()) << self.level_shift.val())
            | (bit_cast::<32, PIXEL_BITS>(self.left2.q.val()) << (self.level_shift.val() << 1));
        self.o_tag2.d.next = bit_cast::<32, PIXEL_BITS>(self.window.pix4.val())
            | (bit_cast::<32, PIXEL_BITS>(self.right1.val()) << self.level_shift.val())
            | (bit_cast::<32, PIXEL_BITS>(self.right2.val()) << (self.level_shift.val() << 1));
        self.o_tag3.d.next = bit_cast::<32, DT_BITS>(self.window.dt4.val());
        if self.mk_pending.q.val() {
            self.o_dividend.d.next = 0.into();
            self.o_divisor.d.next = 1.into();
            self.o_tag0.d.next = (bit_cast::<32, 1>(true.into()) << self.marker_shift.val()) | (bit_cast::<32, X_BITS>(self.mk_end.q.val()) << self.end_shift.val());
            self.o_tag1.d.next = bit_cast::<32, COUNT_BITS>(self.mk_count.q.val());
            self.o_tag2.d.next = bit_cast::<32, 1>(self.mk_wide.q.val().into())
                | (bit_cast::<32, 1>(self.mk_full.q.val().into()) << 1)
                | (bit_cast::<32, 1>(self.mk_sof.q.val().into()) << 2);
            self.o_tag3.d.next = bit_cast::<32, DT_BITS>(self.mk_dt.q.val());
        }
        self.item_valid.next = self.o_valid.q.val();
        self.item_dividend.next = self.o_dividend.q.val();
        self.item_divisor.next = self.o_divisor.q.val();
        self.item_tag0.next = self.o_tag0.q.val();
        self.item_tag1.next = self.o_tag1.q.val();
        self.item_tag2.next = self.o_tag2.q.val();
        self.item_tag3.next = self.o_tag3.q.val();
    }
}
