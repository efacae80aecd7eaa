//! The `hd` configuration: lines up to 2048 pixels (1280- to 1920-pixel
//! cameras) with up to 256 characteristic declivities each. The `rtl-hd`
//! crate is this configuration.

/// The configuration's name, as `--config` takes it.
pub const NAME: &str = "hd";
/// log2 of the widest line `W_MAX` (2048 pixels).
pub const W_MAX_BITS: usize = 11;
/// log2 of `N_MAX`, the characteristic declivities kept per line (256).
pub const N_MAX_BITS: usize = 8;
