//! A table in LUTs: a read-only memory whose read address is registered and
//! whose word comes out of logic, one function of the address per data bit.
//!
//! Yosys maps a rust-hdl `SyncROM` of a few hundred words to an ECP5 block
//! RAM without its output register, whose clock-to-out takes most of a
//! clock period, too much for a path from the table into another memory
//! (the interpolator's reciprocal table into its segment memory). Here the
//! address is the register and the table is logic after it (LUT4s and the
//! slices' `PFUMX`/`L6MUX21`, five levels for a 9-bit address), which the
//! reader takes on the same clock, best into a register beside it (the
//! interpolator's `s4_recip`, not straight into the segment memory, which
//! may be placed far off). No
//! memory is declared in the Verilog, so Yosys cannot turn it back into a
//! block RAM: each bit is a constant vector indexed by the address.
//!
//! ## Ports
//! - `clock`, `address` (in), `data` (out).
//!
//! ## Timing
//! `data` is the word at the `address` of the previous clock, exactly as a
//! rust-hdl `SyncROM`; before the first clock it is word 0 (the address
//! register starts at 0, in the model and in the Verilog). Throughput one
//! read per clock. The model is the register and a table lookup. No reset
//! beyond the address register's initial value.
//!
//! No paper equation: a memory primitive.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub(crate) struct LogicRom<const D: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    pub address: Signal<In, Bits<A>>,
    pub data: Signal<Out, Bits<D>>,
    addr_q: DFF<Bits<A>>,
    _table: Vec<u64>,
}

impl<const D: usize, const A: usize> LogicRom<D, A> {
    /// The table, word `i` at address `i`; missing words are 0.
    ///
    /// # Panics
    /// If the table has more than `2^A` words or a word more than `D` bits
    /// (a generation-time parameter error).
    pub(crate) fn new(table: Vec<u64>) -> Self {
        assert!(table.len() <= 1 << A, "a table of {} words behind a {A}-bit address", table.len());
        assert!(D <= 64 && table.iter().all(|&w| D == 64 || w >> D == 0), "a word wider than {D} bits");
        let mut words = table;
        words.resize(1 << A, 0);
        LogicRom {
            clock: Default::default(),
            address: Default::default(),
            data: Default::default(),
            addr_q: Default::default(),
            _table: words,
        }
    }
}

impl<const D: usize, const A: usize> Logic for LogicRom<D, A> {
    fn update(&mut self) {
        self.addr_q.clock.next = self.clock.val();
        self.addr_q.d.next = self.address.val();
        self.data.next = self._table[self.addr_q.q.val().index()].into();
    }

    fn connect(&mut self) {
        self.addr_q.clock.connect();
        self.addr_q.d.connect();
        self.data.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Wrapper(Wrapper { code: table_logic(&self._table, D, A), cores: String::new() })
    }
}

/// The Verilog body: the address register, then one constant vector of
/// `2^a` bits per data bit (bit `i` of vector `k` is bit `k` of word `i`),
/// indexed by the registered address.
fn table_logic(words: &[u64], d: usize, a: usize) -> String {
    let mut code = format!("reg [{top}:0] addr_q = {a}'d0;\nalways @(posedge clock) addr_q <= address;\n", top = a - 1);
    let n = 1usize << a;
    for k in 0..d {
        // Hex digits, most significant (highest address) first.
        let digits: String = (0..n.div_ceil(4))
            .rev()
            .map(|g| {
                let nibble = (0..4).filter(|&b| 4 * g + b < n).fold(0u32, |acc, b| acc | ((((words[4 * g + b] >> k) & 1) as u32) << b));
                char::from_digit(nibble, 16).expect("a nibble")
            })
            .collect();
        code.push_str(&format!("localparam [{hi}:0] BIT_{k} = {n}'h{digits};\nassign data[{k}] = BIT_{k}[addr_q];\n", hi = n - 1));
    }
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The word shows a clock after its address, and is the table's word.
    #[test]
    fn a_word_reads_a_clock_after_its_address() {
        let table: Vec<u64> = (0..8).map(|i| (i * 37 + 5) & 0x3f).collect();
        let mut r = LogicRom::<6, 3>::new(table.clone());
        r.connect_all();
        for a in [5u64, 0, 7, 3] {
            r.address.next = a.into();
            assert!(simulate(&mut r, 100));
            crate::tick(&mut r, |u| &mut u.clock);
            assert_eq!(r.data.val(), Bits::<6>::from(table[a as usize]), "address {a}");
        }
    }

    /// Bit `i` of vector `k` is bit `k` of word `i`: word 1 = 0b10 sets bit 1
    /// of `BIT_1` (hex digit 2) and nothing in `BIT_0`.
    #[test]
    fn the_verilog_holds_each_data_bit_as_a_vector_over_the_addresses() {
        let v = table_logic(&[0, 2, 0, 0, 0, 0, 0, 1], 2, 3);
        assert!(v.contains("localparam [7:0] BIT_0 = 8'h80;"), "{v}");
        assert!(v.contains("localparam [7:0] BIT_1 = 8'h02;"), "{v}");
        assert!(v.contains("assign data[1] = BIT_1[addr_q];"), "{v}");
        assert!(!v.contains("mem"), "no memory for Yosys to map: {v}");
    }
}
