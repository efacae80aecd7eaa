//! A camera input's register slice (a "skid buffer", as Forencich's
//! `axis_register` with `REG_TYPE = 2`): an AXI4-Stream-video beat
//! (`tdata`, `tuser`, `tlast`) passes through registers on its way from the
//! camera to the declivity detector, and the camera's `tready` is a
//! register, so that neither the camera's handshake nor the detector's
//! `tready` crosses the die in one clock.
//!
//! ## Ports
//! - In from the camera: `s_tdata`, `s_tvalid`, `s_tuser`, `s_tlast`; out
//!   `s_tready`, a register: high while the skid register is empty.
//! - Out to the detector: `m_tdata`, `m_tvalid`, `m_tuser`, `m_tlast`, all
//!   registers; in `m_tready`.
//!
//! ## Timing
//! Latency [`SKID_LAG`] = 1 clock: a beat accepted at clock `t` is offered
//! downstream at `t + 1`. Throughput one beat per clock while `m_tready` is
//! high. When `m_tready` goes low, the beat arriving in that clock (the
//! camera still saw `s_tready` high) waits in the skid register and
//! `s_tready` falls the clock after; when `m_tready` rises again the output
//! register is refilled from the skid register first, so beats stay in
//! order and none is lost or duplicated. `s_tvalid` low is a bubble that
//! passes through. The registers start empty (`m_tvalid` low, `s_tready`
//! high) from their Verilog initial values; `reset` (synchronous, active high) returns them there.
//!
//! No paper equation: stream plumbing.

use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from a beat accepted from the camera to the same beat offered to
/// the detector.
pub const SKID_LAG: usize = 1;

#[derive(LogicBlock)]
pub struct SkidBuffer<const D: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub s_tdata: Signal<In, Bits<D>>,
    pub s_tvalid: Signal<In, Bit>,
    pub s_tuser: Signal<In, Bit>,
    pub s_tlast: Signal<In, Bit>,
    pub s_tready: Signal<Out, Bit>,
    pub m_tdata: Signal<Out, Bits<D>>,
    pub m_tvalid: Signal<Out, Bit>,
    pub m_tuser: Signal<Out, Bit>,
    pub m_tlast: Signal<Out, Bit>,
    pub m_tready: Signal<In, Bit>,
    // The output register.
    o_valid: ResetDff<Bit>,
    o_data: ResetDff<Bits<D>>,
    o_user: ResetDff<Bit>,
    o_last: ResetDff<Bit>,
    // The skid register: the beat that came while the output was stalled.
    k_valid: ResetDff<Bit>,
    k_data: ResetDff<Bits<D>>,
    k_user: ResetDff<Bit>,
    k_last: ResetDff<Bit>,
    // The output register is free for a new beat at the clock's edge.
    o_free: Signal<Local, Bit>,
}

impl<const D: usize> Default for SkidBuffer<D> {
    fn default() -> Self {
        SkidBuffer {
            clock: Default::default(),
            reset: Default::default(),
            s_tdata: Default::default(),
            s_tvalid: Default::default(),
            s_tuser: Default::default(),
            s_tlast: Default::default(),
            s_tready: Default::default(),
            m_tdata: Default::default(),
            m_tvalid: Default::default(),
            m_tuser: Default::default(),
            m_tlast: Default::default(),
            m_tready: Default::default(),
            o_valid: Default::default(),
            o_data: Default::default(),
            o_user: Default::default(),
            o_last: Default::default(),
            k_valid: Default::default(),
            k_data: Default::default(),
            k_user: Default::default(),
            k_last: Default::default(),
            o_free: Default::default(),
        }
    }
}

impl<const D: usize> Logic for SkidBuffer<D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, o_valid, o_data, o_user, o_last, k_valid, k_data, k_user, k_last);
        self.o_valid.reset.next = self.reset.val();
        self.o_data.reset.next = self.reset.val();
        self.o_user.reset.next = self.reset.val();
        self.o_last.reset.next = self.reset.val();
        self.k_valid.reset.next = self.reset.val();
        self.k_data.reset.next = self.reset.val();
        self.k_user.reset.next = self.reset.val();
        self.k_last.reset.next = self.reset.val();
        self.s_tready.next = !self.k_valid.q.val();
        self.m_tvalid.next = self.o_valid.q.val();
        self.m_tdata.next = self.o_data.q.val();
        self.m_tuser.next = self.o_user.q.val();
        self.m_tlast.next = self.o_last.q.val();
        self.o_free.next = !self.o_valid.q.val() | self.m_tready.val();
        if self.o_free.val() {
            // The skid register's beat first (while it holds one, s_tready
            // is low: nothing new comes in this clock).
            if self.k_valid.q.val() {
                self.o_valid.d.next = true;
                self.o_data.d.next = self.k_data.q.val();
                self.o_user.d.next = self.k_user.q.val();
                self.o_last.d.next = self.k_last.q.val();
                self.k_valid.d.next = false;
            } else {
                self.o_valid.d.next = self.s_tvalid.val();
                self.o_data.d.next = self.s_tdata.val();
                self.o_user.d.next = self.s_tuser.val();
                self.o_last.d.next = self.s_tlast.val();
            }
        } else if self.s_tvalid.val() & !self.k_valid.q.val() {
            self.k_valid.d.next = true;
            self.k_data.d.next = self.s_tdata.val();
            self.k_user.d.next = self.s_tuser.val();
            self.k_last.d.next = self.s_tlast.val();
        }
    }
}
