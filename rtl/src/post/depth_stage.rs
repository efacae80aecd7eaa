//! The depth stage (paper §II, eq. 1; `golden::reconstruct::depth`): one
//! disparity per clock in, its depth in millimetres out.
//!
//! With parallel optical axes, a disparity of `d` pixels is at depth
//! `Z = f_px · b / d`. A disparity arrives in the position format,
//! `D = 16·d` ([`POS_FRAC_BITS`] fraction bits), so
//! `Z_mm = f_px · b_mm · 16 / D`. The camera is a generation-time parameter
//! ([`DepthCamera`]): [`DepthScale::of`] turns `f_px · b_mm · 16` into one
//! integer numerator `K = round(f_px · b_mm · 16 · 2^s)`, the exponent `s`
//! chosen so that `K` lies in `[DEPTH_K_LIMIT / 2, DEPTH_K_LIMIT]` (about
//! `2^30 ..= 2^31`), and `Z_mm = K / (D · 2^s)`.
//!
//! The division: `D` is shifted left until its top bit is set (`lz`
//! places, `m = D · 2^lz ∈ [2^13, 2^14)`), so `Z_mm = (K / m) · 2^(lz - s)`.
//! A table of 512 entries `T_i = round(K / m_i)` at the bucket boundaries
//! `m_i = 2^13 + 16 i` (block RAM, addressed by the [`DEPTH_INDEX_BITS`]
//! bits of `m` after its leading one) holds each entry beside its slope
//! `T_i - T_(i+1)`; the last four bits `w` of `m` interpolate linearly,
//! `T = T_i - round(slope · w / 16)` (one product, a DSP block), and the
//! depth is `T · 2^(lz - s)` rounded to the nearest millimetre (half up).
//!
//! ## Accuracy
//! Against golden's `Z = f_px · b_m / d` (in mm) for the same fixed-point
//! disparity: `|z_mm - min(Z, 65535)| ≤ ½ + Z · 2^-15` mm (at most 2.5 mm
//! at the top of the range). The interpolated entry is within 1.25 of
//! `K / m` (entries rounded, ½; the chord of `1/m` over a bucket of
//! relative width `2^-9`, `T · 2^-20 < ¼`; the step's rounding, ½), and an
//! entry is above `2^16 - 1`, so this error is below `Z · 2^-15` after the
//! shift; `K`'s own rounding adds `Z · 2^-30`; the final rounding adds ½.
//! A disparity of 0 gives 0 ("no depth"), every other one a depth of at
//! least 1 mm ([`DEPTH_SCALE_MAX`]). A depth whose rounding reaches 65536
//! reads 65535 ([`DEPTH_MAX_MM`]).
//!
//! ## Ports
//! - In, a disparity stream in the interpolator's `p_*` format (in the
//!   line processor, the vertical median's output, registered): `p_valid`, `p_d`
//!   (disparity, [`POS_FRAC_BITS`] fraction bits, 0 = none), `p_last`
//!   (a line's last pixel), `p_sof` (a frame's first pixel).
//! - Out: `z_valid`, `z_mm` (depth in millimetres, rounded; 0 = no depth;
//!   65535 from 65535 mm on), `z_d` (the pixel's disparity, as it came in),
//!   `z_last`, `z_sof` (as they came in).
//!
//! ## Timing
//! A pipeline without back-pressure or state between pixels: the pixel on
//! `p_*` at a clock is on `z_*` [`DEPTH_LAG`] clocks later, one pixel per
//! clock, any pattern of `p_valid`. A clock with `p_valid` low gives, after
//! the same lag, `z_valid` low and all other outputs 0. The
//! pipeline's registers start from their Verilog initial values (zero: no
//! valid pixel); `reset` (synchronous, active high) returns them to these values.

use crate::primitives::dsp_multiplier::DspMultiplier;
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;
use std::fmt;

/// Clocks from a pixel on `p_*` to its depth on `z_*`: the normalisation
/// (two clocks, two shift levels each), the table's address register and the
/// table, the table's output register, its word split into entry and slope
/// (the slope into the DSP block's input register), the product, the
/// interpolated entry, the shift, the rounding and saturation.
pub const DEPTH_LAG: usize = 9;

/// The camera pair as the depth stage needs it: eq. 1's `f/p` and `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthCamera {
    /// Focal length in pixels (`f / p`), at the resolution of the images
    /// whose disparities come in.
    pub focal_px: f64,
    /// Baseline in millimetres.
    pub baseline_mm: f64,
}

impl DepthCamera {
    /// Middlebury 2014 Motorcycle at full resolution (its `calib.txt`:
    /// `cam0` focal length 3979.911 px, baseline 193.001 mm, 2964 px wide).
    /// Eq. 1 has no disparity offset: the dataset's `doffs` (124.343 px)
    /// is not added, as golden does not add it.
    pub const MOTORCYCLE_FULL: DepthCamera = DepthCamera { focal_px: 3979.911, baseline_mm: 193.001 };
    /// The same camera at the quarter size of the project's `motorcycle`
    /// pair (741 px wide): focal length 994.978 px. Its depths (d = 7 to
    /// 60 px: 27.4 m down to 3.2 m) fit 16 bits; disparities below
    /// 2.93 px saturate.
    pub const MOTORCYCLE_QUARTER: DepthCamera = DepthCamera { focal_px: 3979.911 / 4.0, baseline_mm: 193.001 };

    /// `f_px · b_mm`, the numerator of eq. 1 in pixel-millimetres.
    pub fn product(&self) -> f64 {
        self.focal_px * self.baseline_mm
    }
}

impl Default for DepthCamera {
    /// [`DepthCamera::MOTORCYCLE_QUARTER`], the camera of the project's
    /// motorcycle pair.
    fn default() -> Self {
        DepthCamera::MOTORCYCLE_QUARTER
    }
}

/// Why a camera cannot be built into a depth stage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DepthError {
    /// The focal length or the baseline is not a positive finite number.
    NotPositive { focal_px: f64, baseline_mm: f64 },
    /// `f_px · b_mm` is so small that the depth of the largest disparity
    /// (below `2^10` px) would round under 1 mm, which would read as "no
    /// depth": the numerator needs a scale exponent above
    /// [`DEPTH_SCALE_MAX`].
    ProductTooSmall { product: f64, min: f64 },
    /// `f_px · b_mm` is so large that every depth, even at the largest
    /// disparity, is above [`DEPTH_MAX_MM`]: the scale exponent would be
    /// below [`DEPTH_SCALE_MIN`].
    ProductTooLarge { product: f64, max: f64 },
}

impl fmt::Display for DepthError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DepthError::NotPositive { focal_px, baseline_mm } => {
                write!(f, "focal length {focal_px} px and baseline {baseline_mm} mm must be positive and finite")
            }
            DepthError::ProductTooSmall { product, min } => write!(
                f,
                "focal length × baseline = {product} px·mm is below {min}: the farthest depths would round under 1 mm"
            ),
            DepthError::ProductTooLarge { product, max } => write!(
                f,
                "focal length × baseline = {product} px·mm is not below {max}: every depth would exceed {DEPTH_MAX_MM} mm"
            ),
        }
    }
}

impl std::error::Error for DepthError {}

/// A camera's numerator in the depth stage's format:
/// `Z_mm = k / (D_lsb · 2^scale)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthScale {
    /// `round(f_px · b_mm · 2^POS_FRAC_BITS · 2^scale)`, in
    /// `[DEPTH_K_LIMIT / 2, DEPTH_K_LIMIT]`.
    pub k: u64,
    /// The exponent `s`, `DEPTH_SCALE_MIN ..= DEPTH_SCALE_MAX`.
    pub scale: u32,
}

impl DepthScale {
    /// The numerator of `camera`: the largest exponent `s` with
    /// `f_px · b_mm · 16 · 2^s < DEPTH_K_LIMIT`, checked against the range
    /// the hardware's shifts cover.
    pub fn of(camera: &DepthCamera) -> Result<DepthScale, DepthError> {
        let (f, b) = (camera.focal_px, camera.baseline_mm);
        if !(f.is_finite() && b.is_finite() && f > 0.0 && b > 0.0) {
            return Err(DepthError::NotPositive { focal_px: f, baseline_mm: b });
        }
        let unit = (1u64 << POS_FRAC_BITS) as f64;
        let limit = DEPTH_K_LIMIT as f64;
        // The range of f·b these exponents cover (powers of two: exact).
        let min = limit / unit / 2f64.powi(DEPTH_SCALE_MAX as i32 + 1);
        let max = limit / unit / 2f64.powi(DEPTH_SCALE_MIN as i32);
        let product = camera.product();
        if product < min {
            return Err(DepthError::ProductTooSmall { product, min });
        }
        if product >= max {
            return Err(DepthError::ProductTooLarge { product, max });
        }
        let k0 = product * unit;
        let scale = (DEPTH_SCALE_MIN..=DEPTH_SCALE_MAX)
            .rev()
            .find(|&s| k0 * 2f64.powi(s as i32) < limit)
            .expect("the product's range has an exponent");
        let k = (k0 * 2f64.powi(scale as i32)).round() as u64;
        Ok(DepthScale { k, scale })
    }
}

/// The normalised disparity of table entry `i` (a bucket's lower end; entry
/// `2^DEPTH_INDEX_BITS` is the top of the last bucket).
fn table_point(i: u64) -> u64 {
    (1u64 << (POS_BITS - 1)) + (i << DEPTH_WEIGHT_BITS)
}

/// The depth table of `scale`: word `i` is the entry `T_i = round(k / m_i)`
/// above its slope `T_i - T_(i+1)` ([`DEPTH_SLOPE_BITS`] bits), `m_i` the
/// lower end of bucket `i` of the normalised disparities.
pub fn depth_table(scale: &DepthScale) -> Vec<u64> {
    let entry = |i: u64| {
        let m = table_point(i);
        (scale.k + m / 2) / m
    };
    (0..1u64 << DEPTH_INDEX_BITS)
        .map(|i| {
            let (t, next) = (entry(i), entry(i + 1));
            assert!(t < 1 << DEPTH_TABLE_BITS, "entry {i}: {t} fits {DEPTH_TABLE_BITS} bits");
            assert!(t - next < 1 << DEPTH_SLOPE_BITS, "slope {i}: {} fits {DEPTH_SLOPE_BITS} bits", t - next);
            (t << DEPTH_SLOPE_BITS) | (t - next)
        })
        .collect()
}

/// Bits of the normalisation's shift `lz` (`0 ..= POS_BITS - 1`).
const LZ_BITS: usize = 4;
/// Bits of the final rounding's sum: an entry, one more for the carry.
const ROUND_BITS: usize = DEPTH_TABLE_BITS + 1;

#[derive(LogicBlock)]
pub struct DepthStage {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    // ---- In: the disparity stream.
    pub p_valid: Signal<In, Bit>,
    pub p_d: Signal<In, Bits<POS_BITS>>,
    pub p_last: Signal<In, Bit>,
    pub p_sof: Signal<In, Bit>,
    // ---- Out: the depth stream.
    pub z_valid: Signal<Out, Bit>,
    pub z_mm: Signal<Out, Bits<DEPTH_BITS>>,
    pub z_d: Signal<Out, Bits<POS_BITS>>,
    pub z_last: Signal<Out, Bit>,
    pub z_sof: Signal<Out, Bit>,
    // ---- The pixel's flags and disparity, alongside the pipeline.
    s1_valid: ResetDff<Bit>,
    s1_last: ResetDff<Bit>,
    s1_sof: ResetDff<Bit>,
    s1_zero: ResetDff<Bit>,
    s1_d: ResetDff<Bits<POS_BITS>>,
    s2_valid: ResetDff<Bit>,
    s2_last: ResetDff<Bit>,
    s2_sof: ResetDff<Bit>,
    s2_zero: ResetDff<Bit>,
    s2_d: ResetDff<Bits<POS_BITS>>,
    s3_valid: ResetDff<Bit>,
    s3_last: ResetDff<Bit>,
    s3_sof: ResetDff<Bit>,
    s3_zero: ResetDff<Bit>,
    s3_d: ResetDff<Bits<POS_BITS>>,
    t_valid: ResetDff<Bit>,
    t_last: ResetDff<Bit>,
    t_sof: ResetDff<Bit>,
    t_zero: ResetDff<Bit>,
    t_d: ResetDff<Bits<POS_BITS>>,
    s4_valid: ResetDff<Bit>,
    s4_last: ResetDff<Bit>,
    s4_sof: ResetDff<Bit>,
    s4_zero: ResetDff<Bit>,
    s4_d: ResetDff<Bits<POS_BITS>>,
    s5_valid: ResetDff<Bit>,
    s5_last: ResetDff<Bit>,
    s5_sof: ResetDff<Bit>,
    s5_zero: ResetDff<Bit>,
    s5_d: ResetDff<Bits<POS_BITS>>,
    s6_valid: ResetDff<Bit>,
    s6_last: ResetDff<Bit>,
    s6_sof: ResetDff<Bit>,
    s6_zero: ResetDff<Bit>,
    s6_d: ResetDff<Bits<POS_BITS>>,
    s7_valid: ResetDff<Bit>,
    s7_last: ResetDff<Bit>,
    s7_sof: ResetDff<Bit>,
    s7_zero: ResetDff<Bit>,
    s7_d: ResetDff<Bits<POS_BITS>>,
    // ---- The arithmetic. S1: two shift levels; S2: two more (m, lz);
    // S3: the table's read, the weight, the shift and the saturation flag;
    // T: the table's output register; S4: the entry and the slope; S5: the
    // step's product; S6: the interpolated entry; S7: the entry shifted.
    s1_n: ResetDff<Bits<POS_BITS>>,
    s1_lz: ResetDff<Bits<LZ_BITS>>,
    s2_m: ResetDff<Bits<POS_BITS>>,
    s2_lz: ResetDff<Bits<LZ_BITS>>,
    depth_rom: SyncROM<Bits<DEPTH_WORD_BITS>, DEPTH_INDEX_BITS>,
    s3_w: ResetDff<Bits<16>>,
    s3_sat: ResetDff<Bit>,
    s3_shift: ResetDff<Bits<DEPTH_SHIFT_BITS>>,
    // T: the table's word in its output register, nothing between the
    // block RAM's data out and it (in a DP16KD, its own output register),
    // so that the RAM's clock-to-out and the route to the DSP column are
    // not in one clock.
    t_word: ResetDff<Bits<DEPTH_WORD_BITS>>,
    t_w: ResetDff<Bits<16>>,
    t_sat: ResetDff<Bit>,
    t_shift: ResetDff<Bits<DEPTH_SHIFT_BITS>>,
    s4_t: ResetDff<Bits<DEPTH_TABLE_BITS>>,
    // S4's slope and weight in the DSP block's own input registers, so
    // that the route into the DSP column, the product and the route out
    // are not in one clock (as a `*` of fabric registers would have them).
    slope_w: DspMultiplier,
    s4_sat: ResetDff<Bit>,
    s4_shift: ResetDff<Bits<DEPTH_SHIFT_BITS>>,
    s5_t: ResetDff<Bits<DEPTH_TABLE_BITS>>,
    s5_prod: ResetDff<Bits<32>>,
    s5_sat: ResetDff<Bit>,
    s5_shift: ResetDff<Bits<DEPTH_SHIFT_BITS>>,
    s6_t: ResetDff<Bits<DEPTH_TABLE_BITS>>,
    s6_sat: ResetDff<Bit>,
    s6_shift: ResetDff<Bits<DEPTH_SHIFT_BITS>>,
    s7_half: ResetDff<Bits<DEPTH_TABLE_BITS>>,
    s7_sat: ResetDff<Bit>,
    // ---- The outputs' registers.
    o_valid: ResetDff<Bit>,
    o_last: ResetDff<Bit>,
    o_sof: ResetDff<Bit>,
    o_z: ResetDff<Bits<DEPTH_BITS>>,
    o_d: ResetDff<Bits<POS_BITS>>,
    // ---- Locals.
    n1: Signal<Local, Bits<POS_BITS>>,
    l1: Signal<Local, Bits<LZ_BITS>>,
    n3: Signal<Local, Bits<POS_BITS>>,
    l3: Signal<Local, Bits<LZ_BITS>>,
    // The normalisation's tests `x < 2^(POS_BITS - k)` as "the top k bits
    // of x are zero": no comparator (a carry chain each, two in series per
    // stage).
    z8: Signal<Local, Bit>,
    z4: Signal<Local, Bit>,
    z2: Signal<Local, Bit>,
    z1: Signal<Local, Bit>,
    prod: Signal<Local, Bits<32>>,
    rounded_step: Signal<Local, Bits<32>>,
    step: Signal<Local, Bits<DEPTH_TABLE_BITS>>,
    wide: Signal<Local, Bits<ROUND_BITS>>,
    z_full: Signal<Local, Bits<ROUND_BITS>>,
    // ---- Constants.
    top8: Constant<Bits<8>>,
    top4: Constant<Bits<8>>,
    top2: Constant<Bits<8>>,
    top1: Constant<Bits<8>>,
    sh8: Constant<Bits<8>>,
    sh4: Constant<Bits<8>>,
    sh2: Constant<Bits<8>>,
    sh1: Constant<Bits<8>>,
    lz8: Constant<Bits<LZ_BITS>>,
    lz4: Constant<Bits<LZ_BITS>>,
    lz2: Constant<Bits<LZ_BITS>>,
    lz1: Constant<Bits<LZ_BITS>>,
    index_shift: Constant<Bits<8>>,
    weight_mask: Constant<Bits<POS_BITS>>,
    slope_bits: Constant<Bits<8>>,
    slope_mask: Constant<Bits<DEPTH_WORD_BITS>>,
    scale_less1: Constant<Bits<DEPTH_SHIFT_BITS>>,
    step_half: Constant<Bits<32>>,
    weight_bits: Constant<Bits<8>>,
    one: Constant<Bits<ROUND_BITS>>,
    sh_round: Constant<Bits<8>>,
    depth_bits: Constant<Bits<8>>,
    depth_max: Constant<Bits<DEPTH_BITS>>,
}

impl DepthStage {
    /// A depth stage for `camera`; an error if its `f_px · b_mm` is outside
    /// the range the hardware's shifts cover (see [`DepthScale::of`]).
    pub fn new(camera: DepthCamera) -> Result<Self, DepthError> {
        let scale = DepthScale::of(&camera)?;
        let cp = |v: u64| Constant::<Bits<POS_BITS>>::new(v.into());
        let c8 = |v: u64| Constant::<Bits<8>>::new(v.into());
        let cl = |v: u64| Constant::<Bits<LZ_BITS>>::new(v.into());
        Ok(DepthStage {
            clock: Default::default(),
            reset: Default::default(),
            p_valid: Default::default(),
            p_d: Default::default(),
            p_last: Default::default(),
            p_sof: Default::default(),
            z_valid: Default::default(),
            z_mm: Default::default(),
            z_d: Default::default(),
            z_last: Default::default(),
            z_sof: Default::default(),
            s1_valid: Default::default(),
            s1_last: Default::default(),
            s1_sof: Default::default(),
            s1_zero: Default::default(),
            s1_d: Default::default(),
            s2_valid: Default::default(),
            s2_last: Default::default(),
            s2_sof: Default::default(),
            s2_zero: Default::default(),
            s2_d: Default::default(),
            s3_valid: Default::default(),
            s3_last: Default::default(),
            s3_sof: Default::default(),
            s3_zero: Default::default(),
            s3_d: Default::default(),
            s4_valid: Default::default(),
            s4_last: Default::default(),
            s4_sof: Default::default(),
            s4_zero: Default::default(),
            s4_d: Default::default(),
            s5_valid: Default::default(),
            s5_last: Default::default(),
            s5_sof: Default::default(),
            s5_zero: Default::default(),
            s5_d: Default::default(),
            s6_valid: Default::default(),
            s6_last: Default::default(),
            s6_sof: Default::default(),
            s6_zero: Default::default(),
            s6_d: Default::default(),
            s7_valid: Default::default(),
            s7_last: Default::default(),
            s7_sof: Default::default(),
            s7_zero: Default::default(),
            s7_d: Default::default(),
            s1_n: Default::default(),
            s1_lz: Default::default(),
            s2_m: Default::default(),
            s2_lz: Default::default(),
            depth_rom: depth_table(&scale).into_iter().map(Bits::<DEPTH_WORD_BITS>::from).into(),
            s3_w: Default::default(),
            s3_sat: Default::default(),
            s3_shift: Default::default(),
            t_word: Default::default(),
            t_w: Default::default(),
            t_sat: Default::default(),
            t_shift: Default::default(),
            t_valid: Default::default(),
            t_last: Default::default(),
            t_sof: Default::default(),
            t_zero: Default::default(),
            t_d: Default::default(),
            s4_t: Default::default(),
            slope_w: Default::default(),
            s4_sat: Default::default(),
            s4_shift: Default::default(),
            s5_t: Default::default(),
            s5_prod: Default::default(),
            s5_sat: Default::default(),
            s5_shift: Default::default(),
            s6_t: Default::default(),
            s6_sat: Default::default(),
            s6_shift: Default::default(),
            s7_half: Default::default(),
            s7_sat: Default::default(),
            o_valid: Default::default(),
            o_last: Default::default(),
            o_sof: Default::default(),
            o_z: Default::default(),
            o_d: Default::default(),
            n1: Default::default(),
            l1: Default::default(),
            n3: Default::default(),
            l3: Default::default(),
            z8: Default::default(),
            z4: Default::default(),
            z2: Default::default(),
            z1: Default::default(),
            prod: Default::default(),
            rounded_step: Default::default(),
            step: Default::default(),
            wide: Default::default(),
            z_full: Default::default(),
            top8: c8((POS_BITS - 8) as u64),
            top4: c8((POS_BITS - 4) as u64),
            top2: c8((POS_BITS - 2) as u64),
            top1: c8((POS_BITS - 1) as u64),
            sh8: c8(8),
            sh4: c8(4),
            sh2: c8(2),
            sh1: c8(1),
            lz8: cl(8),
            lz4: cl(4),
            lz2: cl(2),
            lz1: cl(1),
            index_shift: c8(DEPTH_WEIGHT_BITS as u64),
            weight_mask: cp((1 << DEPTH_WEIGHT_BITS) - 1),
            slope_bits: c8(DEPTH_SLOPE_BITS as u64),
            slope_mask: Constant::new(((1u64 << DEPTH_SLOPE_BITS) - 1).into()),
            scale_less1: Constant::new(((scale.scale - 1) as u64).into()),
            step_half: Constant::new((1u64 << (DEPTH_WEIGHT_BITS - 1)).into()),
            weight_bits: c8(DEPTH_WEIGHT_BITS as u64),
            one: Constant::new(1u64.into()),
            sh_round: c8(1),
            depth_bits: c8(DEPTH_BITS as u64),
            depth_max: Constant::new(DEPTH_MAX_MM.into()),
        })
    }
}

impl Default for DepthStage {
    /// The stage of the default camera ([`DepthCamera::MOTORCYCLE_QUARTER`]).
    fn default() -> Self {
        DepthStage::new(DepthCamera::default()).expect("the default camera is in range")
    }
}

impl Logic for DepthStage {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, s1_valid, s1_last, s1_sof, s1_zero, s1_d, s2_valid, s2_last, s2_sof, s2_zero, s2_d, s3_valid, s3_last, s3_sof, s3_zero, s3_d, t_valid, t_last, t_sof, t_zero, t_d, s4_valid, s4_last, s4_sof, s4_zero, s4_d, s5_valid, s5_last, s5_sof, s5_zero, s5_d, s6_valid, s6_last, s6_sof, s6_zero, s6_d, s7_valid, s7_last, s7_sof, s7_zero, s7_d, s1_n, s1_lz, s2_m, s2_lz, s3_w, s3_sat, s3_shift, t_word, t_w, t_sat, t_shift, s4_t, s4_sat, s4_shift, s5_t, s5_prod, s5_sat, s5_shift, s6_t, s6_sat, s6_shift, s7_half, s7_sat, o_valid, o_last, o_sof, o_z, o_d);
        self.s1_valid.reset.next = self.reset.val();
        self.s1_last.reset.next = self.reset.val();
        self.s1_sof.reset.next = self.reset.val();
        self.s1_zero.reset.next = self.reset.val();
        self.s1_d.reset.next = self.reset.val();
        self.s2_valid.reset.next = self.reset.val();
        self.s2_last.reset.next = self.reset.val();
        self.s2_sof.reset.next = self.reset.val();
        self.s2_zero.reset.next = self.reset.val();
        self.s2_d.reset.next = self.reset.val();
        self.s3_valid.reset.next = self.reset.val();
        self.s3_last.reset.next = self.reset.val();
        self.s3_sof.reset.next = self.reset.val();
        self.s3_zero.reset.next = self.reset.val();
        self.s3_d.reset.next = self.reset.val();
        self.t_valid.reset.next = self.reset.val();
        self.t_last.reset.next = self.reset.val();
        self.t_sof.reset.next = self.reset.val();
        self.t_zero.reset.next = self.reset.val();
        self.t_d.reset.next = self.reset.val();
        self.s4_valid.reset.next = self.reset.val();
        self.s4_last.reset.next = self.reset.val();
        self.s4_sof.reset.next = self.reset.val();
        self.s4_zero.reset.next = self.reset.val();
        self.s4_d.reset.next = self.reset.val();
        self.s5_valid.reset.next = self.reset.val();
        self.s5_last.reset.next = self.reset.val();
        self.s5_sof.reset.next = self.reset.val();
        self.s5_zero.reset.next = self.reset.val();
        self.s5_d.reset.next = self.reset.val();
        self.s6_valid.reset.next = self.reset.val();
        self.s6_last.reset.next = self.reset.val();
        self.s6_sof.reset.next = self.reset.val();
        self.s6_zero.reset.next = self.reset.val();
        self.s6_d.reset.next = self.reset.val();
        self.s7_valid.reset.next = self.reset.val();
        self.s7_last.reset.next = self.reset.val();
        self.s7_sof.reset.next = self.reset.val();
        self.s7_zero.reset.next = self.reset.val();
        self.s7_d.reset.next = self.reset.val();
        self.s1_n.reset.next = self.reset.val();
        self.s1_lz.reset.next = self.reset.val();
        self.s2_m.reset.next = self.reset.val();
        self.s2_lz.reset.next = self.reset.val();
        self.s3_w.reset.next = self.reset.val();
        self.s3_sat.reset.next = self.reset.val();
        self.s3_shift.reset.next = self.reset.val();
        self.t_word.reset.next = self.reset.val();
        self.t_w.reset.next = self.reset.val();
        self.t_sat.reset.next = self.reset.val();
        self.t_shift.reset.next = self.reset.val();
        self.s4_t.reset.next = self.reset.val();
        self.s4_sat.reset.next = self.reset.val();
        self.s4_shift.reset.next = self.reset.val();
        self.s5_t.reset.next = self.reset.val();
        self.s5_prod.reset.next = self.reset.val();
        self.s5_sat.reset.next = self.reset.val();
        self.s5_shift.reset.next = self.reset.val();
        self.s6_t.reset.next = self.reset.val();
        self.s6_sat.reset.next = self.reset.val();
        self.s6_shift.reset.next = self.reset.val();
        self.s7_half.reset.next = self.reset.val();
        self.s7_sat.reset.next = self.reset.val();
        self.o_valid.reset.next = self.reset.val();
        self.o_last.reset.next = self.reset.val();
        self.o_sof.reset.next = self.reset.val();
        self.o_z.reset.next = self.reset.val();
        self.o_d.reset.next = self.reset.val();
        self.depth_rom.clock.next = self.clock.val();
        // The pixel's flags and disparity travel beside the arithmetic.
        self.s1_valid.d.next = self.p_valid.val();
        self.s1_last.d.next = self.p_valid.val() & self.p_last.val();
        self.s1_sof.d.next = self.p_valid.val() & self.p_sof.val();
        self.s1_zero.d.next = !self.p_d.val().any();
        // The disparity of a pixel that is not valid is cleared on its way
        // into the output register, by the valid bit that travels beside
        // it: `p_valid` drives only `s1_valid`, not the clear of a whole
        // register (the line processor's vertical median, which drives it,
        // sits far away), and no valid bit crosses the die to the lane's
        // registers (as it would if `s1_valid` cleared `s2_d`).
        self.s1_d.d.next = self.p_d.val();
        self.s2_valid.d.next = self.s1_valid.q.val();
        self.s2_last.d.next = self.s1_last.q.val();
        self.s2_sof.d.next = self.s1_sof.q.val();
        self.s2_zero.d.next = self.s1_zero.q.val();
        self.s2_d.d.next = self.s1_d.q.val();
        self.s3_valid.d.next = self.s2_valid.q.val();
        self.s3_last.d.next = self.s2_last.q.val();
        self.s3_sof.d.next = self.s2_sof.q.val();
        self.s3_zero.d.next = self.s2_zero.q.val();
        self.s3_d.d.next = self.s2_d.q.val();
        self.t_valid.d.next = self.s3_valid.q.val();
        self.t_last.d.next = self.s3_last.q.val();
        self.t_sof.d.next = self.s3_sof.q.val();
        self.t_zero.d.next = self.s3_zero.q.val();
        self.t_d.d.next = self.s3_d.q.val();
        self.s4_valid.d.next = self.t_valid.q.val();
        self.s4_last.d.next = self.t_last.q.val();
        self.s4_sof.d.next = self.t_sof.q.val();
        self.s4_zero.d.next = self.t_zero.q.val();
        self.s4_d.d.next = self.t_d.q.val();
        self.s5_valid.d.next = self.s4_valid.q.val();
        self.s5_last.d.next = self.s4_last.q.val();
        self.s5_sof.d.next = self.s4_sof.q.val();
        self.s5_zero.d.next = self.s4_zero.q.val();
        self.s5_d.d.next = self.s4_d.q.val();
        self.s6_valid.d.next = self.s5_valid.q.val();
        self.s6_last.d.next = self.s5_last.q.val();
        self.s6_sof.d.next = self.s5_sof.q.val();
        self.s6_zero.d.next = self.s5_zero.q.val();
        self.s6_d.d.next = self.s5_d.q.val();
        self.s7_valid.d.next = self.s6_valid.q.val();
        self.s7_last.d.next = self.s6_last.q.val();
        self.s7_sof.d.next = self.s6_sof.q.val();
        self.s7_zero.d.next = self.s6_zero.q.val();
        self.s7_d.d.next = self.s6_d.q.val();

        // S1: the disparity shifted left by 8 and 4 places where its top
        // bits are clear (a disparity of 0 stays 0, `lz` 12: its depth is
        // replaced by 0 at the end).
        self.z8.next = !(self.p_d.val() >> self.top8.val()).any();
        self.n1.next = self.p_d.val();
        self.l1.next = 0.into();
        if self.z8.val() {
            self.n1.next = self.p_d.val() << self.sh8.val();
            self.l1.next = self.lz8.val();
        }
        self.z4.next = !(self.n1.val() >> self.top4.val()).any();
        self.s1_n.d.next = self.n1.val();
        self.s1_lz.d.next = self.l1.val();
        if self.z4.val() {
            self.s1_n.d.next = self.n1.val() << self.sh4.val();
            self.s1_lz.d.next = self.l1.val() + self.lz4.val();
        }
        // S2: by 2 and 1: m = D · 2^lz has its top bit set.
        self.z2.next = !(self.s1_n.q.val() >> self.top2.val()).any();
        self.n3.next = self.s1_n.q.val();
        self.l3.next = self.s1_lz.q.val();
        if self.z2.val() {
            self.n3.next = self.s1_n.q.val() << self.sh2.val();
            self.l3.next = self.s1_lz.q.val() + self.lz2.val();
        }
        self.z1.next = !(self.n3.val() >> self.top1.val()).any();
        self.s2_m.d.next = self.n3.val();
        self.s2_lz.d.next = self.l3.val();
        if self.z1.val() {
            self.s2_m.d.next = self.n3.val() << self.sh1.val();
            self.s2_lz.d.next = self.l3.val() + self.lz1.val();
        }
        // S3: the table read at the bits after the leading one; the weight
        // (the bits below them); Z = T · 2^(lz - s): saturated when
        // lz ≥ s (T > 2^16 - 1), else shifted right by s - lz, done as
        // s - 1 - lz here and 1 with the rounding.
        self.depth_rom.address.next = bit_cast::<DEPTH_INDEX_BITS, POS_BITS>(self.s2_m.q.val() >> self.index_shift.val());
        self.s3_w.d.next = bit_cast::<16, POS_BITS>(self.s2_m.q.val() & self.weight_mask.val());
        self.s3_sat.d.next = self.s2_lz.q.val() > self.scale_less1.val();
        self.s3_shift.d.next = self.scale_less1.val() - self.s2_lz.q.val();
        // T: the table's word in its output register (nothing between the
        // RAM and it).
        self.t_word.d.next = self.depth_rom.data.val();
        self.t_w.d.next = self.s3_w.q.val();
        self.t_sat.d.next = self.s3_sat.q.val();
        self.t_shift.d.next = self.s3_shift.q.val();
        // S4: the entry registered, the slope and the weight into the DSP
        // block's input registers.
        self.s4_t.d.next = bit_cast::<DEPTH_TABLE_BITS, DEPTH_WORD_BITS>(self.t_word.q.val() >> self.slope_bits.val());
        self.slope_w.clock.next = self.clock.val();
        self.slope_w.a.next = bit_cast::<16, DEPTH_WORD_BITS>(self.t_word.q.val() & self.slope_mask.val());
        self.slope_w.b.next = self.t_w.q.val();
        self.s4_sat.d.next = self.t_sat.q.val();
        self.s4_shift.d.next = self.t_shift.q.val();
        // S5: slope · w (the DSP block, after its input registers; the
        // product registered in the fabric).
        self.prod.next = self.slope_w.p.val();
        self.s5_prod.d.next = self.prod.val();
        self.s5_t.d.next = self.s4_t.q.val();
        self.s5_sat.d.next = self.s4_sat.q.val();
        self.s5_shift.d.next = self.s4_shift.q.val();
        // S6: T = T_i - round(slope · w / 16).
        self.rounded_step.next = self.s5_prod.q.val() + self.step_half.val();
        self.step.next = bit_cast::<DEPTH_TABLE_BITS, 32>(self.rounded_step.val() >> self.weight_bits.val());
        self.s6_t.d.next = self.s5_t.q.val() - self.step.val();
        self.s6_sat.d.next = self.s5_sat.q.val();
        self.s6_shift.d.next = self.s5_shift.q.val();
        // S7: T / 2^(s - 1 - lz), truncated.
        self.s7_half.d.next = self.s6_t.q.val() >> self.s6_shift.q.val();
        self.s7_sat.d.next = self.s6_sat.q.val();
        // S8: the last halving rounded (half up), saturation, no depth.
        self.wide.next = bit_cast::<ROUND_BITS, DEPTH_TABLE_BITS>(self.s7_half.q.val()) + self.one.val();
        self.z_full.next = self.wide.val() >> self.sh_round.val();
        self.o_z.d.next = bit_cast::<DEPTH_BITS, ROUND_BITS>(self.z_full.val());
        if self.s7_sat.q.val() | (self.z_full.val() >> self.depth_bits.val()).any() {
            self.o_z.d.next = self.depth_max.val();
        }
        if self.s7_zero.q.val() | !self.s7_valid.q.val() {
            self.o_z.d.next = 0.into();
        }
        self.o_valid.d.next = self.s7_valid.q.val();
        self.o_last.d.next = self.s7_last.q.val();
        self.o_sof.d.next = self.s7_sof.q.val();
        self.o_d.d.next = 0.into();
        if self.s7_valid.q.val() {
            self.o_d.d.next = self.s7_d.q.val();
        }
        self.z_valid.next = self.o_valid.q.val();
        self.z_mm.next = self.o_z.q.val();
        self.z_d.next = self.o_d.q.val();
        self.z_last.next = self.o_last.q.val();
        self.z_sof.next = self.o_sof.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_camera_scales_into_range_and_its_table_fits() {
        let s = DepthScale::of(&DepthCamera::default()).expect("in range");
        assert!(s.k * 2 >= DEPTH_K_LIMIT && s.k <= DEPTH_K_LIMIT, "{s:?}");
        assert_eq!(depth_table(&s).len(), 1 << DEPTH_INDEX_BITS);
        assert!(matches!(
            DepthScale::of(&DepthCamera { focal_px: 0.0, baseline_mm: 1.0 }),
            Err(DepthError::NotPositive { .. })
        ));
    }
}
