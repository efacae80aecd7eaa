//! The `sd` configuration: lines up to 1024 pixels with up to 128
//! characteristic declivities each (the sizes of `DESIGN.md` §3, the
//! paper's 512-pixel world with room to spare). The `rtl` crate is this
//! configuration.

/// The configuration's name, as `--config` takes it.
pub const NAME: &str = "sd";
/// log2 of the widest line `W_MAX` (1024 pixels).
pub const W_MAX_BITS: usize = 10;
/// log2 of `N_MAX`, the characteristic declivities kept per line (128).
pub const N_MAX_BITS: usize = 7;
