//! The division of eq. 3 as a pipelined restoring divider.
//!
//! Eq. 3 places a declivity at `X_i = Σ g²(x + ½) / Σ g²`. The tracker
//! accumulates the two integer sums `S0 = Σ g²` and `S1 = Σ g²(2x + 1)`
//! (twice the numerator), so that
//!
//! ```text
//! X_i · 2^POS_FRAC_BITS = S1 · 2^(POS_FRAC_BITS - 1) / S0
//! ```
//!
//! and this block returns its floor, `⌊X_i · 2^POS_FRAC_BITS⌋`: a position
//! with [`POS_FRAC_BITS`] fraction bits, below golden's f64 value by less than
//! one LSB. rust-hdl has no divider; this one is long division, one quotient
//! bit per pipeline stage, so it accepts a division every clock.
//!
//! ## Ports
//! - `in_valid`, `in_dividend` (`S1 · 2^(POS_FRAC_BITS-1)`, [`DIVIDEND_BITS`]),
//!   `in_divisor` (`S0 > 0`, [`S0_BITS`]) and four 32-bit tag lanes
//!   `in_tag0..3` that travel with the division untouched.
//! - `out_valid`, `out_quotient` ([`POS_BITS`]) and `out_tag0..3`.
//!
//! ## Timing
//! Latency [`DIVIDER_LATENCY`] = [`POS_BITS`] clocks (one per quotient bit),
//! throughput one division per clock, no back-pressure: a bubble
//! (`in_valid` low) travels through as a bubble. The tags wait in four small
//! RAMs written every clock and read [`POS_BITS`] clocks later (distributed
//! RAM instead of `4 × 32 × POS_BITS` flip-flops). The quotient must fit in
//! [`POS_BITS`] bits, which holds for any position `X_i < W_MAX`: then
//! `dividend >> POS_BITS < divisor`. A zero divisor gives an all-ones
//! quotient (it never happens on a declivity, which has a non-zero gradient).

use crate::params::*;
use rust_hdl::prelude::*;

/// Clocks from a division entering to its quotient leaving.
pub const DIVIDER_LATENCY: usize = POS_BITS;
/// Bits of a trial remainder: one above the divisor.
pub const TRIAL_BITS: usize = S0_BITS + 1;

/// One step of long division: shift the next dividend bit into the
/// remainder, subtract the divisor if it fits; the dividend's remaining low
/// bits and the quotient share one register (`lq`), bits leaving at the top
/// as quotient bits enter at the bottom. The result is registered.
#[derive(LogicBlock)]
pub struct DivisionStep {
    pub clock: Signal<In, Clock>,
    pub in_valid: Signal<In, Bit>,
    pub in_rem: Signal<In, Bits<S0_BITS>>,
    pub in_lq: Signal<In, Bits<POS_BITS>>,
    pub in_den: Signal<In, Bits<S0_BITS>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_rem: Signal<Out, Bits<S0_BITS>>,
    pub out_lq: Signal<Out, Bits<POS_BITS>>,
    pub out_den: Signal<Out, Bits<S0_BITS>>,
    valid: DFF<Bit>,
    rem: DFF<Bits<S0_BITS>>,
    lq: DFF<Bits<POS_BITS>>,
    den: DFF<Bits<S0_BITS>>,
    trial: Signal<Local, Bits<TRIAL_BITS>>,
    divisor: Signal<Local, Bits<TRIAL_BITS>>,
    msb: Constant<Bits<8>>,
}

impl Default for DivisionStep {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            in_valid: Default::default(),
            in_rem: Default::default(),
            in_lq: Default::default(),
            in_den: Default::default(),
            out_valid: Default::default(),
            out_rem: Default::default(),
            out_lq: Default::default(),
            out_den: Default::default(),
            valid: Default::default(),
            rem: Default::default(),
            lq: Default::default(),
            den: Default::default(),
            trial: Default::default(),
            divisor: Default::default(),
            msb: Constant::new(((POS_BITS - 1) as u64).into()),
        }
    }
}

impl Logic for DivisionStep {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid, rem, lq, den);
        self.out_valid.next = self.valid.q.val();
        self.out_rem.next = self.rem.q.val();
        self.out_lq.next = self.lq.q.val();
        self.out_den.next = self.den.q.val();
        self.valid.d.next = self.in_valid.val();
        self.den.d.next = self.in_den.val();
        // Doubling by addition: rust-hdl 0.46 simulates shifts through big
        // integers, additions natively (the Verilog is the same).
        self.trial.next = bit_cast::<TRIAL_BITS, S0_BITS>(self.in_rem.val())
            + bit_cast::<TRIAL_BITS, S0_BITS>(self.in_rem.val())
            + bit_cast::<TRIAL_BITS, 1>(self.in_lq.val().get_bit(self.msb.val().index()).into());
        self.divisor.next = bit_cast::<TRIAL_BITS, S0_BITS>(self.in_den.val());
        if self.trial.val() >= self.divisor.val() {
            self.rem.d.next = bit_cast::<S0_BITS, TRIAL_BITS>(self.trial.val() - self.divisor.val());
            self.lq.d.next = self.in_lq.val() + self.in_lq.val() + 1;
        } else {
            self.rem.d.next = bit_cast::<S0_BITS, TRIAL_BITS>(self.trial.val());
            self.lq.d.next = self.in_lq.val() + self.in_lq.val();
        }
    }
}

/// Address bits of the tag delay RAMs: 2^TAG_ADDR_BITS > DIVIDER_LATENCY.
const TAG_ADDR_BITS: usize = 4;

/// The pipelined divider: [`POS_BITS`] [`DivisionStep`]s in a row, the tags
/// beside them in RAM.
#[derive(LogicBlock)]
pub struct PositionDivider {
    pub clock: Signal<In, Clock>,
    pub in_valid: Signal<In, Bit>,
    pub in_dividend: Signal<In, Bits<DIVIDEND_BITS>>,
    pub in_divisor: Signal<In, Bits<S0_BITS>>,
    pub in_tag0: Signal<In, Bits<32>>,
    pub in_tag1: Signal<In, Bits<32>>,
    pub in_tag2: Signal<In, Bits<32>>,
    pub in_tag3: Signal<In, Bits<32>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_quotient: Signal<Out, Bits<POS_BITS>>,
    pub out_tag0: Signal<Out, Bits<32>>,
    pub out_tag1: Signal<Out, Bits<32>>,
    pub out_tag2: Signal<Out, Bits<32>>,
    pub out_tag3: Signal<Out, Bits<32>>,
    steps: [DivisionStep; POS_BITS],
    tags0: RAM<Bits<32>, TAG_ADDR_BITS>,
    tags1: RAM<Bits<32>, TAG_ADDR_BITS>,
    tags2: RAM<Bits<32>, TAG_ADDR_BITS>,
    tags3: RAM<Bits<32>, TAG_ADDR_BITS>,
    /// Write pointer; the read pointer trails it by `DIVIDER_LATENCY - 1`
    /// (the read is synchronous).
    wptr: DFF<Bits<TAG_ADDR_BITS>>,
    quotient_bits: Constant<Bits<8>>,
    read_lag: Constant<Bits<TAG_ADDR_BITS>>,
}

impl Default for PositionDivider {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            in_valid: Default::default(),
            in_dividend: Default::default(),
            in_divisor: Default::default(),
            in_tag0: Default::default(),
            in_tag1: Default::default(),
            in_tag2: Default::default(),
            in_tag3: Default::default(),
            out_valid: Default::default(),
            out_quotient: Default::default(),
            out_tag0: Default::default(),
            out_tag1: Default::default(),
            out_tag2: Default::default(),
            out_tag3: Default::default(),
            steps: core::array::from_fn(|_| Default::default()),
            tags0: Default::default(),
            tags1: Default::default(),
            tags2: Default::default(),
            tags3: Default::default(),
            wptr: Default::default(),
            quotient_bits: Constant::new((POS_BITS as u64).into()),
            read_lag: Constant::new(((DIVIDER_LATENCY - 1) as u64).into()),
        }
    }
}

impl Logic for PositionDivider {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..POS_BITS {
            self.steps[k].clock.next = self.clock.val();
        }
        self.tags0.read_clock.next = self.clock.val();
        self.tags0.write_clock.next = self.clock.val();
        self.tags1.read_clock.next = self.clock.val();
        self.tags1.write_clock.next = self.clock.val();
        self.tags2.read_clock.next = self.clock.val();
        self.tags2.write_clock.next = self.clock.val();
        self.tags3.read_clock.next = self.clock.val();
        self.tags3.write_clock.next = self.clock.val();
        dff_setup!(self, clock, wptr);
        // The dividend's bits above the quotient's are the first remainder
        // (smaller than the divisor when the quotient fits).
        // (Only on a valid item: rust-hdl simulates shifts slowly.)
        self.steps[0].in_valid.next = self.in_valid.val();
        self.steps[0].in_rem.next = 0.into();
        self.steps[0].in_lq.next = 0.into();
        if self.in_valid.val() {
            self.steps[0].in_rem.next = bit_cast::<S0_BITS, DIVIDEND_BITS>(self.in_dividend.val() >> self.quotient_bits.val());
            self.steps[0].in_lq.next = bit_cast::<POS_BITS, DIVIDEND_BITS>(self.in_dividend.val());
        }
        self.steps[0].in_den.next = self.in_divisor.val();
        for k in 1..POS_BITS {
            self.steps[k].in_valid.next = self.steps[k - 1].out_valid.val();
            self.steps[k].in_rem.next = self.steps[k - 1].out_rem.val();
            self.steps[k].in_lq.next = self.steps[k - 1].out_lq.val();
            self.steps[k].in_den.next = self.steps[k - 1].out_den.val();
        }
        // Tags: written every clock, read DIVIDER_LATENCY - 1 clocks later
        // so they leave with their quotient.
        self.wptr.d.next = self.wptr.q.val() + 1;
        self.tags0.write_address.next = self.wptr.q.val();
        self.tags1.write_address.next = self.wptr.q.val();
        self.tags2.write_address.next = self.wptr.q.val();
        self.tags3.write_address.next = self.wptr.q.val();
        self.tags0.write_enable.next = true;
        self.tags1.write_enable.next = true;
        self.tags2.write_enable.next = true;
        self.tags3.write_enable.next = true;
        self.tags0.write_data.next = self.in_tag0.val();
        self.tags1.write_data.next = self.in_tag1.val();
        self.tags2.write_data.next = self.in_tag2.val();
        self.tags3.write_data.next = self.in_tag3.val();
        self.tags0.read_address.next = self.wptr.q.val() - self.read_lag.val();
        self.tags1.read_address.next = self.wptr.q.val() - self.read_lag.val();
        self.tags2.read_address.next = self.wptr.q.val() - self.read_lag.val();
        self.tags3.read_address.next = self.wptr.q.val() - self.read_lag.val();
        for k in (POS_BITS - 1)..POS_BITS {
            self.out_valid.next = self.steps[k].out_valid.val();
            self.out_quotient.next = self.steps[k].out_lq.val();
        }
        self.out_tag0.next = self.tags0.read_data.val();
        self.out_tag1.next = self.tags1.read_data.val();
        self.out_tag2.next = self.tags2.read_data.val();
        self.out_tag3.next = self.tags3.read_data.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clock(uut: &mut PositionDivider) {
        crate::tick(uut, |u| &mut u.clock);
    }

    #[test]
    fn quotients_are_floors_of_the_exact_division_one_per_clock() {
        let mut uut = PositionDivider::default();
        uut.connect_all();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut cases = Vec::new();
        for _ in 0..500 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let s0 = 1 + seed % 65025;
            let x = (seed >> 20) % (W_MAX as u64 * 16);
            // A dividend whose quotient is x (plus a remainder below s0).
            let dividend = x * s0 + (seed >> 40) % s0;
            cases.push((dividend, s0, x));
        }
        let mut got = Vec::new();
        for cycle in 0..cases.len() + DIVIDER_LATENCY {
            if let Some(&(n, d, _)) = cases.get(cycle) {
                uut.in_valid.next = true;
                uut.in_dividend.next = (n as u64).into();
                uut.in_divisor.next = d.into();
                uut.in_tag0.next = (cycle as u64).into();
            } else {
                uut.in_valid.next = false;
            }
            assert!(simulate(&mut uut, 100));
            if uut.out_valid.val() {
                got.push((uut.out_tag0.val().to_u64(), uut.out_quotient.val().to_u64()));
            }
            clock(&mut uut);
        }
        assert_eq!(got.len(), cases.len());
        for (i, &(tag, q)) in got.iter().enumerate() {
            assert_eq!(tag, i as u64, "in order");
            assert_eq!(q, cases[i].2, "{:?}", cases[i]);
        }
    }

    #[test]
    fn verilog_generates() {
        let mut uut = PositionDivider::default();
        uut.connect_all();
        let v = generate_verilog(&uut);
        assert!(v.contains("module top"));
        if let Ok(path) = std::env::var("DUMP_VERILOG") {
            std::fs::write(path, &v).unwrap();
        }
    }
}
