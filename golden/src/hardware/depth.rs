//! The depth stage of the line processor (`rtl::post::depth_stage`): eq. 1
//! on a disparity in position LSBs, `Z_mm = f_px · b_mm · 2^f / D`, as the
//! hardware computes it, to the millimetre it outputs (`u16`, 0 = no
//! depth, 65535 = that far or farther). golden's f64 eq. 1 is
//! [`crate::reconstruct::depth`]; the two differ by at most
//! `½ + Z·2^-15` mm below the saturation.
//!
//! The steps, each a function below:
//! - the camera's numerator ([`DepthScale::of`]):
//!   `K = round(f_px · b_mm · 2^f · 2^s)`, the exponent `s`
//!   ([`DEPTH_SCALE_MIN`] ..= [`DEPTH_SCALE_MAX`]) the largest that keeps `K`
//!   below `DEPTH_K_LIMIT = 2^(P−1+18) − 2^(P−1)` ([`depth_k_limit`]), so
//!   `Z_mm = K / (D · 2^s)`;
//! - the table ([`depth_table`]): 512 entries `T_i = round(K / m_i)` at the
//!   bucket boundaries `m_i = 2^(P−1) + i·2^w` (`w` = [`depth_weight_bits`]
//!   = 4) of the normalised disparities, each with its slope `T_i − T_(i+1)`;
//! - the pixel ([`DepthStage::depth_mm`]): `D` normalised
//!   (`m = D · 2^lz ∈ [2^(P−1), 2^P)`), `T = T_i − ((slope·w + 2^(w−1)) >> w)`
//!   for the bits `i` after `m`'s leading one and the `w` bits below them,
//!   `Z = T · 2^(lz−s)`: 65535 when `lz ≥ s`, else `T >> (s − 1 − lz)`
//!   then halved rounding half up, 65535 from 65536 on; 0 for `D = 0`.

use crate::hardware::interpolate::{normalise, position_bits};
use crate::hardware::HardwareLimits;
use crate::reconstruct::Camera;

/// Bits of a depth in millimetres (`rtl::params::DEPTH_BITS`).
pub const DEPTH_BITS: u32 = 16;
/// The largest depth, millimetres: depths from it on read as it.
pub const DEPTH_MAX_MM: u16 = u16::MAX;
/// Index bits of the depth table: the normalised disparity's bits after its
/// leading one (`rtl::params::DEPTH_INDEX_BITS`, 512 entries).
pub const DEPTH_INDEX_BITS: u32 = 9;
/// Bits of a table entry `round(K / m)` (`rtl::params::DEPTH_TABLE_BITS`).
pub const DEPTH_TABLE_BITS: u32 = 18;
/// Bits of an entry's slope (`rtl::params::DEPTH_SLOPE_BITS`).
pub const DEPTH_SLOPE_BITS: u32 = 10;
/// Bits of the stage's shift amounts `s − 1 − lz`
/// (`rtl::params::DEPTH_SHIFT_BITS`).
pub const DEPTH_SHIFT_BITS: u32 = 4;
/// The smallest scale exponent `s` (`rtl::params::DEPTH_SCALE_MIN`).
pub const DEPTH_SCALE_MIN: u32 = 1;
/// The largest scale exponent `s`, `2^DEPTH_SHIFT_BITS`
/// (`rtl::params::DEPTH_SCALE_MAX`).
pub const DEPTH_SCALE_MAX: u32 = 1 << DEPTH_SHIFT_BITS;

/// The bits of a normalised disparity below the table's index (`w`, the
/// interpolation's weight): `P − 1 − DEPTH_INDEX_BITS`.
pub fn depth_weight_bits(limits: HardwareLimits) -> u32 {
    position_bits(limits) - 1 - DEPTH_INDEX_BITS
}

/// The bound on the numerator `K`: `2^(P−1+DEPTH_TABLE_BITS) − 2^(P−1)`
/// (every entry `round(K/m)` then fits [`DEPTH_TABLE_BITS`] bits).
pub fn depth_k_limit(limits: HardwareLimits) -> u64 {
    let p = position_bits(limits);
    (1u64 << (p - 1 + DEPTH_TABLE_BITS)) - (1u64 << (p - 1))
}

/// The camera pair as the depth stage takes it: eq. 1's `f/p` and `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthCamera {
    /// Focal length in pixels.
    pub focal_px: f64,
    /// Baseline in millimetres.
    pub baseline_mm: f64,
}

impl DepthCamera {
    /// golden's camera (baseline in metres, times 1000).
    pub fn of(camera: &Camera) -> Self {
        DepthCamera { focal_px: camera.focal_px, baseline_mm: camera.baseline_m * 1000.0 }
    }

    /// `f_px · b_mm`, eq. 1's numerator in pixel-millimetres.
    pub fn product(&self) -> f64 {
        self.focal_px * self.baseline_mm
    }
}

/// A camera the depth stage's formats do not cover.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum DepthRangeError {
    /// The focal length or the baseline is not a positive finite number.
    #[error("focal length {focal_px} px and baseline {baseline_mm} mm must be positive and finite")]
    NotPositive { focal_px: f64, baseline_mm: f64 },
    /// `f_px · b_mm` is so small that the farthest depths would round under
    /// 1 mm: the exponent would be above [`DEPTH_SCALE_MAX`].
    #[error("focal length × baseline = {product} px·mm is below {min}: the farthest depths would round under 1 mm")]
    ProductTooSmall { product: f64, min: f64 },
    /// `f_px · b_mm` is so large that every depth saturates: the exponent
    /// would be below [`DEPTH_SCALE_MIN`].
    #[error("focal length × baseline = {product} px·mm is not below {max}: every depth would saturate")]
    ProductTooLarge { product: f64, max: f64 },
}

/// A camera's numerator: `Z_mm = k / (D · 2^scale)` for `D` in position LSBs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthScale {
    /// `K = round(f_px · b_mm · 2^f · 2^scale)`, in
    /// `[depth_k_limit / 2, depth_k_limit]`.
    pub k: u64,
    /// The exponent `s`.
    pub scale: u32,
}

impl DepthScale {
    /// The numerator of `camera`: the largest exponent `s` with
    /// `f_px · b_mm · 2^f · 2^s < depth_k_limit`, checked against the range
    /// of `s` (the same `f64` operations as the hardware's generator, so the
    /// same `K`).
    pub fn of(camera: &DepthCamera, limits: HardwareLimits) -> Result<DepthScale, DepthRangeError> {
        let (f, b) = (camera.focal_px, camera.baseline_mm);
        if !(f.is_finite() && b.is_finite() && f > 0.0 && b > 0.0) {
            return Err(DepthRangeError::NotPositive { focal_px: f, baseline_mm: b });
        }
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        let limit = depth_k_limit(limits) as f64;
        let min = limit / unit / 2f64.powi(DEPTH_SCALE_MAX as i32 + 1);
        let max = limit / unit / 2f64.powi(DEPTH_SCALE_MIN as i32);
        let product = camera.product();
        if product < min {
            return Err(DepthRangeError::ProductTooSmall { product, min });
        }
        if product >= max {
            return Err(DepthRangeError::ProductTooLarge { product, max });
        }
        let k0 = product * unit;
        let scale = (DEPTH_SCALE_MIN..=DEPTH_SCALE_MAX)
            .rev()
            .find(|&s| k0 * 2f64.powi(s as i32) < limit)
            .expect("the product's range has an exponent");
        Ok(DepthScale { k: (k0 * 2f64.powi(scale as i32)).round() as u64, scale })
    }
}

/// A depth table entry: `T_i` and its slope `T_i − T_(i+1)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthEntry {
    /// `T_i = round(K / m_i)`, [`DEPTH_TABLE_BITS`] bits.
    pub entry: u32,
    /// `T_i − T_(i+1)`, [`DEPTH_SLOPE_BITS`] bits.
    pub slope: u32,
}

/// The depth table of `scale`: entry `i` is `T_i = round(K / m_i)` (half
/// up, `(K + m/2) / m` on integers) at `m_i = 2^(P−1) + i·2^w`, the lower
/// end of bucket `i` of the normalised disparities, with its slope to
/// `T_(i+1)` (`T_512` at `m = 2^P`).
pub fn depth_table(scale: &DepthScale, limits: HardwareLimits) -> Vec<DepthEntry> {
    let (p, w) = (position_bits(limits), depth_weight_bits(limits));
    let entry = |i: u64| {
        let m = (1u64 << (p - 1)) + (i << w);
        (scale.k + m / 2) / m
    };
    (0..1u64 << DEPTH_INDEX_BITS)
        .map(|i| {
            let (t, next) = (entry(i), entry(i + 1));
            debug_assert!(t < 1 << DEPTH_TABLE_BITS && t - next < 1 << DEPTH_SLOPE_BITS, "entry {i}: {t}, slope {}", t - next);
            DepthEntry { entry: t as u32, slope: (t - next) as u32 }
        })
        .collect()
}

/// The depth stage of a camera: its numerator and table.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DepthStage {
    scale: DepthScale,
    table: Vec<DepthEntry>,
    pos_bits: u32,
    weight_bits: u32,
}

impl DepthStage {
    /// The depth stage of `camera` on the hardware with `limits`; an error
    /// if the camera is outside the range the formats cover.
    pub fn new(camera: &DepthCamera, limits: HardwareLimits) -> Result<Self, DepthRangeError> {
        let scale = DepthScale::of(camera, limits)?;
        Ok(DepthStage { scale, table: depth_table(&scale, limits), pos_bits: position_bits(limits), weight_bits: depth_weight_bits(limits) })
    }

    /// The camera's numerator.
    pub fn scale(&self) -> DepthScale {
        self.scale
    }

    /// The depth in mm of a disparity `d` in position LSBs (`P` bits), as
    /// the stage outputs it (module doc): 0 for 0, at least 1 otherwise,
    /// [`DEPTH_MAX_MM`] from there on.
    pub fn depth_mm(&self, d: u32) -> u16 {
        if d == 0 {
            return 0;
        }
        let (m, lz) = normalise(d, self.pos_bits);
        let s = self.scale.scale;
        if lz >= s {
            return DEPTH_MAX_MM;
        }
        let i = (m >> self.weight_bits) & ((1 << DEPTH_INDEX_BITS) - 1);
        let w = m & ((1 << self.weight_bits) - 1);
        let DepthEntry { entry, slope } = self.table[i as usize];
        let step = (slope * w + (1 << (self.weight_bits - 1))) >> self.weight_bits;
        let t = entry - step;
        let half = t >> (s - 1 - lz);
        let z = (half + 1) >> 1;
        if z >> DEPTH_BITS != 0 {
            DEPTH_MAX_MM
        } else {
            z as u16
        }
    }

    /// The depth of every pixel of a dense map in px (`0.0` = none; in
    /// hardware parity every value is a multiple of `2^-f` below `2^(P−f)`,
    /// so `d·2^f` is exact).
    pub fn depth_map_mm(&self, disparity: &[f64], limits: HardwareLimits) -> Vec<u16> {
        let unit = (1u64 << limits.pos_frac_bits) as f64;
        disparity.iter().map(|&d| self.depth_mm((d * unit) as u32)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quarter-size Middlebury Motorcycle camera (994.978 px, 193.001 mm).
    const QUARTER: DepthCamera = DepthCamera { focal_px: 3979.911 / 4.0, baseline_mm: 193.001 };

    #[test]
    fn every_depth_is_eq1_within_half_plus_z_2pow15_saturation_and_no_depth_exact() {
        let limits = HardwareLimits::default();
        for cam in [QUARTER, DepthCamera { focal_px: 3979.911, baseline_mm: 193.001 }, DepthCamera { focal_px: 300.0, baseline_mm: 4.0 }] {
            let stage = DepthStage::new(&cam, limits).expect("in range");
            let s = stage.scale();
            assert!(s.k * 2 >= depth_k_limit(limits) && s.k <= depth_k_limit(limits), "{s:?}");
            assert_eq!(stage.depth_mm(0), 0);
            for d in 1..1u32 << 14 {
                let z = cam.product() * 16.0 / d as f64;
                let got = stage.depth_mm(d);
                assert!(got >= 1, "{cam:?} d {d}");
                let bound = 0.5 + z / 32768.0;
                if z - bound > 65535.0 {
                    assert_eq!(got, DEPTH_MAX_MM, "{cam:?} d {d}");
                } else {
                    assert!((got as f64 - z.min(65535.0)).abs() <= bound, "{cam:?} d {d}: {got} vs {z}");
                }
            }
        }
    }

    #[test]
    fn cameras_outside_the_range_are_refused() {
        let limits = HardwareLimits::default();
        assert!(matches!(DepthScale::of(&DepthCamera { focal_px: 0.0, baseline_mm: 1.0 }, limits), Err(DepthRangeError::NotPositive { .. })));
        assert!(matches!(DepthScale::of(&DepthCamera { focal_px: 1.0, baseline_mm: 1.0 }, limits), Err(DepthRangeError::ProductTooSmall { .. })));
        assert!(matches!(DepthScale::of(&DepthCamera { focal_px: 1e5, baseline_mm: 1e3 }, limits), Err(DepthRangeError::ProductTooLarge { .. })));
        let cam = Camera { focal_px: 994.978, baseline_m: 0.193, cx: 0.0, cy: 0.0 };
        assert_eq!(DepthCamera::of(&cam).baseline_mm, 193.0);
    }
}
