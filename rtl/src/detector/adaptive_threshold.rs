//! The self-adaptive threshold of paper eq. 2, `d_t = 5.6 σ`, with σ from the
//! line itself by the estimator of `DESIGN.md` §2.1 (golden `noise`): the
//! median `m` of `|I(x+1) - I(x)|` interpolated inside its bin, and
//! `d_t = max(K·m, 5.6/√12)` with `K = 5.6/(0.6745·√2)`.
//!
//! Two histogram banks in block RAM ([`HIST_BINS`] counts of
//! [`HIST_COUNT_BITS`] bits each) let one line be counted while the line
//! before is scanned. Each is a [`BlockRam`], whose read's output register
//! is the `DP16KD`'s own: the RAM's clock-to-out is most of a clock
//! period, so neither the route to a register in the fabric nor the
//! count's increment follows it in the same clock.
//!
//! ## Ports
//! - Counting: `inc_valid`, `inc_bank`, `inc_bin` (one |ΔI| per clock, any
//!   bin sequence: a four-clock read-modify-write pipeline — read, block
//!   RAM output register, increment into a register, write from it —
//!   forwards the three writes still in flight when a bin repeats).
//! - Scanning: `scan_start` (a one-clock pulse while `busy` is low) with
//!   `scan_bank` and `scan_n` (the number of differences counted in that bank,
//!   `W - 1`); `busy`; `done` pulses for one clock with `dt` (`d_t` with
//!   [`DT_FRAC_BITS`] fraction bits, [`DT_BITS`] bits) valid, and `dt` holds
//!   until the next scan ends.
//!
//! ## Timing
//! Two clocks after `scan_start` let the last count land; the scan then
//! reads every bin once ([`HIST_BINS`] + 3 clocks: the synchronous read, the
//! output register and the running count add three), clears it behind itself so the bank is ready
//! for the line after next, finds the median bin `v` (the first non-empty bin
//! where the counts reach `n/2`), then divides the in-bin fraction
//! `(n - 2·below) / (2h)` to [`MEDIAN_FRAC_BITS`] bits ([`MEDIAN_Q_BITS`]
//! clocks, one bit each) and scales it (3 clocks):
//! `done` comes [`THRESHOLD_LATENCY`] clocks after `scan_start`, whatever the
//! line. A bank must not be counted into while it is being scanned.
//! `inc_valid` low counts nothing. The block starts idle with both banks
//! empty (Verilog initial values, all zero). `reset` (synchronous, active
//! high) returns it to idle and then clears both banks, one bin of each a
//! clock: `clearing` is high for [`HIST_BINS`] clocks after the reset's
//! last clock, and nothing may be counted meanwhile ([`CLEAR_CLOCKS`]).
//!
//! ## Fixed point
//! `K·m·2^20` is the sum of `(2v - 1)·round(K·2^19)` (accumulated bin by bin
//! during the scan) and `q·round(K·2^13) / 2^8` (`q` the 16-bit fraction,
//! halved again in bin 0, whose width is ½); rounding to 5 fraction bits then
//! leaves `d_t` within half an LSB plus about 0.001 of golden's f64 value.
//! The floor `5.6/√12` is [`DT_FLOOR`]; a line of one pixel (`n = 0`) gets it.

use crate::primitives::block_ram::BlockRam;
use crate::primitives::dsp_multiplier::{DspMultiplier, MUL_OPERAND_BITS, MUL_PRODUCT_BITS};
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from `scan_start` to `done`: three to start (the last count of
/// the line lands), [`HIST_BINS`] + 3 to read, count and test every bin,
/// [`MEDIAN_Q_BITS`] to divide, 3 to scale (product, sum, rounding).
pub const THRESHOLD_LATENCY: usize = 3 + HIST_BINS + 3 + MEDIAN_Q_BITS + 3;

/// Clocks after a reset during which the banks are cleared (`clearing`).
pub const CLEAR_CLOCKS: usize = HIST_BINS;

/// Bits of the scan counter `0 ..= HIST_BINS + 1`.
const SCAN_BITS: usize = HIST_ADDR_BITS + 2;
/// Bits of the division's running remainder: below twice the divisor.
const REM_BITS: usize = HIST_COUNT_BITS + 1;
/// Bits of the division's step counter.
const STEP_BITS: usize = 5;
/// Bits of `need`, `n - 1 - 2·cum` in two's complement: from `n - 1` down
/// to `-n - 1`.
const NEED_BITS: usize = HIST_COUNT_BITS + 1;
/// The shift from `q·K` (`MEDIAN_FRAC_BITS + K_FRAC_BITS` fraction bits) to
/// the accumulator's [`DT_ACC_FRAC_BITS`].
const FRAC_SHIFT: usize = MEDIAN_FRAC_BITS + K_FRAC_BITS - DT_ACC_FRAC_BITS;
/// Bits of the sum `term1·2^FRAC_SHIFT + q·K` before its shift to the
/// accumulator's format.
const WIDE_BITS: usize = DT_ACC_BITS + FRAC_SHIFT;
/// The Round stage's floor test on the sum: `⌊(sum + ½) / 2^s⌋ < DT_FLOOR`
/// (s = `DT_ACC_FRAC_BITS - DT_FRAC_BITS`) ⇔ `sum < DT_FLOOR·2^s - ½·2^s`.
const FLOOR_SUM: u64 = (DT_FLOOR << (DT_ACC_FRAC_BITS - DT_FRAC_BITS)) - (1 << (DT_ACC_FRAC_BITS - DT_FRAC_BITS - 1));
const _: () = assert!(FLOOR_SUM < 1 << DT_ACC_BITS);

#[derive(Copy, Clone, Debug, PartialEq, LogicState)]
enum ThresholdState {
    Idle,
    Settle,
    Settle2,
    Scan,
    Divide,
    Scale,
    Sum,
    Round,
}

#[derive(LogicBlock)]
pub(crate) struct AdaptiveThreshold {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub inc_valid: Signal<In, Bit>,
    pub inc_bank: Signal<In, Bit>,
    pub inc_bin: Signal<In, Bits<HIST_ADDR_BITS>>,
    pub scan_start: Signal<In, Bit>,
    pub scan_bank: Signal<In, Bit>,
    pub scan_n: Signal<In, Bits<HIST_COUNT_BITS>>,
    pub busy: Signal<Out, Bit>,
    /// High while the banks are cleared after a reset; nothing may be
    /// counted meanwhile.
    pub clearing: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    pub dt: Signal<Out, Bits<DT_BITS>>,
    hist0: BlockRam<HIST_COUNT_BITS, HIST_ADDR_BITS>,
    hist1: BlockRam<HIST_COUNT_BITS, HIST_ADDR_BITS>,
    // The sweep that clears both banks after a reset (a reset can cut a
    // line's counting or a scan short, leaving counts behind): it is set by
    // `reset` itself, not reset to its power-up value, because the banks
    // are already empty after configuration.
    sweeping: ResetDff<Bit>,
    sweep_bin: ResetDff<Bits<HIST_ADDR_BITS>>,
    // Counting pipeline: the increments whose read is under way (p1: read
    // issued last clock; p2: data in the output register), the count being
    // written (f1: its bin, bank and new count in registers, on the RAM's
    // write port), and the counts written one and two clocks ago (f2, f3),
    // forwarded to a repeated bin. The increment is registered in f1 and
    // written on the next clock, so that the RAM's output, the forwarding,
    // the increment and the route back into the RAM are not in one clock.
    p1_valid: ResetDff<Bit>,
    p1_bank: ResetDff<Bit>,
    p1_bin: ResetDff<Bits<HIST_ADDR_BITS>>,
    p2_valid: ResetDff<Bit>,
    p2_bank: ResetDff<Bit>,
    p2_bin: ResetDff<Bits<HIST_ADDR_BITS>>,
    f1_valid: ResetDff<Bit>,
    f1_bank: ResetDff<Bit>,
    f1_bin: ResetDff<Bits<HIST_ADDR_BITS>>,
    f1_count: ResetDff<Bits<HIST_COUNT_BITS>>,
    hit1: ResetDff<Bit>,
    hit2: ResetDff<Bit>,
    hit3: ResetDff<Bit>,
    f2_valid: ResetDff<Bit>,
    f2_bank: ResetDff<Bit>,
    f2_bin: ResetDff<Bits<HIST_ADDR_BITS>>,
    f2_count: ResetDff<Bits<HIST_COUNT_BITS>>,
    f3_valid: ResetDff<Bit>,
    f3_bank: ResetDff<Bit>,
    f3_bin: ResetDff<Bits<HIST_ADDR_BITS>>,
    f3_count: ResetDff<Bits<HIST_COUNT_BITS>>,
    new_count: Signal<Local, Bits<HIST_COUNT_BITS>>,
    // Scan.
    state: ResetDff<ThresholdState>,
    bank: ResetDff<Bit>,
    n: ResetDff<Bits<HIST_COUNT_BITS>>,
    cnt: ResetDff<Bits<SCAN_BITS>>,
    cum: ResetDff<Bits<HIST_COUNT_BITS>>,
    hv: ResetDff<Bits<HIST_COUNT_BITS>>,
    hv_nz: ResetDff<Bit>,
    counting: ResetDff<Bit>,
    testing: ResetDff<Bit>,
    first_test: ResetDff<Bit>,
    last_test: ResetDff<Bit>,
    found: ResetDff<Bit>,
    zero_bin: ResetDff<Bit>,
    term1: ResetDff<Bits<DT_ACC_BITS>>,
    ramp: ResetDff<Bits<DT_ACC_BITS>>,
    den: ResetDff<Bits<HIST_COUNT_BITS>>,
    rem: ResetDff<Bits<REM_BITS>>,
    quotient: ResetDff<Bits<MEDIAN_Q_BITS>>,
    step: ResetDff<Bits<STEP_BITS>>,
    // `q·K` in a DSP block, as `(q >> 1 << 1)·K + q[0]·K`: the block's
    // input registers are loaded on the last Divide clock with the quotient
    // register shifted (its last bit still being decided), so the product
    // is out in Scale, and the last bit's comparison and the route to the
    // DSP column are not in one clock. Scale also forms `addend`,
    // `term1·2^FRAC_SHIFT + q[0]·K` (`q[0]·K` alone in bin 0, which has no
    // `term1`), so that Sum is one adder, `(product + addend) >> FRAC_SHIFT`:
    // the same value as `term1 + ((product + q[0]·K) >> FRAC_SHIFT)`
    // without its two adders in series.
    scale: DspMultiplier,
    product: ResetDff<Bits<MUL_PRODUCT_BITS>>,
    addend: ResetDff<Bits<WIDE_BITS>>,
    lsb_k: Signal<Local, Bits<WIDE_BITS>>,
    q_shifted: Signal<Local, Bits<MEDIAN_Q_BITS>>,
    wide_sum: Signal<Local, Bits<WIDE_BITS>>,
    sum: ResetDff<Bits<DT_ACC_BITS>>,
    dt_reg: ResetDff<Bits<DT_BITS>>,
    done_reg: ResetDff<Bit>,
    h: Signal<Local, Bits<HIST_COUNT_BITS>>,
    // Whether the counts reach n/2 at a bin, `2·(cum + h) ≥ n`, decided on
    // the clock that adds the bin: `need` = `n - 1 - 2·cum` is kept as a
    // register, so the test is the sign of `need - 2·h`, and `reach` is
    // that bit registered for the bin's test on the next clock, so that
    // the comparison and the test's fan-out into the division's registers
    // are not in one clock.
    need: ResetDff<Bits<NEED_BITS>>,
    need_next: Signal<Local, Bits<NEED_BITS>>,
    reach: ResetDff<Bit>,
    // `n − 2·below`, `below` the count under the bin tested next: made on
    // the clock that adds that bin to `cum` (from `cum` before the add), so
    // the test loads it into the division from a register instead of
    // forming `cum − hv` and its doubled subtraction (three carry chains in
    // series) on the test's clock.
    num: ResetDff<Bits<HIST_COUNT_BITS>>,
    bin: Signal<Local, Bits<HIST_ADDR_BITS>>,
    acc: Signal<Local, Bits<DT_ACC_BITS>>,
    rounded: Signal<Local, Bits<DT_ACC_BITS>>,
    // A scan starts on this clock (Idle and `scan_start`).
    scan_clear: Signal<Local, Bit>,
    // Constants of the fixed-point scaling.
    k_half: Constant<Bits<DT_ACC_BITS>>,
    k_frac: Constant<Bits<MUL_OPERAND_BITS>>,
    dt_floor: Constant<Bits<DT_ACC_BITS>>,
    round_half: Constant<Bits<DT_ACC_BITS>>,
    floor_sum: Constant<Bits<DT_ACC_BITS>>,
    round_shift: Constant<Bits<8>>,
    frac_shift: Constant<Bits<8>>,
    last_step: Constant<Bits<STEP_BITS>>,
    pre_last_scan: Constant<Bits<SCAN_BITS>>,
    k_step: Constant<Bits<DT_ACC_BITS>>,
    need_sign: Constant<Bits<8>>,
    last_bin: Constant<Bits<HIST_ADDR_BITS>>,
}

impl Default for AdaptiveThreshold {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            inc_valid: Default::default(),
            inc_bank: Default::default(),
            inc_bin: Default::default(),
            scan_start: Default::default(),
            scan_bank: Default::default(),
            scan_n: Default::default(),
            busy: Default::default(),
            clearing: Default::default(),
            sweeping: Default::default(),
            sweep_bin: Default::default(),
            done: Default::default(),
            dt: Default::default(),
            hist0: Default::default(),
            hist1: Default::default(),
            p1_valid: Default::default(),
            p1_bank: Default::default(),
            p1_bin: Default::default(),
            p2_valid: Default::default(),
            p2_bank: Default::default(),
            p2_bin: Default::default(),
            f1_valid: Default::default(),
            f1_bank: Default::default(),
            f1_bin: Default::default(),
            f1_count: Default::default(),
            hit1: Default::default(),
            hit2: Default::default(),
            hit3: Default::default(),
            f2_valid: Default::default(),
            f2_bank: Default::default(),
            f2_bin: Default::default(),
            f2_count: Default::default(),
            f3_valid: Default::default(),
            f3_bank: Default::default(),
            f3_bin: Default::default(),
            f3_count: Default::default(),
            new_count: Default::default(),
            state: Default::default(),
            bank: Default::default(),
            n: Default::default(),
            cnt: Default::default(),
            cum: Default::default(),
            hv: Default::default(),
            hv_nz: Default::default(),
            counting: Default::default(),
            testing: Default::default(),
            first_test: Default::default(),
            last_test: Default::default(),
            found: Default::default(),
            zero_bin: Default::default(),
            term1: Default::default(),
            ramp: Default::default(),
            den: Default::default(),
            rem: Default::default(),
            quotient: Default::default(),
            step: Default::default(),
            scale: Default::default(),
            product: Default::default(),
            addend: Default::default(),
            lsb_k: Default::default(),
            q_shifted: Default::default(),
            wide_sum: Default::default(),
            sum: Default::default(),
            dt_reg: Default::default(),
            done_reg: Default::default(),
            h: Default::default(),
            need: Default::default(),
            need_next: Default::default(),
            reach: Default::default(),
            num: Default::default(),
            bin: Default::default(),
            acc: Default::default(),
            scan_clear: Default::default(),
            rounded: Default::default(),
            k_half: Constant::new(K_HALF.into()),
            k_frac: Constant::new(K_FRAC.into()),
            dt_floor: Constant::new(DT_FLOOR.into()),
            round_half: Constant::new((1u64 << (DT_ACC_FRAC_BITS - DT_FRAC_BITS - 1)).into()),
            floor_sum: Constant::new(FLOOR_SUM.into()),
            round_shift: Constant::new(((DT_ACC_FRAC_BITS - DT_FRAC_BITS) as u64).into()),
            frac_shift: Constant::new((FRAC_SHIFT as u64).into()),
            last_step: Constant::new(((MEDIAN_Q_BITS - 1) as u64).into()),
            pre_last_scan: Constant::new((HIST_BINS as u64 + 1).into()),
            k_step: Constant::new((2 * K_HALF).into()),
            need_sign: Constant::new(((NEED_BITS - 1) as u64).into()),
            last_bin: Constant::new(((HIST_BINS - 1) as u64).into()),
        }
    }
}

impl Logic for AdaptiveThreshold {
    #[hdl_gen]
    fn update(&mut self) {
        self.hist0.clock.next = self.clock.val();
        self.hist1.clock.next = self.clock.val();
        dff_setup!(self, clock, sweeping, sweep_bin);
        self.sweeping.reset.next = false;
        self.sweep_bin.reset.next = false;
        dff_setup!(
            self, clock, p1_valid, p1_bank, p1_bin, p2_valid, p2_bank, p2_bin, f1_valid, f1_bank, f1_bin,
            f1_count, hit1, hit2, hit3, f2_valid, f2_bank, f2_bin, f2_count, f3_valid, f3_bank, f3_bin, f3_count, state, bank, n, cnt, cum, num, need, reach, hv, hv_nz, counting, testing, first_test, last_test, found,
            zero_bin, term1, ramp, den, rem, quotient, step, product, addend, sum, dt_reg, done_reg
        );
        self.p1_valid.reset.next = self.reset.val();
        self.p1_bank.reset.next = self.reset.val();
        self.p1_bin.reset.next = self.reset.val();
        self.p2_valid.reset.next = self.reset.val();
        self.p2_bank.reset.next = self.reset.val();
        self.p2_bin.reset.next = self.reset.val();
        self.f1_valid.reset.next = self.reset.val();
        self.f1_bank.reset.next = self.reset.val();
        self.f1_bin.reset.next = self.reset.val();
        self.f1_count.reset.next = self.reset.val();
        self.hit1.reset.next = self.reset.val();
        self.hit2.reset.next = self.reset.val();
        self.hit3.reset.next = self.reset.val();
        self.f2_valid.reset.next = self.reset.val();
        self.f2_bank.reset.next = self.reset.val();
        self.f2_bin.reset.next = self.reset.val();
        self.f2_count.reset.next = self.reset.val();
        self.f3_valid.reset.next = self.reset.val();
        self.f3_bank.reset.next = self.reset.val();
        self.f3_bin.reset.next = self.reset.val();
        self.f3_count.reset.next = self.reset.val();
        self.state.reset.next = self.reset.val();
        self.bank.reset.next = self.reset.val();
        self.n.reset.next = self.reset.val();
        self.num.reset.next = self.reset.val();
        self.need.reset.next = self.reset.val();
        self.reach.reset.next = self.reset.val();
        self.hv_nz.reset.next = self.reset.val();
        self.counting.reset.next = self.reset.val();
        self.testing.reset.next = self.reset.val();
        self.first_test.reset.next = self.reset.val();
        self.last_test.reset.next = self.reset.val();
        self.found.reset.next = self.reset.val();
        self.zero_bin.reset.next = self.reset.val();
        self.ramp.reset.next = self.reset.val();
        self.den.reset.next = self.reset.val();
        self.rem.reset.next = self.reset.val();
        self.quotient.reset.next = self.reset.val();
        self.step.reset.next = self.reset.val();
        self.product.reset.next = self.reset.val();
        self.addend.reset.next = self.reset.val();
        self.sum.reset.next = self.reset.val();
        self.dt_reg.reset.next = self.reset.val();
        self.done_reg.reset.next = self.reset.val();
        // ---- Counting: read on the clock of the increment, the block RAM's
        // output register on the next, the increment into `f1_count` on the
        // third, written from it on the fourth, forwarding the three counts
        // made before when the bin repeats.
        self.p1_valid.d.next = self.inc_valid.val();
        self.p1_bank.d.next = self.inc_bank.val();
        self.p1_bin.d.next = self.inc_bin.val();
        self.p2_valid.d.next = self.p1_valid.q.val();
        self.p2_bank.d.next = self.p1_bank.q.val();
        self.p2_bin.d.next = self.p1_bin.q.val();
        self.hist0.read_address.next = self.inc_bin.val();
        self.hist1.read_address.next = self.inc_bin.val();
        // (Each count is incremented where it comes from, the block RAMs'
        // outputs and the three forwards, and the incremented one picked
        // after: the carry chain starts at the DP16KD's output, not behind
        // the four-way pick.)
        self.new_count.next = self.hist0.read_data.val() + 1;
        if self.p2_bank.q.val() {
            self.new_count.next = self.hist1.read_data.val() + 1;
        }
        // Which writes in flight hold the bin, compared one clock ahead:
        // p1 against p2 (next clock's f1), f1 (next clock's f2) and f2
        // (next clock's f3). Their writes came too late for p2's read: f1
        // writes now, f2 wrote on the clock of the read, f3 after it.
        self.hit1.d.next = self.p2_valid.q.val() & (self.p2_bank.q.val() == self.p1_bank.q.val()) & (self.p2_bin.q.val() == self.p1_bin.q.val());
        self.hit2.d.next = self.f1_valid.q.val() & (self.f1_bank.q.val() == self.p1_bank.q.val()) & (self.f1_bin.q.val() == self.p1_bin.q.val());
        self.hit3.d.next = self.f2_valid.q.val() & (self.f2_bank.q.val() == self.p1_bank.q.val()) & (self.f2_bin.q.val() == self.p1_bin.q.val());
        if self.hit3.q.val() {
            self.new_count.next = self.f3_count.q.val() + 1;
        }
        if self.hit2.q.val() {
            self.new_count.next = self.f2_count.q.val() + 1;
        }
        if self.hit1.q.val() {
            self.new_count.next = self.f1_count.q.val() + 1;
        }
        self.f1_valid.d.next = self.p2_valid.q.val();
        self.f1_bank.d.next = self.p2_bank.q.val();
        self.f1_bin.d.next = self.p2_bin.q.val();
        self.f1_count.d.next = self.new_count.val();
        self.f2_valid.d.next = self.f1_valid.q.val();
        self.f2_bank.d.next = self.f1_bank.q.val();
        self.f2_bin.d.next = self.f1_bin.q.val();
        self.f2_count.d.next = self.f1_count.q.val();
        self.f3_valid.d.next = self.f2_valid.q.val();
        self.f3_bank.d.next = self.f2_bank.q.val();
        self.f3_bin.d.next = self.f2_bin.q.val();
        self.f3_count.d.next = self.f2_count.q.val();
        self.hist0.write_address.next = self.f1_bin.q.val();
        self.hist1.write_address.next = self.f1_bin.q.val();
        self.hist0.write_data.next = self.f1_count.q.val();
        self.hist1.write_data.next = self.f1_count.q.val();
        self.hist0.write_enable.next = self.f1_valid.q.val() & !self.f1_bank.q.val();
        self.hist1.write_enable.next = self.f1_valid.q.val() & self.f1_bank.q.val();
        // ---- After a reset: every bin of both banks to zero, one a clock.
        self.clearing.next = self.sweeping.q.val();
        if self.sweeping.q.val() {
            self.hist0.write_address.next = self.sweep_bin.q.val();
            self.hist1.write_address.next = self.sweep_bin.q.val();
            self.hist0.write_data.next = 0.into();
            self.hist1.write_data.next = 0.into();
            self.hist0.write_enable.next = true;
            self.hist1.write_enable.next = true;
            self.sweep_bin.d.next = self.sweep_bin.q.val() + 1;
            if self.sweep_bin.q.val() == self.last_bin.val() {
                self.sweeping.d.next = false;
            }
        }
        if self.reset.val() {
            self.sweeping.d.next = true;
            self.sweep_bin.d.next = 0.into();
        }

        // ---- Scan: bin v is read at cnt = v, added to the running count
        // and cleared at cnt = v + 2 (from the output register), and tested
        // at cnt = v + 3.
        self.h.next = self.hist0.read_data.val();
        if self.bank.q.val() {
            self.h.next = self.hist1.read_data.val();
        }
        self.bin.next = bit_cast::<HIST_ADDR_BITS, SCAN_BITS>(self.cnt.q.val() - 2);
        self.need_next.next = self.need.q.val() - (bit_cast::<NEED_BITS, HIST_COUNT_BITS>(self.h.val()) << 1);
        // The final quotient's last bit times K, and Sum's one addition
        // (see `addend`).
        self.lsb_k.next = 0.into();
        if self.quotient.q.val().get_bit(0) {
            self.lsb_k.next = bit_cast::<WIDE_BITS, MUL_OPERAND_BITS>(self.k_frac.val());
        }
        self.wide_sum.next = bit_cast::<WIDE_BITS, MUL_PRODUCT_BITS>(self.product.q.val()) + self.addend.q.val();
        self.acc.next = 0.into();
        self.rounded.next = 0.into();
        self.done_reg.d.next = false;
        self.busy.next = self.state.q.val() != ThresholdState::Idle;
        self.done.next = self.done_reg.q.val();
        self.dt.next = self.dt_reg.q.val();
        match self.state.q.val() {
            ThresholdState::Idle => {
                if self.scan_start.val() {
                    self.bank.d.next = self.scan_bank.val();
                    self.n.d.next = self.scan_n.val();
                    // (`cnt`, `cum`, `hv` and `term1` are cleared through
                    // their synchronous reset, below.)
                    self.found.d.next = false;
                    self.zero_bin.d.next = false;
                    // (2v - 1)·K_HALF at v = 0, wrapping: -K_HALF.
                    self.ramp.d.next = 0 - self.k_half.val();
                    self.den.d.next = 1.into();
                    self.rem.d.next = 0.into();
                    self.counting.d.next = false;
                    self.testing.d.next = false;
                    self.first_test.d.next = false;
                    self.last_test.d.next = false;
                    self.state.d.next = ThresholdState::Settle;
                }
            }
            ThresholdState::Settle => {
                // (`n - 1` from the register, not from `scan_n`, so that
                // the detector's count of the line and this subtraction are
                // not two carry chains in series. `need` is first read on
                // the scan's counting clocks.)
                self.need.d.next = bit_cast::<NEED_BITS, HIST_COUNT_BITS>(self.n.q.val()) - 1;
                self.state.d.next = ThresholdState::Settle2;
            }
            ThresholdState::Settle2 => {
                self.state.d.next = ThresholdState::Scan;
            }
            ThresholdState::Scan => {
                if self.bank.q.val() {
                    self.hist1.read_address.next = bit_cast::<HIST_ADDR_BITS, SCAN_BITS>(self.cnt.q.val());
                } else {
                    self.hist0.read_address.next = bit_cast::<HIST_ADDR_BITS, SCAN_BITS>(self.cnt.q.val());
                }
                self.cnt.d.next = self.cnt.q.val() + 1;
                // The phase flags of the next clock, from this clock's count.
                self.counting.d.next = self.cnt.q.val() >= 1;
                self.testing.d.next = self.cnt.q.val() >= 2;
                self.first_test.d.next = self.cnt.q.val() == 2;
                self.last_test.d.next = self.cnt.q.val() == self.pre_last_scan.val();
            }
            ThresholdState::Divide => {
                // One quotient bit per clock: rem < 2·den throughout.
                self.step.d.next = self.step.q.val() + 1;
                if self.rem.q.val() >= bit_cast::<REM_BITS, HIST_COUNT_BITS>(self.den.q.val()) {
                    self.rem.d.next = (self.rem.q.val() - bit_cast::<REM_BITS, HIST_COUNT_BITS>(self.den.q.val())) << 1;
                    self.quotient.d.next = (self.quotient.q.val() << 1) | 1;
                } else {
                    self.rem.d.next = self.rem.q.val() << 1;
                    self.quotient.d.next = self.quotient.q.val() << 1;
                }
                if self.step.q.val() == self.last_step.val() {
                    self.state.d.next = ThresholdState::Scale;
                }
            }
            ThresholdState::Scale => {
                self.product.d.next = self.scale.p.val();
                self.addend.d.next = (bit_cast::<WIDE_BITS, DT_ACC_BITS>(self.term1.q.val()) << self.frac_shift.val()) + self.lsb_k.val();
                if self.zero_bin.q.val() {
                    self.addend.d.next = self.lsb_k.val();
                }
                self.state.d.next = ThresholdState::Sum;
            }
            ThresholdState::Sum => {
                // Bin 0 has no (2v - 1)·K/2 term, and its fraction counts
                // half (the bin is ½ wide).
                self.acc.next = bit_cast::<DT_ACC_BITS, WIDE_BITS>(self.wide_sum.val() >> self.frac_shift.val());
                if self.zero_bin.q.val() {
                    self.acc.next = bit_cast::<DT_ACC_BITS, WIDE_BITS>(self.wide_sum.val() >> (self.frac_shift.val() + 1));
                }
                self.sum.d.next = self.acc.val();
                self.state.d.next = ThresholdState::Round;
            }
            ThresholdState::Round => {
                self.rounded.next = (self.sum.q.val() + self.round_half.val()) >> self.round_shift.val();
                self.dt_reg.d.next = bit_cast::<DT_BITS, DT_ACC_BITS>(self.rounded.val());
                // (`rounded < floor` ⇔ `sum < FLOOR_SUM`: a comparison of
                // the register beside the rounding's adder, not after it.)
                if (self.sum.q.val() < self.floor_sum.val()) | !self.found.q.val() {
                    self.dt_reg.d.next = bit_cast::<DT_BITS, DT_ACC_BITS>(self.dt_floor.val());
                }
                self.done_reg.d.next = true;
                self.state.d.next = ThresholdState::Idle;
            }
            _ => {
                self.state.d.next = ThresholdState::Idle;
            }
        }
        // The scan's counting and testing, outside the state match: the
        // phase flags hold only while scanning (cleared before and after).
        if self.counting.q.val() {
            // Bin v = cnt - 2 is in the output register: add it to
            // the running count and clear it.
            if self.bank.q.val() {
                self.hist1.write_enable.next = true;
                self.hist1.write_address.next = self.bin.val();
                self.hist1.write_data.next = 0.into();
            } else {
                self.hist0.write_enable.next = true;
                self.hist0.write_address.next = self.bin.val();
                self.hist0.write_data.next = 0.into();
            }
            self.cum.d.next = self.cum.q.val() + self.h.val();
            self.num.d.next = self.n.q.val() - (self.cum.q.val() << 1);
            self.need.d.next = self.need_next.val();
            self.reach.d.next = self.need_next.val().get_bit(self.need_sign.val().index());
            self.hv.d.next = self.h.val();
            self.hv_nz.d.next = self.h.val() != 0;
        }
        if self.testing.q.val() {
            // Bin v = cnt - 3 is tested: the first non-empty bin
            // whose running count reaches n/2 holds the median.
            self.ramp.d.next = self.ramp.q.val() + self.k_step.val();
            if !self.found.q.val() & self.hv_nz.q.val() & self.reach.q.val() {
                self.found.d.next = true;
                self.zero_bin.d.next = self.first_test.q.val();
                self.term1.d.next = self.ramp.q.val();
                // The fraction (n - 2·below) / (2h), divided next.
                self.rem.d.next = bit_cast::<REM_BITS, HIST_COUNT_BITS>(self.num.q.val());
                self.den.d.next = self.hv.q.val() << 1;
            }
            if self.last_test.q.val() {
                self.step.d.next = 0.into();
                self.quotient.d.next = 0.into();
                self.counting.d.next = false;
                self.testing.d.next = false;
                self.first_test.d.next = false;
                self.last_test.d.next = false;
                self.state.d.next = ThresholdState::Divide;
            }
        }
        // The scan's start clears its counts and its median's term through
        // the registers' synchronous reset, beside the block's (on the
        // flip-flops' LSR: a clear in the data would cost a LUT a bit once
        // the reset holds the LSR). The same values as a clear in Idle:
        // `cnt` is written only in Idle and Scan, `cum` and `hv` only while
        // `counting`, `term1` only while `testing`, and both flags are high
        // only in Scan (set there, cleared on its last clock, at the start
        // and by the reset).
        self.scan_clear.next = (self.state.q.val() == ThresholdState::Idle) & self.scan_start.val();
        self.cnt.reset.next = self.reset.val() | self.scan_clear.val();
        self.cum.reset.next = self.reset.val() | self.scan_clear.val();
        self.hv.reset.next = self.reset.val() | self.scan_clear.val();
        self.term1.reset.next = self.reset.val() | self.scan_clear.val();
        // The quotient register shifted: on the last Divide clock, the
        // final quotient but its last bit (added in Sum through `lsb_k`).
        self.scale.clock.next = self.clock.val();
        self.q_shifted.next = self.quotient.q.val() << 1;
        self.scale.a.next = bit_cast::<MUL_OPERAND_BITS, MEDIAN_Q_BITS>(self.q_shifted.val());
        self.scale.b.next = self.k_frac.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tick(uut: &mut AdaptiveThreshold) {
        crate::tick(uut, |u| &mut u.clock);
    }

    /// golden's eq. 2 on the differences `diffs` (the estimator's median and
    /// floor), written out here in f64 so the test is independent of the
    /// block's fixed point.
    fn dt_of(diffs: &[u8]) -> f64 {
        let n = diffs.len();
        if n == 0 {
            return 5.6 / 12f64.sqrt();
        }
        let mut h = [0u64; 256];
        diffs.iter().for_each(|&d| h[d as usize] += 1);
        let half = n as f64 / 2.0;
        let mut below = 0u64;
        for v in 0..256 {
            if h[v] > 0 && (below + h[v]) as f64 >= half {
                let (lo, w) = if v == 0 { (0.0, 0.5) } else { (v as f64 - 0.5, 1.0) };
                let m = lo + w * (half - below as f64) / h[v] as f64;
                return (THRESHOLD_PER_MEDIAN * m).max(5.6 / 12f64.sqrt());
            }
            below += h[v];
        }
        unreachable!()
    }

    #[test]
    fn threshold_is_within_one_lsb_of_the_f64_estimator_and_banks_are_cleared() {
        let mut uut = AdaptiveThreshold::default();
        uut.connect_all();
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for case in 0..60 {
            let n = match case {
                0 => 0,
                1 => 1,
                _ => (next() % 1023) as usize,
            };
            let spread = 1 + next() % 256;
            let mut diffs: Vec<u8> = (0..n)
                .map(|i| if case % 3 == 0 && i % 2 == 0 { 7 } else { (next() % spread) as u8 })
                .collect();
            if case == 4 || case == 5 {
                // The median is the last count (bin 0), scanned right after
                // it: d_t ≈ 2.9 with it, 32 if the scan missed it.
                diffs = vec![9, 0];
            }
            let n = diffs.len();
            let bank = case % 2 == 1;
            for &d in &diffs {
                uut.inc_valid.next = true;
                uut.inc_bank.next = bank;
                uut.inc_bin.next = (d as u64).into();
                assert!(simulate(&mut uut, 100));
                tick(&mut uut);
            }
            // The scan starts on the clock after the line's last count (the
            // earliest the detector can start it; the last count, often bin
            // 0, is then still on its way into the RAM), or a clock later.
            uut.inc_valid.next = false;
            if case % 4 >= 2 {
                assert!(simulate(&mut uut, 100));
                tick(&mut uut);
            }
            uut.scan_start.next = true;
            uut.scan_bank.next = bank;
            uut.scan_n.next = (n as u64).into();
            assert!(simulate(&mut uut, 100));
            let mut clocks = 0;
            loop {
                tick(&mut uut);
                uut.scan_start.next = false;
                assert!(simulate(&mut uut, 100));
                clocks += 1;
                if uut.done.val() {
                    break;
                }
                assert!(clocks < 1000, "hangs");
            }
            assert_eq!(clocks, THRESHOLD_LATENCY);
            let got = uut.dt.val().to_u64() as f64 / (1u64 << DT_FRAC_BITS) as f64;
            let want = dt_of(&diffs);
            let lsb = 1.0 / (1u64 << DT_FRAC_BITS) as f64;
            assert!((got - want).abs() < lsb, "case {case}: n {n}, d_t {got} vs {want}");
        }
    }
}
