//! Pictures of the method's intermediate and final results, as in the paper:
//! the characteristic declivities over the image (photos 3–4), the matching
//! graph of one pair of lines with its optimal path (fig. 4), the disparity
//! map coded in grey levels, near = bright (photo 5), plus machine-readable
//! outputs: 16-bit disparity and depth PNGs and an ASCII PLY point cloud
//! (eq. 1).
//!
//! Every picture function is pure and returns an `image` buffer; writing is
//! done by [`save_png`] and [`write_ply`], whose errors ([`PictureError`])
//! name the file. Lines, discs and the little 5×7 bitmap font of the graph's
//! legend are drawn here with plain pixel loops.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::ops::Deref;
use std::path::{Path, PathBuf};

use golden::dp::GainTable;
use golden::gain::{gmax, in_search_area, pair_disparity};
use golden::line::{gain_table, LineFeatures, LineResult};
use golden::reconstruct::{depth, point, Camera};
use golden::{FrameResult, GreyImage, Params};
use image::{EncodableLayout, GrayImage, ImageBuffer, ImageFormat, Luma, Pixel, PixelWithColorType, Rgb, RgbImage};

/// A failure to write a picture or a point cloud, with the file concerned.
#[derive(Debug, thiserror::Error)]
pub enum PictureError {
    /// Creating or writing the file failed.
    #[error("cannot write {}: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Encoding the image (or writing it) failed in the `image` crate.
    #[error("cannot encode {}: {source}", .path.display())]
    Encode {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: image::ImageError,
    },
    /// The colour image given to [`write_ply`] does not have the frame's size.
    #[error("colour image for {} is {colour_w}x{colour_h}, the frame is {frame_w}x{frame_h}", .path.display())]
    SizeMismatch {
        /// The file that was to be written.
        path: PathBuf,
        /// Width of the colour image.
        colour_w: usize,
        /// Height of the colour image.
        colour_h: usize,
        /// Width of the frame.
        frame_w: usize,
        /// Height of the frame.
        frame_h: usize,
    },
}

/// Colour of a rising characteristic declivity (amplitude > 0) in
/// [`declivity_overlay`].
const RISING: Rgb<u8> = Rgb([255, 0, 0]);
/// Colour of a falling characteristic declivity (amplitude < 0) in
/// [`declivity_overlay`].
const FALLING: Rgb<u8> = Rgb([0, 255, 255]);
/// Colour of the rings ("double edges") around the optimal path's nodes in
/// [`matching_graph`].
const PATH_RING: Rgb<u8> = Rgb([0, 255, 0]);
/// Colour of the segments joining consecutive path nodes in
/// [`matching_graph`].
const PATH_LINE: Rgb<u8> = Rgb([0, 150, 0]);
/// Colour of the square frames around the nodes of the second path in
/// [`matching_graph_two_paths`] (the rtl path).
const RTL_BOX: Rgb<u8> = Rgb([255, 150, 0]);
/// Colour of the segments joining the second path's nodes in
/// [`matching_graph_two_paths`].
const RTL_LINE: Rgb<u8> = Rgb([235, 110, 0]);
/// Background of the cells inside the search area (eq. 6) in
/// [`matching_graph`]; cells outside it stay black.
const SEARCH_AREA: Rgb<u8> = Rgb([28, 28, 48]);
/// Colour of nodes whose gain is zero or negative in [`matching_graph`].
const WEAK_NODE: Rgb<u8> = Rgb([80, 80, 80]);

const BLACK: Rgb<u8> = Rgb([0, 0, 0]);
const TEXT: Rgb<u8> = Rgb([200, 200, 200]);

/// Converts an image dimension; the `image` crate's buffers are limited to
/// `u32` sides.
fn dim(v: usize) -> u32 {
    u32::try_from(v).expect("image side exceeds u32::MAX")
}

/// Checks that a frame's dense map matches its size.
fn check_frame(frame: &FrameResult) {
    assert_eq!(
        frame.disparity.len(),
        frame.width * frame.height,
        "FrameResult: disparity has {} entries for a {}x{} frame",
        frame.disparity.len(),
        frame.width,
        frame.height
    );
}

/// Maps a non-negative value (already in output units) to `1..=u16::MAX`:
/// rounded, saturating, never 0 (0 means "none").
fn to_u16_nonzero(v: f64) -> u16 {
    // `as` saturates (and +inf becomes u16::MAX).
    (v.round() as u16).max(1)
}

/// The dense disparity map as a 16-bit grey image with 4 fractional bits:
/// pixel = `round(d · 16)`, so `d = pixel / 16` pixels.
///
/// `0` means "no disparity" (`d ≤ 0` or NaN in the map). A positive disparity
/// never becomes 0: values that round to 0 are stored as 1, and values above
/// `u16::MAX / 16 ≈ 4096` px saturate at `u16::MAX`. The image has the
/// frame's size; every pixel is defined (no border handling is needed).
///
/// Panics if `frame.disparity.len() != width · height`.
pub(crate) fn disparity_png16(frame: &FrameResult) -> ImageBuffer<Luma<u16>, Vec<u16>> {
    check_frame(frame);
    let data = frame
        .disparity
        .iter()
        .map(|&d| if d > 0.0 { to_u16_nonzero(d * 16.0) } else { 0 })
        .collect();
    ImageBuffer::from_raw(dim(frame.width), dim(frame.height), data).expect("buffer has width × height pixels")
}

/// The disparity map coded in grey levels as the paper's photo 5: high grey
/// levels are closer to the viewer (large disparity = bright).
///
/// A pixel with disparity `d > 0` gets `1 + round(254 · min(d / dispmax, 1))`,
/// so valid pixels lie in `1..=255` and are never black; pixels without
/// disparity are 0 (black). `dispmax` is normally the search bound
/// `frame.params.dispmax`; if it is not a positive finite number, the frame's
/// largest disparity is used instead. Same size as the frame, no border
/// handling needed.
///
/// Panics if `frame.disparity.len() != width · height`.
pub(crate) fn disparity_visual(frame: &FrameResult, dispmax: f64) -> GrayImage {
    check_frame(frame);
    disparity_visual_of(&frame.disparity, frame.width, frame.height, dispmax)
}

/// [`disparity_visual`] of any row-major disparity map (`0` = none), e.g. a
/// ground truth, so that maps drawn with the same `dispmax` compare.
///
/// Panics if `disparity.len() != width · height`.
pub(crate) fn disparity_visual_of(disparity: &[f64], width: usize, height: usize, dispmax: f64) -> GrayImage {
    assert_eq!(disparity.len(), width * height, "disparity map of {width}x{height}");
    let scale = if dispmax > 0.0 && dispmax.is_finite() {
        dispmax
    } else {
        disparity.iter().copied().filter(|d| d.is_finite()).fold(0.0, f64::max)
    };
    let data = disparity
        .iter()
        .map(|&d| {
            // NaN and `d <= 0` are "none"; a NaN or zero scale makes every
            // valid pixel white.
            if d > 0.0 {
                if scale > 0.0 {
                    let t = (d / scale).min(1.0);
                    1 + (254.0 * t).round() as u8
                } else {
                    255
                }
            } else {
                0
            }
        })
        .collect();
    GrayImage::from_raw(dim(width), dim(height), data).expect("buffer has width × height pixels")
}

/// The characteristic declivities of one view, one entry per row, in the
/// order [`declivity_overlay`] takes them (the reference view of `frame`).
pub(crate) fn reference_features(frame: &FrameResult) -> Vec<&LineFeatures> {
    frame.lines.iter().map(|l| &l.reference).collect()
}

/// The other (non-reference) view's characteristic declivities, one entry
/// per row, for [`declivity_overlay`] on the other image.
pub(crate) fn other_features(frame: &FrameResult) -> Vec<&LineFeatures> {
    frame.lines.iter().map(|l| &l.other).collect()
}

/// The characteristic declivities drawn over their image, as the paper's
/// photos 3–4.
///
/// The grey image is dimmed to half its level (grey `v` → RGB `(v/2, v/2,
/// v/2)`); then each characteristic declivity of row `y` (`features[y]`) is
/// marked by one pixel at column `round(position)` (its eq. 3 sub-pixel
/// position; pixel `x` has its centre at `x`), clamped into the row:
/// [`RISING`] (red) for a rising declivity (amplitude > 0), [`FALLING`]
/// (cyan) for a falling one. `features` should hold one entry per row:
/// rows without an entry stay unmarked and entries beyond the image's height
/// are ignored.
pub(crate) fn declivity_overlay(image: &GreyImage, features: &[&LineFeatures]) -> RgbImage {
    let (w, h) = (image.width(), image.height());
    let pixels = image.pixels();
    let mut out = RgbImage::from_fn(dim(w), dim(h), |x, y| {
        let v = pixels[y as usize * w + x as usize] / 2;
        Rgb([v, v, v])
    });
    for (y, f) in features.iter().enumerate().take(h) {
        for d in &f.declivities {
            if !d.position.is_finite() {
                continue;
            }
            let x = d.position.round().clamp(0.0, (w - 1) as f64) as u32;
            let c = if d.amplitude > 0 { RISING } else { FALLING };
            out.put_pixel(x, y as u32, c);
        }
    }
    out
}

/// Largest grid side of [`matching_graph`] in pixels; with the legend and
/// labels the picture stays within about 1024 pixels.
const GRID_BUDGET: usize = 960;
/// Largest cell side of [`matching_graph`].
const MAX_CELL: u32 = 24;
/// Smallest cell side of [`matching_graph`].
const MIN_CELL: u32 = 4;
const PAD: u32 = 6;
const GLYPH_W: u32 = 5;
const GLYPH_H: u32 = 7;
const ADVANCE: u32 = GLYPH_W + 1;
const LINE_H: u32 = GLYPH_H + 3;

/// One line of a graph's legend: runs of text, each in its colour.
type LegendLine = Vec<(String, Rgb<u8>)>;

/// The legend lines of a graph of `n × m` cells.
fn legend(n: usize, m: usize) -> [String; 3] {
    [
        format!("MATCHING GRAPH (FIG. 4)  N={n}  M={m}"),
        "ROWS I: REFERENCE VIEW   COLUMNS J: OTHER VIEW".to_string(),
        "DOT: NODE, BIGGER/BRIGHTER = MORE GAIN   RING: OPTIMAL PATH".to_string(),
    ]
}

/// [`legend`] in the text colour.
fn plain_legend(n: usize, m: usize) -> Vec<LegendLine> {
    legend(n, m).into_iter().map(|s| vec![(s, TEXT)]).collect()
}

/// The legend of [`matching_graph_two_paths`]: its last line names the two
/// paths in their colours.
fn two_path_legend(n: usize, m: usize) -> Vec<LegendLine> {
    let [title, axes, _] = legend(n, m);
    vec![
        vec![(title, TEXT)],
        vec![(axes, TEXT)],
        vec![("DOT: NODE, BIGGER/BRIGHTER = MORE GAIN".to_string(), TEXT)],
        vec![
            ("RING: GOLDEN OPTIMAL PATH".to_string(), PATH_RING),
            ("   ".to_string(), TEXT),
            ("BOX: RTL PATH".to_string(), RTL_BOX),
        ],
    ]
}

/// Width in pixels of a legend line.
fn legend_width(line: &LegendLine) -> u32 {
    line.iter().map(|(s, _)| s.chars().count() as u32).sum::<u32>() * ADVANCE
}

fn digits(v: usize) -> u32 {
    v.to_string().len() as u32
}

/// Where [`matching_graph`] puts things: the picture's size and the grid of
/// `n` rows (reference declivities `i`) by `m` columns (other-view
/// declivities `j`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct GraphLayout {
    /// Rows of the grid (reference declivities).
    pub n: usize,
    /// Columns of the grid (other-view declivities).
    pub m: usize,
    /// Side of one cell in pixels: `clamp(960 / max(n, m), 4, 24)`.
    pub cell: u32,
    /// Column of the grid's left edge.
    pub left: u32,
    /// Row of the grid's top edge (below the legend and column labels).
    pub top: u32,
    /// Width of the picture.
    pub width: u32,
    /// Height of the picture.
    pub height: u32,
}

impl GraphLayout {
    /// The layout of an `n × m` graph (`n, m ≥ 1`; the picture of an empty
    /// graph is a blank image, see [`matching_graph`]).
    #[cfg(test)]
    fn new(n: usize, m: usize) -> Self {
        Self::with_legend(n, m, &plain_legend(n, m))
    }

    /// The layout of an `n × m` graph under the legend `lines`.
    fn with_legend(n: usize, m: usize, lines: &[LegendLine]) -> Self {
        let side = n.max(m).max(1);
        let cell = ((GRID_BUDGET / side) as u32).clamp(MIN_CELL, MAX_CELL);
        let legend_w = lines.iter().map(legend_width).max().unwrap_or(0);
        let left = PAD + digits(n.saturating_sub(1)) * ADVANCE + 4;
        let top = PAD + dim(lines.len()) * LINE_H + 4 + LINE_H;
        let width = (left + dim(m) * cell + PAD).max(2 * PAD + legend_w);
        let height = top + dim(n) * cell + PAD;
        GraphLayout { n, m, cell, left, top, width, height }
    }

    /// The top-left pixel of cell `(i, j)`.
    fn cell_origin(&self, i: usize, j: usize) -> (u32, u32) {
        (self.left + dim(j) * self.cell, self.top + dim(i) * self.cell)
    }

    /// The centre of node `(i, j)` in continuous pixel coordinates (pixel
    /// `(x, y)` covers `[x, x+1) × [y, y+1)`).
    fn node_centre(&self, i: usize, j: usize) -> (f64, f64) {
        let (x, y) = self.cell_origin(i, j);
        let h = self.cell as f64 / 2.0;
        (x as f64 + h, y as f64 + h)
    }

    /// Outer and inner radius of a path node's ring: the ring touches the
    /// cell's edges and is `max(1, round(cell / 8))` pixels wide.
    fn ring_radii(&self) -> (f64, f64) {
        let ro = self.cell as f64 / 2.0;
        let w = (self.cell as f64 / 8.0).round().max(1.0);
        (ro, ro - w)
    }

    /// Smallest and largest dot radius (the largest stays inside the ring).
    fn dot_radii(&self) -> (f64, f64) {
        let (_, ri) = self.ring_radii();
        let max = (ri - 0.5).max(0.75);
        let min = (0.3 * max).max(0.75).min(max);
        (min, max)
    }
}

/// Sets every pixel whose centre lies at a distance in `[r_in, r_out]` of
/// `(cx, cy)` (a disc for `r_in ≤ 0`), clipped to the image.
fn fill_annulus(img: &mut RgbImage, cx: f64, cy: f64, r_in: f64, r_out: f64, c: Rgb<u8>) {
    let (w, h) = (img.width() as i64, img.height() as i64);
    let x0 = ((cx - r_out).floor() as i64).max(0);
    let x1 = ((cx + r_out).ceil() as i64).min(w - 1);
    let y0 = ((cy - r_out).floor() as i64).max(0);
    let y1 = ((cy + r_out).ceil() as i64).min(h - 1);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let r = (x as f64 + 0.5 - cx).hypot(y as f64 + 0.5 - cy);
            if r >= r_in && r <= r_out {
                img.put_pixel(x as u32, y as u32, c);
            }
        }
    }
}

/// A segment from `a` to `b` (continuous coordinates), `thick` pixels wide,
/// clipped to the image.
fn draw_line(img: &mut RgbImage, a: (f64, f64), b: (f64, f64), thick: f64, c: Rgb<u8>) {
    let len = (b.0 - a.0).hypot(b.1 - a.1);
    let steps = (len * 2.0).ceil().max(1.0) as usize;
    for k in 0..=steps {
        let t = k as f64 / steps as f64;
        let (x, y) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
        fill_annulus(img, x, y, -1.0, (thick / 2.0).max(0.5), c);
    }
}

/// The 5×7 glyph of `ch` (rows top to bottom, bit 4 = leftmost column);
/// unknown characters are blank.
fn glyph(ch: char) -> [u8; 7] {
    match ch.to_ascii_uppercase() {
        '0' => [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E],
        '1' => [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E],
        '2' => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F],
        '3' => [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E],
        '4' => [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02],
        '5' => [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E],
        '6' => [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E],
        '7' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E],
        '9' => [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C],
        'A' => [0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'B' => [0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E],
        'C' => [0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E],
        'D' => [0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C],
        'E' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F],
        'F' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10],
        'G' => [0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F],
        'H' => [0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'I' => [0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E],
        'J' => [0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C],
        'K' => [0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11],
        'L' => [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F],
        'M' => [0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11],
        'N' => [0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11],
        'O' => [0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'P' => [0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10],
        'Q' => [0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D],
        'R' => [0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11],
        'S' => [0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E],
        'T' => [0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04],
        'U' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'V' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04],
        'W' => [0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A],
        'X' => [0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11],
        'Y' => [0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04],
        'Z' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F],
        '=' => [0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00],
        '-' => [0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00],
        '+' => [0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00],
        ',' => [0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C],
        ':' => [0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00],
        '/' => [0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00],
        '(' => [0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02],
        ')' => [0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08],
        _ => [0; 7],
    }
}

/// Writes `text` with its top-left corner at `(x, y)`, clipped to the image.
fn draw_text(img: &mut RgbImage, x: u32, y: u32, text: &str, c: Rgb<u8>) {
    for (k, ch) in text.chars().enumerate() {
        let g = glyph(ch);
        let gx = x + k as u32 * ADVANCE;
        for (row, bits) in g.iter().enumerate() {
            for col in 0..GLYPH_W {
                if bits & (0x10 >> col) != 0 {
                    let (px, py) = (gx + col, y + row as u32);
                    if px < img.width() && py < img.height() {
                        img.put_pixel(px, py, c);
                    }
                }
            }
        }
    }
}

/// The smallest step in 1, 2, 5, 10, 20, 50, … with `step · cell ≥ need`.
fn label_step(cell: u32, need: u32) -> usize {
    let mut base = 1usize;
    loop {
        for k in [1, 2, 5] {
            let s = base * k;
            if s as u64 * cell as u64 >= need as u64 {
                return s;
            }
        }
        base *= 10;
    }
}

/// The matching graph of two segmented lines with its optimal path, as the
/// paper's fig. 4.
///
/// A grid of `n × m` square cells: row `i` is the reference view's
/// characteristic declivity `i`, column `j` the other view's declivity `j`
/// (both 0-based; a legend strip at the top says so, and the indices are
/// labelled along the left and top edges). The cell side adapts to the graph
/// (see [`GraphLayout`]): at most 24 px, at least 4 px, so that the picture
/// stays within about 1024 px up to 240 declivities per line (larger graphs
/// keep 4 px cells and grow).
///
/// - Cells outside the search area of eq. 6 (`0 < d < dispmax`) are left
///   black; cells inside it get the dark blue [`SEARCH_AREA`] background.
/// - Every node (where [`golden::line::gain_table`] gives `Some(gain)`) is a
///   dot at the cell's centre: a positive gain gives a grey-to-white dot whose
///   radius and brightness grow with `gain / (3·gmax)` (eq. 7–8: `3·gmax` is
///   the largest possible gain); a zero or negative gain gives a small dim
///   [`WEAK_NODE`] dot. Rejected pairs inside the search area have no dot.
/// - The nodes of `path` (pairs `(i, j)`, e.g. from
///   [`golden::dp::best_path`] or the line's matches) are joined in order by
///   [`PATH_LINE`] segments and drawn "double edged": a [`PATH_RING`] ring
///   around the dot, touching the cell's edges. Path entries outside the grid
///   are ignored.
///
/// With no declivity in either line the result is a blank (black) 32×32
/// image.
fn matching_graph(reference: &LineFeatures, other: &LineFeatures, params: &Params, path: &[(usize, usize)]) -> RgbImage {
    let (n, m) = (reference.declivities.len(), other.declivities.len());
    let table = gain_table(reference, other, params);
    let optimal = GraphPath { nodes: path, marker: PathMarker::Ring, node: PATH_RING, line: PATH_LINE, widen: 0.0 };
    draw_graph(reference, other, params, &table, &[optimal], &plain_legend(n, m))
}

/// The matching graph of two segmented lines, as [`matching_graph`], with
/// two paths through it: `golden` (e.g. golden's optimal path) drawn as
/// [`matching_graph`] draws its path ([`PATH_RING`] rings joined by wide
/// [`PATH_LINE`] segments) and `rtl` (e.g. the hardware's matches) as
/// [`RTL_BOX`] square frames along the cells' edges joined by thin
/// [`RTL_LINE`] segments drawn over golden's. Where the paths share a node
/// both marks show (the ring inside the frame), and where they share a
/// segment the thin one runs inside the wide one. A fourth legend line
/// names the two marks in their colours.
///
/// The node dots come from `table` (its gains, e.g. those the paths were
/// found on) instead of [`golden::line::gain_table`]; `params` gives the
/// search area (`dispmax`, reference view) and nothing else. Path entries
/// outside the grid are ignored; with no declivity in either line the
/// result is a blank 32×32 image.
///
/// Panics if `table` is not `reference`'s declivities by `other`'s.
pub(crate) fn matching_graph_two_paths(
    reference: &LineFeatures,
    other: &LineFeatures,
    params: &Params,
    table: &GainTable,
    golden: &[(usize, usize)],
    rtl: &[(usize, usize)],
) -> RgbImage {
    let (n, m) = (reference.declivities.len(), other.declivities.len());
    assert_eq!((table.n(), table.m()), (n, m), "the gain table is not the lines' {n}x{m}");
    let paths = [
        GraphPath { nodes: golden, marker: PathMarker::Ring, node: PATH_RING, line: PATH_LINE, widen: 2.0 },
        GraphPath { nodes: rtl, marker: PathMarker::Box, node: RTL_BOX, line: RTL_LINE, widen: 0.0 },
    ];
    draw_graph(reference, other, params, table, &paths, &two_path_legend(n, m))
}

/// How a node of a path is marked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PathMarker {
    /// A ring touching the cell's edges, around the dot.
    Ring,
    /// A square frame along the cell's edges.
    Box,
}

/// A path to draw over a matching graph.
struct GraphPath<'a> {
    nodes: &'a [(usize, usize)],
    marker: PathMarker,
    /// Colour of the node marks.
    node: Rgb<u8>,
    /// Colour of the segments.
    line: Rgb<u8>,
    /// Pixels added to the segments' base width `1 + cell / 12`.
    widen: f64,
}

/// Draws a matching graph: search area, `paths`' segments (in order),
/// node dots from `table`, `paths`' node marks (in reverse order, so the
/// first path's marks stay whole), `legend` and index labels.
fn draw_graph(
    reference: &LineFeatures,
    other: &LineFeatures,
    params: &Params,
    table: &GainTable,
    paths: &[GraphPath],
    legend: &[LegendLine],
) -> RgbImage {
    let (n, m) = (reference.declivities.len(), other.declivities.len());
    if n == 0 || m == 0 {
        return RgbImage::from_pixel(32, 32, BLACK);
    }
    let layout = GraphLayout::with_legend(n, m, legend);
    let mut img = RgbImage::from_pixel(layout.width, layout.height, BLACK);
    let cell = layout.cell;

    // Search area backgrounds.
    for (i, r) in reference.declivities.iter().enumerate() {
        for (j, o) in other.declivities.iter().enumerate() {
            if in_search_area(pair_disparity(r.position, o.position, params.ref_view), params.dispmin, params.dispmax) {
                let (x0, y0) = layout.cell_origin(i, j);
                for y in y0..y0 + cell {
                    for x in x0..x0 + cell {
                        img.put_pixel(x, y, SEARCH_AREA);
                    }
                }
            }
        }
    }

    // Path segments, under the dots and marks.
    let on_grid = |p: &GraphPath| -> Vec<(usize, usize)> { p.nodes.iter().copied().filter(|&(i, j)| i < n && j < m).collect() };
    let thick = 1.0 + (cell / 12) as f64;
    for p in paths {
        for pair in on_grid(p).windows(2) {
            let a = layout.node_centre(pair[0].0, pair[0].1);
            let b = layout.node_centre(pair[1].0, pair[1].1);
            draw_line(&mut img, a, b, thick + p.widen, p.line);
        }
    }

    // Nodes.
    let full = 3.0 * gmax(reference.dt, other.dt);
    let table_max = (0..n).flat_map(|i| (0..m).map(move |j| (i, j))).filter_map(|(i, j)| table.get(i, j)).fold(0.0, f64::max);
    let scale = if full > 0.0 && full.is_finite() { full } else { table_max };
    let (r_min, r_max) = layout.dot_radii();
    for i in 0..n {
        for j in 0..m {
            let Some(g) = table.get(i, j) else { continue };
            let (cx, cy) = layout.node_centre(i, j);
            if g > 0.0 && scale > 0.0 {
                let t = (g / scale).clamp(0.0, 1.0);
                let v = (110.0 + 145.0 * t).round() as u8;
                fill_annulus(&mut img, cx, cy, -1.0, r_min + (r_max - r_min) * t, Rgb([v, v, v]));
            } else {
                fill_annulus(&mut img, cx, cy, -1.0, r_min, WEAK_NODE);
            }
        }
    }

    // Marks of the paths' nodes ("double edges").
    let (ro, ri) = layout.ring_radii();
    for p in paths.iter().rev() {
        for (i, j) in on_grid(p) {
            match p.marker {
                PathMarker::Ring => {
                    let (cx, cy) = layout.node_centre(i, j);
                    fill_annulus(&mut img, cx, cy, ri, ro, p.node);
                }
                PathMarker::Box => {
                    let (x0, y0) = layout.cell_origin(i, j);
                    let w = (ro - ri).round() as u32;
                    for y in y0..y0 + cell {
                        for x in x0..x0 + cell {
                            let edge = x < x0 + w || x >= x0 + cell - w || y < y0 + w || y >= y0 + cell - w;
                            if edge {
                                img.put_pixel(x, y, p.node);
                            }
                        }
                    }
                }
            }
        }
    }

    // Legend and index labels.
    for (k, line) in legend.iter().enumerate() {
        let mut x = PAD;
        for (s, c) in line {
            draw_text(&mut img, x, PAD + k as u32 * LINE_H, s, *c);
            x += s.chars().count() as u32 * ADVANCE;
        }
    }
    let label_y = PAD + dim(legend.len()) * LINE_H + 4;
    let col_step = label_step(cell, digits(m - 1) * ADVANCE + 3);
    for j in (0..m).step_by(col_step) {
        let s = j.to_string();
        let (cx, _) = layout.node_centre(0, j);
        let x = (cx - (s.len() as u32 * ADVANCE - 1) as f64 / 2.0).round().max(0.0) as u32;
        draw_text(&mut img, x, label_y, &s, TEXT);
    }
    let row_step = label_step(cell, GLYPH_H + 2);
    for i in (0..n).step_by(row_step) {
        let s = i.to_string();
        let (_, cy) = layout.node_centre(i, 0);
        let x = layout.left - 4 - s.len() as u32 * ADVANCE + 1;
        let y = (cy - GLYPH_H as f64 / 2.0).round().max(0.0) as u32;
        draw_text(&mut img, x, y, &s, TEXT);
    }
    img
}

/// [`matching_graph`] of one processed line, its path being the line's
/// matches `(ref_index, other_index)`.
pub(crate) fn line_matching_graph(line: &LineResult, params: &Params) -> RgbImage {
    let path: Vec<(usize, usize)> = line.matches.iter().map(|mt| (mt.ref_index, mt.other_index)).collect();
    matching_graph(&line.reference, &line.other, params, &path)
}

/// The depth map (eq. 1) as a 16-bit grey image in millimetres: pixel =
/// `round(1000 · Z)` with `Z = f·b / d` metres from
/// [`golden::reconstruct::depth`].
///
/// `0` means "no depth" (no disparity, or a depth that is not a positive
/// finite number). A positive depth never becomes 0 (depths under 0.5 mm are
/// stored as 1) and depths beyond 65.535 m saturate at `u16::MAX`. Same size
/// as the frame, no border handling needed.
///
/// Panics if `frame.disparity.len() != width · height`.
pub(crate) fn depth_png16(frame: &FrameResult, cam: &Camera) -> ImageBuffer<Luma<u16>, Vec<u16>> {
    check_frame(frame);
    let data = frame
        .disparity
        .iter()
        .map(|&d| match depth(d, cam) {
            Some(z) if z > 0.0 && !z.is_nan() => to_u16_nonzero(z * 1000.0),
            _ => 0,
        })
        .collect();
    ImageBuffer::from_raw(dim(frame.width), dim(frame.height), data).expect("buffer has width × height pixels")
}

/// Writes the point cloud of `frame` (eq. 1) as ASCII PLY to any writer;
/// see [`write_ply`]. Returns the number of points.
fn write_ply_to<W: Write>(out: &mut W, frame: &FrameResult, cam: &Camera, colour: &GreyImage) -> std::io::Result<usize> {
    check_frame(frame);
    let w = frame.width;
    let points = || {
        frame.disparity.iter().enumerate().filter_map(move |(k, &d)| {
            let (x, y) = (k % w, k / w);
            point(x as f64, y as f64, d, cam).map(|p| (p, colour.pixels()[k]))
        })
    };
    let count = points().count();
    writeln!(out, "ply")?;
    writeln!(out, "format ascii 1.0")?;
    writeln!(out, "comment declivity stereo: eq. 1 points in metres, camera frame (x right, y down, z forward)")?;
    writeln!(out, "comment focal_px {} baseline_m {} cx {} cy {}", cam.focal_px, cam.baseline_m, cam.cx, cam.cy)?;
    writeln!(out, "element vertex {count}")?;
    for p in ["x", "y", "z"] {
        writeln!(out, "property float {p}")?;
    }
    for c in ["red", "green", "blue"] {
        writeln!(out, "property uchar {c}")?;
    }
    writeln!(out, "end_header")?;
    for ([x, y, z], v) in points() {
        writeln!(out, "{x} {y} {z} {v} {v} {v}")?;
    }
    Ok(count)
}

/// Writes the point cloud of `frame` as an ASCII PLY file: one vertex per
/// pixel with a disparity, `x y z` (float, metres, from
/// [`golden::reconstruct::point`]: camera frame, `y` down) and `red green
/// blue` (uchar, all three the grey level of `colour` at that pixel —
/// normally the reference image). Pixels without disparity are skipped.
/// Returns the number of points written.
///
/// Fails with [`PictureError::SizeMismatch`] if `colour` does not have the
/// frame's size and [`PictureError::Io`] if the file cannot be written.
pub(crate) fn write_ply(path: &Path, frame: &FrameResult, cam: &Camera, colour: &GreyImage) -> Result<usize, PictureError> {
    if colour.width() != frame.width || colour.height() != frame.height {
        return Err(PictureError::SizeMismatch {
            path: path.to_path_buf(),
            colour_w: colour.width(),
            colour_h: colour.height(),
            frame_w: frame.width,
            frame_h: frame.height,
        });
    }
    let io = |source| PictureError::Io { path: path.to_path_buf(), source };
    let mut out = BufWriter::new(File::create(path).map_err(io)?);
    let count = write_ply_to(&mut out, frame, cam, colour).map_err(io)?;
    out.flush().map_err(io)?;
    Ok(count)
}

/// Saves `img`, any 8- or 16-bit grey or RGB image buffer, as PNG at `path`
/// (whatever its extension). 16-bit images keep their full range.
///
/// Fails with [`PictureError::Encode`], naming the file, when the file cannot
/// be created or written or the image cannot be encoded.
pub(crate) fn save_png<P, C>(img: &ImageBuffer<P, C>, path: &Path) -> Result<(), PictureError>
where
    P: Pixel + PixelWithColorType,
    [P::Subpixel]: EncodableLayout,
    C: Deref<Target = [P::Subpixel]>,
{
    img.save_with_format(path, ImageFormat::Png)
        .map_err(|source| PictureError::Encode { path: path.to_path_buf(), source })
}

#[cfg(test)]
mod tests {
    use super::*;
    use golden::dp::best_path;
    use golden::line::line_features;
    use golden::{process_frame, EndRule, Threads};

    fn params(dispmax: f64) -> Params {
        Params::paper(dispmax).unwrap()
    }

    /// A frame of the given size and dense map, with no line results.
    fn frame_of(width: usize, height: usize, disparity: Vec<f64>) -> FrameResult {
        FrameResult { width, height, params: params(10.0), lines: Vec::new(), disparity }
    }

    /// A step from 50 to 200 between pixels `at - 1` and `at`.
    fn step_row(width: usize, at: usize) -> Vec<u8> {
        (0..width).map(|x| if x < at { 50 } else { 200 }).collect()
    }

    /// A 20×3 pair whose step moves by 3 pixels: every pixel gets d = 3
    /// (one match at X = 9.5 / 6.5, held to the ends).
    fn shifted_step_pair(ends: EndRule) -> (GreyImage, GreyImage, FrameResult) {
        let (w, h) = (20, 3);
        let left = GreyImage::new(w, h, step_row(w, 10).repeat(h)).unwrap();
        let right = GreyImage::new(w, h, step_row(w, 7).repeat(h)).unwrap();
        let mut p = params(10.0);
        p.ends = ends;
        let f = process_frame(&left, &right, &p, Threads::One).unwrap();
        (left, right, f)
    }

    #[test]
    fn disparity_png16_exact_values() {
        let d = vec![0.0, 0.01, 2.5, 2.53125, 1.0 / 32.0, 4095.96, 4096.0, 5000.0, -1.0, f64::NAN, f64::INFINITY, 3.0];
        let img = disparity_png16(&frame_of(12, 1, d));
        assert_eq!(img.dimensions(), (12, 1));
        // By hand: round(16 d), positive never 0, saturating; none = 0.
        let expected = [0u16, 1, 40, 41, 1, 65535, 65535, 65535, 0, 0, 65535, 48];
        assert_eq!(img.as_raw().as_slice(), &expected);
    }

    #[test]
    fn disparity_png16_of_processed_pair() {
        let (_, _, f) = shifted_step_pair(EndRule::Hold);
        assert_eq!(f.matches(), 3);
        let img = disparity_png16(&f);
        assert_eq!(img.dimensions(), (20, 3));
        assert!(img.pixels().all(|p| p.0[0] == 48), "{:?}", img.as_raw());
    }

    #[test]
    fn visual_is_brighter_for_nearer_and_black_for_none() {
        let img = disparity_visual(&frame_of(5, 1, vec![0.0, 1.0, 5.0, 10.0, 25.0]), 10.0);
        let v: Vec<u8> = img.pixels().map(|p| p.0[0]).collect();
        assert_eq!(v, vec![0, 1 + 25, 128, 255, 255]);
        assert!(v[2] > v[1]);
        // Tiny disparities stay visible.
        let tiny = disparity_visual(&frame_of(1, 1, vec![1e-9]), 60.0);
        assert_eq!(tiny.get_pixel(0, 0).0[0], 1);
        // Without a usable dispmax the frame's maximum is the scale.
        let auto = disparity_visual(&frame_of(2, 1, vec![2.0, 4.0]), 0.0);
        assert_eq!(auto.as_raw(), &vec![128, 255]);
    }

    #[test]
    fn overlay_marks_rising_red_and_falling_cyan() {
        let (w, h) = (16, 2);
        // Row 0: rise 40 -> 220 at x 4|5, fall back at x 11|12. Row 1: flat.
        let mut row0: Vec<u8> = (0..w).map(|x| if (5..12).contains(&x) { 220 } else { 40 }).collect();
        let row1 = vec![100u8; w];
        row0.extend_from_slice(&row1);
        let img = GreyImage::new(w, h, row0).unwrap();
        let f: Vec<LineFeatures> = (0..h).map(|y| line_features(img.row(y))).collect();
        let refs: Vec<&LineFeatures> = f.iter().collect();
        assert_eq!(f[0].declivities.len(), 2);
        assert_eq!(f[0].declivities[0].position, 4.5);
        let out = declivity_overlay(&img, &refs);
        assert_eq!(out.dimensions(), (16, 2));
        // round(4.5) = 5 (half away from zero), round(11.5) = 12.
        assert_eq!(*out.get_pixel(5, 0), RISING);
        assert_eq!(*out.get_pixel(12, 0), FALLING);
        assert_eq!(*out.get_pixel(4, 0), Rgb([20, 20, 20]));
        assert_eq!(*out.get_pixel(8, 0), Rgb([110, 110, 110]));
        assert!(out.enumerate_pixels().filter(|(_, y, _)| *y == 1).all(|(_, _, p)| *p == Rgb([50, 50, 50])));
        // Missing rows are simply unmarked.
        let partial = declivity_overlay(&img, &refs[..1]);
        assert_eq!(*partial.get_pixel(5, 0), RISING);
    }

    /// Two lines with several steps, the other shifted by 4 pixels.
    fn graph_lines() -> (LineFeatures, LineFeatures) {
        let levels = [30u8, 180, 60, 220, 90, 200, 40];
        let line = |shift: usize| -> Vec<u8> { (0..80).map(|x| levels[((x + shift) / 10).min(levels.len() - 1)]).collect() };
        (line_features(&line(0)), line_features(&line(4)))
    }

    #[test]
    fn matching_graph_layout_and_path_rings() {
        let (r, o) = graph_lines();
        let p = params(12.0);
        let (n, m) = (r.declivities.len(), o.declivities.len());
        assert!(n >= 4 && m >= 4, "{n} {m}");
        let path = best_path(&gain_table(&r, &o, &p)).nodes;
        assert!(path.len() >= 3, "{path:?}");
        let img = matching_graph(&r, &o, &p, &path);
        let layout = GraphLayout::new(n, m);
        assert_eq!(img.dimensions(), (layout.width, layout.height));
        assert_eq!(layout.cell, MAX_CELL);
        assert!(layout.width >= layout.left + m as u32 * layout.cell);
        assert!(layout.height >= layout.top + n as u32 * layout.cell);
        let cell_pixels = |i: usize, j: usize| {
            let (x0, y0) = layout.cell_origin(i, j);
            (y0..y0 + layout.cell).flat_map(move |y| (x0..x0 + layout.cell).map(move |x| (x, y)))
        };
        let table = gain_table(&r, &o, &p);
        for i in 0..n {
            for j in 0..m {
                let rings = cell_pixels(i, j).filter(|&(x, y)| *img.get_pixel(x, y) == PATH_RING).count();
                let (cx, cy) = layout.node_centre(i, j);
                let centre = *img.get_pixel(cx as u32, cy as u32);
                if path.contains(&(i, j)) {
                    assert!(rings > 20, "path node ({i},{j}) has {rings} ring pixels");
                    assert_ne!(centre, PATH_RING);
                    assert!(centre.0[0] >= 110, "path node dot {centre:?}");
                } else {
                    assert_eq!(rings, 0, "({i},{j}) is not on the path");
                }
                match table.get(i, j) {
                    Some(g) if g > 0.0 => assert!(centre.0[0] >= 110 && centre.0[0] == centre.0[2]),
                    Some(_) => assert_eq!(centre, WEAK_NODE),
                    None => assert!(centre == BLACK || centre == SEARCH_AREA || centre == PATH_LINE),
                }
            }
        }
        // A cell outside the search area (d <= 0: other declivity to the right) is blank.
        let (i, j) = (0, m - 1);
        assert!(pair_disparity(r.declivities[i].position, o.declivities[j].position, p.ref_view) <= 0.0);
        assert!(cell_pixels(i, j).all(|(x, y)| *img.get_pixel(x, y) == BLACK));
        // Bigger gain, bigger dot: the path node versus a weak node in size.
        assert!(img.pixels().any(|p| *p == PATH_LINE));
    }

    #[test]
    fn matching_graph_sizes_and_empty_lines() {
        let empty = LineFeatures { sigma: 1.0, dt: 5.6, declivities: Vec::new() };
        let (r, _) = graph_lines();
        let p = params(12.0);
        let img = matching_graph(&empty, &r, &p, &[]);
        assert_eq!(img.dimensions(), (32, 32));
        assert!(img.pixels().all(|px| *px == BLACK));
        let img = matching_graph(&r, &empty, &p, &[(0, 0)]);
        assert_eq!(img.dimensions(), (32, 32));
        // Out-of-grid path entries are ignored.
        let ok = matching_graph(&r, &r, &p, &[(0, 0), (99, 99)]);
        assert!(ok.width() > 0);
        // Adaptive cells: ~1024 px at most down to the 4 px floor.
        for side in [1usize, 7, 40, 100, 240] {
            let l = GraphLayout::new(side, side);
            assert!(l.cell >= MIN_CELL && l.cell <= MAX_CELL);
            assert!(l.width <= 1024 && l.height <= 1024, "{side}: {l:?}");
        }
        let big = GraphLayout::new(600, 10);
        assert_eq!(big.cell, MIN_CELL);
    }

    /// Pixels of colour `c` in cell `(i, j)` of a graph drawn with `layout`.
    fn cell_count(img: &RgbImage, layout: &GraphLayout, i: usize, j: usize, c: Rgb<u8>) -> usize {
        let (x0, y0) = layout.cell_origin(i, j);
        (y0..y0 + layout.cell)
            .flat_map(|y| (x0..x0 + layout.cell).map(move |x| (x, y)))
            .filter(|&(x, y)| *img.get_pixel(x, y) == c)
            .count()
    }

    #[test]
    fn two_path_graph_marks_both_paths_and_names_them() {
        let (r, o) = graph_lines();
        let p = params(12.0);
        let (n, m) = (r.declivities.len(), o.declivities.len());
        let table = gain_table(&r, &o, &p);
        let golden = best_path(&table).nodes;
        assert!(golden.len() >= 3, "{golden:?}");
        // The rtl path shares golden's first node and leaves it afterwards.
        let mut rtl = vec![golden[0]];
        let spare = (0..n)
            .flat_map(|i| (0..m).map(move |j| (i, j)))
            .find(|&(i, j)| i > golden[0].0 && j > golden[0].1 && !golden.contains(&(i, j)));
        rtl.extend(spare);
        assert_eq!(rtl.len(), 2);
        let img = matching_graph_two_paths(&r, &o, &p, &table, &golden, &rtl);
        let layout = GraphLayout::with_legend(n, m, &two_path_legend(n, m));
        assert_eq!(img.dimensions(), (layout.width, layout.height));
        assert_eq!(layout.top, GraphLayout::new(n, m).top + LINE_H, "one more legend line");
        let count = |i: usize, j: usize, c: Rgb<u8>| cell_count(&img, &layout, i, j, c);
        for i in 0..n {
            for j in 0..m {
                let (rings, boxes) = (count(i, j, PATH_RING), count(i, j, RTL_BOX));
                assert_eq!(golden.contains(&(i, j)), rings > 20, "({i},{j}): {rings} ring pixels");
                assert_eq!(rtl.contains(&(i, j)), boxes > 20, "({i},{j}): {boxes} box pixels");
                if rtl.contains(&(i, j)) {
                    // A frame: the cell's corner pixel is the box colour.
                    let (x0, y0) = layout.cell_origin(i, j);
                    assert_eq!(*img.get_pixel(x0, y0), RTL_BOX);
                }
            }
        }
        // Where they share a node the ring is whole inside the frame.
        let (i, j) = golden[0];
        let solo = matching_graph(&r, &o, &p, &golden);
        assert_eq!(count(i, j, PATH_RING), cell_count(&solo, &GraphLayout::new(n, m), i, j, PATH_RING));
        // Both segment colours are drawn, and the legend names the paths in their colours.
        assert!(img.pixels().any(|px| *px == PATH_LINE) && img.pixels().any(|px| *px == RTL_LINE));
        let legend_row = PAD + 3 * LINE_H..PAD + 3 * LINE_H + GLYPH_H;
        let in_legend = |c: Rgb<u8>| legend_row.clone().any(|y| (0..img.width()).any(|x| *img.get_pixel(x, y) == c));
        assert!(in_legend(PATH_RING) && in_legend(RTL_BOX));
        // Empty lines give the blank picture.
        let empty = LineFeatures { sigma: 1.0, dt: 5.6, declivities: Vec::new() };
        let blank = matching_graph_two_paths(&empty, &o, &p, &GainTable::new(0, m), &[], &[]);
        assert_eq!(blank.dimensions(), (32, 32));
    }

    #[test]
    fn depth_png16_in_millimetres() {
        let cam = Camera { focal_px: 500.0, baseline_m: 0.1, cx: 1.5, cy: 0.0 };
        let img = depth_png16(&frame_of(4, 1, vec![4.0, 0.0, 0.5, 1e9]), &cam);
        // 500 * 0.1 / 4 = 12.5 m; / 0.5 = 100 m saturates; 5e-8 m -> 1.
        assert_eq!(img.as_raw(), &vec![12500, 0, 65535, 1]);
    }

    #[test]
    fn ply_header_count_and_depth() {
        let (left, _, f) = shifted_step_pair(EndRule::Empty);
        // With empty ends only the anchor interval holds disparity: none here
        // (one anchor at 9.5), so add a hand-made map too.
        let mut f = f;
        f.disparity = (0..60).map(|k| if k % 3 == 0 { 0.0 } else { 2.0 + (k % 7) as f64 }).collect();
        let valid = f.disparity.iter().filter(|&&d| d > 0.0).count();
        let cam = Camera::centred(400.0, 0.08, f.width, f.height);
        let path = std::env::temp_dir().join(format!("sim-pictures-test-{}.ply", std::process::id()));
        let n = write_ply(&path, &f, &cam, &left).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(n, valid);
        assert!(text.starts_with("ply\nformat ascii 1.0\n"));
        assert!(text.contains(&format!("\nelement vertex {valid}\n")));
        let body: Vec<&str> = text.split("end_header\n").nth(1).unwrap().lines().collect();
        assert_eq!(body.len(), valid);
        // First point: pixel (1, 0) with d = 3.
        let v: Vec<f64> = body[0].split(' ').map(|s| s.parse().unwrap()).collect();
        let d = f.disparity[1];
        assert_eq!(d, 3.0);
        assert!((v[2] - 400.0 * 0.08 / d).abs() < 1e-12, "{v:?}");
        assert!((v[0] - (1.0 - cam.cx) * 0.08 / d).abs() < 1e-12);
        assert_eq!(&v[3..], &[50.0, 50.0, 50.0]);
        // A colour image of the wrong size is an error naming the file.
        let small = GreyImage::new(2, 2, vec![0; 4]).unwrap();
        let err = write_ply(Path::new("/nonexistent/x.ply"), &f, &cam, &small).unwrap_err();
        assert!(matches!(err, PictureError::SizeMismatch { .. }));
        let err = write_ply(Path::new("/nonexistent/dir/x.ply"), &f, &cam, &left).unwrap_err();
        assert!(matches!(err, PictureError::Io { .. }));
        assert!(err.to_string().contains("/nonexistent/dir/x.ply"), "{err}");
    }

    #[test]
    fn save_png_round_trips_16_bit_and_names_the_file() {
        let img = disparity_png16(&frame_of(3, 1, vec![0.0, 1.5, 4000.0]));
        let path = std::env::temp_dir().join(format!("sim-pictures-test-{}.png", std::process::id()));
        save_png(&img, &path).unwrap();
        let back = image::open(&path).unwrap().into_luma16();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(back.as_raw(), &vec![0, 24, 64000]);
        let err = save_png(&img, Path::new("/nonexistent/dir/a.png")).unwrap_err();
        assert!(err.to_string().contains("/nonexistent/dir/a.png"), "{err}");
    }
}
