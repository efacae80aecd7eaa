//! A simple dual-port block RAM with its output register: ECP5 `DP16KD`
//! primitives (18-bit mode, 1024 words) instantiated with `REGMODE_B =
//! "OUTREG"`, one per 18 bits of width.
//!
//! Yosys's ECP5 memory mapping never uses a block RAM's output register,
//! and without it the RAM's clock-to-out takes most of a clock period,
//! leaving too little for the route to a register beside it. Instantiated,
//! the register is inside the RAM.
//!
//! ## Ports
//! - `clock`; write: `write_enable`, `write_address`, `write_data`; read:
//!   `read_address`, `read_data`.
//!
//! ## Timing
//! A write lands at the clock edge it is on the ports. A read's data is on
//! `read_data` two clocks after its address (the RAM's registered read,
//! then the output register), exactly as a rust-hdl `RAM` followed by a
//! `DFF`, which is this block's simulation model. A read at an address on
//! the clock it is written returns the old word in the model; the primitive
//! is then undefined, and the matcher never does it (`no_rw_check`, see
//! `sim::hdl::verilog`). The Verilog instantiates the primitive by name: Yosys's
//! `synth_ecp5` knows it, and the co-simulation and lint read a behavioural
//! model of it (`sim::hdl::primitives`). No reset: the words start at zero (the
//! primitive's default `INITVAL`s, and the model's `RAM`).
//!
//! No paper equation: a memory primitive.

use rust_hdl::prelude::*;

/// Data bits of one `DP16KD` in its 18-bit mode.
pub const DP16KD_WIDTH: usize = 18;
/// Address bits of one `DP16KD` in its 18-bit mode (1024 words).
pub const DP16KD_ADDR_BITS: usize = 10;

#[derive(LogicBlock, Default)]
pub(crate) struct BlockRam<const D: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Signal<In, Bit>,
    pub write_address: Signal<In, Bits<A>>,
    pub write_data: Signal<In, Bits<D>>,
    pub read_address: Signal<In, Bits<A>>,
    pub read_data: Signal<Out, Bits<D>>,
    ram: RAM<Bits<D>, A>,
    out_reg: DFF<Bits<D>>,
}

impl<const D: usize, const A: usize> Logic for BlockRam<D, A> {
    fn update(&mut self) {
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();
        self.out_reg.clock.next = self.clock.val();
        self.ram.write_enable.next = self.write_enable.val();
        self.ram.write_address.next = self.write_address.val();
        self.ram.write_data.next = self.write_data.val();
        self.ram.read_address.next = self.read_address.val();
        self.out_reg.d.next = self.ram.read_data.val();
        self.read_data.next = self.out_reg.q.val();
    }

    fn connect(&mut self) {
        self.ram.read_clock.connect();
        self.ram.write_clock.connect();
        self.out_reg.clock.connect();
        self.ram.write_enable.connect();
        self.ram.write_address.connect();
        self.ram.write_data.connect();
        self.ram.read_address.connect();
        self.out_reg.d.connect();
        self.read_data.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Wrapper(Wrapper { code: dp16kd_instances(D, A), cores: String::new() })
    }
}

/// The Verilog body: `⌈d / 18⌉` `DP16KD`s side by side, port A writing,
/// port B reading through its output register.
fn dp16kd_instances(d: usize, a: usize) -> String {
    assert!(a <= DP16KD_ADDR_BITS, "at most 1024 words per DP16KD in its 18-bit mode");
    let addr = |name: &str, port: &str| -> String {
        // AD[13:4] is the word address, AD[3:2] unused, AD[1:0] the byte
        // enables of a write (both set) or unused (read).
        let mut pins = Vec::new();
        for k in 0..DP16KD_ADDR_BITS {
            let bit = if k < a { format!("{name}[{k}]") } else { "1'b0".to_string() };
            pins.push(format!(".AD{port}{}({bit})", k + 4));
        }
        let be = if port == "A" { "1'b1" } else { "1'b0" };
        pins.push(format!(".AD{port}3(1'b0), .AD{port}2(1'b0), .AD{port}1({be}), .AD{port}0({be})"));
        pins.join(", ")
    };
    let mut code = String::new();
    let n = d.div_ceil(DP16KD_WIDTH);
    for i in 0..n {
        let lo = i * DP16KD_WIDTH;
        let w = (d - lo).min(DP16KD_WIDTH);
        let mut di = Vec::new();
        let mut dout = Vec::new();
        for k in 0..DP16KD_WIDTH {
            let bit = if k < w { format!("write_data[{}]", lo + k) } else { "1'b0".to_string() };
            di.push(format!(".DIA{k}({bit})"));
            di.push(format!(".DIB{k}(1'b0)"));
            if k < w {
                dout.push(format!(".DOB{k}(read_data[{}])", lo + k));
            }
        }
        code.push_str(&format!(
            r#"
DP16KD #(
    .DATA_WIDTH_A(18), .DATA_WIDTH_B(18),
    .REGMODE_A("NOREG"), .REGMODE_B("OUTREG"),
    .RESETMODE("SYNC"), .ASYNC_RESET_RELEASE("SYNC"),
    .CSDECODE_A("0b000"), .CSDECODE_B("0b000"),
    .WRITEMODE_A("NORMAL"), .WRITEMODE_B("NORMAL"),
    .GSR("AUTO")
) ram_{i} (
    .CLKA(clock), .CEA(1'b1), .OCEA(1'b1), .WEA(write_enable), .RSTA(1'b0),
    .CSA0(1'b0), .CSA1(1'b0), .CSA2(1'b0),
    {addr_a},
    .CLKB(clock), .CEB(1'b1), .OCEB(1'b1), .WEB(1'b0), .RSTB(1'b0),
    .CSB0(1'b0), .CSB1(1'b0), .CSB2(1'b0),
    {addr_b},
    {di},
    {dout}
);
"#,
            addr_a = addr("write_address", "A"),
            addr_b = addr("read_address", "B"),
            di = di.join(", "),
            dout = dout.join(", "),
        ));
    }
    code
}
