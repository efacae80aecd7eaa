//! A D flip-flop with a synchronous, active-high reset: the register every
//! block's state is kept in, so that one `reset` input returns a block to its
//! state after configuration.
//!
//! ## Ports
//! - `clock`; `reset` (synchronous, active high); `d`; `q`.
//!
//! ## Timing
//! `q` takes `d` at each rising edge of `clock`, or `init` when `reset` is
//! high at that edge. Its power-up value (a Verilog `initial`) is `init` as
//! well, so that after a reset the register is as after configuration. No
//! paper equation: it is the storage the equations' pipelines are built of.
//!
//! In the ECP5 a synchronous reset is the flip-flop's own `LSR` input
//! (`TRELLIS_FF` in `SYNC` mode), in a 7-series the `R`/`S` input of `FDRE`/`FDSE`:
//! the reset costs no LUT in front of the register.

use rust_hdl::prelude::*;

/// A register with a synchronous reset to `init` (by default zero).
#[derive(Clone, Debug, LogicBlock)]
pub struct ResetDff<T: Synth> {
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// The value after configuration and after a reset.
    pub init: Constant<T>,
}

impl<T: Synth> ResetDff<T> {
    /// A register that powers up and resets to `init`.
    pub fn new(init: T) -> Self {
        Self {
            d: Signal::default(),
            q: Signal::new_with_default(init),
            clock: Signal::default(),
            reset: Signal::default(),
            init: Constant::new(init),
        }
    }
}

impl<T: Synth> Default for ResetDff<T> {
    fn default() -> Self {
        Self::new(T::default())
    }
}

impl<T: Synth> Logic for ResetDff<T> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            self.q.next = if self.reset.val() { self.init.val() } else { self.d.val() };
        }
    }
    fn connect(&mut self) {
        self.q.connect();
    }
    fn hdl(&self) -> Verilog {
        Verilog::Custom(
            "\
initial begin
   q = init;
end

always @(posedge clock) begin
   if (reset) q <= init;
   else q <= d;
end
      "
            .into(),
        )
    }
    fn timing(&self) -> Vec<TimingInfo> {
        vec![TimingInfo {
            name: "reset_dff".into(),
            clock: "clock".into(),
            inputs: vec!["d".into(), "reset".into()],
            outputs: vec!["q".into()],
        }]
    }
}
