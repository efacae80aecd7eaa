//! Eq. 3 as the detector computes it: the tracker's two integer sums
//! (`rtl::detector::declivity_tracker`) and the divider's quotient
//! (`rtl::detector::position_divider`).
//!
//! `X_i = Σ g²(x + ½) / Σ g²` over `x = x_i … x_{i+1}-1`, with
//! `g(x) = I(x+1) - I(x)`, is
//!
//! ```text
//! X_i · 2^P = S1 · 2^(P-1) / S0,   S0 = Σ g²,   S1 = Σ g²(2x + 1)
//! ```
//!
//! for `P` fraction bits, and the divider returns its floor. Zero gradients
//! (a plateau inside the run) add nothing to either sum, so the sums over
//! the run's non-zero gradients, which the tracker accumulates, are the
//! sums over all of `x_i … x_{i+1}-1`. Neither sum saturates: a
//! declivity's gradients share a sign and add up to at most 255, so
//! `S0 ≤ 255²` (16 bits) and `S1 < 255² · 2·W_MAX` (27 bits at
//! `W_MAX` = 1024).

/// The tracker's sums of the declivity `(start, end)` of `line`:
/// `(S0, S1) = (Σ g², Σ g²(2x + 1))`, exact integers.
pub fn eq3_sums(line: &[u8], start: usize, end: usize) -> (u64, u64) {
    crate::declivity::position_sums_windowed(line, start, end)
}

/// The divider's quotient, the position in units of `1/2^pos_frac_bits`
/// px: `⌊S1 · 2^(pos_frac_bits - 1) / S0⌋` (`S0 > 0`: a declivity has a
/// non-zero gradient).
pub fn divided_position(s0: u64, s1: u64, pos_frac_bits: u32) -> u32 {
    assert!(pos_frac_bits >= 1, "S1 holds twice the numerator: one fraction bit at least");
    ((s1 << (pos_frac_bits - 1)) / s0) as u32
}

/// The position of the declivity `(start, end)` of `line` as the detector
/// sends it, in units of `1/2^pos_frac_bits` px.
pub fn position_lsb(line: &[u8], start: usize, end: usize, pos_frac_bits: u32) -> u32 {
    let (s0, s1) = eq3_sums(line, start, end);
    divided_position(s0, s1, pos_frac_bits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::declivity::{declivity_bounds, position};

    #[test]
    fn the_quotient_is_the_floor_of_the_f64_position_away_from_exact_multiples() {
        let mut rng = crate::test_rng::TestRng::new(0x9051_7105_d1c1_de00);
        let (mut exact, mut checked) = (0, 0);
        for _ in 0..2000 {
            let n = 2 + (rng.next() % 60) as usize;
            let line: Vec<u8> = (0..n).map(|_| (rng.next() % 256) as u8).collect();
            for (s, e) in declivity_bounds(&line) {
                let lsb = position_lsb(&line, s, e, 4);
                let x = position(&line, s, e) * 16.0;
                let (s0, s1) = eq3_sums(&line, s, e);
                if (s1 * 8) % s0 == 0 {
                    // An exact multiple of 1/16: the quotient is it, whatever
                    // the f64 rounding did.
                    assert_eq!(lsb as u64 * s0, s1 * 8);
                    exact += 1;
                } else {
                    assert_eq!(lsb, x.floor() as u32, "{s}..{e} of {line:?}");
                }
                checked += 1;
            }
        }
        assert!(exact > 100 && checked > 10_000, "{exact} exact of {checked}");
    }

    #[test]
    fn a_one_step_declivity_sits_at_its_half_pixel() {
        // g(3) = 40 alone: X = 3.5, 56 sixteenths.
        let line = [10, 10, 10, 10, 50, 50];
        assert_eq!(position_lsb(&line, 3, 4, 4), 56);
        // g(1) = g(2): X = 2, exactly.
        assert_eq!(position_lsb(&[0, 0, 5, 10, 10], 1, 3, 4), 32);
    }
}
