//! Can inter-scanline support (`golden::Features::contour`, the `contour`
//! mode) remove the robust mode's wrong matches? It can only where the row
//! above matched the contour right. For each of the robust mode's reported
//! matches with ground truth (rows 1 and below), the nearest matched
//! declivity of the row above with the same polarity within 1 px (the
//! contour it continues, as `golden::line::contour_disparities` finds it)
//! is looked up, and the example counts, per pair and over all eight:
//! - right matches (|d − truth| ≤ 1 px) whose contour has their disparity
//!   within 1 px (the support a right match gets);
//! - wrong matches whose contour has the same wrong disparity (the support
//!   an error gets);
//! - wrong matches whose contour has the true disparity (the errors the row
//!   above could correct).
//!
//! The matches are the reported ones (after the row check and the edge
//! flag), and so are the row above's.
//!
//! `cargo run --release -p sim --example contour_support`
//! (`DECLIVITY_DATA` overrides the pairs' folder).
use golden::line::{contour_disparities, ContourPoint};
use golden::{process_frame, Mode, Params, Threads};
use sim::eval::io::{load_pair_dir, stereo_data_dir};

const PAIRS: [&str; 8] = ["tsukuba", "venus", "sawtooth", "map", "cones", "teddy", "art", "motorcycle"];

/// Counts of one pair: right, right supported, wrong, wrong supported,
/// wrong whose contour is right.
#[derive(Default, Clone, Copy)]
struct Counts([usize; 5]);

fn pct(a: usize, b: usize) -> f64 {
    100.0 * a as f64 / b.max(1) as f64
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut total = Counts::default();
    println!("pair        right  supported (%)  wrong  supported at the wrong d (%)  row above right (%)");
    for name in PAIRS {
        let p = load_pair_dir(&stereo_data_dir().join(name))?;
        let params = Params::with_mode(Mode::Robust, p.dispmax + 1.0)?;
        let frame = process_frame(&p.left, &p.right, &params, Threads::One)?;
        let w = frame.width;
        let mut c = Counts::default();
        let mut dc = Vec::new();
        for y in 1..frame.height {
            let above: Vec<ContourPoint> = frame.lines[y - 1].contour_points().collect();
            let line = &frame.lines[y];
            let reported: Vec<_> = line.matches.iter().filter(|m| !m.edge).collect();
            let decls: Vec<_> = reported.iter().map(|m| line.reference.declivities[m.ref_index]).collect();
            contour_disparities(&decls, &above, 1.0, &mut dc);
            for (m, &d_contour) in reported.iter().zip(&dc) {
                let g = p.gt_left[y * w + (m.x_ref.round() as usize).min(w - 1)];
                if !(g > 0.0 && g.is_finite()) {
                    continue;
                }
                let supported = (d_contour - m.disparity).abs() <= 1.0;
                if (m.disparity - g).abs() <= 1.0 {
                    c.0[0] += 1;
                    c.0[1] += supported as usize;
                } else {
                    c.0[2] += 1;
                    c.0[3] += supported as usize;
                    c.0[4] += ((d_contour - g).abs() <= 1.0) as usize;
                }
            }
        }
        let [r, rs, wr, ws, wc] = c.0;
        println!("{name:11} {r:6} {:14.1} {wr:6} {:29.1} {:20.1}", pct(rs, r), pct(ws, wr), pct(wc, wr));
        for k in 0..5 {
            total.0[k] += c.0[k];
        }
    }
    let [r, rs, wr, ws, wc] = total.0;
    println!("all         {r:6} {:14.1} {wr:6} {:29.1} {:20.1}", pct(rs, r), pct(ws, wr), pct(wc, wr));
    println!(
        "sparse_acc1 over all matches {:.2} %; with every error whose row above is right corrected {:.2} %",
        pct(r, r + wr),
        pct(r + wc, r + wr)
    );
    Ok(())
}
