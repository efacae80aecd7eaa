//! Conversions between golden's real values and the hardware's fixed-point
//! formats (`rtl::params`), in one place for every driver, job and report.

use rtl::params::POS_FRAC_BITS;

use crate::config::Config;

/// One pixel in the positions' unit, `1/2^POS_FRAC_BITS` px.
pub(crate) const POSITION_UNIT: f64 = (1u32 << POS_FRAC_BITS) as f64;

/// A position as the detector gives it: `⌊X · 2^POS_FRAC_BITS⌋`
/// (`rtl::detector::position_divider`).
pub(crate) fn position_lsb(x: f64) -> u32 {
    (x * POSITION_UNIT).floor() as u32
}

/// A real disparity (pixels, `0.0` = none) in the depth stage's input
/// format: rounded to `POS_FRAC_BITS` fraction bits, at least one LSB when
/// positive, at most the largest value of `config`'s `POS_BITS` bits.
pub fn disparity_lsb(d: f64, config: Config) -> u64 {
    if d > 0.0 {
        ((d * POSITION_UNIT).round() as u64).clamp(1, (1u64 << config.sizes().pos_bits) - 1)
    } else {
        0
    }
}

/// A search bound the matcher does not take.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("--{option} {value}: {why}")]
pub struct DispmaxError {
    /// The option: `dispmax` or `dispmin`.
    pub option: &'static str,
    /// The bound asked for, px.
    pub value: f64,
    /// What is wrong with it.
    pub why: String,
}

/// `--dispmax` in the matcher's unit, `1/2^POS_FRAC_BITS` px: a finite
/// value greater than 1 (eq. 6 searches `0 < d < dispmax`), at most
/// `config`'s `W_MAX`, on that grid. A bound of `W_MAX` is clamped to the
/// largest the matcher's port holds, which no disparity inside a line
/// reaches.
pub fn dispmax_lsb(dispmax: f64, config: Config) -> Result<u32, DispmaxError> {
    let (w_max, dispmax_bits) = (config.sizes().w_max, config.sizes().dispmax_bits);
    let err = |why: String| DispmaxError { option: "dispmax", value: dispmax, why };
    if !dispmax.is_finite() || dispmax <= 1.0 {
        return Err(err("dispmax must be greater than 1 (eq. 6 searches 0 < d < dispmax)".into()));
    }
    if dispmax > w_max as f64 {
        return Err(err(format!("dispmax must be at most W_MAX = {w_max} px (the widest line the {config} hardware stores)")));
    }
    let lsb = on_grid(dispmax, 1.0 + 1.0 / POSITION_UNIT).map_err(err)?;
    Ok(lsb.min((1u32 << dispmax_bits) - 1))
}

/// Eq. 6's search area `dispmin < d < dispmax` in the matcher's unit,
/// `1/2^POS_FRAC_BITS` px: its ports `dispmin` and `dispmax`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct SearchArea {
    /// The lower bound (0: the paper's `0 < d`).
    pub dispmin: u32,
    /// The upper bound.
    pub dispmax: u32,
}

impl SearchArea {
    /// The paper's area `0 < d < dispmax` (`dispmax` in LSBs).
    pub fn below(dispmax: u32) -> Self {
        SearchArea { dispmin: 0, dispmax }
    }

    /// `--dispmin` and `--dispmax` (px) in the matcher's unit: `dispmax` as
    /// [`dispmax_lsb`] takes it, `dispmin` as golden's hardware parity in
    /// `config` does (`golden::Params::validate`: at least 0, less than
    /// `dispmax - 1`, on the positions' grid).
    pub fn from_px(dispmin: f64, dispmax: f64, config: Config) -> Result<Self, DispmaxError> {
        let max = dispmax_lsb(dispmax, config)?;
        let err = |why: String| DispmaxError { option: "dispmin", value: dispmin, why };
        golden::Params::new(dispmax)
            .and_then(|p| golden::Params { dispmin, hardware: Some(config.limits()), ..p }.validate())
            .map_err(|e| err(e.to_string()))?;
        Ok(SearchArea { dispmin: on_grid(dispmin, 0.0).map_err(err)?, dispmax: max })
    }

    /// The lower bound in px.
    pub fn dispmin_px(&self) -> f64 {
        self.dispmin as f64 / POSITION_UNIT
    }
}

/// `px` in `1/2^POS_FRAC_BITS` px when it is on that grid; else why not,
/// with the grid value nearest, at least `least`.
fn on_grid(px: f64, least: f64) -> Result<u32, String> {
    let unit = POSITION_UNIT;
    let lsb = px * unit;
    if lsb.fract() != 0.0 {
        return Err(format!("the matcher takes search bounds in 1/{unit} px; give a multiple of 1/{unit}, e.g. {}", (lsb.round() / unit).max(least)));
    }
    Ok(lsb as u32)
}
