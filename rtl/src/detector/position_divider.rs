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
//! Like rust-hdl's own `RAM` and `DFF`, this block is a primitive: its Rust
//! model (`update`) and its Verilog (`hdl`, written out stage by stage from
//! the same parameters) are two descriptions of one circuit, and the
//! co-simulation tests hold them to each other clock by clock. As one
//! block it keeps rust-hdl's simulator, which re-evaluates every block until
//! nothing changes, from stepping one generated sub-block per stage.
//!
//! ## Ports
//! - `in_valid`, `in_dividend` (`S1 · 2^(POS_FRAC_BITS-1)`, [`DIVIDEND_BITS`]),
//!   `in_divisor` (`S0 > 0`, [`S0_BITS`]) and four 32-bit tag lanes
//!   `in_tag0..3` that travel with the division untouched.
//! - `out_valid`, `out_quotient` ([`POS_BITS`]) and the record's fields,
//!   unpacked from the tags as [`TagLayout`] lays them out: `out_marker`,
//!   `out_start`, `out_end`, `out_amp`, `out_left0..2`, `out_right0..2`,
//!   `out_count`, `out_wide`, `out_full`, `out_sof`, `out_dt`.
//!
//! ## Timing
//! Latency [`DIVIDER_LATENCY`] = [`POS_BITS`] clocks (one per quotient bit),
//! throughput one division per clock, no back-pressure: a bubble
//! (`in_valid` low) travels through as a bubble. The tags wait in four small
//! memories written every clock and read [`POS_BITS`] clocks later
//! (distributed RAM instead of `4 × 32 × POS_BITS` flip-flops). Every
//! register starts at zero; `reset` (synchronous, active high) empties the
//! stages (the tag memories are a delay line and need none). The quotient must fit in
//! [`POS_BITS`] bits, which holds for any position `X_i < W_MAX`: then
//! `dividend >> POS_BITS < divisor`. A zero divisor gives an all-ones
//! quotient (it never happens on a declivity, which has a non-zero gradient).

use crate::detector::declivity_tracker::TagLayout;
use crate::params::*;
use rust_hdl::prelude::*;

/// Clocks from a division entering to its quotient leaving.
pub(crate) const DIVIDER_LATENCY: usize = POS_BITS;
/// Bits of a trial remainder: one above the divisor.
const TRIAL_BITS: usize = S0_BITS + 1;
/// Entries of the tag delay memories (more than [`DIVIDER_LATENCY`]).
const TAG_DEPTH: usize = 16;
/// Address bits of the tag delay memories.
const TAG_ADDR_BITS: usize = 4;

/// One stage's registers: the partial remainder, the divisor, and in one
/// register (`lq`) the dividend's remaining low bits and the quotient so far
/// (bits leave at the top as quotient bits enter at the bottom).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Stage {
    valid: bool,
    rem: u64,
    lq: u64,
    den: u64,
}

/// One step of long division: shift the next dividend bit into the
/// remainder, subtract the divisor if it fits, append the quotient bit.
fn step(valid: bool, rem: u64, lq: u64, den: u64) -> Stage {
    let lq_mask = (1u64 << POS_BITS) - 1;
    let trial = (rem << 1) | (lq >> (POS_BITS - 1)) & 1;
    let fits = trial >= den;
    Stage {
        valid,
        rem: (if fits { trial - den } else { trial }) & ((1u64 << S0_BITS) - 1),
        lq: ((lq << 1) | fits as u64) & lq_mask,
        den,
    }
}

#[derive(LogicBlock)]
pub(crate) struct PositionDivider {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset: the stages emptied.
    pub reset: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_dividend: Signal<In, Bits<DIVIDEND_BITS>>,
    pub in_divisor: Signal<In, Bits<S0_BITS>>,
    pub in_tag0: Signal<In, Bits<32>>,
    pub in_tag1: Signal<In, Bits<32>>,
    pub in_tag2: Signal<In, Bits<32>>,
    pub in_tag3: Signal<In, Bits<32>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_quotient: Signal<Out, Bits<POS_BITS>>,
    pub out_marker: Signal<Out, Bit>,
    pub out_start: Signal<Out, Bits<X_BITS>>,
    pub out_end: Signal<Out, Bits<X_BITS>>,
    pub out_amp: Signal<Out, Bits<AMP_BITS>>,
    pub out_left0: Signal<Out, Bits<PIXEL_BITS>>,
    pub out_left1: Signal<Out, Bits<PIXEL_BITS>>,
    pub out_left2: Signal<Out, Bits<PIXEL_BITS>>,
    pub out_right0: Signal<Out, Bits<PIXEL_BITS>>,
    pub out_right1: Signal<Out, Bits<PIXEL_BITS>>,
    pub out_right2: Signal<Out, Bits<PIXEL_BITS>>,
    pub out_count: Signal<Out, Bits<COUNT_BITS>>,
    pub out_wide: Signal<Out, Bit>,
    pub out_full: Signal<Out, Bit>,
    pub out_sof: Signal<Out, Bit>,
    pub out_dt: Signal<Out, Bits<DT_BITS>>,
    _stages: [Stage; POS_BITS],
    _tags: [[u32; 4]; TAG_DEPTH],
    _wptr: usize,
}

impl Default for PositionDivider {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            in_valid: Default::default(),
            in_dividend: Default::default(),
            in_divisor: Default::default(),
            in_tag0: Default::default(),
            in_tag1: Default::default(),
            in_tag2: Default::default(),
            in_tag3: Default::default(),
            out_valid: Default::default(),
            out_quotient: Default::default(),
            out_marker: Default::default(),
            out_start: Default::default(),
            out_end: Default::default(),
            out_amp: Default::default(),
            out_left0: Default::default(),
            out_left1: Default::default(),
            out_left2: Default::default(),
            out_right0: Default::default(),
            out_right1: Default::default(),
            out_right2: Default::default(),
            out_count: Default::default(),
            out_wide: Default::default(),
            out_full: Default::default(),
            out_sof: Default::default(),
            out_dt: Default::default(),
            _stages: [Stage::default(); POS_BITS],
            _tags: [[0; 4]; TAG_DEPTH],
            _wptr: 0,
        }
    }
}

impl Logic for PositionDivider {
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        // Stages from the last to the first, each from its predecessor's
        // value before the edge.
        for k in (1..POS_BITS).rev() {
            let p = self._stages[k - 1];
            self._stages[k] = step(p.valid, p.rem, p.lq, p.den);
        }
        let valid = self.in_valid.val();
        let dividend = if valid { self.in_dividend.val().to_u64() } else { 0 };
        self._stages[0] = step(valid, dividend >> POS_BITS, dividend & ((1u64 << POS_BITS) - 1), self.in_divisor.val().to_u64());
        // Tags: read the entry written DIVIDER_LATENCY - 1 clocks ago, then
        // write this clock's.
        let read = self._tags[(self._wptr + TAG_DEPTH - (DIVIDER_LATENCY - 1)) % TAG_DEPTH];
        self._tags[self._wptr] =
            [self.in_tag0.val(), self.in_tag1.val(), self.in_tag2.val(), self.in_tag3.val()].map(|t| t.to_u64() as u32);
        self._wptr = (self._wptr + 1) % TAG_DEPTH;
        if self.reset.val() {
            self._stages = [Stage::default(); POS_BITS];
        }
        let last = self._stages[POS_BITS - 1];
        self.out_valid.next = last.valid;
        self.out_quotient.next = last.lq.into();

        // The record's fields, out of the tag lanes (TagLayout).
        let field = |lane: u32, shift: usize, bits: usize| ((lane as u64) >> shift) & ((1u64 << bits) - 1);
        self.out_marker.next = field(read[0], TagLayout::MARKER_SHIFT, 1) == 1;
        self.out_start.next = field(read[0], 0, X_BITS).into();
        self.out_end.next = field(read[0], TagLayout::END_SHIFT, X_BITS).into();
        self.out_amp.next = field(read[0], TagLayout::AMP_SHIFT, AMP_BITS).into();
        self.out_left0.next = field(read[1], 0, PIXEL_BITS).into();
        self.out_left1.next = field(read[1], TagLayout::LEVEL_SHIFT, PIXEL_BITS).into();
        self.out_left2.next = field(read[1], 2 * TagLayout::LEVEL_SHIFT, PIXEL_BITS).into();
        self.out_right0.next = field(read[2], 0, PIXEL_BITS).into();
        self.out_right1.next = field(read[2], TagLayout::LEVEL_SHIFT, PIXEL_BITS).into();
        self.out_right2.next = field(read[2], 2 * TagLayout::LEVEL_SHIFT, PIXEL_BITS).into();
        self.out_count.next = field(read[1], 0, COUNT_BITS).into();
        self.out_wide.next = field(read[2], 0, 1) == 1;
        self.out_full.next = field(read[2], 1, 1) == 1;
        self.out_sof.next = field(read[2], 2, 1) == 1;
        self.out_dt.next = field(read[TagLayout::DT_LANE], 0, DT_BITS).into();
    }

    fn connect(&mut self) {
        self.out_valid.connect();
        self.out_quotient.connect();
        self.out_marker.connect();
        self.out_start.connect();
        self.out_end.connect();
        self.out_amp.connect();
        self.out_left0.connect();
        self.out_left1.connect();
        self.out_left2.connect();
        self.out_right0.connect();
        self.out_right1.connect();
        self.out_right2.connect();
        self.out_count.connect();
        self.out_wide.connect();
        self.out_full.connect();
        self.out_sof.connect();
        self.out_dt.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(divider_verilog())
    }
}

/// The Verilog body of [`PositionDivider`], stage by stage.
fn divider_verilog() -> String {
    let (n, s0, q, d, t) = (POS_BITS, S0_BITS, POS_BITS, DIVIDEND_BITS, TRIAL_BITS);
    // The record's fields: (port, tag lane, shift, bits), as TagLayout lays
    // them out.
    let level = TagLayout::LEVEL_SHIFT;
    let fields: [(&str, usize, usize, usize); 15] = [
        ("out_marker", 0, TagLayout::MARKER_SHIFT, 1),
        ("out_start", 0, 0, X_BITS),
        ("out_end", 0, TagLayout::END_SHIFT, X_BITS),
        ("out_amp", 0, TagLayout::AMP_SHIFT, AMP_BITS),
        ("out_left0", 1, 0, PIXEL_BITS),
        ("out_left1", 1, level, PIXEL_BITS),
        ("out_left2", 1, 2 * level, PIXEL_BITS),
        ("out_right0", 2, 0, PIXEL_BITS),
        ("out_right1", 2, level, PIXEL_BITS),
        ("out_right2", 2, 2 * level, PIXEL_BITS),
        ("out_count", 1, 0, COUNT_BITS),
        ("out_wide", 2, 0, 1),
        ("out_full", 2, 1, 1),
        ("out_sof", 2, 2, 1),
        ("out_dt", TagLayout::DT_LANE, 0, DT_BITS),
    ];
    let mut v = String::new();
    v += &format!("wire [{}:0] rem_in = in_valid ? in_dividend[{}:{}] : {}'d0;\n", s0 - 1, d - 1, q, s0);
    v += &format!("wire [{}:0] lq_in = in_valid ? in_dividend[{}:0] : {}'d0;\n", q - 1, q - 1, q);
    // The last stage's quotient and valid bit are the output registers; its
    // remainder and divisor are not needed.
    for k in 0..n {
        if k + 1 < n {
            v += &format!("reg valid_{k} = 1'b0;\nreg [{}:0] rem_{k} = {s0}'d0;\nreg [{}:0] lq_{k} = {q}'d0;\nreg [{}:0] den_{k} = {s0}'d0;\n", s0 - 1, q - 1, s0 - 1);
        }
        let (rem, lq, den) = if k == 0 {
            ("rem_in".to_string(), "lq_in".to_string(), "in_divisor".to_string())
        } else {
            (format!("rem_{}", k - 1), format!("lq_{}", k - 1), format!("den_{}", k - 1))
        };
        v += &format!("wire [{}:0] trial_{k} = {{{rem}, {lq}[{}]}};\n", t - 1, q - 1);
        v += &format!("wire fits_{k} = trial_{k} >= {{1'b0, {den}}};\n");
    }
    v += &format!("reg [31:0] tags0 [0:{}];\nreg [31:0] tags1 [0:{}];\nreg [31:0] tags2 [0:{}];\nreg [31:0] tags3 [0:{}];\n", TAG_DEPTH - 1, TAG_DEPTH - 1, TAG_DEPTH - 1, TAG_DEPTH - 1);
    v += &format!("reg [{}:0] wptr = {}'d0;\n", TAG_ADDR_BITS - 1, TAG_ADDR_BITS);
    v += &format!("wire [{}:0] rptr = wptr - {}'d{};\n", TAG_ADDR_BITS - 1, TAG_ADDR_BITS, DIVIDER_LATENCY - 1);
    v += "integer i;\ninitial begin\n";
    v += &format!("    for (i = 0; i < {TAG_DEPTH}; i = i + 1) begin\n        tags0[i] = 32'd0; tags1[i] = 32'd0; tags2[i] = 32'd0; tags3[i] = 32'd0;\n    end\n");
    for (name, _, _, bits) in &fields {
        v += &format!("    {name} = {bits}'d0;\n");
    }
    v += &format!("    out_valid = 1'b0; out_quotient = {q}'d0;\nend\n");
    v += "always @(posedge clock) begin\n  if (reset) begin\n";
    for k in 0..n - 1 {
        v += &format!("    valid_{k} <= 1'b0; rem_{k} <= {s0}'d0; lq_{k} <= {q}'d0; den_{k} <= {s0}'d0;\n");
    }
    v += &format!("    out_valid <= 1'b0; out_quotient <= {q}'d0;\n  end else begin\n");
    for k in 0..n {
        let (valid, den) = if k == 0 { ("in_valid".to_string(), "in_divisor".to_string()) } else { (format!("valid_{}", k - 1), format!("den_{}", k - 1)) };
        let lq = if k == 0 { "lq_in".to_string() } else { format!("lq_{}", k - 1) };
        if k + 1 < n {
            v += &format!("    valid_{k} <= {valid};\n    den_{k} <= {den};\n");
            v += &format!("    rem_{k} <= fits_{k} ? trial_{k} - {{1'b0, {den}}} : trial_{k};\n");
            v += &format!("    lq_{k} <= {{{lq}[{}:0], fits_{k}}};\n", q - 2);
        } else {
            v += &format!("    out_valid <= {valid};\n    out_quotient <= {{{lq}[{}:0], fits_{k}}};\n", q - 2);
        }
    }
    v += "  end\n";
    for (name, lane, shift, bits) in &fields {
        v += &format!("    {name} <= tags{lane}[rptr][{}:{shift}];\n", shift + bits - 1);
    }
    v += "    tags0[wptr] <= in_tag0; tags1[wptr] <= in_tag1; tags2[wptr] <= in_tag2; tags3[wptr] <= in_tag3;\n";
    v += "    wptr <= wptr + 1'b1;\nend\n";
    v
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
                uut.in_tag3.next = (3 * cycle as u64).into();
            } else {
                uut.in_valid.next = false;
            }
            assert!(simulate(&mut uut, 100));
            if uut.out_valid.val() {
                got.push((uut.out_start.val().to_u64(), uut.out_quotient.val().to_u64()));
                assert_eq!(uut.out_dt.val().to_u64(), 3 * uut.out_start.val().to_u64(), "lane 3 rides with lane 0");
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
