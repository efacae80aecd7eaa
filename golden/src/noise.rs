//! Self-adaptive threshold (paper §II, eq. 2): `d_t = 5.6 σ`, with σ the
//! standard deviation of the line's white Gaussian noise, estimated from the
//! line itself.
//!
//! The paper does not give its estimator; `DESIGN.md` §2.1 settles a robust
//! stand-in that the hardware can stream:
//!
//! 1. the histogram of `|I(x+1) - I(x)|` over the line ([`abs_diff_histogram`]);
//! 2. its median `m` with linear interpolation inside the median bin
//!    ([`interpolated_median`]), so that `m` is not stuck at integers;
//! 3. `σ = m / (0.6745·√2)`: the median absolute value of the difference of
//!    two samples of white noise of deviation σ is `0.6745·√2·σ`
//!    ([`noise_sigma`]);
//! 4. σ floored at the quantization noise `1/√12`, so that a flat line does
//!    not turn every ripple into a feature.

/// Number of bins of the |ΔI| histogram: 8-bit grey levels.
pub const HIST_BINS: usize = 256;

/// The median of |N(0,1)|: `Φ⁻¹(3/4)`.
pub const MAD_NORMAL: f64 = 0.674_489_750_196_081_7;

/// Deviation of uniform quantization noise of one grey level: `1/√12`.
pub const SIGMA_FLOOR: f64 = 0.288_675_134_594_812_9;

/// The factor of eq. 2.
pub const THRESHOLD_FACTOR: f64 = 5.6;

/// Histogram of the absolute differences `|I(x+1) - I(x)|`, `x = 0 … W-2`.
/// A line of fewer than two pixels gives an empty histogram.
pub fn abs_diff_histogram(line: &[u8]) -> [u32; HIST_BINS] {
    // Two interleaved histograms, summed at the end: consecutive increments
    // of the same bin (frequent: noise is small) then do not wait on each
    // other.
    let mut h = [[0u32; HIST_BINS]; 2];
    let diffs = line.windows(2).map(|w| w[0].abs_diff(w[1]) as usize);
    for (k, d) in diffs.enumerate() {
        h[k & 1][d] += 1;
    }
    std::array::from_fn(|v| h[0][v] + h[1][v])
}

/// Median of an integer-valued histogram with linear interpolation inside
/// the median bin; `None` for an empty histogram.
///
/// The integer value `v ≥ 1` stands for the interval `[v - ½, v + ½)` of the
/// underlying continuous |ΔI|; `v = 0` stands for `[0, ½)` (an absolute value
/// is never negative). With `n` samples, `c` of them in bins below `v` and
/// `h` in bin `v`, where `c < n/2 ≤ c + h`, the median is
/// `lower(v) + width(v) · (n/2 - c) / h`.
pub fn interpolated_median(hist: &[u32; HIST_BINS]) -> Option<f64> {
    let n: u64 = hist.iter().map(|&h| h as u64).sum();
    if n == 0 {
        return None;
    }
    let half = n as f64 / 2.0;
    let mut below = 0u64;
    for (v, &h) in hist.iter().enumerate() {
        if h > 0 && (below + h as u64) as f64 >= half {
            let (lower, width) = if v == 0 { (0.0, 0.5) } else { (v as f64 - 0.5, 1.0) };
            return Some(lower + width * (half - below as f64) / h as f64);
        }
        below += h as u64;
    }
    unreachable!("the cumulative count reaches n")
}

/// σ of the line's noise (DESIGN §2.1): `max(m / (0.6745·√2), 1/√12)` with
/// `m` the interpolated median of |ΔI|. A line of fewer than two pixels has
/// no differences and gets the floor.
pub fn noise_sigma(line: &[u8]) -> f64 {
    let hist = abs_diff_histogram(line);
    sigma_from_histogram(&hist)
}

/// σ from an already built |ΔI| histogram (the hardware builds it while the
/// line streams in).
pub fn sigma_from_histogram(hist: &[u32; HIST_BINS]) -> f64 {
    match interpolated_median(hist) {
        Some(m) => (m / (MAD_NORMAL * std::f64::consts::SQRT_2)).max(SIGMA_FLOOR),
        None => SIGMA_FLOOR,
    }
}

/// Eq. 2: the self-adaptive declivity threshold `d_t = 5.6 σ`.
pub fn threshold(sigma: f64) -> f64 {
    THRESHOLD_FACTOR * sigma
}

/// Eq. 2 on a line: `d_t` from the line's own noise estimate.
pub fn line_threshold(line: &[u8]) -> f64 {
    threshold(noise_sigma(line))
}
