//! Eq. 2 as the detector's threshold engine computes it
//! (`rtl::detector::adaptive_threshold`): the same estimator as
//! [`crate::noise`] — the median `m` of `|I(x+1) - I(x)|` interpolated
//! inside its bin, `d_t = max(K·m, 5.6/√12)` with `K = 5.6/(0.6745·√2)` —
//! in the engine's integers, step for step, so that the result is the
//! engine's `d_t` to the last bit:
//!
//! 1. [`abs_diff_histogram`](crate::noise::abs_diff_histogram) of the stored
//!    pixels: the counts the input engine makes while the line streams in,
//!    `n = W - 1` differences;
//! 2. [`median_bin`]: the scan's median bin `v`, the first non-empty bin
//!    where the counts reach `n/2`, with the count below it and its own;
//! 3. [`in_bin_fraction`]: `q = (n/2 - below)/h` by long division to
//!    [`MEDIAN_FRAC_BITS`] fraction bits, rounded down;
//! 4. [`scaled_median`]: `K·m·2^DT_ACC_FRAC_BITS` as the engine's
//!    accumulator sums it, `(2v - 1)·K_HALF + ⌊q·K_FRAC / 2^8⌋`
//!    (`⌊q·K_FRAC / 2^9⌋` in bin 0, whose width is ½);
//! 5. [`rounded_threshold`]: rounded to the detector's `d_t` format and
//!    floored at [`dt_floor_lsb`].
//!
//! The constants are golden's own, derived from its f64 constants
//! ([`THRESHOLD_FACTOR`], [`MAD_NORMAL`], [`SIGMA_FLOOR`]) with the rounding
//! the engine's documentation gives; a workspace test holds them equal to
//! `rtl::params`'s.

use crate::noise::{abs_diff_histogram, HIST_BINS, MAD_NORMAL, SIGMA_FLOOR, THRESHOLD_FACTOR};

/// `K = 5.6 / (0.6745·√2)`: `d_t` per unit of the median of |ΔI| (eq. 2
/// with the MAD estimator of `DESIGN.md` §2.1).
pub const THRESHOLD_PER_MEDIAN: f64 = THRESHOLD_FACTOR / (MAD_NORMAL * std::f64::consts::SQRT_2);

/// Fraction bits of the in-bin fraction `q` ([`in_bin_fraction`]); `q`
/// itself has one bit more, as it can be exactly 1.
pub const MEDIAN_FRAC_BITS: u32 = 15;

/// Fraction bits of `K·m` in the engine's accumulator ([`scaled_median`]).
pub const DT_ACC_FRAC_BITS: u32 = 20;

/// Fraction bits of [`K_FRAC`].
pub const K_FRAC_BITS: u32 = 13;

/// `round(K · 2^(DT_ACC_FRAC_BITS - 1))`: the bin term `K·(v - ½)` in the
/// accumulator is `(2v - 1)·K_HALF`.
pub const K_HALF: u64 = round_positive(THRESHOLD_PER_MEDIAN * (1u64 << (DT_ACC_FRAC_BITS - 1)) as f64);

/// `round(K · 2^K_FRAC_BITS)`: the factor of the in-bin fraction.
pub const K_FRAC: u64 = round_positive(THRESHOLD_PER_MEDIAN * (1u64 << K_FRAC_BITS) as f64);

/// The shift from `q·K_FRAC` (`MEDIAN_FRAC_BITS + K_FRAC_BITS` fraction
/// bits) to the accumulator's [`DT_ACC_FRAC_BITS`].
const FRAC_SHIFT: u32 = MEDIAN_FRAC_BITS + K_FRAC_BITS - DT_ACC_FRAC_BITS;

/// `round(x)` for `0 ≤ x < 2^52` in a constant (`f64::round` is not `const`
/// at the crate's minimum Rust): `x + ½` is exact there, and the cast
/// rounds down.
const fn round_positive(x: f64) -> u64 {
    (x + 0.5) as u64
}

/// The σ floor of the estimator (`1/√12`) as a `d_t` of `dt_frac_bits`
/// fraction bits: `round(5.6/√12 · 2^dt_frac_bits)` (52 at 5 bits).
pub fn dt_floor_lsb(dt_frac_bits: u32) -> u32 {
    round_positive(THRESHOLD_FACTOR * SIGMA_FLOOR * (1u64 << dt_frac_bits) as f64) as u32
}

/// The histogram bin that holds the median, as the engine's scan finds it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MedianBin {
    /// The bin `v`: the integer |ΔI| of the median.
    pub value: u32,
    /// Differences in the bins below `v`.
    pub below: u32,
    /// Differences in bin `v` (at least one).
    pub count: u32,
}

/// The scan of the histogram `hist` of `n` differences: the first non-empty
/// bin `v` whose running count reaches `n/2`, `2·(below + h) ≥ n`; `None`
/// when `n = 0` (a line of one pixel).
pub fn median_bin(hist: &[u32; HIST_BINS], n: u32) -> Option<MedianBin> {
    let mut below = 0u32;
    for (v, &h) in hist.iter().enumerate() {
        if h > 0 && 2 * (below + h) >= n {
            return Some(MedianBin { value: v as u32, below, count: h });
        }
        below += h;
    }
    None
}

/// The in-bin fraction of the median, `(n/2 - below) / h`, with
/// [`MEDIAN_FRAC_BITS`] fraction bits, rounded down:
/// `q = ⌊(n - 2·below) · 2^MEDIAN_FRAC_BITS / (2h)⌋`, the engine's long
/// division (one quotient bit per clock), `0 < q ≤ 2^MEDIAN_FRAC_BITS`.
pub fn in_bin_fraction(bin: &MedianBin, n: u32) -> u32 {
    let num = (n - 2 * bin.below) as u64;
    ((num << MEDIAN_FRAC_BITS) / (2 * bin.count as u64)) as u32
}

/// `K·m · 2^DT_ACC_FRAC_BITS` as the engine's accumulator holds it, for the
/// median `m = v - ½ + q` (bin `v ≥ 1`, one grey level wide) or `m = q/2`
/// (bin 0, `[0, ½)`):
/// - `v ≥ 1`: `(2v - 1)·K_HALF + ⌊q·K_FRAC / 2^8⌋`;
/// - `v = 0`: `⌊q·K_FRAC / 2^9⌋` (the fraction counts half).
///
/// (`2^8` is `2^(MEDIAN_FRAC_BITS + K_FRAC_BITS - DT_ACC_FRAC_BITS)`.)
pub fn scaled_median(bin: &MedianBin, q: u32) -> u64 {
    let fraction = q as u64 * K_FRAC;
    if bin.value == 0 {
        fraction >> (FRAC_SHIFT + 1)
    } else {
        (2 * bin.value as u64 - 1) * K_HALF + (fraction >> FRAC_SHIFT)
    }
}

/// `d_t` in the detector's format, `dt_frac_bits` fraction bits: the
/// accumulator `acc` ([`DT_ACC_FRAC_BITS`] fraction bits) rounded to
/// nearest, halves up, `⌊(acc + 2^(s-1)) / 2^s⌋` with
/// `s = DT_ACC_FRAC_BITS - dt_frac_bits`, and at least
/// [`dt_floor_lsb`]`(dt_frac_bits)`; no median (`None`) gives the floor.
pub fn rounded_threshold(acc: Option<u64>, dt_frac_bits: u32) -> u32 {
    assert!(dt_frac_bits < DT_ACC_FRAC_BITS, "d_t has fewer fraction bits than the accumulator");
    let floor = dt_floor_lsb(dt_frac_bits);
    let s = DT_ACC_FRAC_BITS - dt_frac_bits;
    match acc {
        Some(acc) => (((acc + (1 << (s - 1))) >> s) as u32).max(floor),
        None => floor,
    }
}

/// Eq. 2 on the stored pixels of a line, as the threshold engine computes
/// it: `d_t · 2^dt_frac_bits`, an integer (module doc, steps 1–5).
pub fn adaptive_threshold(stored: &[u8], dt_frac_bits: u32) -> u32 {
    let n = stored.len().saturating_sub(1) as u32;
    let hist = abs_diff_histogram(stored);
    let acc = median_bin(&hist, n).map(|bin| scaled_median(&bin, in_bin_fraction(&bin, n)));
    rounded_threshold(acc, dt_frac_bits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::noise::{interpolated_median, line_threshold};

    /// The engine's long division, a bit per step (restoring): the quotient
    /// that [`in_bin_fraction`] computes with one `/`.
    fn long_division(num: u64, den: u64, bits: u32) -> u64 {
        let (mut rem, mut q) = (num, 0u64);
        for _ in 0..bits {
            if rem >= den {
                rem = (rem - den) << 1;
                q = (q << 1) | 1;
            } else {
                rem <<= 1;
                q <<= 1;
            }
        }
        q
    }

    #[test]
    fn in_bin_fraction_is_the_engines_long_division() {
        for n in 1..300u32 {
            for below in 0..=(n - 1) / 2 {
                for count in [1, 2, 3, (n + 1) / 2, n - below] {
                    if count == 0 || 2 * (below + count) < n || below + count > n {
                        continue;
                    }
                    let bin = MedianBin { value: 1, below, count };
                    let q = in_bin_fraction(&bin, n);
                    let want = long_division((n - 2 * below) as u64, 2 * count as u64, MEDIAN_FRAC_BITS + 1);
                    assert_eq!(q as u64, want, "n {n}, below {below}, h {count}");
                    assert!(q > 0 && q <= 1 << MEDIAN_FRAC_BITS);
                }
            }
        }
    }

    #[test]
    fn the_fixed_point_threshold_is_within_half_an_lsb_and_a_little_of_the_f64_one() {
        // The engine's doc: within half an LSB plus about 0.001 grey level.
        let mut rng = crate::test_rng::TestRng::new(0x0dd_ba11_5eed_d7d7);
        for case in 0..4000 {
            let n = (rng.next() % 700) as usize;
            let spread = 1 + rng.next() % 200;
            let line: Vec<u8> = (0..n).map(|_| (100 + rng.next() % spread).min(255) as u8).collect();
            let got = adaptive_threshold(&line, 5) as f64 / 32.0;
            let want = line_threshold(&line);
            assert!((got - want).abs() <= 0.5 / 32.0 + 0.002, "case {case}: {got} vs {want} (median {:?})", interpolated_median(&abs_diff_histogram(&line)));
        }
    }

    #[test]
    fn short_and_flat_lines_get_the_floor() {
        for line in [&[][..], &[9], &[3, 3], &[7; 100]] {
            assert_eq!(adaptive_threshold(line, 5), 52, "{line:?}");
        }
        // One difference of 9: bin 9, q = ½, so m = 8.5 + ½ = 9 and
        // d_t = 9K ≈ 52.84, 1690.8 in 1/32.
        assert_eq!(adaptive_threshold(&[0, 9], 5), 1691);
    }
}
