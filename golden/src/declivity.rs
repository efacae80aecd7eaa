//! Declivities (paper §II–III): segmentation of a line into the runs between
//! consecutive extrema, the amplitude test that keeps the characteristic ones,
//! their sub-pixel position (eq. 3) and their attributes.
//!
//! ## Extrema and the plateau rule
//! The gradient is `g(x) = I(x+1) - I(x)`, `x = 0 … W-2`. A local extremum is
//! where the sign of the **non-zero** gradient changes; zero steps (flat runs)
//! are skipped while tracking the sign, so a flat stretch inside a monotone run
//! does not break it. A declivity is the run between two consecutive extrema.
//!
//! Bounds follow the *tight* rule: a declivity starts at the pixel `x_i` of its
//! first non-zero gradient and ends at the pixel `x_{i+1}` just after its last
//! non-zero gradient. Of a plateau between a rise and a fall, the rise ends at
//! the plateau's first pixel and the fall starts at its last pixel. The line's
//! ends close the first and last declivity the same way: a flat run at either
//! end of the line belongs to no declivity. A flat line has no declivity.
//! Neither choice changes eq. 3 (zero gradients have no weight) nor the
//! amplitude (a plateau is flat); they fix which pixels the attributes read.

/// One declivity of a line with the attributes the matcher uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Declivity {
    /// First extremum `x_i` (pixel index).
    pub start: usize,
    /// Second extremum `x_{i+1}` (pixel index), `> start`.
    pub end: usize,
    /// `a_i = I(x_{i+1}) - I(x_i)`; its sign is the polarity.
    pub amplitude: i32,
    /// Sub-pixel position `X_i` of eq. 3, in pixel coordinates (pixel `x`
    /// has its centre at `x`).
    pub position: f64,
    /// `I(x_i - k)`, k = 0, 1, 2, clamped at the line's first pixel.
    pub left: [u8; 3],
    /// `I(x_{i+1} + k)`, k = 0, 1, 2, clamped at the line's last pixel.
    pub right: [u8; 3],
}

impl Declivity {
    /// `+1` for a rising declivity, `-1` for a falling one.
    pub fn polarity(&self) -> i32 {
        self.amplitude.signum()
    }
}

/// Iterator over the bounds `(x_i, x_{i+1})` of every declivity of a line,
/// left to right (the plateau rule is in the module doc).
#[derive(Debug, Clone)]
pub struct DeclivityBounds<'a> {
    line: &'a [u8],
    x: usize,
}

impl Iterator for DeclivityBounds<'_> {
    type Item = (usize, usize);

    fn next(&mut self) -> Option<(usize, usize)> {
        let line = self.line;
        let n = line.len();
        // Skip flat steps up to the first non-zero gradient.
        while self.x + 1 < n && line[self.x] == line[self.x + 1] {
            self.x += 1;
        }
        if self.x + 1 >= n {
            return None;
        }
        let start = self.x;
        let rising = line[start + 1] > line[start];
        let mut last_nonzero = start;
        let mut x = start + 1;
        while x + 1 < n {
            let (a, b) = (line[x], line[x + 1]);
            if a != b {
                if (b > a) != rising {
                    break;
                }
                last_nonzero = x;
            }
            x += 1;
        }
        let end = last_nonzero + 1;
        // The next declivity starts at or after this one's end.
        self.x = end;
        Some((start, end))
    }
}

/// The bounds of every declivity of `line`, characteristic or not, walked
/// run by run exactly as the module doc defines them (the reference that
/// [`declivity_bounds`] is tested against).
pub fn declivity_bounds_reference(line: &[u8]) -> DeclivityBounds<'_> {
    DeclivityBounds { line, x: 0 }
}

/// The bounds `(x_i, x_{i+1})` of the declivities of `line` whose amplitude
/// exceeds `threshold` in absolute value, left to right: the same as the
/// reference walk ([`declivity_bounds_reference`]) filtered by amplitude,
/// computed 64 gradients at a time.
///
/// For each block of 64 gradients `g(x) = I(x+1) - I(x)` two bit masks are
/// built: `nz` (g ≠ 0) and `up` (g > 0). A declivity starts at every non-zero
/// gradient whose sign differs from the last non-zero sign before it; that
/// sign is `up` filled forward through the zero gradients (a segmented
/// prefix scan on the bits, carried from block to block). Only the starts
/// are then visited, one by one: each closes the declivity under way, which
/// ends one pixel after the last non-zero gradient before the start. The
/// flat run between that end and the start keeps the end's level, so the
/// amplitude `I(start) - I(x_i)` is known there and tested against
/// `threshold`.
pub(crate) fn declivity_spans(line: &[u8], threshold: u32) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    declivity_spans_into(line, threshold, &mut spans);
    spans
}

/// [`declivity_spans`] into `spans` (cleared first), so that its allocation
/// can be reused from line to line.
fn declivity_spans_into(line: &[u8], threshold: u32, spans: &mut Vec<(usize, usize)>) {
    spans.clear();
    let n = line.len();
    if n < 2 {
        return;
    }
    let gradients = n - 1;
    spans.reserve(n);
    // The declivities a block closes: the first k are kept; each is written
    // into slot k, which the next one overwrites unless it was kept (no
    // branch on the outcome). A block has at most 64 starts.
    let mut closed = [(0usize, 0usize); 64];
    // State carried across blocks: a non-zero gradient was met, the sign of
    // the last one, the declivity under way and one past its last non-zero
    // gradient.
    let (mut seen, mut rising) = (false, false);
    let (mut start, mut start_level, mut end) = (0usize, 0u8, 0usize);
    let mut base = 0usize;
    while base < gradients {
        let len = (gradients - base).min(64);
        let (up, nz) = gradient_masks(&line[base..=base + len]);
        if nz != 0 {
            // f: the sign of the last non-zero gradient at or before each bit.
            let mut f = up & nz;
            let mut copy = !nz;
            if rising {
                f |= copy & !copy.wrapping_add(1); // the zeros before the first non-zero
            }
            let mut s = 1;
            while s < 64 {
                f |= (f << s) & copy;
                copy &= copy << s;
                s <<= 1;
            }
            let before = (f << 1) | rising as u64;
            let mut starts = nz & (up ^ before);
            if !seen {
                starts |= nz & nz.wrapping_neg(); // the line's first non-zero gradient
            }
            // nz with its bits reversed: the nearest non-zero gradient below a
            // bit is then a trailing zero count (fast) rather than a leading
            // one (a slow `bsr` on x86-64 without `lzcnt`).
            let rnz = nz.reverse_bits();
            let mut k = 0usize;
            while starts != 0 {
                let p = starts.trailing_zeros() as usize;
                starts &= starts - 1;
                // Bit j: gradient p - 1 - j is non-zero; none in the block
                // only before its first start.
                let below = (rnz >> (63 - p)) >> 1;
                let e = if below != 0 { base + p - below.trailing_zeros() as usize } else { end };
                let x = base + p;
                closed[k] = (start, e);
                k += (seen & (line[x].abs_diff(start_level) as u32 > threshold)) as usize;
                seen = true;
                start = x;
                start_level = line[x];
            }
            spans.extend_from_slice(&closed[..k]);
            end = base + 64 - nz.leading_zeros() as usize;
            rising = (up >> (63 - nz.leading_zeros())) & 1 == 1;
        }
        base += 64;
    }
    if seen && line[end].abs_diff(start_level) as u32 > threshold {
        spans.push((start, end));
    }
}

/// Bit masks of the gradients of `w` (at most 65 pixels, so at most 64
/// gradients): bit `i` of `up` is `w[i+1] > w[i]`, bit `i` of `nz` is
/// `w[i+1] != w[i]`.
#[inline]
fn gradient_masks(w: &[u8]) -> (u64, u64) {
    let len = w.len() - 1;
    debug_assert!(len <= 64);
    let mut upb = [0u8; 64];
    let mut nzb = [0u8; 64];
    for i in 0..len {
        upb[i] = (w[i + 1] > w[i]) as u8;
        nzb[i] = (w[i + 1] != w[i]) as u8;
    }
    // Eight 0/1 bytes to eight bits: the product moves byte i's bit to bit
    // 56 + i (the classic multiply-gather), and no two terms collide there.
    let pack = |b: &[u8; 64]| -> u64 {
        (0..8).fold(0u64, |m, j| {
            let chunk = u64::from_le_bytes(b[8 * j..8 * j + 8].try_into().expect("8 bytes"));
            m | ((chunk.wrapping_mul(0x0102_0408_1020_4080) >> 56) << (8 * j))
        })
    };
    (pack(&upb), pack(&nzb))
}

/// The bounds `(x_i, x_{i+1})` of every declivity of `line`, left to right:
/// the same as [`declivity_bounds_reference`], from [`declivity_spans`]
/// (every declivity has `|a_i| ≥ 1 > 0`).
pub fn declivity_bounds(line: &[u8]) -> Vec<(usize, usize)> {
    declivity_spans(line, 0)
}

/// The amplitude threshold of [`declivity_spans`] equivalent to `|a_i| > d_t`:
/// amplitudes are integers, so `|a| > d_t ⇔ |a| > ⌊d_t⌋` for `d_t ≥ 0`.
pub fn integer_threshold(dt: f64) -> u32 {
    dt.max(0.0).floor().min(u32::MAX as f64) as u32
}

/// Amplitude `a_i = I(x_{i+1}) - I(x_i)` of the declivity `(start, end)`.
#[inline]
pub fn amplitude(line: &[u8], start: usize, end: usize) -> i32 {
    line[end] as i32 - line[start] as i32
}

/// A declivity is characteristic when its amplitude exceeds the line's
/// threshold: `|a_i| > d_t` (paper §II, with `d_t` of eq. 2).
#[inline]
pub fn is_characteristic(amplitude: i32, dt: f64) -> bool {
    amplitude.unsigned_abs() as f64 > dt
}

/// The two sums of eq. 3 over `x = start … end-1`, exact in integers:
/// `(Σ g(x)², Σ g(x)²·(2x+1))`. The second is twice `Σ g²(x + 0.5)`.
#[inline]
pub fn position_sums(line: &[u8], start: usize, end: usize) -> (u64, u64) {
    let mut s0 = 0u64;
    let mut s1 = 0u64;
    for x in start..end {
        let g = line[x + 1] as i64 - line[x] as i64;
        let g2 = (g * g) as u64;
        s0 += g2;
        s1 += g2 * (2 * x as u64 + 1);
    }
    (s0, s1)
}

/// Eq. 3: `X_i = Σ g(x)² (x + 0.5) / Σ g(x)²` over `x = x_i … x_{i+1}-1`,
/// `g(x) = I(x+1) - I(x)`. Every declivity has a non-zero gradient, so the
/// denominator is positive.
#[inline]
pub fn position(line: &[u8], start: usize, end: usize) -> f64 {
    let (s0, s1) = position_sums_windowed(line, start, end);
    debug_assert!(s0 > 0, "a declivity has a non-zero gradient");
    s1 as f64 / (2.0 * s0 as f64)
}

/// Gradients summed at once by [`position_sums_windowed`].
const POSITION_WINDOW: usize = 8;

/// [`position_sums`], the same integers, over a fixed window of
/// [`POSITION_WINDOW`] gradients from `start` with those at or past `end`
/// weighted 0, when the declivity and the window fit (most declivities span
/// a few pixels): no loop whose length varies from one declivity to the
/// next, so no mispredicted exit. `Σ g²(2x+1)` is taken as
/// `(2·start+1)·Σ g² + 2·Σ k·g²` with `x = start + k`.
#[inline]
pub(crate) fn position_sums_windowed(line: &[u8], start: usize, end: usize) -> (u64, u64) {
    let Some(w) = line.get(start..start + POSITION_WINDOW + 1).filter(|_| end - start <= POSITION_WINDOW) else {
        return position_sums(line, start, end);
    };
    let (mut s0, mut sk) = (0u32, 0u32);
    for k in 0..POSITION_WINDOW {
        let g = w[k + 1] as i32 - w[k] as i32;
        let g2 = (g * g) as u32 * (start + k < end) as u32;
        s0 += g2;
        sk += g2 * k as u32;
    }
    let (s0, sk) = (s0 as u64, sk as u64);
    (s0, (2 * start as u64 + 1) * s0 + 2 * sk)
}

/// The attributes of paper §III: the grey levels `I(x_i - k)` and
/// `I(x_{i+1} + k)` for k = 0, 1, 2, clamped at the line's ends.
#[inline]
pub fn neighbour_levels(line: &[u8], start: usize, end: usize) -> ([u8; 3], [u8; 3]) {
    // Away from the line's ends (nearly always): two slices, no clamping.
    if let (Some(&[l2, l1, l0]), Some(&[r0, r1, r2])) = (start.checked_sub(2).and_then(|s| line.get(s..=start)), line.get(end..end + 3)) {
        return ([l0, l1, l2], [r0, r1, r2]);
    }
    let last = line.len() - 1;
    let left = [0, 1, 2].map(|k| line[start.saturating_sub(k)]);
    let right = [0, 1, 2].map(|k| line[(end + k).min(last)]);
    (left, right)
}

/// The declivity `(start, end)` of `line` with its amplitude, eq. 3 position
/// and attributes.
#[inline(always)]
pub fn describe(line: &[u8], start: usize, end: usize) -> Declivity {
    let (left, right) = neighbour_levels(line, start, end);
    Declivity {
        start,
        end,
        amplitude: amplitude(line, start, end),
        position: position(line, start, end),
        left,
        right,
    }
}

/// Every declivity of the line, described (used for pictures and tests).
pub fn all_declivities(line: &[u8]) -> Vec<Declivity> {
    declivity_bounds(line).into_iter().map(|(s, e)| describe(line, s, e)).collect()
}

/// The characteristic declivities of a line for the threshold `dt`, left to
/// right, with positions and attributes. The amplitude test `|a_i| > d_t`
/// runs inside the extrema pass ([`declivity_spans`]); only the kept
/// declivities are bounded and described.
pub fn characteristic_declivities(line: &[u8], dt: f64) -> Vec<Declivity> {
    characteristic_declivities_with(line, dt, &mut Vec::new())
}

/// [`characteristic_declivities`] with `spans` as the extrema pass's
/// working vector (its allocation reused from line to line).
pub(crate) fn characteristic_declivities_with(line: &[u8], dt: f64, spans: &mut Vec<(usize, usize)>) -> Vec<Declivity> {
    declivity_spans_into(line, integer_threshold(dt), spans);
    spans.iter().map(|&(s, e)| describe(line, s, e)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;


    #[test]
    fn integer_threshold_is_the_characteristic_test() {
        for dt10 in 0..3000 {
            let dt = dt10 as f64 / 10.0;
            for a in -300i32..=300 {
                assert_eq!(is_characteristic(a, dt), a.unsigned_abs() > integer_threshold(dt), "a {a}, dt {dt}");
            }
        }
    }

    #[test]
    fn neighbour_levels_are_the_clamped_levels() {
        let mut rng = crate::test_rng::TestRng::new(0x7e1e_0e15_0c1a_3b2d);
        for _ in 0..300 {
            let n = 2 + (rng.next() % 12) as usize;
            let line: Vec<u8> = (0..n).map(|_| (rng.next() % 256) as u8).collect();
            for start in 0..n - 1 {
                for end in start + 1..n {
                    let clamp = |x: isize| line[x.clamp(0, n as isize - 1) as usize];
                    let want = ([0, 1, 2].map(|k| clamp(start as isize - k)), [0, 1, 2].map(|k| clamp((end + k) as isize)));
                    assert_eq!(neighbour_levels(&line, start, end), want, "{start}..{end} of {line:?}");
                }
            }
        }
    }

    #[test]
    fn windowed_position_sums_equal_the_loop() {
        let mut rng = crate::test_rng::TestRng::new(0x51de_0f5e_7a11_c0de);
        for case in 0..3000 {
            let n = 2 + (rng.next() % 40) as usize;
            let line: Vec<u8> = (0..n).map(|_| (rng.next() % 256) as u8).collect();
            for _ in 0..20 {
                let start = (rng.next() % (n as u64 - 1)) as usize;
                let end = start + 1 + (rng.next() % (n - start - 1) as u64) as usize;
                assert_eq!(position_sums_windowed(&line, start, end), position_sums(&line, start, end), "case {case}: {start}..{end}");
            }
        }
    }

    #[test]
    fn fast_bounds_equal_reference_bounds_on_random_lines_with_plateaus() {
        let mut rng = crate::test_rng::TestRng::new(0x9e37_79b9_7f4a_7c15);
        let mut next = move || rng.next();
        for case in 0..3000 {
            let n = (next() % 300) as usize;
            // Few levels make plateaus and repeated values frequent.
            let levels = 1 + next() % 6;
            let line: Vec<u8> = (0..n).map(|_| (next() % levels) as u8 * 40).collect();
            let fast = declivity_bounds(&line);
            let reference: Vec<_> = declivity_bounds_reference(&line).collect();
            assert_eq!(fast, reference, "case {case}, line {line:?}");
            // The amplitude test inside the pass keeps exactly the declivities
            // the reference walk finds characteristic.
            let dt = (next() % 2000) as f64 / 10.0;
            let kept: Vec<_> = reference
                .iter()
                .filter(|&&(s, e)| is_characteristic(amplitude(&line, s, e), dt))
                .map(|&(s, e)| describe(&line, s, e))
                .collect();
            assert_eq!(characteristic_declivities(&line, dt), kept, "case {case}, dt {dt}, line {line:?}");
        }
    }
}
