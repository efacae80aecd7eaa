//! The interpolator of the line processor (`rtl::post::interpolator`): a
//! row's matches in the matcher's format ([`FixedMatch`]) to one disparity
//! per pixel in the same format, computed as the hardware computes it
//! (golden's f64 interpolation is [`crate::disparity::interpolate_into`];
//! the two differ only on the pixels of a ramp, by the reciprocal table's
//! and the weight's rounding, at most `½ + |Δd|·2^-RECIP_INDEX_BITS` LSB).
//!
//! Formats, from the hardware's sizes as `rtl::params` derives them:
//! positions and disparities are unsigned with `f = pos_frac_bits`
//! fraction bits in `P` = [`position_bits`] bits (14 = 10 + 4 for
//! `w_max` = 1024); `1/(X_b − X_a)` comes from a table of
//! `2^`[`RECIP_INDEX_BITS`] entries of [`RECIP_BITS`] bits
//! ([`recip_table`]); the weight `t` has [`WEIGHT_FRAC_BITS`] fraction
//! bits; the two products are 16 × 16 → 32 bits.
//!
//! The steps:
//! - between consecutive matches `a`, `b`, the pixels `⌈X_a⌉ ≤ x < ⌈X_b⌉`
//!   form a segment when `⌈X_b⌉ > ⌈X_a⌉` ([`Interpolator::segment`]: its
//!   distance normalised ([`normalise`]), its reciprocal, `|Δd|`, the
//!   edge jump);
//! - a segment's pixel is `d_a ± ⌊t·|Δd| + ½⌋` ([`Interpolator::ramp_pixel`]),
//!   or across a jump (`|Δd| > J`) the smaller disparity;
//! - a row: before the first match's `⌈X⌉` its disparity, the segments,
//!   from the last match's `⌈X⌉` on its disparity; a row without a match
//!   is 0 ("no disparity") ([`Interpolator::row`]).

use crate::hardware::row_check::FixedMatch;
use crate::hardware::HardwareLimits;
use crate::params::Features;

/// Index bits of the reciprocal table: the normalised distance's bits after
/// its leading one (`rtl::params::RECIP_INDEX_BITS`).
pub const RECIP_INDEX_BITS: u32 = 9;
/// Bits of a reciprocal table entry (`rtl::params::RECIP_BITS`).
pub const RECIP_BITS: u32 = 16;
/// Fraction bits of the weight `t = (x − X_a) / (X_b − X_a)`
/// (`rtl::params::WEIGHT_FRAC_BITS`).
pub const WEIGHT_FRAC_BITS: u32 = 16;
/// Bits of an operand of the hardware's multipliers (a DSP block's 16 × 16
/// product, `rtl::primitives::dsp_multiplier::MUL_OPERAND_BITS`).
pub const MUL_OPERAND_BITS: u32 = 16;

/// `P`, the bits of a position or a disparity: the bits of a pixel index
/// below `w_max` and `pos_frac_bits` fraction bits (`rtl::params::POS_BITS`).
pub fn position_bits(limits: HardwareLimits) -> u32 {
    limits.w_max.next_power_of_two().trailing_zeros() + limits.pos_frac_bits
}

/// `RECIP_SHIFT = P − 1 + RECIP_BITS`: an entry is `2^RECIP_SHIFT / m` for a
/// distance `m` normalised to `[2^(P−1), 2^P)`, between `2^(RECIP_BITS−1)`
/// and `2^RECIP_BITS`.
pub fn recip_shift(limits: HardwareLimits) -> u32 {
    position_bits(limits) - 1 + RECIP_BITS
}

/// The reciprocal table: entry `i` is `⌊2^RECIP_SHIFT / m_i⌋` for the
/// middle `m_i` of the bucket of normalised distances whose
/// [`RECIP_INDEX_BITS`] bits after the leading one are `i`:
/// `m_i = ((2^RECIP_INDEX_BITS + i) << low) + 2^(low−1)`,
/// `low = P − 1 − RECIP_INDEX_BITS` (the hardware's `recip_table`).
pub fn recip_table(limits: HardwareLimits) -> Vec<u32> {
    let low = position_bits(limits) - 1 - RECIP_INDEX_BITS;
    (0..1u64 << RECIP_INDEX_BITS)
        .map(|i| {
            let m = ((i + (1 << RECIP_INDEX_BITS)) << low) + (1 << (low - 1));
            ((1u64 << recip_shift(limits)) / m) as u32
        })
        .collect()
}

/// A value `0 < v < 2^bits` shifted left until its top bit (bit `bits − 1`)
/// is set: `(m, lz)` with `m = v · 2^lz ∈ [2^(bits−1), 2^bits)` (the
/// hardware shifts by 8, 4, 2 and 1 where the top bits are clear: the same
/// count).
pub fn normalise(v: u32, bits: u32) -> (u32, u32) {
    debug_assert!(v > 0 && v < 1 << bits, "{v} is not a non-zero value of {bits} bits");
    let lz = v.leading_zeros() - (32 - bits);
    (v << lz, lz)
}

/// The first pixel centre at or after a position of `frac_bits` fraction
/// bits: `⌈X / 2^frac_bits⌉`.
pub fn first_pixel(x: u32, frac_bits: u32) -> u32 {
    (x + (1 << frac_bits) - 1) >> frac_bits
}

/// A segment between consecutive matches `a`, `b` whose pixels differ
/// (`⌈X_b⌉ > ⌈X_a⌉`): its pixels are `⌈X_a⌉ ..= last`. Values in position
/// LSBs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Segment {
    /// Its last pixel, `⌈X_b⌉ − 1`.
    pub last: u32,
    /// `X_a`.
    pub x_a: u32,
    /// What the ramp starts from: `d_a`, or across a jump `min(d_a, d_b)`.
    pub base: u32,
    /// `|d_b − d_a|`.
    pub dd: u32,
    /// `d_b < d_a`: the ramp goes down.
    pub falling: bool,
    /// `|d_b − d_a|` is above the edge jump: every pixel is `base`.
    pub jump: bool,
    /// The shift `lz` that normalises `X_b − X_a` (`0 ..= P − 1`).
    pub lz: u32,
    /// The table's `1/(X_b − X_a)` ([`recip_table`]).
    pub recip: u32,
}

/// The interpolator of a hardware: its formats, its edge jump and its
/// reciprocal table.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Interpolator {
    frac_bits: u32,
    pos_bits: u32,
    jump: Option<u32>,
    recip: Vec<u32>,
}

impl Interpolator {
    /// The interpolator of the hardware with `limits`, edge jump `jump`
    /// (position LSBs; `None` bridges every pair of matches).
    ///
    /// # Panics
    /// If a position does not fit a multiplier's operand
    /// ([`MUL_OPERAND_BITS`]): no such hardware is generated.
    pub fn new(limits: HardwareLimits, jump: Option<u32>) -> Self {
        let pos_bits = position_bits(limits);
        assert!(pos_bits <= MUL_OPERAND_BITS, "positions of {pos_bits} bits do not fit the {MUL_OPERAND_BITS}-bit multipliers");
        Interpolator { frac_bits: limits.pos_frac_bits, pos_bits, jump, recip: recip_table(limits) }
    }

    /// The interpolator of a mode's `features`: their edge jump (px) as
    /// `⌊J · 2^f⌋` LSBs (for integer `|Δd|`, `|Δd| > ⌊J·2^f⌋` is
    /// `|Δd|/2^f > J`).
    pub fn of_features(limits: HardwareLimits, features: &Features) -> Self {
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        Self::new(limits, features.edge_jump.map(|j| (j * unit).floor() as u32))
    }

    /// The segment engine: the segment from match `a` to the next match `b`
    /// (`X_a < X_b`, `⌈X_b⌉ > ⌈X_a⌉`). The distance `X_b − X_a` is
    /// normalised ([`normalise`], `P` bits) and the [`RECIP_INDEX_BITS`]
    /// bits after its leading one address the table.
    pub fn segment(&self, a: FixedMatch, b: FixedMatch) -> Segment {
        let (m, lz) = normalise(b.x - a.x, self.pos_bits);
        let index = (m >> (self.pos_bits - 1 - RECIP_INDEX_BITS)) & ((1 << RECIP_INDEX_BITS) - 1);
        let dd = a.d.abs_diff(b.d);
        let jump = self.jump.is_some_and(|j| dd > j);
        Segment {
            last: (b.x - 1) >> self.frac_bits,
            x_a: a.x,
            base: if jump { a.d.min(b.d) } else { a.d },
            dd,
            falling: b.d < a.d,
            jump,
            lz,
            recip: self.recip[index as usize],
        }
    }

    /// The pixel engine on pixel `x` of `seg` (LSBs): the distance
    /// `u = x·2^f − X_a` normalised as the segment's (`v = u·2^lz < 2^P`),
    /// the weight `t = v·recip >> (P − 1)` ([`WEIGHT_FRAC_BITS`] fraction
    /// bits, clamped to `2^16 − 1` below 1), the step
    /// `δ = (t·|Δd| + 2^15) >> 16` (rounded half up), the pixel
    /// `base ± δ`; across a jump, `base`.
    pub fn ramp_pixel(&self, seg: &Segment, x: u32) -> u32 {
        if seg.jump {
            return seg.base;
        }
        let mask = (1u32 << self.pos_bits) - 1;
        let u = ((x << self.frac_bits).wrapping_sub(seg.x_a)) & mask;
        let v = u64::from(u << seg.lz);
        let prod = v * u64::from(seg.recip);
        let t = if prod >> (self.pos_bits - 1 + WEIGHT_FRAC_BITS) != 0 {
            (1u64 << WEIGHT_FRAC_BITS) - 1
        } else {
            prod >> (self.pos_bits - 1)
        };
        let delta = ((t * u64::from(seg.dd) + (1 << (WEIGHT_FRAC_BITS - 1))) >> WEIGHT_FRAC_BITS) as u32;
        // δ ≤ |Δd|: the ramp stays between d_a and d_b (no wrap).
        if seg.falling {
            seg.base.wrapping_sub(delta) & mask
        } else {
            seg.base.wrapping_add(delta) & mask
        }
    }

    /// One row of `out.len()` pixels from its matches (strictly increasing
    /// `X`, every `X` below `2^f · out.len()`), disparities in LSBs (0 =
    /// none): the first match's disparity before its `⌈X⌉`, then each
    /// segment's pixels, then from the last match's `⌈X⌉` on its disparity;
    /// 0 everywhere without a match.
    pub fn row(&self, matches: &[FixedMatch], out: &mut [u16]) {
        let (Some(first), Some(last)) = (matches.first(), matches.last()) else {
            out.fill(0);
            return;
        };
        let width = out.len();
        let head = (first_pixel(first.x, self.frac_bits) as usize).min(width);
        out[..head].fill(first.d as u16);
        let mut x = head;
        for w in matches.windows(2) {
            let (a, b) = (w[0], w[1]);
            // ⌈X_b⌉ > ⌈X_a⌉ ⇔ X_b > ⌈X_a⌉·2^f.
            if b.x > first_pixel(a.x, self.frac_bits) << self.frac_bits {
                let seg = self.segment(a, b);
                let end = (seg.last as usize + 1).min(width);
                while x < end {
                    out[x] = self.ramp_pixel(&seg, x as u32) as u16;
                    x += 1;
                }
            }
        }
        out[x..].fill(last.d as u16);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::disparity::{interpolate_into, Anchor};
    use crate::params::EndRule;

    #[test]
    fn normalise_shifts_to_the_top_bit_for_every_value() {
        for v in 1..1u32 << 14 {
            let (m, lz) = normalise(v, 14);
            assert!((1 << 13..1 << 14).contains(&m) && m == v << lz, "{v}");
        }
    }

    #[test]
    fn the_table_is_within_half_a_bucket_of_the_reciprocal_and_fits_its_bits() {
        let limits = HardwareLimits::default();
        let table = recip_table(limits);
        assert_eq!((position_bits(limits), recip_shift(limits), table.len()), (14, 29, 512));
        for m in (1u64 << 13)..(1u64 << 14) {
            let r = table[((m >> 4) & 511) as usize] as f64;
            let exact = (1u64 << 29) as f64 / m as f64;
            assert!(r < 65536.0 && (r - exact).abs() / exact < 1.0 / 1024.0 + 1.0 / 32768.0, "m {m}");
        }
    }

    /// The row against golden's f64 interpolation of the same matches: the
    /// held and jump pixels equal, the ramp pixels within the arithmetic's
    /// bound (`½ + |Δd|·2^-9` LSB).
    #[test]
    fn a_row_is_golden_interpolation_held_values_exact_ramps_within_the_bound() {
        let limits = HardwareLimits::default();
        let mut rng = crate::test_rng::TestRng::new(0x1e7e_4a12_0000_0001);
        let (mut ramps, mut exact) = (0usize, 0usize);
        for case in 0..2000 {
            let width = 1 + (rng.next() % 300) as usize;
            let mut x = (rng.next() % 64) as u32;
            let mut matches = Vec::new();
            while (x as usize) < 16 * width && matches.len() < 40 {
                matches.push(FixedMatch { x, d: 1 + (rng.next() % 1200) as u32 });
                x += 1 + (rng.next() % 200) as u32;
            }
            matches.truncate((rng.next() % 40) as usize);
            for jump in [None, Some(96)] {
                let interp = Interpolator::new(limits, jump);
                let mut got = vec![7u16; width];
                interp.row(&matches, &mut got);
                let anchors: Vec<Anchor> =
                    matches.iter().map(|m| Anchor { x: m.x as f64 / 16.0, d: m.d as f64 / 16.0 }).collect();
                let mut want = vec![0.0; width];
                interpolate_into(&anchors, EndRule::Hold, jump.map(|j| j as f64 / 16.0), &mut want);
                for (px, (&g, &w)) in got.iter().zip(&want).enumerate() {
                    let w = w * 16.0;
                    let k = matches.windows(2).position(|p| {
                        first_pixel(p[0].x, 4) as usize <= px && (px as u32) < first_pixel(p[1].x, 4)
                    });
                    let ramp = k.filter(|&k| jump.is_none_or(|j| matches[k].d.abs_diff(matches[k + 1].d) <= j));
                    match ramp {
                        Some(k) => {
                            let dd = matches[k].d.abs_diff(matches[k + 1].d) as f64;
                            assert!((g as f64 - w).abs() <= 0.5 + dd / 512.0, "case {case} pixel {px}: {g} vs {w}");
                            ramps += 1;
                            exact += (g as f64 == w.round()) as usize;
                        }
                        None => assert_eq!(g as f64, w, "case {case} pixel {px}: {matches:?}"),
                    }
                }
            }
        }
        assert!(ramps > 100_000 && exact < ramps, "{exact} of {ramps} ramp pixels round as f64 does");
    }
}
