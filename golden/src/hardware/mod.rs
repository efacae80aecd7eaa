//! Hardware parity: the limits of the streaming detector applied to golden,
//! so that golden and the `rtl` detector can be compared line for line, and
//! frames processed as the hardware would process them.
//!
//! The hardware stores at most `w_max` pixels of a line and sends at most
//! `n_max` characteristic declivities per line (`rtl::detector::declivity_detector`):
//! - a longer line is processed as its first `w_max` pixels (its threshold,
//!   declivities and attributes come from them alone) and flagged `wide`;
//! - a line with more characteristic declivities keeps the first `n_max`,
//!   left to right, and is flagged `full`.
//!
//! and the matcher sees the detector's fixed-point outputs
//! ([`matcher_view`]): positions rounded down to `pos_frac_bits` fraction
//! bits (the eq. 3 divider's quotient), `d_t` rounded to `dt_frac_bits`
//! (the threshold unit's) then down to `match_dt_frac_bits` (the gain
//! rule's). Without the last step, golden's optimal path differs from the
//! hardware's on some pixels: a position moved by less than 1/16 px changes
//! a near tie of eq. 9.
//!
//! Everything else is golden's f64 method unchanged.

use crate::declivity::{characteristic_declivities, Declivity};
use crate::noise::line_threshold;

pub mod depth;
pub mod interpolate;
pub mod row_check;

/// The sizes of the hardware (its generation-time parameters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HardwareLimits {
    /// Widest line stored, pixels.
    pub w_max: usize,
    /// Characteristic declivities sent per line.
    pub n_max: usize,
    /// Fraction bits of a position as the detector sends it (rounded down).
    pub pos_frac_bits: u32,
    /// Fraction bits of `d_t` as the detector sends it (rounded).
    pub dt_frac_bits: u32,
    /// Fraction bits of `d_t` in the matcher's gain rule (rounded down from
    /// the detector's).
    pub match_dt_frac_bits: u32,
}

impl Default for HardwareLimits {
    /// The default hardware: `W_MAX` = 1024, `N_MAX` = 128 (`DESIGN.md` §3),
    /// positions in 1/16 px, `d_t` in 1/32 grey level, matched in 1/2.
    fn default() -> Self {
        HardwareLimits { w_max: 1024, n_max: 128, pos_frac_bits: 4, dt_frac_bits: 5, match_dt_frac_bits: 1 }
    }
}

/// What the hardware's matcher sees of a line: `d_t` and the declivities
/// in the detector's fixed-point formats (module doc), as reals.
pub fn matcher_view(line: &LimitedLine, limits: HardwareLimits) -> (f64, Vec<Declivity>) {
    let unit = (1u64 << limits.pos_frac_bits) as f64;
    let declivities = line.declivities.iter().map(|d| Declivity { position: (d.position * unit).floor() / unit, ..*d }).collect();
    let dt_lsb = (line.dt * (1u64 << limits.dt_frac_bits) as f64).round() as u64;
    let drop = limits.dt_frac_bits.saturating_sub(limits.match_dt_frac_bits);
    let dt = (dt_lsb >> drop) as f64 / (1u64 << (limits.dt_frac_bits - drop)) as f64;
    (dt, declivities)
}

/// One line through the limited detector.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitedLine {
    /// Eq. 2 threshold of the stored pixels.
    pub dt: f64,
    /// The characteristic declivities sent, left to right.
    pub declivities: Vec<Declivity>,
    /// The line was longer than `w_max`.
    pub wide: bool,
    /// The line had more than `n_max` characteristic declivities.
    pub full: bool,
}

/// The characteristic declivities of `line` as the hardware with `limits`
/// finds them (module doc).
pub fn detect_line(line: &[u8], limits: HardwareLimits) -> LimitedLine {
    let wide = line.len() > limits.w_max;
    let stored = &line[..line.len().min(limits.w_max)];
    let dt = line_threshold(stored);
    let mut declivities = characteristic_declivities(stored, dt);
    let full = declivities.len() > limits.n_max;
    declivities.truncate(limits.n_max);
    LimitedLine { dt, declivities, wide, full }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wide_line_is_its_first_w_max_pixels_and_a_full_line_keeps_the_first_n_max() {
        // 16 flat pixels, then a zig-zag of amplitude 100: within the first
        // 30 pixels the median |ΔI| is 0 (15 zeros of 29), so every one of
        // the 14 gradients of the zig-zag is a characteristic declivity.
        let mut line = vec![50u8; 16];
        line.extend((0..84).map(|x| if x % 2 == 0 { 150 } else { 50 }));
        let limits = HardwareLimits { w_max: 30, n_max: 10, ..HardwareLimits::default() };
        let got = detect_line(&line, limits);
        assert!(got.wide && got.full);
        assert_eq!(got.declivities.len(), 10);
        // The first 30 pixels hold 14 declivities; the kept ten are the
        // leftmost, as in the full line.
        let all = characteristic_declivities(&line[..30], got.dt);
        assert_eq!(all.len(), 14);
        assert_eq!(got.declivities, all[..10].to_vec());
        let roomy = detect_line(&line, HardwareLimits { w_max: 1000, n_max: 1000, ..HardwareLimits::default() });
        assert!(!roomy.wide && !roomy.full);
    }
}

#[cfg(test)]
mod parity_tests {
    use super::*;
    use crate::line::process_line;
    use crate::params::Params;

    fn textured(n: usize, seed: u64) -> Vec<u8> {
        let mut rng = crate::test_rng::TestRng::new(seed);
        let mut level = 128i32;
        (0..n)
            .map(|_| {
                level = (level + (rng.next() % 41) as i32 - 20).clamp(0, 255);
                level as u8
            })
            .collect()
    }

    #[test]
    fn parity_mode_changes_only_the_formats_within_the_limits_and_cuts_lines_beyond_them() {
        use crate::line::{line_features, line_features_with};
        let limits = HardwareLimits::default();
        let with = |p: &Params| Params { hardware: Some(limits), ..*p };
        let params = Params::new(40.0).unwrap();
        // Within the limits: the same declivities, positions rounded down
        // to 1/16 px, d_t to the matcher's 1/2 grey level.
        let l = textured(600, 1);
        let (free, hw) = (line_features(&l), line_features_with(&l, Some(limits)));
        assert_eq!(free.declivities.len(), hw.declivities.len());
        for (f, h) in free.declivities.iter().zip(&hw.declivities) {
            assert_eq!((f.start, f.end, f.amplitude, f.left, f.right), (h.start, h.end, h.amplitude, h.left, h.right));
            let lsb = f.position - h.position;
            assert!((0.0..1.0 / 16.0).contains(&lsb) && (h.position * 16.0).fract() == 0.0, "{} -> {}", f.position, h.position);
        }
        assert_eq!(hw.dt, ((free.dt * 32.0).round() / 16.0).floor() / 2.0);
        assert!(free.dt - hw.dt < 0.5 + 1.0 / 64.0);
        // A 1500-px line: parity keeps the first W_MAX pixels' declivities.
        let (l, r) = (textured(1500, 3), textured(1500, 4));
        let free = process_line(&l, &r, &params);
        let cut = process_line(&l, &r, &with(&params));
        assert!(free.reference.declivities.iter().any(|d| d.end >= limits.w_max));
        assert!(cut.reference.declivities.iter().all(|d| d.end < limits.w_max));
        assert_eq!(cut.reference.declivities, matcher_view(&detect_line(&l, limits), limits).1);
    }
}
