//! Reading images and Middlebury-style pair folders.
//!
//! A pair folder (layout of `data/stereo/`) holds `left_gray.png` and
//! `right_gray.png` (or colour `left.png` / `right.png`), a ground-truth
//! disparity `disp_gt.png` or `disp_gt.pgm` for the left view (integer =
//! d × scale, 0 = unknown), optionally `disp_gt_right.*` and `nonocc.png`,
//! and `meta.txt` with `key: value` lines giving at least `scale` and
//! `dispmax`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use golden::GreyImage;
use image::DynamicImage;

use crate::error::SimError;

/// A grey image and whether it had to be converted from colour.
#[derive(Debug, Clone)]
pub struct LoadedImage {
    /// The 8-bit grey image.
    pub image: GreyImage,
    /// `Some(note)` when the file was colour or deeper than 8 bits and was
    /// converted.
    pub converted: Option<String>,
}

/// ITU-R 601 luma with the same fixed-point rounding as PIL's
/// `convert("L")`, so colour inputs give the grey images of `data/stereo`.
fn luma601(r: u8, g: u8, b: u8) -> u8 {
    ((r as u32 * 19595 + g as u32 * 38470 + b as u32 * 7471 + 0x8000) >> 16) as u8
}

/// Turns a decoded image into 8-bit grey; colour goes through ITU-R 601 luma
/// (as PIL's `convert("L")`), 16-bit grey keeps its high byte.
fn to_grey(img: DynamicImage) -> Result<(GreyImage, Option<String>), golden::GoldenError> {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let (data, note) = match img {
        DynamicImage::ImageLuma8(g) => (g.into_raw(), None),
        DynamicImage::ImageLuma16(g) => (
            g.into_raw().into_iter().map(|v| (v >> 8) as u8).collect(),
            Some("16-bit grey reduced to 8 bits".to_string()),
        ),
        other => {
            let kind = format!("{:?}", other.color());
            let rgb = other.to_rgb8();
            (
                rgb.pixels().map(|p| luma601(p[0], p[1], p[2])).collect(),
                Some(format!("{kind} image converted to grey (ITU-R 601 luma)")),
            )
        }
    };
    Ok((GreyImage::new(w, h, data)?, note))
}

/// Reads an image file as 8-bit grey (colour is converted, with a note).
pub fn load_grey(path: &Path) -> Result<LoadedImage, SimError> {
    let bytes = std::fs::read(path).map_err(|source| SimError::Io { path: path.to_path_buf(), source })?;
    decode_grey(&bytes, path)
}

/// Decodes image bytes (PNG, PGM/PPM) as 8-bit grey; `path` names them in
/// errors.
pub(crate) fn decode_grey(bytes: &[u8], path: &Path) -> Result<LoadedImage, SimError> {
    let img = image::load_from_memory(bytes).map_err(|source| SimError::Image { path: path.to_path_buf(), source })?;
    let (image, converted) = to_grey(img)?;
    Ok(LoadedImage { image, converted })
}

/// The two images of a rectified pair, grey, of one size, with a note for
/// each that was converted (`(path, note)`).
pub fn load_pair_images(left: &Path, right: &Path) -> Result<(GreyImage, GreyImage, Vec<String>), SimError> {
    let (l, r) = (load_grey(left)?, load_grey(right)?);
    let notes = [(left, &l), (right, &r)]
        .iter()
        .filter_map(|(p, img)| img.converted.as_ref().map(|n| format!("{}: {n}", p.display())))
        .collect();
    let (l, r) = (l.image, r.image);
    if (l.width(), l.height()) != (r.width(), r.height()) {
        return Err(golden::GoldenError::SizeMismatch { left_w: l.width(), left_h: l.height(), right_w: r.width(), right_h: r.height() }.into());
    }
    Ok((l, r, notes))
}

/// `key: value` lines of a `meta.txt`.
fn parse_meta(text: &str) -> HashMap<String, String> {
    text.lines()
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect()
}

/// The number a value starts with, its sign included
/// (`"55 (Middlebury eval used ndisp=60)"` → 55, `"-3"` → −3); `None` when
/// the value does not start with one.
fn first_number(s: &str) -> Option<f64> {
    let s = s.trim_start();
    let sign = usize::from(s.starts_with(['-', '+']));
    let end = s[sign..].find(|c: char| !(c.is_ascii_digit() || c == '.')).map_or(s.len(), |e| e + sign);
    s[..end].parse().ok().filter(|v: &f64| v.is_finite())
}

/// The scale of the ground-truth file `gt_name` from the `scale` value of
/// `meta_path`: where the value lists several (`"1 (npz float) ; 256
/// (disp_gt.png)"`), the one naming the file, else the number the value
/// starts with, else `fallback`; refused unless positive.
fn scale_for(meta_path: &Path, scale_value: &str, gt_name: &str, fallback: Option<f64>) -> Result<f64, SimError> {
    let scale = scale_value
        .split(';')
        .find(|part| part.contains(gt_name))
        .and_then(first_number)
        .or_else(|| first_number(scale_value))
        .or(fallback)
        .ok_or_else(|| pair_err(meta_path, "`scale:` does not start with a number"))?;
    if scale <= 0.0 {
        return Err(pair_err(meta_path, format!("`scale:` of {gt_name} must be positive (got {scale})")));
    }
    Ok(scale)
}

/// A stereo pair with ground truth, read from a pair folder.
#[derive(Debug, Clone)]
pub struct PairData {
    /// Folder name.
    pub name: String,
    /// Folder.
    pub dir: PathBuf,
    /// Left view.
    pub left: GreyImage,
    /// Right view.
    pub right: GreyImage,
    /// Largest ground-truth disparity (`dispmax` in `meta.txt`).
    pub dispmax: f64,
    /// Ground truth for the left view in pixels, row-major, `0.0` = unknown.
    pub gt_left: Vec<f64>,
    /// Ground truth for the right view, where the folder has it.
    pub gt_right: Option<Vec<f64>>,
    /// `nonocc.png > 127` for the left view, where the folder has it.
    pub nonocc: Option<Vec<bool>>,
    /// Notes on converted inputs.
    pub notes: Vec<String>,
}

fn pair_err(dir: &Path, msg: impl Into<String>) -> SimError {
    SimError::PairDir { path: dir.to_path_buf(), msg: msg.into() }
}

fn first_existing(dir: &Path, names: &[&str]) -> Option<PathBuf> {
    names.iter().map(|n| dir.join(n)).find(|p| p.is_file())
}

/// Reads a ground-truth disparity file (integer = d × scale, 0 = unknown)
/// and checks its size.
fn load_gt(path: &Path, scale: f64, w: usize, h: usize) -> Result<Vec<f64>, SimError> {
    let bytes = std::fs::read(path).map_err(|source| SimError::Io { path: path.to_path_buf(), source })?;
    decode_gt(&bytes, path, scale, w, h)
}

/// Decodes ground-truth bytes (one-channel PNG/PGM, 8 or 16 bits, value =
/// d × scale, 0 = unknown) into disparities in pixels; `path` names them in
/// errors.
pub(crate) fn decode_gt(bytes: &[u8], path: &Path, scale: f64, w: usize, h: usize) -> Result<Vec<f64>, SimError> {
    let img = image::load_from_memory(bytes).map_err(|source| SimError::Image { path: path.to_path_buf(), source })?;
    if img.width() as usize != w || img.height() as usize != h {
        return Err(SimError::SizeMismatch {
            path: path.to_path_buf(),
            got_w: img.width(),
            got_h: img.height(),
            want_w: w,
            want_h: h,
        });
    }
    let raw: Vec<u32> = match img {
        DynamicImage::ImageLuma16(g) => g.into_raw().into_iter().map(u32::from).collect(),
        DynamicImage::ImageLuma8(g) => g.into_raw().into_iter().map(u32::from).collect(),
        _ => return Err(pair_err(path, "ground truth must be a one-channel (grey) image")),
    };
    Ok(raw
        .into_iter()
        .map(|v| if v == 0 { 0.0 } else { v as f64 / scale })
        .collect())
}

/// Reads a pair folder: images, `meta.txt` (`scale`, `dispmax`), ground
/// truth for the left view (and the right where present) and `nonocc.png`.
pub fn load_pair_dir(dir: &Path) -> Result<PairData, SimError> {
    if !dir.is_dir() {
        return Err(pair_err(dir, "not a folder"));
    }
    let meta_path = dir.join("meta.txt");
    let meta_text = std::fs::read_to_string(&meta_path).map_err(|source| SimError::Io { path: meta_path.clone(), source })?;
    let meta = parse_meta(&meta_text);
    let get = |k: &str| meta.get(k).ok_or_else(|| pair_err(&meta_path, format!("has no `{k}:` line")));
    let dispmax = first_number(get("dispmax")?).ok_or_else(|| pair_err(&meta_path, "`dispmax:` does not start with a number"))?;
    if dispmax <= 0.0 {
        return Err(pair_err(&meta_path, format!("`dispmax:` must be positive (got {dispmax})")));
    }
    let scale_value = get("scale")?.clone();

    let left_path = first_existing(dir, &["left_gray.png", "left.png"]).ok_or_else(|| pair_err(dir, "has no left_gray.png or left.png"))?;
    let right_path =
        first_existing(dir, &["right_gray.png", "right.png"]).ok_or_else(|| pair_err(dir, "has no right_gray.png or right.png"))?;
    let (l, r) = (load_grey(&left_path)?, load_grey(&right_path)?);
    let (w, h) = (l.image.width(), l.image.height());
    if (r.image.width(), r.image.height()) != (w, h) {
        return Err(golden::GoldenError::SizeMismatch {
            left_w: w,
            left_h: h,
            right_w: r.image.width(),
            right_h: r.image.height(),
        }
        .into());
    }
    let mut notes = Vec::new();
    for (p, im) in [(&left_path, &l), (&right_path, &r)] {
        if let Some(n) = &im.converted {
            notes.push(format!("{}: {n}", p.display()));
        }
    }

    let gt_path = first_existing(dir, &["disp_gt.png", "disp_gt.pgm"]).ok_or_else(|| pair_err(dir, "has no disp_gt.png or disp_gt.pgm"))?;
    let gt_name = gt_path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
    let scale = scale_for(&meta_path, &scale_value, gt_name, None)?;
    let gt_left = load_gt(&gt_path, scale, w, h)?;
    let gt_right = match first_existing(dir, &["disp_gt_right.png", "disp_gt_right.pgm"]) {
        Some(p) => {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or_default();
            Some(load_gt(&p, scale_for(&meta_path, &scale_value, name, Some(scale))?, w, h)?)
        }
        None => None,
    };
    let nonocc = match first_existing(dir, &["nonocc.png"]) {
        Some(p) => {
            let m = load_grey(&p)?.image;
            if (m.width(), m.height()) != (w, h) {
                return Err(SimError::SizeMismatch { path: p, got_w: m.width() as u32, got_h: m.height() as u32, want_w: w, want_h: h });
            }
            Some(m.pixels().iter().map(|&v| v > 127).collect())
        }
        None => None,
    };
    let name = dir
        .canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| dir.display().to_string());
    Ok(PairData { name, dir: dir.to_path_buf(), left: l.image, right: r.image, dispmax, gt_left, gt_right, nonocc, notes })
}

/// The Middlebury pairs in the repository (`data/stereo/`, with their
/// citations), or `$DECLIVITY_DATA` if set.
pub fn stereo_data_dir() -> PathBuf {
    match std::env::var_os("DECLIVITY_DATA") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/stereo"),
    }
}

/// The folders of the pairs `names` in [`stereo_data_dir`].
pub fn stereo_pair_dirs(names: &[&str]) -> Vec<PathBuf> {
    names.iter().map(|n| stereo_data_dir().join(n)).collect()
}

/// The left and right images of each pair folder in `dirs`.
pub fn load_image_pairs(dirs: &[PathBuf]) -> Result<Vec<(GreyImage, GreyImage)>, SimError> {
    dirs.iter().map(|d| load_pair_dir(d).map(|p| (p.left, p.right))).collect()
}

/// The pair folders named by `paths`: a folder with a `meta.txt` is a pair;
/// a folder without one stands for its sub-folders that have one (sorted),
/// so `data/stereo` names all eight pairs. Anything else is an error.
pub fn expand_pair_dirs(paths: &[PathBuf]) -> Result<Vec<PathBuf>, SimError> {
    let mut out = Vec::new();
    for p in paths {
        if !p.is_dir() {
            return Err(pair_err(p, "not a pair folder (a folder with meta.txt, or a folder of such folders)"));
        }
        if p.join("meta.txt").is_file() {
            out.push(p.clone());
            continue;
        }
        let entries = std::fs::read_dir(p).map_err(|source| SimError::Io { path: p.clone(), source })?;
        let mut subs: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|s| s.join("meta.txt").is_file())
            .collect();
        if subs.is_empty() {
            return Err(pair_err(p, "has no meta.txt and no pair folders inside: nothing to evaluate"));
        }
        subs.sort();
        out.extend(subs);
    }
    Ok(out)
}
