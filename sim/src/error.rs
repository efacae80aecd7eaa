//! Typed errors of the `sim` library; the CLI reports them with context.

use std::path::PathBuf;

use thiserror::Error;

/// What can go wrong reading inputs or writing results.
#[derive(Debug, Error)]
pub enum SimError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A file is not an image the `image` crate can decode.
    #[error("{}: cannot read image: {source}", path.display())]
    Image {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    /// A pair folder lacks something the evaluation needs.
    #[error("{}: {msg}", path.display())]
    PairDir { path: PathBuf, msg: String },
    /// Ground truth or mask of a size other than the images'.
    #[error("{}: is {got_w}x{got_h}, the images are {want_w}x{want_h}", path.display())]
    SizeMismatch {
        path: PathBuf,
        got_w: u32,
        got_h: u32,
        want_w: usize,
        want_h: usize,
    },
    /// A command-line argument that does not fit the inputs.
    #[error("{0}")]
    Argument(String),
    /// The golden model refused its inputs.
    #[error(transparent)]
    Golden(#[from] golden::GoldenError),
    /// A picture could not be written.
    #[error(transparent)]
    Picture(#[from] crate::eval::pictures::PictureError),
    /// A latency budget was asked for sizes the hardware does not take.
    #[error(transparent)]
    Budget(#[from] crate::budget::BudgetError),
    /// A Verilog simulator failed or disagreed.
    #[error(transparent)]
    Cosim(#[from] crate::hdl::cosim::CosimError),
    /// Synthesis or place and route failed.
    #[error(transparent)]
    Synth(#[from] crate::hdl::synth::SynthError),
    /// A search bound the matcher does not take.
    #[error(transparent)]
    Dispmax(#[from] crate::formats::DispmaxError),
    /// A check of the design found it wrong (the fault campaign's
    /// invariants broken).
    #[error("{0}")]
    Check(String),
}
