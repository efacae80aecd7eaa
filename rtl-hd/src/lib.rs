//! # rtl-hd — the declivity stereo sensor in the `hd` configuration
//!
//! The blocks of the `rtl` crate, the same source files, built with the
//! `hd` sizes: lines up to 2048 pixels (1280- to 1920-pixel cameras), up to
//! 256 characteristic declivities each. Every width derives from
//! [`config`] in [`params`]; the blocks' documentation is `rtl`'s.

#![allow(rustdoc::private_intra_doc_links)]

/// The configuration this crate is built for: `hd`.
#[path = "../../rtl/src/config/hd.rs"]
pub mod config;
include!("../../rtl/src/blocks.rs");
