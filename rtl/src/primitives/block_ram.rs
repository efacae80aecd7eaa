//! A simple dual-port block RAM with its output register: ECP5 `DP16KD`
//! primitives instantiated with `REGMODE_B = "OUTREG"` side by side, in the
//! widest mode that holds the depth ([`dp16kd_mode`]: 18 bits of 1024
//! words up to 1024 words, 9 bits of 2048, 4 of 4096, 2 of 8192, 1 of
//! 16384), one per that many bits of width. Up to 1024 words it can start
//! with given words ([`BlockRam::with_words`], the primitives' `INITVAL_xx`):
//! a table, read-only when its writer never writes (the interpolator's
//! reciprocal table, about 650 LUT4s as logic).
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
//! model of it (`sim::hdl::primitives`). No reset: the words start at zero or at
//! the words given (the primitive's `INITVAL`s, and the model's `RAM`), the
//! output register at zero.
//!
//! No paper equation: a memory primitive.

use rust_hdl::prelude::*;

/// Data bits of one `DP16KD` in its 18-bit mode.
pub const DP16KD_WIDTH: usize = 18;
/// Address bits of one `DP16KD` in its 18-bit mode (1024 words).
pub const DP16KD_ADDR_BITS: usize = 10;
/// Address bits of one `DP16KD` in its 1-bit mode (16384 words), the
/// deepest.
pub const DP16KD_MAX_ADDR_BITS: usize = 14;

/// The `DP16KD` mode of a memory of `2^addr_bits` words: the data bits of
/// one primitive (`DATA_WIDTH_A/B`), the widest whose depth holds the
/// words: 18 up to [`DP16KD_ADDR_BITS`], then 9, 4, 2 and 1 bits for each
/// address bit more (the primitive's 18 Kbit, then its 16 Kbit without the
/// parity bits).
pub const fn dp16kd_mode(addr_bits: usize) -> usize {
    match addr_bits {
        0..=DP16KD_ADDR_BITS => DP16KD_WIDTH,
        11 => 9,
        12 => 4,
        13 => 2,
        DP16KD_MAX_ADDR_BITS => 1,
        _ => panic!("at most 16384 words per DP16KD"),
    }
}

/// The `DP16KD`s of a [`BlockRam`] of `data_bits` bits and `2^addr_bits`
/// words.
pub const fn dp16kd_count(data_bits: usize, addr_bits: usize) -> usize {
    data_bits.div_ceil(dp16kd_mode(addr_bits))
}

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
    /// The initial words, if not zero.
    _words: Option<Vec<u64>>,
}

impl<const D: usize, const A: usize> BlockRam<D, A> {
    /// A RAM that starts with `words` (word `i` at address `i`; missing
    /// words are 0).
    ///
    /// # Panics
    /// If there are more than `2^A` words, a word has more than `D` bits,
    /// or `A` is more than the 18-bit mode's [`DP16KD_ADDR_BITS`] (initial
    /// words are laid out for that mode only; a generation-time parameter
    /// error).
    pub(crate) fn with_words(words: Vec<u64>) -> Self {
        assert!(A <= DP16KD_ADDR_BITS, "initial words in at most {} words", 1 << DP16KD_ADDR_BITS);
        assert!(words.len() <= 1 << A, "{} words behind a {A}-bit address", words.len());
        assert!(D < 64 && words.iter().all(|&w| w >> D == 0), "a word wider than {D} bits");
        BlockRam { ram: RAM::from(words.iter().map(|&w| Bits::<D>::from(w))), _words: Some(words), ..Default::default() }
    }
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
        Verilog::Wrapper(Wrapper { code: dp16kd_instances(D, A, self._words.as_deref()), cores: String::new() })
    }
}

/// Words of the 18-bit mode in one `INITVAL_xx` parameter (320 bits: a word
/// in the low 18 bits of each 20, as Yosys's `synth_ecp5` lays a memory's
/// initial words out, `techlibs/lattice/brams_map_16kd.v`).
const INITVAL_WORDS: usize = 16;
/// Hex digits of one word's place (20 bits) in an `INITVAL_xx` parameter.
const INITVAL_SLOT_DIGITS: usize = 5;
/// The `INITVAL_xx` parameters of a `DP16KD`.
const INITVAL_ROWS: usize = (1 << DP16KD_ADDR_BITS) / INITVAL_WORDS;

/// The `INITVAL_00` to `INITVAL_3F` parameters of the 18-bit-mode
/// `DP16KD` that holds bits `lo .. lo + 18` of `words` (word `i` at address
/// `i`): row `r` holds words `16·r .. 16·r + 16`, word `16·r + k` in bits
/// `20·k .. 20·k + 18`.
pub fn initvals(words: &[u64], lo: usize) -> String {
    assert!(words.len() <= 1 << DP16KD_ADDR_BITS, "at most 1024 words in the 18-bit mode");
    (0..INITVAL_ROWS)
        .map(|r| {
            // A slot of five hex digits a word, the highest slot first.
            let digits: String = (0..INITVAL_WORDS)
                .rev()
                .map(|k| {
                    let word = words.get(r * INITVAL_WORDS + k).map_or(0, |&w| (w >> lo) & ((1 << DP16KD_WIDTH) - 1));
                    format!("{word:0width$X}", width = INITVAL_SLOT_DIGITS)
                })
                .collect();
            format!(".INITVAL_{r:02X}(320'h{digits})")
        })
        .collect::<Vec<_>>()
        .join(",\n    ")
}

/// The Verilog body: [`dp16kd_count`]`(d, a)` `DP16KD`s side by side in
/// the mode [`dp16kd_mode`]`(a)`, port A writing, port B reading through
/// its output register; with `words`, those as the RAMs' initial words
/// (the 18-bit mode only). The word address is on `AD[13:14-a']` for the mode's
/// `a'` address bits (`AD[13:4]` in the 18-bit mode, `AD[13:3]` in the
/// 9-bit one, and so on), the bits below it tied off, except that in the
/// 18-bit mode `AD[1:0]` are a write's byte enables (both set); a word's
/// bits are on `DI[w-1:0]` and `DO[w-1:0]` (as Yosys's `synth_ecp5` maps
/// the modes, `techlibs/lattice/brams_map_16kd.v`).
fn dp16kd_instances(d: usize, a: usize, words: Option<&[u64]>) -> String {
    let width = dp16kd_mode(a);
    assert!(words.is_none() || width == DP16KD_WIDTH, "initial words in the 18-bit mode only");
    let mode_addr_bits = a.max(DP16KD_ADDR_BITS);
    let low = DP16KD_MAX_ADDR_BITS - mode_addr_bits;
    let addr = |name: &str, port: &str| -> String {
        let mut pins = Vec::new();
        for k in 0..mode_addr_bits {
            let bit = if k < a { format!("{name}[{k}]") } else { "1'b0".to_string() };
            pins.push(format!(".AD{port}{}({bit})", k + low));
        }
        for k in (0..low).rev() {
            let be = width == DP16KD_WIDTH && k < 2 && port == "A";
            pins.push(format!(".AD{port}{k}({})", if be { "1'b1" } else { "1'b0" }));
        }
        pins.join(", ")
    };
    let mut code = String::new();
    let n = dp16kd_count(d, a);
    for i in 0..n {
        let lo = i * width;
        let w = (d - lo).min(width);
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
    .DATA_WIDTH_A({width}), .DATA_WIDTH_B({width}),
    .REGMODE_A("NOREG"), .REGMODE_B("OUTREG"),
    .RESETMODE("SYNC"), .ASYNC_RESET_RELEASE("SYNC"),
    .CSDECODE_A("0b000"), .CSDECODE_B("0b000"),
    .WRITEMODE_A("NORMAL"), .WRITEMODE_B("NORMAL"),
    .GSR("AUTO"){init}
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
            init = words.map_or(String::new(), |words| format!(",\n    {}", initvals(words, lo))),
            addr_a = addr("write_address", "A"),
            addr_b = addr("read_address", "B"),
            di = di.join(", "),
            dout = dout.join(", "),
        ));
    }
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each mode is one of the primitive's (`DATA_WIDTH` 18, 9, 4, 2, 1 of
    /// 1024 to 16384 words), holds the depth, and the instances hold the
    /// width; the word address takes the mode's top address pins.
    #[test]
    fn each_depth_takes_the_widest_mode_that_holds_it() {
        let modes: Vec<(usize, usize)> = (0..=DP16KD_MAX_ADDR_BITS).map(|a| (a, dp16kd_mode(a))).collect();
        assert_eq!(&modes[9..], &[(9, 18), (10, 18), (11, 9), (12, 4), (13, 2), (14, 1)]);
        for a in 0..=DP16KD_MAX_ADDR_BITS {
            let w = dp16kd_mode(a);
            // 1024 x 18, 2048 x 9, 4096 x 4, ...: 16 Kbit of data, 18 Kbit in the 18- and 9-bit modes.
            assert!((w << a.max(DP16KD_ADDR_BITS)) <= 18 * 1024, "{a}: {w}");
            assert_eq!(dp16kd_count(20, a), 20usize.div_ceil(w));
        }
        let v = dp16kd_instances(8, 11, None);
        assert_eq!(v.matches("DP16KD #(").count(), 1);
        assert!(v.contains(".DATA_WIDTH_A(9), .DATA_WIDTH_B(9)"));
        assert!(v.contains(".ADA3(write_address[0])") && v.contains(".ADA13(write_address[10])") && v.contains(".ADA2(1'b0)"));
        assert!(v.contains(".DOB7(read_data[7])") && !v.contains(".DOB8("));
        let v = dp16kd_instances(15, 10, None);
        assert!(v.contains(".ADA4(write_address[0])") && v.contains(".ADA1(1'b1), .ADA0(1'b1)") && v.contains(".ADB1(1'b0), .ADB0(1'b0)"));
    }

    /// A RAM given words reads each two clocks after its address.
    #[test]
    fn a_word_given_reads_two_clocks_after_its_address() {
        let table: Vec<u64> = (0..8).map(|i| (i * 37 + 5) & 0x3f).collect();
        let mut r = BlockRam::<6, 3>::with_words(table.clone());
        r.connect_all();
        for a in [5u64, 0, 7, 3] {
            r.read_address.next = a.into();
            assert!(simulate(&mut r, 100));
            crate::tick(&mut r, |u| &mut u.clock);
            r.read_address.next = 1.into();
            crate::tick(&mut r, |u| &mut u.clock);
            assert_eq!(r.read_data.val(), Bits::<6>::from(table[a as usize]), "address {a}");
        }
    }

    /// The Verilog holds word `16·r + k` in bits `20·k ..` of `INITVAL_r`:
    /// word 17 = 0x3 is the second slot of
    /// `INITVAL_01` (hex digits 5 to 9 from the right), word 0 = 0x3FFFF
    /// fills the first slot of `INITVAL_00`; a table of 20 bits takes two
    /// RAMs, the second holding the words' top two bits.
    #[test]
    fn the_verilog_holds_the_words_given_as_the_rams_initial_words() {
        let mut table = vec![0u64; 32];
        table[0] = 0x3_FFFF;
        table[17] = 0x3;
        let v = dp16kd_instances(18, 5, Some(&table));
        assert_eq!(v.matches("DP16KD #(").count(), 1);
        assert!(v.contains(&format!(".INITVAL_00(320'h{}3FFFF)", "0".repeat(75))), "{v}");
        assert!(v.contains(&format!(".INITVAL_01(320'h{}0000300000)", "0".repeat(70))), "{v}");
        assert!(v.contains(&format!(".INITVAL_3F(320'h{})", "0".repeat(80))), "{v}");
        assert!(v.contains(".ADB4(read_address[0])") && v.contains(".DOB17(read_data[17])"), "{v}");
        let table: Vec<u64> = (0..4).map(|i| i << 18).collect();
        let v = dp16kd_instances(20, 2, Some(&table));
        assert_eq!(v.matches("DP16KD #(").count(), 2);
        let second = v.split("ram_0").nth(1).expect("a second RAM after the first");
        assert!(second.contains(&format!(".INITVAL_00(320'h{}00003000020000100000)", "0".repeat(60))), "{v}");
    }
}
