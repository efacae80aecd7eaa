//! The line processor's configurations (`--config`): its generation-time
//! sizes. The rtl sources are built once per configuration, as a crate of
//! its own (`rtl` is `sd`, `rtl-hd` is `hd`), because rust-hdl's widths are
//! const generics that stable Rust cannot compute from a parameter; this
//! module names them and gives their sizes as values, for the code that
//! serves both (Verilog, the frame simulators, the budget, the reports).

use golden::hardware::HardwareLimits;

/// A configuration of the line processor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Config {
    /// Lines up to 1024 pixels, 128 declivities each (`rtl`): the paper's
    /// 512-pixel world and VGA-class cameras.
    #[default]
    Sd,
    /// Lines up to 2048 pixels, 256 declivities each (`rtl-hd`): 1280- to
    /// 1920-pixel cameras.
    Hd,
}

/// A configuration's sizes, as its crate's `params` has them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Sizes {
    /// The configuration's name.
    pub config: &'static str,
    /// The widest line stored, pixels.
    pub w_max: usize,
    /// Characteristic declivities kept per line.
    pub n_max: usize,
    /// Gain cells of the sensor's matcher, each of `rows_per_cell` rows.
    pub cells: usize,
    pub rows_per_cell: usize,
    /// Bits of a position or disparity (`1/2^POS_FRAC_BITS` px).
    pub pos_bits: usize,
    /// Bits of the `dispmax` port.
    pub dispmax_bits: usize,
    /// Bits of the `height` port (the frame's rows).
    pub height_bits: usize,
    /// The most clocks apart two frame starts are paired (the matcher's
    /// Pairing).
    pub sof_skew_max: usize,
}

/// The sizes of the configuration crate `$k`.
macro_rules! sizes_of {
    ($k:ident) => {
        Sizes {
            config: $k::params::CONFIG,
            w_max: $k::params::W_MAX,
            n_max: $k::params::N_MAX,
            cells: $k::params::N_CELLS,
            rows_per_cell: $k::params::ROWS_PER_CELL,
            pos_bits: $k::params::POS_BITS,
            dispmax_bits: $k::params::DISPMAX_BITS,
            height_bits: $k::stereo_line_processor::HEIGHT_BITS,
            sof_skew_max: $k::params::SOF_SKEW_MAX,
        }
    };
}

impl Config {
    /// Every configuration, smallest first.
    pub const ALL: [Config; 2] = [Config::Sd, Config::Hd];

    /// Its sizes.
    pub fn sizes(self) -> Sizes {
        match self {
            Config::Sd => sizes_of!(rtl),
            Config::Hd => sizes_of!(rtl_hd),
        }
    }

    /// Its name (`sd`, `hd`).
    pub fn name(self) -> &'static str {
        self.sizes().config
    }

    /// The configuration named `name`.
    pub fn from_name(name: &str) -> Option<Config> {
        Config::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The smallest configuration that stores lines of `width` pixels
    /// whole, if any.
    pub fn fitting(width: usize) -> Option<Config> {
        Config::ALL.into_iter().find(|c| width <= c.sizes().w_max)
    }

    /// What to do with lines of `width` pixels too wide for some
    /// configuration: the configuration that takes them (`the hd
    /// configuration takes lines up to 2048 pixels: --config hd`), or that
    /// none does.
    pub fn fitting_hint(width: usize) -> String {
        match Config::fitting(width) {
            Some(c) => format!("the {c} configuration takes lines up to {} pixels: --config {c}", c.sizes().w_max),
            None => "no configuration takes lines this wide".to_string(),
        }
    }

    /// The gain-cell counts its matcher can be generated with (`--cells`):
    /// up to the sensor's cells, arrays of fewer than 16 cells dividing 16
    /// (their phases share a word of the choice memory,
    /// `rtl::matcher::choice_word`).
    pub fn matcher_cells(self) -> &'static [usize] {
        match self {
            Config::Sd => &[2, 4, 8, 16, 32],
            Config::Hd => &[2, 4, 8, 16, 32, 64],
        }
    }

    /// Its limits and formats as golden's hardware-parity mode takes them.
    pub fn limits(self) -> HardwareLimits {
        use rtl::params::{DT_FRAC_BITS, MATCH_DT_FRAC_BITS, POS_FRAC_BITS};
        let sizes = self.sizes();
        HardwareLimits {
            w_max: sizes.w_max,
            n_max: sizes.n_max,
            pos_frac_bits: POS_FRAC_BITS as u32,
            dt_frac_bits: DT_FRAC_BITS as u32,
            match_dt_frac_bits: MATCH_DT_FRAC_BITS as u32,
        }
    }
}

impl std::fmt::Display for Config {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hd_doubles_sds_line_and_declivities_and_every_width_follows() {
        let (sd, hd) = (Config::Sd.sizes(), Config::Hd.sizes());
        assert_eq!((sd.w_max, sd.n_max, sd.cells), (1024, 128, 32));
        assert_eq!((hd.w_max, hd.n_max, hd.cells), (2048, 256, 64));
        assert_eq!(hd.pos_bits, sd.pos_bits + 1);
        assert_eq!(hd.height_bits, sd.height_bits + 1);
        for c in Config::ALL {
            let s = c.sizes();
            assert_eq!(Config::from_name(s.config), Some(c));
            assert_eq!(s.cells * s.rows_per_cell, s.n_max);
            assert_eq!(c.matcher_cells().last(), Some(&s.cells));
            assert_eq!(1 << s.pos_bits, s.w_max << 4, "positions of 1/16 px up to W_MAX");
        }
        // The formats that do not depend on the sizes are the same in both.
        assert_eq!(
            (rtl::params::POS_FRAC_BITS, rtl::params::DT_FRAC_BITS, rtl::params::MATCH_DT_FRAC_BITS, rtl::params::DEPTH_BITS, rtl::params::PIXEL_BITS),
            (rtl_hd::params::POS_FRAC_BITS, rtl_hd::params::DT_FRAC_BITS, rtl_hd::params::MATCH_DT_FRAC_BITS, rtl_hd::params::DEPTH_BITS, rtl_hd::params::PIXEL_BITS)
        );
        assert_eq!(Config::fitting(1024), Some(Config::Sd));
        assert_eq!(Config::fitting(1025), Some(Config::Hd));
        assert_eq!(Config::fitting(1920), Some(Config::Hd));
        assert_eq!(Config::fitting(2049), None);
    }
}
