//! A whole rectified image pair, line by line, on one thread or all cores.

use rayon::prelude::*;

use crate::disparity::{interpolate_into, Anchor};
use crate::error::GoldenError;
use crate::line::{process_line, LineResult};
use crate::params::Params;

/// An 8-bit grey image, row-major.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GreyImage {
    width: usize,
    height: usize,
    data: Vec<u8>,
}

impl GreyImage {
    /// Wraps a row-major buffer of `width × height` bytes.
    pub fn new(width: usize, height: usize, data: Vec<u8>) -> Result<Self, GoldenError> {
        if data.len() != width * height {
            return Err(GoldenError::BufferSize { width, height, len: data.len() });
        }
        if width == 0 || height == 0 {
            return Err(GoldenError::EmptyImage { width, height });
        }
        Ok(GreyImage { width, height, data })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row `y` (an epipolar line).
    pub fn row(&self, y: usize) -> &[u8] {
        &self.data[y * self.width..(y + 1) * self.width]
    }

    /// All pixels, row-major.
    pub fn pixels(&self) -> &[u8] {
        &self.data
    }
}

/// How many threads process the lines. Results are identical either way:
/// lines are independent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Threads {
    /// The calling thread only.
    One,
    /// All cores (rayon's global pool).
    #[default]
    All,
}

/// The method's result on a frame.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameResult {
    /// Width of the images.
    pub width: usize,
    /// Height of the images.
    pub height: usize,
    /// The parameters used.
    pub params: Params,
    /// One result per row.
    pub lines: Vec<LineResult>,
    /// Dense disparity of the reference view, row-major, `0.0` = none.
    pub disparity: Vec<f64>,
}

impl FrameResult {
    /// Characteristic declivities of the reference view.
    pub fn reference_declivities(&self) -> usize {
        self.lines.iter().map(|l| l.reference.declivities.len()).sum()
    }

    /// Matched reference declivities.
    pub fn matches(&self) -> usize {
        self.lines.iter().map(|l| l.matches.len()).sum()
    }
}

/// Runs the method on a rectified pair: every row of `left` with the same
/// row of `right`, then interpolation along each reference row.
pub fn process_frame(left: &GreyImage, right: &GreyImage, params: &Params, threads: Threads) -> Result<FrameResult, GoldenError> {
    params.validate()?;
    if left.width != right.width || left.height != right.height {
        return Err(GoldenError::SizeMismatch {
            left_w: left.width,
            left_h: left.height,
            right_w: right.width,
            right_h: right.height,
        });
    }
    let (w, h) = (left.width, left.height);
    let mut disparity = vec![0.0; w * h];
    let one_row = |(y, out): (usize, &mut [f64])| -> LineResult {
        let res = process_line(left.row(y), right.row(y), params);
        let anchors: Vec<Anchor> = res.matches.iter().map(|m| m.anchor()).collect();
        interpolate_into(&anchors, params.ends, out);
        res
    };
    let lines: Vec<LineResult> = match threads {
        Threads::One => disparity.chunks_mut(w).enumerate().map(one_row).collect(),
        Threads::All => disparity.par_chunks_mut(w).enumerate().map(one_row).collect(),
    };
    Ok(FrameResult { width: w, height: h, params: *params, lines, disparity })
}
