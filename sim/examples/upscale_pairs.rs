//! Test data at HD widths: pair folders up-scaled by an integer factor
//! (default 2), laid out as `data/stereo/<pair>/`, so that `declivity eval`
//! and `eval --rtl` read them as they are.
//!
//! The up-scaling and the folder are `sim::eval::upscale`'s (views
//! bicubic, ground truth times the factor, nearest; `meta.txt` names the
//! source).
//!
//! Then, for each folder, the characteristic declivities per line of both
//! views (golden's default mode, unlimited), which size the detector's
//! `N_MAX` and the matcher at these widths: the median, the 99th percentile
//! and the largest count of a line, and the lines above 128 and 256.
//!
//! `cargo run --release -p sim --example upscale_pairs -- OUT_DIR [FACTOR] [PAIR_DIRS...]`
//! (pairs: `data/stereo` by default)

use std::path::PathBuf;

use sim::eval::upscale::{upscale_pair, write_pair_dir, MAX_FACTOR};

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
    if !(1..=MAX_FACTOR).contains(&factor) {
        return Err(format!("FACTOR {factor}: from 1 to {MAX_FACTOR}").into());
    }
    let mut dirs: Vec<PathBuf> = args.map(PathBuf::from).collect();
    if dirs.is_empty() {
        dirs.push(sim::eval::io::stereo_data_dir());
    }
    println!("characteristic declivities per line, both views (golden's default mode)");
    println!("pair        size        median  p99   max   lines > 128  lines > 256");
    for dir in sim::eval::io::expand_pair_dirs(&dirs)? {
        let pair = sim::eval::io::load_pair_dir(&dir)?;
        let up = sim::eval::io::load_pair_dir(&write_pair_dir(&upscale_pair(&pair, factor)?, &pair.dir, factor, &out)?)?;
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
