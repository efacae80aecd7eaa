//! Verilog of the rtl blocks, as rust-hdl generates it.

use rust_hdl::prelude::*;

/// A block that `declivity verilog` and `declivity synth` can generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Top {
    /// The declivity detector of one camera (`rtl::declivity_detector`).
    Detector,
}

impl Top {
    /// Name used for files.
    pub fn name(self) -> &'static str {
        match self {
            Top::Detector => "detector",
        }
    }
}

/// The Verilog of `top`; its top module is named `top`.
pub fn generate(top: Top) -> String {
    match top {
        Top::Detector => {
            let mut uut = rtl::declivity_detector::DeclivityDetector::default();
            uut.connect_all();
            generate_verilog(&uut)
        }
    }
}
