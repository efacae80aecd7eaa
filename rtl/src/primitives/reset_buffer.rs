//! The line processor's `reset` on its way to every register: an ECP5
//! `DCCA` clock buffer puts it on the global network.
//!
//! `reset` reaches the synchronous reset (`LSR`) of every flip-flop, some
//! 31 000 in `sd` and 58 000 in `hd`.
//! On the general routing such a net is slow to route and slow to arrive;
//! nextpnr-ecp5 promotes only clock nets to the global network by itself.
//! Driven by a `DCCA`, the net is routed on a global (one of the eight that
//! may also reach the fabric), which reaches every slice's `LSR` and,
//! through the fabric, the few LUTs that read the reset as logic.
//!
//! ## Ports
//! - `reset_in`: the top's `reset` input; `reset`: the same, to the blocks.
//!
//! ## Timing
//! Combinational: `reset = reset_in` at every instant (no register, no
//! latency), which is this block's simulation model. The Verilog
//! instantiates the primitive by name with its enable tied high, so that
//! it is a buffer; the co-simulation and lint read a behavioural model of
//! it, and the `generic` target puts that model inside the block
//! (`sim::hdl::primitives`). Other vendors' tools route a high-fanout
//! reset by themselves.
//!
//! No paper equation: a buffer.

use rust_hdl::prelude::*;

/// A buffer that puts the reset on a global net (an ECP5 `DCCA`).
#[derive(LogicBlock, Default)]
pub struct ResetBuffer {
    pub reset_in: Signal<In, Bit>,
    pub reset: Signal<Out, Bit>,
}

impl Logic for ResetBuffer {
    fn update(&mut self) {
        self.reset.next = self.reset_in.val();
    }

    fn connect(&mut self) {
        self.reset.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Wrapper(Wrapper { code: dcca_instance().into(), cores: String::new() })
    }
}

/// The Verilog body: one `DCCA`, enable high.
fn dcca_instance() -> &'static str {
    "DCCA reset_dcca (.CLKI(reset_in), .CE(1'b1), .CLKO(reset));\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_buffer_passes_the_reset_unchanged_at_every_instant() {
        let mut uut = ResetBuffer::default();
        uut.connect_all();
        for level in [false, true, true, false, true, false] {
            uut.reset_in.next = level;
            assert!(simulate(&mut uut, 100));
            assert_eq!(uut.reset.val(), level);
        }
    }

    #[test]
    fn the_verilog_instantiates_one_dcca_enabled_from_reset_in_to_reset() {
        let v = dcca_instance();
        assert_eq!(v.matches("DCCA ").count(), 1);
        assert!(v.contains(".CLKI(reset_in)") && v.contains(".CE(1'b1)") && v.contains(".CLKO(reset)"));
    }
}
