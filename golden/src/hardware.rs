//! Hardware parity: the limits of the streaming detector applied to golden,
//! so that golden and the `rtl` detector can be compared line for line, and
//! frames processed as the hardware would process them.
//!
//! The hardware stores at most `w_max` pixels of a line and sends at most
//! `n_max` characteristic declivities per line (`rtl::declivity_detector`):
//! - a longer line is processed as its first `w_max` pixels (its threshold,
//!   declivities and attributes come from them alone) and flagged `wide`;
//! - a line with more characteristic declivities keeps the first `n_max`,
//!   left to right, and is flagged `full`.
//!
//! Everything else is golden's f64 method unchanged.

use crate::declivity::{characteristic_declivities, Declivity};
use crate::noise::line_threshold;

/// The sizes of the hardware (its generation-time parameters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HardwareLimits {
    /// Widest line stored, pixels.
    pub w_max: usize,
    /// Characteristic declivities sent per line.
    pub n_max: usize,
}

impl Default for HardwareLimits {
    /// The default hardware: `W_MAX` = 1024, `N_MAX` = 128 (`DESIGN.md` §3).
    fn default() -> Self {
        HardwareLimits { w_max: 1024, n_max: 128 }
    }
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
        let limits = HardwareLimits { w_max: 30, n_max: 10 };
        let got = detect_line(&line, limits);
        assert!(got.wide && got.full);
        assert_eq!(got.declivities.len(), 10);
        // The first 30 pixels hold 14 declivities; the kept ten are the
        // leftmost, as in the full line.
        let all = characteristic_declivities(&line[..30], got.dt);
        assert_eq!(all.len(), 14);
        assert_eq!(got.declivities, all[..10].to_vec());
        let roomy = detect_line(&line, HardwareLimits { w_max: 1000, n_max: 1000 });
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
    fn parity_mode_changes_nothing_within_the_limits_and_cuts_lines_beyond_them() {
        let limits = HardwareLimits::default();
        let with = |p: &Params| Params { hardware: Some(limits), ..*p };
        let params = Params::new(40.0).unwrap();
        // Within the limits: the same result.
        let (l, r) = (textured(600, 1), textured(600, 2));
        assert_eq!(process_line(&l, &r, &params), process_line(&l, &r, &with(&params)));
        // A 1500-px line: parity keeps the first W_MAX pixels' declivities.
        let (l, r) = (textured(1500, 3), textured(1500, 4));
        let free = process_line(&l, &r, &params);
        let cut = process_line(&l, &r, &with(&params));
        assert!(free.reference.declivities.iter().any(|d| d.end >= limits.w_max));
        assert!(cut.reference.declivities.iter().all(|d| d.end < limits.w_max));
        assert_eq!(cut.reference.declivities, detect_line(&l, limits).declivities);
    }
}
