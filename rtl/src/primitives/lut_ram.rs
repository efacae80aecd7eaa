//! A register file of four words in LUT RAM: ECP5 `TRELLIS_DPR16X4`
//! primitives (16 words of 4 bits, synchronous write, asynchronous read;
//! the two upper address bits tied low), one per 4 bits of width.
//!
//! A gain cell keeps its four reference rows in one (`crate::matcher::gain_cell`):
//! held in flip-flops, the rows cost a four-way multiplexer per bit in front
//! of the register that takes the row of the next column (two LUT4s and a
//! `PFUMX` a bit, and their enables), where a LUT RAM is the memory and the
//! multiplexer in one.
//!
//! ## Ports
//! - `clock`; write: `write_enable`, `write_address`, `write_data`; read:
//!   `read_address`, `read_data`.
//!
//! ## Timing
//! A write lands at the clock edge it is on the ports; `read_data` shows
//! the word at `read_address` on the same clock (no register: the reader
//! registers it), the old word on a write's own clock. The rust-hdl model
//! is four registers and a multiplexer; the Verilog instantiates the
//! primitive by name: Yosys's `synth_ecp5` knows it, and the co-simulation
//! and lint read a behavioural model of it (`sim::hdl::primitives`). Words start
//! at zero, as the model's registers do (`INITVAL` 0); there is no reset.
//!
//! No paper equation: a memory primitive.

use rust_hdl::prelude::*;

/// Words of the register file.
pub(crate) const LUT_RAM_WORDS: usize = 4;
/// Address bits of the register file.
const LUT_RAM_ADDR_BITS: usize = 2;
/// Data bits of one `TRELLIS_DPR16X4`.
pub const DPR16X4_WIDTH: usize = 4;
/// Address bits of one `TRELLIS_DPR16X4` (16 words).
const DPR16X4_ADDR_BITS: usize = 4;

#[derive(LogicBlock, Default)]
pub(crate) struct LutRam<const D: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Signal<In, Bit>,
    pub write_address: Signal<In, Bits<LUT_RAM_ADDR_BITS>>,
    pub write_data: Signal<In, Bits<D>>,
    pub read_address: Signal<In, Bits<LUT_RAM_ADDR_BITS>>,
    pub read_data: Signal<Out, Bits<D>>,
    words: [DFF<Bits<D>>; LUT_RAM_WORDS],
}

impl<const D: usize> Logic for LutRam<D> {
    fn update(&mut self) {
        let write = self.write_enable.val();
        let at = self.write_address.val().index();
        for (k, w) in self.words.iter_mut().enumerate() {
            w.clock.next = self.clock.val();
            w.d.next = if write && k == at { self.write_data.val() } else { w.q.val() };
        }
        self.read_data.next = self.words[self.read_address.val().index()].q.val();
    }

    fn connect(&mut self) {
        for w in &mut self.words {
            w.clock.connect();
            w.d.connect();
        }
        self.read_data.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Wrapper(Wrapper { code: dpr16x4_instances(D), cores: String::new() })
    }
}

/// The Verilog body: `⌈d / 4⌉` `TRELLIS_DPR16X4`s side by side.
fn dpr16x4_instances(d: usize) -> String {
    let pad = DPR16X4_ADDR_BITS - LUT_RAM_ADDR_BITS;
    let mut code = String::new();
    for i in 0..d.div_ceil(DPR16X4_WIDTH) {
        let lo = i * DPR16X4_WIDTH;
        let w = (d - lo).min(DPR16X4_WIDTH);
        let di: Vec<String> = (0..DPR16X4_WIDTH)
            .rev()
            .map(|k| if k < w { format!("write_data[{}]", lo + k) } else { "1'b0".to_string() })
            .collect();
        // The spare outputs of a last, partial primitive are left unread.
        let (off, on) = if w < DPR16X4_WIDTH {
            ("/* verilator lint_off UNUSEDSIGNAL */\n", "\n/* verilator lint_on UNUSEDSIGNAL */")
        } else {
            ("", "")
        };
        code.push_str(&format!(
            r#"
{off}wire [3:0] do_{i};{on}
TRELLIS_DPR16X4 #(
    .WCKMUX("WCK"), .WREMUX("WRE"), .INITVAL(64'h0000000000000000)
) ram_{i} (
    .DI({{{di}}}), .WAD({{{pad}'b0, write_address}}), .WRE(write_enable), .WCK(clock),
    .RAD({{{pad}'b0, read_address}}), .DO(do_{i})
);
assign read_data[{hi}:{lo}] = do_{i}[{top}:0];
"#,
            di = di.join(", "),
            hi = lo + w - 1,
            top = w - 1,
        ));
    }
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A write shows on the next clock at its address and nowhere else; the
    /// read is combinational.
    #[test]
    fn a_word_written_reads_back_at_its_address_only() {
        let mut r = LutRam::<15>::default();
        r.connect_all();
        r.write_enable.next = true;
        r.write_address.next = 2.into();
        r.write_data.next = 0x5a5a.into();
        r.read_address.next = 2.into();
        assert!(simulate(&mut r, 100));
        assert_eq!(r.read_data.val(), Bits::<15>::from(0), "not written before the edge");
        crate::tick(&mut r, |u| &mut u.clock);
        r.write_enable.next = false;
        for a in 0..4u64 {
            r.read_address.next = a.into();
            assert!(simulate(&mut r, 100));
            let want = if a == 2 { 0x5a5a & 0x7fff } else { 0 };
            assert_eq!(r.read_data.val(), Bits::<15>::from(want), "address {a}");
        }
    }

    /// One primitive per four bits; the last one's spare bits tied low.
    #[test]
    fn the_verilog_has_one_primitive_per_four_bits() {
        let v = dpr16x4_instances(15);
        assert_eq!(v.matches("TRELLIS_DPR16X4 #(").count(), 4);
        assert!(v.contains("assign read_data[14:12] = do_3[2:0];"), "{v}");
        assert!(v.contains(".DI({1'b0, write_data[14], write_data[13], write_data[12]})"), "{v}");
    }
}
