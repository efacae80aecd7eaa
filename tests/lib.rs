//! Shared generators for the workspace tests: seeded random number
//! generators, synthetic lines with known noise, textured lines and their
//! shifted copies, random gain tables and banded gain tables (proptest
//! strategies), and hand-built declivities.
//!
//! Everything random here is either driven by a seeded [`ChaCha8Rng`] (fixed
//! seeds, so loops over many lines are reproducible across machines and
//! versions) or is a proptest strategy (replayable through proptest's
//! persistence of failing cases).

use golden::declivity::Declivity;
use golden::dp::{BandRow, BandedGains, GainTable};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// A reproducible random number generator for the seeded test loops.
pub fn seeded(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

// ---------------------------------------------------------------------------
// Synthetic lines with known noise (for the σ estimator of eq. 2)
// ---------------------------------------------------------------------------

/// The shape of the noiseless profiles of [`clean_profile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileSpec {
    /// Lowest level the noiseless profile may take.
    pub lo: f64,
    /// Highest level the noiseless profile may take.
    pub hi: f64,
    /// Segment lengths are drawn from `min_seg ..= max_seg`.
    pub min_seg: usize,
    /// See `min_seg`.
    pub max_seg: usize,
    /// Largest absolute slope of a ramp segment (grey levels per pixel).
    pub max_slope: f64,
    /// Probability that a segment boundary is a step.
    pub step_prob: f64,
    /// Step amplitudes are drawn from `min_step ..= max_step` (either sign).
    pub min_step: f64,
    /// See `min_step`.
    pub max_step: f64,
}

impl Default for ProfileSpec {
    /// Smooth ramps (|slope| ≤ 0.25 grey level per pixel) and a few steps of
    /// 10–40 grey levels, kept inside 80–175 so that noise up to σ = 16
    /// (5σ = 80) is clamped at 0 or 255 only with a negligible probability.
    fn default() -> Self {
        ProfileSpec {
            lo: 80.0,
            hi: 175.0,
            min_seg: 24,
            max_seg: 120,
            max_slope: 0.25,
            step_prob: 0.5,
            min_step: 10.0,
            max_step: 40.0,
        }
    }
}

/// A noiseless profile of `width` samples: segments that are flat or gentle
/// ramps, separated by steps, all inside `[spec.lo, spec.hi]` (a step or a
/// ramp that would leave the range turns back).
pub fn clean_profile(rng: &mut impl Rng, width: usize, spec: &ProfileSpec) -> Vec<f64> {
    let mut out = Vec::with_capacity(width);
    let mut level = rng.gen_range(spec.lo..=spec.hi);
    while out.len() < width {
        let len = rng.gen_range(spec.min_seg..=spec.max_seg);
        let mut slope = if rng.gen_bool(0.3) { 0.0 } else { rng.gen_range(-spec.max_slope..=spec.max_slope) };
        for _ in 0..len {
            if out.len() == width {
                break;
            }
            out.push(level);
            let next = level + slope;
            if next < spec.lo || next > spec.hi {
                slope = -slope;
            }
            level = (level + slope).clamp(spec.lo, spec.hi);
        }
        if rng.gen_bool(spec.step_prob) {
            let mut a = rng.gen_range(spec.min_step..=spec.max_step);
            if rng.gen_bool(0.5) {
                a = -a;
            }
            if level + a < spec.lo || level + a > spec.hi {
                a = -a;
            }
            level = (level + a).clamp(spec.lo, spec.hi);
        }
    }
    out
}

/// The profile plus white Gaussian noise of deviation `sigma`, rounded to
/// integers and clamped to 0–255.
pub fn add_noise(rng: &mut impl Rng, profile: &[f64], sigma: f64) -> Vec<u8> {
    let normal = Normal::new(0.0, sigma).expect("sigma > 0");
    profile
        .iter()
        .map(|&v| (v + normal.sample(rng)).round().clamp(0.0, 255.0) as u8)
        .collect()
}

/// A 512-pixel synthetic line (default [`ProfileSpec`]) with noise `sigma`.
pub fn noisy_line(rng: &mut impl Rng, sigma: f64) -> Vec<u8> {
    let p = clean_profile(rng, 512, &ProfileSpec::default());
    add_noise(rng, &p, sigma)
}

// ---------------------------------------------------------------------------
// Textured lines for matching
// ---------------------------------------------------------------------------

/// A piecewise-constant line with big transitions: plateaus of 4–24 pixels
/// joined by monotone ramps of 1–3 pixels, each ramp step at least 8 grey
/// levels (a whole transition 24–120). More than half the gradients are zero,
/// so the line's σ estimate stays below `0.5/(0.6745·√2) ≈ 0.52` and
/// `d_t < 3`: every transition is a characteristic declivity.
pub fn block_line(rng: &mut impl Rng, width: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(width);
    let mut level: i32 = rng.gen_range(20..=235);
    while out.len() < width {
        let plateau = rng.gen_range(4..=24);
        for _ in 0..plateau {
            out.push(level as u8);
        }
        let steps = rng.gen_range(1..=3);
        let mut per_step: i32 = rng.gen_range(8..=40);
        if rng.gen_bool(0.5) {
            per_step = -per_step;
        }
        let target = level + per_step * steps;
        if !(0..=255).contains(&target) {
            per_step = -per_step;
        }
        for _ in 0..steps {
            level = (level + per_step).clamp(0, 255);
            out.push(level as u8);
        }
    }
    out.truncate(width);
    out
}

/// The right view of a fronto-parallel scene at integer disparity `d`:
/// `right[x] = left[x + d]`, the vacated end filled with the left line's last
/// pixel (which is exactly how the attributes clamp at the line's end).
pub fn shift_left_to_right(left: &[u8], d: usize) -> Vec<u8> {
    let w = left.len();
    let last = *left.last().expect("non-empty line");
    (0..w).map(|x| if x + d < w { left[x + d] } else { last }).collect()
}

/// Proptest strategy: a random line of `min_w ..= max_w` pixels whose texture
/// is a random mix of noise, ramps and steps (anything 0–255).
pub fn any_line(min_w: usize, max_w: usize) -> impl Strategy<Value = Vec<u8>> {
    (min_w..=max_w, any::<u64>(), 0u8..4).prop_map(|(w, seed, kind)| {
        let mut rng = seeded(seed);
        match kind {
            0 => (0..w).map(|_| rng.gen()).collect(),
            1 => block_line(&mut rng, w),
            2 => {
                let sigma = rng.gen_range(0.5..8.0);
                let p = clean_profile(&mut rng, w, &ProfileSpec::default());
                add_noise(&mut rng, &p, sigma)
            }
            _ => {
                let mut v: i32 = rng.gen_range(0..=255);
                (0..w)
                    .map(|_| {
                        v = (v + rng.gen_range(-12..=12)).clamp(0, 255);
                        v as u8
                    })
                    .collect()
            }
        }
    })
}

// ---------------------------------------------------------------------------
// Gain tables (eq. 9)
// ---------------------------------------------------------------------------

/// Proptest strategy: one local gain, `None` (no node) about a third of the
/// time, otherwise a value from a small set with negatives, zero and repeats
/// (to provoke ties), or an arbitrary value.
pub fn any_gain() -> impl Strategy<Value = Option<f64>> {
    prop_oneof![
        3 => Just(None),
        4 => (-3i32..=6).prop_map(|v| Some(v as f64)),
        1 => Just(Some(0.0)),
        2 => (-50.0f64..50.0).prop_map(Some),
    ]
}

/// Proptest strategy: a gain table of `0..=max_n × 0..=max_m`.
pub fn any_gain_table(max_n: usize, max_m: usize) -> impl Strategy<Value = GainTable> {
    (0..=max_n, 0..=max_m).prop_flat_map(|(n, m)| {
        proptest::collection::vec(any_gain(), n * m)
            .prop_map(move |cells| GainTable::from_fn(n, m, |i, j| cells[i * m + j]))
    })
}

/// Proptest strategy: a banded gain table, as eq. 6 makes it for sorted
/// positions: `m` columns, one band per row with `lo` and `lo + len` both
/// non-decreasing over the rows, empty bands included.
pub fn any_banded_gains(max_n: usize, max_m: usize) -> impl Strategy<Value = BandedGains> {
    (0..=max_n, 0..=max_m)
        .prop_flat_map(|(n, m)| {
            // For each row: an increment of lo, an increment of hi (both
            // then clamped to keep lo <= hi <= m), and the band's gains.
            let row = (0..=3usize, 0..=3usize, proptest::collection::vec(any_gain(), m));
            (Just(m), proptest::collection::vec(row, n))
        })
        .prop_map(|(m, rows)| {
            let (mut lo, mut hi) = (0usize, 0usize);
            let mut out = Vec::with_capacity(rows.len());
            for (dlo, dhi, gains) in rows {
                hi = (hi + dhi).min(m);
                lo = (lo + dlo).min(hi);
                out.push(BandRow { lo, gains: gains[lo..hi].to_vec() });
            }
            BandedGains::from_rows(m, &out)
        })
}

// ---------------------------------------------------------------------------
// Hand-built declivities
// ---------------------------------------------------------------------------

/// A declivity built by hand from its position and its six attribute grey
/// levels (`left = [I(x_i), I(x_i-1), I(x_i-2)]`,
/// `right = [I(x_{i+1}), I(x_{i+1}+1), I(x_{i+1}+2)]`); bounds and amplitude
/// are placeholders consistent with the position.
pub fn hand_declivity(position: f64, left: [u8; 3], right: [u8; 3]) -> Declivity {
    let start = position.floor().max(0.0) as usize;
    Declivity {
        start,
        end: start + 1,
        amplitude: right[0] as i32 - left[0] as i32,
        position,
        left,
        right,
    }
}
