//! Argument types the commands share: the method's options, the matcher's
//! gain rule, the engine, row ranges, and the CLI's names for library types
//! (the library does not depend on clap).

use std::ops::Range;

use clap::{Args, ValueEnum};
use golden::{EndRule, Mode, Params, RefView};
use rtl::matcher::declivity_matcher::GainRule;
use rtl::params::POS_FRAC_BITS;
use sim::jobs::rtl_depth::Engine;
use sim::{Config, SimError};

/// `A..B` (rows A to B-1, not empty).
pub(crate) fn parse_range(s: &str) -> Result<Range<usize>, String> {
    let (a, b) = s.split_once("..").ok_or_else(|| format!("`{s}` is not a range A..B"))?;
    let a: usize = a.trim().parse().map_err(|_| format!("`{a}` is not a row number"))?;
    let b: usize = b.trim().parse().map_err(|_| format!("`{b}` is not a row number"))?;
    if b <= a {
        return Err(format!("the range {a}..{b} is empty"));
    }
    Ok(a..b)
}

/// A finite number greater than 0.
pub(crate) fn parse_positive(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("`{s}` is not a number"))?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("`{s}` must be a finite number greater than 0"))
    }
}

/// A finite number, 0 or more.
pub(crate) fn parse_non_negative(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("`{s}` is not a number"))?;
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("`{s}` must be a finite number, 0 or more"))
    }
}

/// The method's options of `depth` and `eval`.
#[derive(Args, Debug, Clone)]
pub(crate) struct MethodArgs {
    /// Variant of the method: `paper` is the paper's exactly; `robust` (the default) adds every
    /// measured improvement; the others add one each (docs/method.md).
    #[arg(long, value_enum, default_value_t = CliMode(Mode::default()))]
    pub mode: CliMode,
    /// Reference view: its declivities get disparities and its pixels form the map.
    #[arg(long, value_enum, default_value_t = CliRef::Left)]
    pub ref_view: CliRef,
    /// Interpolation before the first and after the last match of a line.
    #[arg(long, value_enum, default_value_t = CliEnds::Hold)]
    pub ends: CliEnds,
    #[arg(long, help = hardware_parity_help())]
    pub hardware_parity: bool,
    #[arg(long, value_enum, default_value_t = CliConfig(Config::Sd), help = config_help("--hardware-parity and --rtl"))]
    pub config: CliConfig,
    #[arg(long, default_value_t = 0.0, value_parser = parse_non_negative, help = dispmin_help())]
    pub dispmin: f64,
}

fn dispmin_help() -> String {
    format!(
        "Lower search bound in px: a match needs dispmin < d < dispmax (eq. 6; the paper's 0). For a \
         verged or offset rig, or a scene with a known nearest range. --hardware-parity and --rtl take it \
         as the line processor's `dispmin` input does, a multiple of 1/{} px",
        1u32 << POS_FRAC_BITS
    )
}

fn hardware_parity_help() -> String {
    format!(
        "Run as the hardware of --config does: declivities of the first W_MAX pixels of a line, the first \
         N_MAX kept, found and placed with the detector's fixed-point values (d_t in 1/{} grey \
         level, positions the eq. 3 divider's quotients in 1/{} px: the records `rtl detect` sends), and \
         matched with d_t rounded down to 1/{} grey level, as `rtl depth` compares with",
        1u32 << rtl::params::DT_FRAC_BITS,
        1u32 << POS_FRAC_BITS,
        1u32 << rtl::params::MATCH_DT_FRAC_BITS
    )
}

impl MethodArgs {
    /// golden's parameters for the search bound `dispmax`.
    pub(crate) fn params(&self, dispmax: f64) -> Result<Params, SimError> {
        let p = Params {
            mode: self.mode.0,
            dispmax,
            dispmin: self.dispmin,
            ref_view: match self.ref_view {
                CliRef::Left => RefView::Left,
                CliRef::Right => RefView::Right,
            },
            ends: match self.ends {
                CliEnds::Hold => EndRule::Hold,
                CliEnds::None => EndRule::Empty,
            },
            hardware: self.hardware_parity.then(|| self.config.0.limits()),
        };
        p.validate()?;
        Ok(p)
    }
}

/// A [`Mode`] on the command line: its names and summaries come from golden.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CliMode(pub Mode);

impl ValueEnum for CliMode {
    fn value_variants<'a>() -> &'a [Self] {
        const ALL: [CliMode; Mode::ALL.len()] = {
            let mut all = [CliMode(Mode::Paper); Mode::ALL.len()];
            let mut k = 0;
            while k < all.len() {
                all[k] = CliMode(Mode::ALL[k]);
                k += 1;
            }
            all
        };
        &ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(clap::builder::PossibleValue::new(self.0.name()).help(self.0.summary()))
    }
}

/// A configuration of the line processor on the command line (`--config`):
/// its names and sizes come from `sim::config`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CliConfig(pub Config);

impl ValueEnum for CliConfig {
    fn value_variants<'a>() -> &'a [Self] {
        &[CliConfig(Config::Sd), CliConfig(Config::Hd)]
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let s = self.0.sizes();
        Some(clap::builder::PossibleValue::new(s.config).help(format!(
            "lines up to W_MAX = {} px, N_MAX = {} declivities a line, {} gain cells of {} rows",
            s.w_max, s.n_max, s.cells, s.rows_per_cell
        )))
    }
}

/// A size of every configuration, for help texts: `sd 1024, hd 2048`.
pub(crate) fn per_config(size: impl Fn(&sim::config::Sizes) -> usize) -> String {
    Config::ALL.iter().map(|c| format!("{} {}", c.name(), size(&c.sizes()))).collect::<Vec<_>>().join(", ")
}

/// The matcher sizes of every configuration, for help texts: `sd: one of
/// [2, 4, …]; hd: one of […]`.
pub(crate) fn cells_per_config() -> String {
    Config::ALL.iter().map(|c| format!("{c}: one of {:?}", c.matcher_cells())).collect::<Vec<_>>().join("; ")
}

/// The help of a `--config` option that applies to `what`.
pub(crate) fn config_help(what: &str) -> String {
    let names: Vec<String> = Config::ALL
        .iter()
        .map(|c| format!("{} (lines up to {} px, {} declivities each)", c.name(), c.sizes().w_max, c.sizes().n_max))
        .collect();
    format!("Configuration of the line processor for {what}: {}", names.join(", "))
}

const _: () = assert!(Config::ALL.len() == 2, "CliConfig::value_variants lists every configuration");

/// The reference view.
#[derive(ValueEnum, Debug, Clone, Copy)]
pub(crate) enum CliRef {
    /// Left view (the ground truth in data/stereo is for it).
    Left,
    /// Right view (the paper's choice).
    Right,
}

/// What the interpolation does at a line's ends.
#[derive(ValueEnum, Debug, Clone, Copy)]
pub(crate) enum CliEnds {
    /// Hold the nearest matched disparity out to the line's ends.
    Hold,
    /// Leave the line's ends without disparity.
    None,
}

/// The matcher's gain rule on the command line.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CliRule {
    /// Eq. 4-8 as the paper writes them (golden's `paper` mode).
    Paper,
    /// Offset-compensated distances, one polarity, one-sided nodes (golden's default `robust`
    /// mode; its other changes act after the matcher).
    Robust,
}

impl CliRule {
    pub(crate) fn rule(self) -> GainRule {
        match self {
            CliRule::Paper => GainRule::Paper,
            CliRule::Robust => GainRule::Robust,
        }
    }
}

/// What simulates the line processor clock by clock.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CliEngine {
    /// The rust-hdl model under direct drive (slow: thousands of clocks per second).
    #[value(name = "rust-hdl")]
    RustHdl,
    /// The generated Verilog under Verilator (the fastest; one build, kept for later runs).
    Verilator,
    /// The generated Verilog under Icarus Verilog (slowest; a few lines).
    Icarus,
}

/// The engine asked for, or the fastest one installed.
pub(crate) fn engine(asked: Option<CliEngine>) -> Engine {
    match asked {
        Some(CliEngine::RustHdl) => Engine::RustHdl,
        Some(CliEngine::Verilator) => Engine::Verilator,
        Some(CliEngine::Icarus) => Engine::Icarus,
        None => Engine::fastest_installed(),
    }
}

/// A block that `verilog` and `synth` generate.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CliTop {
    /// The declivity detector of one camera.
    Detector,
    /// The matcher: systolic array of gain cells and traceback (--cells, --rule).
    Matcher,
    /// The interpolator: a line's matches in, one disparity per pixel per clock out.
    Interpolator,
    /// The whole line processor: two cameras in, disparity and depth out (--cells, --rule).
    Stereo,
}

impl CliTop {
    pub(crate) fn top(self) -> sim::hdl::verilog::Top {
        use sim::hdl::verilog::Top;
        match self {
            CliTop::Detector => Top::Detector,
            CliTop::Matcher => Top::Matcher,
            CliTop::Interpolator => Top::Interpolator,
            CliTop::Stereo => Top::Stereo,
        }
    }
}

/// What `verilog` writes the block for.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CliTarget {
    /// The Lattice ECP5: DP16KD, MULT18X18D, TRELLIS_DPR16X4 and (the line processor's reset)
    /// DCCA instantiated by name (the measured target; their simulation models beside the block).
    Ecp5,
    /// Any FPGA or ASIC flow: the primitives replaced by behavioural Verilog inside the block
    /// (memories with registered reads, `*`), which Yosys, Vivado and Quartus infer.
    Generic,
}

impl CliTarget {
    pub(crate) fn target(self) -> sim::hdl::verilog::Target {
        match self {
            CliTarget::Ecp5 => sim::hdl::verilog::Target::Ecp5,
            CliTarget::Generic => sim::hdl::verilog::Target::Generic,
        }
    }
}

impl std::fmt::Display for CliConfig {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

/// The camera pair whose depths (eq. 1) the depth stage is generated for:
/// `verilog` and `synth --top stereo`, `rtl depth`.
#[derive(Args, Debug, Clone, Copy)]
pub(crate) struct CameraArgs {
    #[arg(long, requires = "baseline_m", value_parser = parse_positive, help = focal_help())]
    pub focal_px: Option<f64>,
    #[arg(long, requires = "focal_px", value_parser = parse_positive, help = baseline_help())]
    pub baseline_m: Option<f64>,
}

fn focal_help() -> String {
    let c = rtl::post::depth_stage::DepthCamera::default();
    format!(
        "Focal length of the camera pair in pixels (f/p, at the resolution of the images), whose \
         depths the depth stage's table holds (eq. 1); with --baseline-m [default: {} px, the \
         motorcycle pair's camera]",
        c.focal_px
    )
}

fn baseline_help() -> String {
    let c = rtl::post::depth_stage::DepthCamera::default();
    format!("Baseline of the camera pair in metres; with --focal-px [default: {} m]", c.baseline_mm / 1000.0)
}

impl CameraArgs {
    /// Whether the command line set the camera.
    pub(crate) fn given(&self) -> bool {
        self.focal_px.is_some()
    }

    /// The camera asked for, or the default one.
    pub(crate) fn camera(&self) -> rtl::post::depth_stage::DepthCamera {
        match (self.focal_px, self.baseline_m) {
            (Some(focal_px), Some(baseline_m)) => rtl::post::depth_stage::DepthCamera { focal_px, baseline_mm: baseline_m * 1000.0 },
            _ => rtl::post::depth_stage::DepthCamera::default(),
        }
    }
}
