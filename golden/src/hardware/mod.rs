//! Hardware parity: golden computes what the streaming detector
//! (`rtl::detector::declivity_detector`) computes, bit for bit, so that
//! golden and the `rtl` detector can be compared record for record, and
//! frames processed as the hardware would process them.
//!
//! [`detect_line`] follows the detector's engines, one function per step:
//!
//! | step | hardware | here |
//! |---|---|---|
//! | store at most `w_max` pixels | input engine (line buffer) | [`stored_pixels`] |
//! | `d_t` (eq. 2) in fixed point | threshold engine (`adaptive_threshold`) | [`threshold::adaptive_threshold`] |
//! | extrema, `\|a_i\| > ⌊d_t⌋` | tracker (`declivity_tracker`) | [`characteristic_spans`] |
//! | `S0 = Σ g²`, `S1 = Σ g²(2x+1)` and `⌊S1·2^(P-1)/S0⌋` (eq. 3) | tracker, divider (`position_divider`) | [`position::position_lsb`] |
//! | the first `n_max` records | tracker | [`detect_line`] |
//!
//! The limits of the hardware:
//! - a line longer than `w_max` is processed as its first `w_max` pixels
//!   (its threshold, declivities and attributes come from them alone) and
//!   flagged `wide`;
//! - a line with more characteristic declivities keeps the first `n_max`,
//!   left to right, and is flagged `full`.
//!
//! The matcher sees the detector's outputs ([`matcher_view`]): the
//! positions as sent, `d_t` rounded down from the detector's
//! `dt_frac_bits` to `match_dt_frac_bits` (the gain rule's).
//!
//! The amplitude, bounds and neighbour levels of a declivity are golden's
//! integers ([`crate::declivity`]), which the tracker computes the same way.
//!
//! Before it, [`framing`] cuts a camera's stream into the lines the detector
//! stores, faults included (a frame's width, cut lines, a `tuser` inside a
//! line).
//!
//! After the matcher, [`row_check`], [`interpolate`] and [`depth`] take the
//! row check, the interpolator and the depth stage in their fixed-point
//! formats.

pub mod depth;
pub mod framing;
pub mod interpolate;
pub mod position;
pub mod row_check;
pub mod threshold;

use crate::declivity::{amplitude, declivity_spans, neighbour_levels, Declivity};

/// The sizes of the hardware (its generation-time parameters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HardwareLimits {
    /// Widest line stored, pixels.
    pub w_max: usize,
    /// Characteristic declivities sent per line.
    pub n_max: usize,
    /// Fraction bits of a position as the detector sends it (the eq. 3
    /// quotient, rounded down).
    pub pos_frac_bits: u32,
    /// Fraction bits of `d_t` as the detector sends it (rounded to nearest
    /// from the threshold engine's accumulator).
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

/// One line through the detector.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitedLine {
    /// The detector's `d_t` (eq. 2) of the stored pixels, in units of
    /// `1/2^dt_frac_bits` grey level ([`threshold::adaptive_threshold`]).
    pub dt_lsb: u32,
    /// The same `d_t` in grey levels, `dt_lsb / 2^dt_frac_bits` (exact).
    pub dt: f64,
    /// The characteristic declivities sent, left to right; each position
    /// is the detector's, an exact multiple of `1/2^pos_frac_bits` px
    /// ([`position::position_lsb`]).
    pub declivities: Vec<Declivity>,
    /// The line was longer than `w_max`.
    pub wide: bool,
    /// The line had more than `n_max` characteristic declivities.
    pub full: bool,
}

/// The pixels the input engine stores: the first `w_max` of `line`, and
/// whether the line was longer (`wide`).
pub fn stored_pixels(line: &[u8], w_max: usize) -> (&[u8], bool) {
    (&line[..line.len().min(w_max)], line.len() > w_max)
}

/// The bounds `(x_i, x_{i+1})` of the declivities the tracker finds
/// characteristic, left to right: `|a_i| > ⌊d_t⌋` with the integer part of
/// the detector's `d_t` (the tracker's `in_thr`, `dt_lsb >> dt_frac_bits`).
/// For an integer amplitude this is `|a_i| > d_t` with the fixed-point
/// `d_t`.
pub fn characteristic_spans(stored: &[u8], dt_lsb: u32, dt_frac_bits: u32) -> Vec<(usize, usize)> {
    declivity_spans(stored, dt_lsb >> dt_frac_bits)
}

/// The record of the declivity `(start, end)` of the stored pixels: golden's
/// amplitude and neighbour levels, and the detector's position.
pub fn declivity_record(stored: &[u8], start: usize, end: usize, pos_frac_bits: u32) -> Declivity {
    let (left, right) = neighbour_levels(stored, start, end);
    let lsb = position::position_lsb(stored, start, end, pos_frac_bits);
    Declivity {
        start,
        end,
        amplitude: amplitude(stored, start, end),
        position: lsb as f64 / (1u64 << pos_frac_bits) as f64,
        left,
        right,
    }
}

/// The characteristic declivities of `line` as the detector with `limits`
/// finds and sends them (module doc).
pub fn detect_line(line: &[u8], limits: HardwareLimits) -> LimitedLine {
    let (stored, wide) = stored_pixels(line, limits.w_max);
    let dt_lsb = threshold::adaptive_threshold(stored, limits.dt_frac_bits);
    let spans = characteristic_spans(stored, dt_lsb, limits.dt_frac_bits);
    let full = spans.len() > limits.n_max;
    let declivities =
        spans.iter().take(limits.n_max).map(|&(s, e)| declivity_record(stored, s, e, limits.pos_frac_bits)).collect();
    let dt = dt_lsb as f64 / (1u64 << limits.dt_frac_bits) as f64;
    LimitedLine { dt_lsb, dt, declivities, wide, full }
}

/// What the hardware's matcher sees of a line: its `d_t` (the detector's
/// rounded down to `match_dt_frac_bits` fraction bits:
/// `dt_lsb >> (dt_frac_bits - match_dt_frac_bits)`) and the declivities
/// as the detector sends them, as reals (exact).
pub fn matcher_view(line: &LimitedLine, limits: HardwareLimits) -> (f64, Vec<Declivity>) {
    let drop = limits.dt_frac_bits.saturating_sub(limits.match_dt_frac_bits);
    let dt = (line.dt_lsb >> drop) as f64 / (1u64 << (limits.dt_frac_bits - drop)) as f64;
    (dt, line.declivities.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::declivity::characteristic_declivities;

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
        // The median is in bin 0 (½ wide), 14.5 of its 15 counts in:
        // m = ½·14.5/15, d_t = K·m ≈ 2.84, 91 in 1/32.
        assert_eq!(got.dt_lsb, 91);
        let all = characteristic_declivities(&line[..30], got.dt);
        assert_eq!(all.len(), 14);
        let bounds = |d: &[Declivity]| d.iter().map(|d| (d.start, d.end, d.amplitude)).collect::<Vec<_>>();
        assert_eq!(bounds(&got.declivities), bounds(&all[..10]));
        // One gradient each: X = x + ½ exactly.
        assert!(got.declivities.iter().all(|d| d.position == d.start as f64 + 0.5));
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
        // Within the limits: the same declivities (no amplitude of this line
        // sits between the f64 and the fixed-point d_t), positions the
        // f64 ones rounded down to 1/16 px (the quotient of exact integers:
        // an f64 a hair below a multiple of 1/16 is that multiple), d_t
        // within half an LSB and a little of the f64 one, and the matcher's
        // d_t the detector's rounded down to 1/2 grey level.
        let l = textured(600, 1);
        let (free, hw, detected) = (line_features(&l), line_features_with(&l, Some(limits)), detect_line(&l, limits));
        assert_eq!(free.declivities.len(), hw.declivities.len());
        for (f, h) in free.declivities.iter().zip(&hw.declivities) {
            assert_eq!((f.start, f.end, f.amplitude, f.left, f.right), (h.start, h.end, h.amplitude, h.left, h.right));
            let lsb = f.position - h.position;
            assert!((-1e-9..1.0 / 16.0).contains(&lsb) && (h.position * 16.0).fract() == 0.0, "{} -> {}", f.position, h.position);
        }
        assert!((detected.dt - free.dt).abs() <= 0.5 / 32.0 + 0.002, "{} vs {}", detected.dt, free.dt);
        assert_eq!(detected.dt, detected.dt_lsb as f64 / 32.0);
        assert_eq!(hw.dt, (detected.dt_lsb >> 4) as f64 / 2.0);
        // A 1500-px line: parity keeps the first W_MAX pixels' declivities.
        let (l, r) = (textured(1500, 3), textured(1500, 4));
        let free = process_line(&l, &r, &params);
        let cut = process_line(&l, &r, &with(&params));
        assert!(free.reference.declivities.iter().any(|d| d.end >= limits.w_max));
        assert!(cut.reference.declivities.iter().all(|d| d.end < limits.w_max));
        assert_eq!(cut.reference.declivities, matcher_view(&detect_line(&l, limits), limits).1);
    }
}
