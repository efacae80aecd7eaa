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
pub(crate) const MAD_NORMAL: f64 = 0.674_489_750_196_081_7;

/// Deviation of uniform quantization noise of one grey level: `1/√12`.
pub(crate) const SIGMA_FLOOR: f64 = 0.288_675_134_594_812_9;

/// The factor of eq. 2.
pub const THRESHOLD_FACTOR: f64 = 5.6;

/// Histogram of the absolute differences `|I(x+1) - I(x)|`, `x = 0 … W-2`.
/// A line of fewer than two pixels gives an empty histogram.
pub fn abs_diff_histogram(line: &[u8]) -> [u32; HIST_BINS] {
    let mut hist = [0u32; HIST_BINS];
    for w in line.windows(2) {
        hist[w[0].abs_diff(w[1]) as usize] += 1;
    }
    hist
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
    interpolated_median_of(n, |v| hist[v] as u64)
}

/// [`interpolated_median`] of `n` samples whose histogram is given bin by
/// bin by `count` (scanned from bin 0 up to the median bin only).
fn interpolated_median_of(n: u64, count: impl Fn(usize) -> u64) -> Option<f64> {
    if n == 0 {
        return None;
    }
    let half = n as f64 / 2.0;
    let mut below = 0u64;
    for v in 0..HIST_BINS {
        let h = count(v);
        if h > 0 && (below + h) as f64 >= half {
            let (lower, width) = if v == 0 { (0.0, 0.5) } else { (v as f64 - 0.5, 1.0) };
            return Some(lower + width * (half - below as f64) / h as f64);
        }
        below += h;
    }
    unreachable!("the counts add up to n")
}

/// σ from a median `m` of |ΔI| (DESIGN §2.1): `max(m / (0.6745·√2), 1/√12)`;
/// no median (fewer than two pixels) gives the floor.
fn sigma_from_median(m: Option<f64>) -> f64 {
    match m {
        Some(m) => (m / (MAD_NORMAL * std::f64::consts::SQRT_2)).max(SIGMA_FLOOR),
        None => SIGMA_FLOOR,
    }
}

/// σ of the line's noise (DESIGN §2.1): `max(m / (0.6745·√2), 1/√12)` with
/// `m` the interpolated median of |ΔI|. A line of fewer than two pixels has
/// no differences and gets the floor.
pub fn noise_sigma(line: &[u8]) -> f64 {
    let n = line.len().saturating_sub(1);
    // Noise is small: the median of |ΔI| usually lies in the first few bins
    // of the histogram, and those bins are counted faster one at a time, by
    // a pass over the differences that compares 16 bytes at once, than the
    // histogram is built a difference at a time.
    let diffs: Vec<u8> = line.iter().zip(line.get(1..).unwrap_or_default()).map(|(a, b)| a.abs_diff(*b)).collect();
    if n > 0 && count_where(&diffs, |d| d < SMALL_BINS) as f64 >= n as f64 / 2.0 {
        // The median bin is below SMALL_BINS: the scan stops there.
        return sigma_from_median(interpolated_median_of(n as u64, |v| {
            let v = v as u8;
            count_where(&diffs, |d| d == v)
        }));
    }
    // The histogram of `abs_diff_histogram`, kept as two interleaved halves
    // of 16-bit counts (consecutive increments of one bin, frequent as noise
    // is small, then do not wait on each other; lines of 65 536 pixels or
    // more take the 32-bit path), and read only up to its median bin.
    if n >= u16::MAX as usize {
        return sigma_from_histogram(&abs_diff_histogram(line));
    }
    let mut h = [[0u16; HIST_BINS]; 2];
    for (k, w) in line.windows(2).enumerate() {
        h[k & 1][w[0].abs_diff(w[1]) as usize] += 1;
    }
    sigma_from_median(interpolated_median_of(n as u64, |v| h[0][v] as u64 + h[1][v] as u64))
}

/// [`noise_sigma`] counts the bins below this one by one when the median
/// lies there, and builds the histogram otherwise.
const SMALL_BINS: u8 = 16;

/// How many of `values` `take` holds for, counted in bytes over runs of 255
/// (no overflow): a compare and a subtract per 16 values.
#[inline]
fn count_where(values: &[u8], take: impl Fn(u8) -> bool) -> u64 {
    values.chunks(255).map(|run| run.iter().fold(0u8, |c, &v| c + take(v) as u8) as u64).sum()
}

/// σ from an already built |ΔI| histogram (the hardware builds it while the
/// line streams in).
pub fn sigma_from_histogram(hist: &[u32; HIST_BINS]) -> f64 {
    sigma_from_median(interpolated_median(hist))
}

/// Eq. 2: the self-adaptive declivity threshold `d_t = 5.6 σ`.
pub fn threshold(sigma: f64) -> f64 {
    THRESHOLD_FACTOR * sigma
}

/// Eq. 2 on a line: `d_t` from the line's own noise estimate.
pub fn line_threshold(line: &[u8]) -> f64 {
    threshold(noise_sigma(line))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_sigma_equals_sigma_of_the_histogram() {
        let mut rng = crate::test_rng::TestRng::new(0x1234_5678_9abc_def1u64);
        let mut next = move || rng.next();
        for _ in 0..5000 {
            let n = (next() % 600) as usize;
            let spread = 1 + next() % 255;
            let base = (next() % 256) as i64;
            let line: Vec<u8> = (0..n).map(|_| (base + (next() % spread) as i64 - spread as i64 / 2).clamp(0, 255) as u8).collect();
            assert_eq!(noise_sigma(&line), sigma_from_histogram(&abs_diff_histogram(&line)), "{line:?}");
        }
    }
}
