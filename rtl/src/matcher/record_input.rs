//! The input register of one of the matcher's record streams: each beat
//! taken on the ports (`valid` and `ready` high) is held for one clock, and
//! the matcher's loader writes it from there, so that no port, and no
//! handshake through the ports, lies on a path into the record memory's
//! block RAM: the route from the ports (`ready` out, `valid` in) and the
//! route to the RAM each get a clock of their own.
//!
//! ## Ports
//! - In: `ready` (the loader's, also the matcher's output of that name),
//!   then the stream as the detector sends it: `valid`, `last`, `pos`,
//!   `amp`, `left0..2`, `right0..2`, `dt`, `wide`, `full` (the reference's
//!   `sof` is registered beside it by the matcher).
//! - Out: `q_valid` (a beat was taken last clock), and its fields `q_last`,
//!   `q_pos`, … `q_full`.
//!
//! ## Timing
//! One clock of latency, one beat per clock; no back-pressure of its own:
//! the loader keeps `ready` low on the clock after it took a line's marker
//! (the marker is then in this register), so the register never holds a
//! beat the loader cannot take. `valid` low (or `ready` low) leaves
//! `q_valid` low on the next clock. `q_valid` starts low (Verilog initial value)
//! and `reset` (synchronous, active high) clears it.
//!
//! No paper equation: stream plumbing.

use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub(crate) struct RecordInput {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub ready: Signal<In, Bit>,
    pub valid: Signal<In, Bit>,
    pub last: Signal<In, Bit>,
    pub pos: Signal<In, Bits<POS_BITS>>,
    pub amp: Signal<In, Bits<AMP_BITS>>,
    pub left0: Signal<In, Bits<PIXEL_BITS>>,
    pub left1: Signal<In, Bits<PIXEL_BITS>>,
    pub left2: Signal<In, Bits<PIXEL_BITS>>,
    pub right0: Signal<In, Bits<PIXEL_BITS>>,
    pub right1: Signal<In, Bits<PIXEL_BITS>>,
    pub right2: Signal<In, Bits<PIXEL_BITS>>,
    pub dt: Signal<In, Bits<DT_BITS>>,
    pub wide: Signal<In, Bit>,
    pub full: Signal<In, Bit>,
    pub q_valid: Signal<Out, Bit>,
    pub q_last: Signal<Out, Bit>,
    pub q_pos: Signal<Out, Bits<POS_BITS>>,
    pub q_amp: Signal<Out, Bits<AMP_BITS>>,
    pub q_left0: Signal<Out, Bits<PIXEL_BITS>>,
    pub q_left1: Signal<Out, Bits<PIXEL_BITS>>,
    pub q_left2: Signal<Out, Bits<PIXEL_BITS>>,
    pub q_right0: Signal<Out, Bits<PIXEL_BITS>>,
    pub q_right1: Signal<Out, Bits<PIXEL_BITS>>,
    pub q_right2: Signal<Out, Bits<PIXEL_BITS>>,
    pub q_dt: Signal<Out, Bits<DT_BITS>>,
    pub q_wide: Signal<Out, Bit>,
    pub q_full: Signal<Out, Bit>,
    r_valid: ResetDff<Bit>,
    r_last: ResetDff<Bit>,
    r_pos: ResetDff<Bits<POS_BITS>>,
    r_amp: ResetDff<Bits<AMP_BITS>>,
    r_left0: ResetDff<Bits<PIXEL_BITS>>,
    r_left1: ResetDff<Bits<PIXEL_BITS>>,
    r_left2: ResetDff<Bits<PIXEL_BITS>>,
    r_right0: ResetDff<Bits<PIXEL_BITS>>,
    r_right1: ResetDff<Bits<PIXEL_BITS>>,
    r_right2: ResetDff<Bits<PIXEL_BITS>>,
    r_dt: ResetDff<Bits<DT_BITS>>,
    r_wide: ResetDff<Bit>,
    r_full: ResetDff<Bit>,
}

impl Logic for RecordInput {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, r_valid, r_last, r_pos, r_amp, r_left0, r_left1, r_left2, r_right0, r_right1, r_right2, r_dt,
            r_wide, r_full
        );
        self.r_valid.reset.next = self.reset.val();
        self.r_last.reset.next = self.reset.val();
        self.r_pos.reset.next = self.reset.val();
        self.r_amp.reset.next = self.reset.val();
        self.r_left0.reset.next = self.reset.val();
        self.r_left1.reset.next = self.reset.val();
        self.r_left2.reset.next = self.reset.val();
        self.r_right0.reset.next = self.reset.val();
        self.r_right1.reset.next = self.reset.val();
        self.r_right2.reset.next = self.reset.val();
        self.r_dt.reset.next = self.reset.val();
        self.r_wide.reset.next = self.reset.val();
        self.r_full.reset.next = self.reset.val();
        self.r_valid.d.next = self.valid.val() & self.ready.val();
        // The fields load on every clock (no enable: the loader looks at
        // them only with `q_valid`).
        self.r_last.d.next = self.last.val();
        self.r_pos.d.next = self.pos.val();
        self.r_amp.d.next = self.amp.val();
        self.r_left0.d.next = self.left0.val();
        self.r_left1.d.next = self.left1.val();
        self.r_left2.d.next = self.left2.val();
        self.r_right0.d.next = self.right0.val();
        self.r_right1.d.next = self.right1.val();
        self.r_right2.d.next = self.right2.val();
        self.r_dt.d.next = self.dt.val();
        self.r_wide.d.next = self.wide.val();
        self.r_full.d.next = self.full.val();
        self.q_valid.next = self.r_valid.q.val();
        self.q_last.next = self.r_last.q.val();
        self.q_pos.next = self.r_pos.q.val();
        self.q_amp.next = self.r_amp.q.val();
        self.q_left0.next = self.r_left0.q.val();
        self.q_left1.next = self.r_left1.q.val();
        self.q_left2.next = self.r_left2.q.val();
        self.q_right0.next = self.r_right0.q.val();
        self.q_right1.next = self.r_right1.q.val();
        self.q_right2.next = self.r_right2.q.val();
        self.q_dt.next = self.r_dt.q.val();
        self.q_wide.next = self.r_wide.q.val();
        self.q_full.next = self.r_full.q.val();
    }
}
