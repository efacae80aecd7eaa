//! An unsigned 16 × 16 multiplier in an ECP5 `MULT18X18D` DSP block, with
//! the block's own input registers.
//!
//! Yosys's ECP5 mapping puts a `*` into a `MULT18X18D` without its
//! registers, so a product registered in the fabric costs a route into the
//! DSP column, the multiply and a route out in one clock, more than a
//! clock period on a full device. Instantiated with `REG_INPUTA_CLK` and
//! `REG_INPUTB_CLK` on the clock, the route in ends on a register inside the
//! DSP block, and the clock after holds only the multiply and the route out.
//!
//! ## Ports
//! - `clock`; `a`, `b` in (16 bits each, unsigned); `p` out (32 bits).
//!
//! ## Timing
//! `p(t) = a(t − 1) · b(t − 1)`: the operands are registered on every clock
//! (no enable, no reset; zero at start), the product is combinational after
//! them, exactly as two rust-hdl `DFF`s and a product, which is this block's
//! simulation model. Feeding it the operands a clock early (the value a
//! fabric register would load) gives the product on the clock that register
//! would have held them: no clock of latency is added. The Verilog
//! instantiates the primitive by name: Yosys's `synth_ecp5` and nextpnr know
//! it, and the co-simulation and lint read a behavioural model of it
//! (`sim::hdl::primitives`).
//!
//! No paper equation: an arithmetic primitive.

use rust_hdl::prelude::*;

/// Operand bits of [`DspMultiplier`] (rust-hdl's product is 16 × 16).
pub const MUL_OPERAND_BITS: usize = 16;
/// Product bits of [`DspMultiplier`].
pub(crate) const MUL_PRODUCT_BITS: usize = 2 * MUL_OPERAND_BITS;
/// Operand bits of one `MULT18X18D`.
const MULT18_BITS: usize = 18;

#[derive(LogicBlock, Default)]
pub(crate) struct DspMultiplier {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<MUL_OPERAND_BITS>>,
    pub b: Signal<In, Bits<MUL_OPERAND_BITS>>,
    pub p: Signal<Out, Bits<MUL_PRODUCT_BITS>>,
    a_reg: DFF<Bits<MUL_OPERAND_BITS>>,
    b_reg: DFF<Bits<MUL_OPERAND_BITS>>,
}

impl Logic for DspMultiplier {
    fn update(&mut self) {
        self.a_reg.clock.next = self.clock.val();
        self.b_reg.clock.next = self.clock.val();
        self.a_reg.d.next = self.a.val();
        self.b_reg.d.next = self.b.val();
        self.p.next = self.a_reg.q.val() * self.b_reg.q.val();
    }

    fn connect(&mut self) {
        self.a_reg.clock.connect();
        self.b_reg.clock.connect();
        self.a_reg.d.connect();
        self.b_reg.d.connect();
        self.p.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Wrapper(Wrapper { code: mult18x18d_instance(), cores: String::new() })
    }
}

/// The Verilog body: one `MULT18X18D`, A and B registered on `CLK0`, the
/// operands' two top bits and port C tied to zero, the product's top four
/// bits (always zero for 16-bit operands) on a wire left unused.
fn mult18x18d_instance() -> String {
    let mut pins = Vec::new();
    for (port, name) in [("A", "a"), ("B", "b")] {
        for k in 0..MULT18_BITS {
            let bit = if k < MUL_OPERAND_BITS { format!("{name}[{k}]") } else { "1'b0".to_string() };
            pins.push(format!(".{port}{k}({bit})"));
        }
    }
    for k in 0..MULT18_BITS {
        pins.push(format!(".C{k}(1'b0)"));
    }
    for k in 0..2 * MULT18_BITS {
        let bit = if k < MUL_PRODUCT_BITS { format!("p[{k}]") } else { format!("p_unused[{}]", k - MUL_PRODUCT_BITS) };
        pins.push(format!(".P{k}({bit})"));
    }
    format!(
        r#"
/* verilator lint_off UNUSEDSIGNAL */
wire [{top}:0] p_unused;
/* verilator lint_on UNUSEDSIGNAL */
MULT18X18D #(
    .REG_INPUTA_CLK("CLK0"), .REG_INPUTA_CE("CE0"), .REG_INPUTA_RST("RST0"),
    .REG_INPUTB_CLK("CLK0"), .REG_INPUTB_CE("CE0"), .REG_INPUTB_RST("RST0"),
    .REG_INPUTC_CLK("NONE"), .REG_PIPELINE_CLK("NONE"), .REG_OUTPUT_CLK("NONE"),
    .CLK0_DIV("ENABLED"), .CLK1_DIV("ENABLED"), .CLK2_DIV("ENABLED"), .CLK3_DIV("ENABLED"),
    .HIGHSPEED_CLK("NONE"), .GSR("DISABLED"), .CAS_MATCH_REG("FALSE"),
    .MULT_BYPASS("DISABLED"), .RESETMODE("SYNC"), .SOURCEB_MODE("B_SHIFT")
) mult (
    .SIGNEDA(1'b0), .SIGNEDB(1'b0), .SOURCEA(1'b0), .SOURCEB(1'b0),
    .CLK0(clock), .CLK1(1'b0), .CLK2(1'b0), .CLK3(1'b0),
    .CE0(1'b1), .CE1(1'b0), .CE2(1'b0), .CE3(1'b0),
    .RST0(1'b0), .RST1(1'b0), .RST2(1'b0), .RST3(1'b0),
    {pins}
);
"#,
        top = 2 * MULT18_BITS - MUL_PRODUCT_BITS - 1,
        pins = pins.join(", "),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_product_of_each_clock_s_operands_is_out_one_clock_later() {
        let mut uut = DspMultiplier::default();
        uut.connect_all();
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut ops = vec![(0u64, 0u64), (0xffff, 0xffff), (1, 0xffff), (0xffff, 1), (255, 255), (255, 2047)];
        for _ in 0..200 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            ops.push((s & 0xffff, (s >> 16) & 0xffff));
        }
        let mut before: Option<(u64, u64)> = None;
        for &(a, b) in &ops {
            uut.a.next = a.into();
            uut.b.next = b.into();
            assert!(simulate(&mut uut, 100));
            // Before the edge: the operands offered a clock ago (zero at start).
            let (pa, pb) = before.unwrap_or((0, 0));
            assert_eq!(uut.p.val().to_u64(), pa * pb, "{pa} × {pb}");
            crate::tick(&mut uut, |u| &mut u.clock);
            before = Some((a, b));
        }
    }

    #[test]
    fn the_verilog_instantiates_one_mult18x18d_with_both_input_registers_and_every_product_pin() {
        let v = mult18x18d_instance();
        assert_eq!(v.matches("MULT18X18D #(").count(), 1);
        assert!(v.contains(r#".REG_INPUTA_CLK("CLK0")"#) && v.contains(r#".REG_INPUTB_CLK("CLK0")"#));
        assert!(v.contains(r#".REG_OUTPUT_CLK("NONE")"#) && v.contains(r#".REG_PIPELINE_CLK("NONE")"#));
        for k in 0..2 * MULT18_BITS {
            assert!(v.contains(&format!(".P{k}(")), "P{k} connected");
        }
        assert!(v.contains(".A15(a[15])") && v.contains(".A16(1'b0)") && v.contains(".P31(p[31])"));
    }
}
