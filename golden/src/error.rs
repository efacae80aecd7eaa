//! Typed errors of the golden model.

use thiserror::Error;

/// What can be wrong with the inputs of the golden model.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GoldenError {
    /// The two views of a pair must have the same size (rectified pair).
    #[error("the two images differ in size: left {left_w}x{left_h}, right {right_w}x{right_h}")]
    SizeMismatch {
        left_w: usize,
        left_h: usize,
        right_w: usize,
        right_h: usize,
    },
    /// Pixel buffer length disagrees with width × height.
    #[error("pixel buffer holds {len} bytes, {width}x{height} needs {}", width * height)]
    BufferSize { width: usize, height: usize, len: usize },
    /// An image without pixels.
    #[error("the image is empty ({width}x{height})")]
    EmptyImage { width: usize, height: usize },
    /// The search bound of eq. 6 must leave room for a positive disparity.
    #[error("dispmax must be greater than 1 (got {0}): eq. 6 needs 0 < d < dispmax")]
    InvalidDispmax(f64),
    /// The lower search bound of eq. 6 must be at least 0 and leave a pixel
    /// of search below `dispmax`.
    #[error("dispmin must be at least 0 and less than dispmax − 1 = {} (got {dispmin}): eq. 6 needs dispmin < d < dispmax", dispmax - 1.0)]
    InvalidDispmin { dispmin: f64, dispmax: f64 },
    /// Hardware parity with a lower search bound between the positions'
    /// values: the line processor takes it on their grid.
    #[error("dispmin {dispmin}: the line processor takes the search bounds in 1/{unit} px, so hardware parity takes a multiple of 1/{unit}")]
    DispminOffGrid { dispmin: f64, unit: f64 },
}
