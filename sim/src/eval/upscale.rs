//! Test data at HD widths: a pair up-scaled by an integer factor `f`, in
//! memory ([`upscale_pair`]) or as a pair folder ([`write_pair_dir`],
//! `sim/examples/upscale_pairs.rs`), so that `declivity eval` and `eval
//! --rtl` read it as they read `data/stereo`.
//!
//! - the views: Catmull-Rom bicubic (`image::imageops::FilterType::CatmullRom`);
//! - the ground truth of each view: each pixel's disparity times `f`,
//!   copied to its `f × f` block (nearest: an unknown pixel stays unknown,
//!   no disparity is blended across a depth edge);
//! - `nonocc`: nearest; `dispmax`: times `f`.
//!
//! A point at `x` of a view lands at `f·x + (f − 1)/2` in both views, so a
//! disparity `d` becomes `f·d` exactly.

use std::path::{Path, PathBuf};

use golden::GreyImage;
use image::imageops::FilterType;
use image::{GrayImage, ImageBuffer, Luma};

use crate::error::SimError;
use crate::eval::io::PairData;

/// A written ground truth holds `d × GT_SCALE` (1/64 px; the largest
/// up-scaled disparity of the eight pairs at 2×, 150 px, is 9 600).
pub const GT_SCALE: f64 = 64.0;

/// The largest factor [`upscale_pair`] takes.
pub const MAX_FACTOR: usize = 8;

/// `values` (row-major, `w` wide) with each value copied to an `f × f`
/// block.
fn nearest<T: Copy>(values: &[T], w: usize, f: usize) -> Vec<T> {
    values
        .chunks(w)
        .flat_map(|row| {
            let wide: Vec<T> = row.iter().flat_map(|&v| std::iter::repeat_n(v, f)).collect();
            std::iter::repeat_n(wide, f).flatten()
        })
        .collect()
}

/// `img` resized by `f` in both directions, Catmull-Rom bicubic.
fn bicubic(img: &GreyImage, f: usize) -> GreyImage {
    let (w, h) = (img.width(), img.height());
    let g = GrayImage::from_raw(w as u32, h as u32, img.pixels().to_vec()).expect("a whole image");
    let up = image::imageops::resize(&g, (w * f) as u32, (h * f) as u32, FilterType::CatmullRom);
    GreyImage::new(w * f, h * f, up.into_raw()).expect("a whole image")
}

/// `pair` up-scaled by `f` (1 ..= [`MAX_FACTOR`]; see the module's doc).
pub fn upscale_pair(pair: &PairData, f: usize) -> Result<PairData, SimError> {
    if !(1..=MAX_FACTOR).contains(&f) {
        return Err(SimError::Argument(format!("up-scaling factor {f}: from 1 to {MAX_FACTOR}")));
    }
    let w = pair.left.width();
    let gt = |g: &[f64]| nearest(g, w, f).into_iter().map(|d| d * f as f64).collect::<Vec<f64>>();
    Ok(PairData {
        name: pair.name.clone(),
        dir: pair.dir.clone(),
        left: bicubic(&pair.left, f),
        right: bicubic(&pair.right, f),
        dispmax: pair.dispmax * f as f64,
        gt_left: gt(&pair.gt_left),
        gt_right: pair.gt_right.as_deref().map(gt),
        nonocc: pair.nonocc.as_deref().map(|m| nearest(m, w, f)),
        notes: vec![format!("{} up-scaled {f}x (views Catmull-Rom bicubic; ground truth x{f} in value, nearest)", pair.name)],
    })
}

/// Writes `pair` (from [`upscale_pair`] of the folder `source`, by `f`)
/// as the pair folder `out/<name>/`: the views, `disp_gt.png` (and
/// `disp_gt_right.png`) 16-bit with [`GT_SCALE`], `nonocc.png`, and
/// `meta.txt` with a note naming the source and how it was made (the
/// source's citation is `data/stereo/README.md`'s). Returns the folder.
pub fn write_pair_dir(pair: &PairData, source: &Path, f: usize, out: &Path) -> Result<PathBuf, SimError> {
    let dir = out.join(&pair.name);
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source: std::io::Error| SimError::Io { path, source }
    };
    let img_err = |path: &Path| {
        let path = path.to_path_buf();
        move |e: image::ImageError| SimError::Io { path, source: std::io::Error::other(e) }
    };
    std::fs::create_dir_all(&dir).map_err(io(&dir))?;
    let (w, h) = (pair.left.width(), pair.left.height());
    for (img, name) in [(&pair.left, "left_gray.png"), (&pair.right, "right_gray.png")] {
        let p = dir.join(name);
        GrayImage::from_raw(w as u32, h as u32, img.pixels().to_vec()).expect("a whole image").save(&p).map_err(img_err(&p))?;
    }
    let mut gts = vec![("disp_gt.png", &pair.gt_left)];
    if let Some(g) = &pair.gt_right {
        gts.push(("disp_gt_right.png", g));
    }
    for (name, gt) in gts {
        let p = dir.join(name);
        let v: Vec<u16> = gt.iter().map(|d| (d * GT_SCALE).round().min(u16::MAX as f64) as u16).collect();
        ImageBuffer::<Luma<u16>, _>::from_raw(w as u32, h as u32, v).expect("a whole map").save(&p).map_err(img_err(&p))?;
    }
    if let Some(mask) = &pair.nonocc {
        let p = dir.join("nonocc.png");
        let v: Vec<u8> = mask.iter().map(|&k| if k { 255 } else { 0 }).collect();
        GrayImage::from_raw(w as u32, h as u32, v).expect("a whole mask").save(&p).map_err(img_err(&p))?;
    }
    let p = dir.join("meta.txt");
    let meta = format!(
        "scale: {GT_SCALE}\ndispmax: {}\nnotes: {} up-scaled {f}x by sim/examples/upscale_pairs.rs (views Catmull-Rom bicubic; ground truth x{f} in value, nearest); source {}\n",
        pair.dispmax,
        pair.name,
        source.display()
    );
    std::fs::write(&p, meta).map_err(io(&p))?;
    Ok(dir)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disparity_becomes_f_times_itself_over_an_f_by_f_block() {
        let img = |v: Vec<u8>| GreyImage::new(2, 2, v).expect("2×2");
        let pair = PairData {
            name: "p".into(),
            dir: PathBuf::from("p"),
            left: img(vec![0, 100, 200, 50]),
            right: img(vec![10, 20, 30, 40]),
            dispmax: 5.0,
            gt_left: vec![1.5, 0.0, 2.0, 3.0],
            gt_right: None,
            nonocc: Some(vec![true, false, false, true]),
            notes: Vec::new(),
        };
        let up = upscale_pair(&pair, 2).expect("factor 2");
        assert_eq!((up.left.width(), up.left.height(), up.dispmax), (4, 4, 10.0));
        assert_eq!(&up.gt_left[..4], &[3.0, 3.0, 0.0, 0.0]);
        assert_eq!(&up.gt_left[4..8], &[3.0, 3.0, 0.0, 0.0]);
        assert_eq!(&up.gt_left[8..], &[4.0, 4.0, 6.0, 6.0, 4.0, 4.0, 6.0, 6.0]);
        assert_eq!(up.nonocc.as_deref().map(|m| m[3]), Some(false));
        assert!(upscale_pair(&pair, 0).is_err() && upscale_pair(&pair, MAX_FACTOR + 1).is_err());
    }
}
