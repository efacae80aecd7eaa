//! Test data at HD widths: pair folders up-scaled by an integer factor
//! (default 2), laid out as `data/stereo/<pair>/`, so that `declivity eval`
//! and `eval --rtl` read them as they are.
//!
//! - the views: Catmull-Rom bicubic (`image::imageops::FilterType::CatmullRom`);
//! - the ground truth of each view: each pixel's disparity times the factor,
//!   copied to its `factor × factor` block (nearest: an unknown pixel stays
//!   unknown, no disparity is blended across a depth edge), written as 16-bit
//!   `disp_gt.png` / `disp_gt_right.png` with [`GT_SCALE`];
//! - `nonocc.png`: nearest;
//! - `meta.txt`: `scale` [`GT_SCALE`], `dispmax` times the factor, and a note
//!   naming the source folder and how it was made (the source's citation is
//!   `data/stereo/README.md`'s).
//!
//! A point at `x` of a view lands at `f·x + (f − 1)/2` in both views, so a
//! disparity `d` becomes `f·d` exactly.
//!
//! Then, for each folder, the characteristic declivities per line of both
//! views (golden's default mode, unlimited), which size the detector's
//! `N_MAX` and the matcher at these widths: the median, the 99th percentile
//! and the largest count of a line, and the lines above 128 and 256.
//!
//! `cargo run --release -p sim --example upscale_pairs -- OUT_DIR [FACTOR] [PAIR_DIRS...]`
//! (pairs: `data/stereo` by default)

use std::path::{Path, PathBuf};

use image::imageops::FilterType;
use image::{GrayImage, ImageBuffer, Luma};

/// Ground-truth values are `d × GT_SCALE` (1/64 px; the largest up-scaled
/// disparity of the eight pairs, 150 px, is 9 600).
const GT_SCALE: f64 = 64.0;

fn grey(img: &golden::GreyImage) -> GrayImage {
    GrayImage::from_raw(img.width() as u32, img.height() as u32, img.pixels().to_vec()).expect("a whole image")
}

/// `values` (row-major, `w` wide) with each pixel copied to an `f × f` block.
fn nearest<T: Copy>(values: &[T], w: usize, f: usize) -> Vec<T> {
    values.chunks(w).flat_map(|row| {
        let wide: Vec<T> = row.iter().flat_map(|&v| std::iter::repeat_n(v, f)).collect();
        std::iter::repeat_n(wide, f).flatten()
    }).collect()
}

fn write_gt(path: &Path, gt: &[f64], w: usize, h: usize, f: usize) -> Result<(), Box<dyn std::error::Error>> {
    let up: Vec<u16> = nearest(gt, w, f).into_iter().map(|d| (d * f as f64 * GT_SCALE).round().min(u16::MAX as f64) as u16).collect();
    ImageBuffer::<Luma<u16>, _>::from_raw((w * f) as u32, (h * f) as u32, up).expect("a whole map").save(path)?;
    Ok(())
}

fn upscale(pair: &sim::eval::io::PairData, out: &Path, f: usize) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let (w, h) = (pair.left.width(), pair.left.height());
    let dir = out.join(&pair.name);
    std::fs::create_dir_all(&dir)?;
    for (img, name) in [(&pair.left, "left_gray.png"), (&pair.right, "right_gray.png")] {
        image::imageops::resize(&grey(img), (w * f) as u32, (h * f) as u32, FilterType::CatmullRom).save(dir.join(name))?;
    }
    write_gt(&dir.join("disp_gt.png"), &pair.gt_left, w, h, f)?;
    if let Some(gt) = &pair.gt_right {
        write_gt(&dir.join("disp_gt_right.png"), gt, w, h, f)?;
    }
    if let Some(mask) = &pair.nonocc {
        let up: Vec<u8> = nearest(mask, w, f).into_iter().map(|k| if k { 255 } else { 0 }).collect();
        GrayImage::from_raw((w * f) as u32, (h * f) as u32, up).expect("a whole mask").save(dir.join("nonocc.png"))?;
    }
    std::fs::write(
        dir.join("meta.txt"),
        format!(
            "scale: {GT_SCALE}\ndispmax: {}\nnotes: {} up-scaled {f}x by sim/examples/upscale_pairs.rs (views Catmull-Rom bicubic; ground truth x{f} in value, nearest); source {}\n",
            pair.dispmax * f as f64,
            pair.name,
            pair.dir.display()
        ),
    )?;
    Ok(dir)
}

/// The `q`-quantile of sorted counts.
fn quantile(sorted: &[usize], q: f64) -> usize {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().ok_or("usage: upscale_pairs OUT_DIR [FACTOR] [PAIR_DIRS...]")?);
    let factor: usize = match args.next() {
        Some(f) => f.parse().map_err(|_| format!("FACTOR `{f}` is not a whole number"))?,
        None => 2,
    };
    if !(1..=8).contains(&factor) {
        return Err(format!("FACTOR {factor}: from 1 to 8").into());
    }
    let mut dirs: Vec<PathBuf> = args.map(PathBuf::from).collect();
    if dirs.is_empty() {
        dirs.push(sim::eval::io::stereo_data_dir());
    }
    println!("characteristic declivities per line, both views (golden's default mode)");
    println!("pair        size        median  p99   max   lines > 128  lines > 256");
    for dir in sim::eval::io::expand_pair_dirs(&dirs)? {
        let pair = sim::eval::io::load_pair_dir(&dir)?;
        let up = sim::eval::io::load_pair_dir(&upscale(&pair, &out, factor)?)?;
        let params = golden::Params::new(up.dispmax + 1.0)?;
        let frame = golden::process_frame(&up.left, &up.right, &params, golden::Threads::All)?;
        let mut counts: Vec<usize> = frame.lines.iter().flat_map(|l| [l.reference.declivities.len(), l.other.declivities.len()]).collect();
        counts.sort_unstable();
        println!(
            "{:<11} {:>4}×{:<6} {:>6} {:>5} {:>5} {:>12} {:>12}",
            up.name,
            up.left.width(),
            up.left.height(),
            quantile(&counts, 0.5),
            quantile(&counts, 0.99),
            counts.last().copied().unwrap_or(0),
            counts.iter().filter(|&&n| n > 128).count(),
            counts.iter().filter(|&&n| n > 256).count()
        );
    }
    println!("written to {}", out.display());
    Ok(())
}
