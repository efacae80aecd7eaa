//! The matcher's load on the eight Middlebury pairs: per pair, its mean
//! clocks per line against the line's width, for the sensor's array (64
//! cells of two rows, an anti-diagonal every two clocks) and for an array of
//! 32 cells of up to four rows whose anti-diagonal period is
//! `max(2, ⌈n/32⌉)` clocks (the area step issue 6 weighs: half the cells),
//! each with the traceback after the sweep (as built) and overlapped with
//! the next line's sweep (a second choice memory: a line then costs the
//! longer of the two).
//!
//! Clocks per line are `rtl::declivity_matcher::line_cycles` with the
//! traceback's bound (walk to anti-diagonal 0, `k = min(n, m)` pairs), on
//! the declivities golden's hardware parity gives each row
//! (`sim::matcher::image_lines`, at most `N_MAX` per line). A line period of
//! `W` clocks (no blanking) is the budget; the record queues absorb bursts
//! of up to a few lines, not a mean above it.
//!
//! `cargo run --release -p sim --example matcher_load [STEREO_DIR]`
use rtl::declivity_matcher::{line_cycles, sweep_cycles};
use rtl::params::{N_CELLS, N_MAX};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = std::env::args().nth(1).map(Into::into).unwrap_or_else(sim::io::shared_stereo_dir);
    println!("mean matcher clocks per line (% of the width W): 64 cells of 2 rows | 32 cells of up to 4 rows; traceback after the sweep | overlapped");
    println!("pair        width  lines  n>64  max n    64×2 after      64×2 overlapped   32×4 after      32×4 overlapped   skew after   skew overlapped");
    for p in ["tsukuba", "cones", "motorcycle", "art", "map", "sawtooth", "teddy", "venus"] {
        let dir = root.join(p);
        let l = sim::io::load_grey(&dir.join("left_gray.png"))?;
        let r = sim::io::load_grey(&dir.join("right_gray.png"))?;
        let w = l.image.width();
        let lines = sim::matcher::image_lines(&l.image, &r.image);
        let (mut heavy, mut n_max) = (0, 0);
        let mut sum = [0usize; 6];
        // Backlog: lines arrive every W clocks, the matcher takes them in
        // order; the most lines waiting or in work when a line arrives.
        let mut free = [0usize; 6];
        let mut ends: [Vec<usize>; 6] = Default::default();
        let mut backlog = [0usize; 6];
        for (a, b) in &lines {
            let (n, m) = (a.records.len().min(N_MAX), b.records.len().min(N_MAX));
            n_max = n_max.max(n);
            heavy += usize::from(n > N_CELLS);
            let today = line_cycles(n, m, 0, n.min(m), N_CELLS);
            let sweep = sweep_cycles(n, m, N_CELLS);
            // The traceback and the output registers.
            let rest = today - sweep;
            // The same sweep at max(2, ⌈n / 32⌉) clocks per anti-diagonal
            // instead of 2 (± the fold clocks).
            let period = n.div_ceil(N_CELLS / 2).max(2);
            let sweep4 = sweep - 2 * (n + m) + period * (n + m);
            // 32 cells of 4 rows, the column moving a cell every 2 clocks:
            // period p = 2 (n <= 64) or 4, node (i, j) at 2i + p·j + i/32, and
            // with p = 4 the choices of cell c delayed 2c to align them.
            let (pp, k) = (if n <= 64 { 2 } else { 4 }, n.saturating_sub(1) / 32);
            let c_last = n.saturating_sub(1) % 32;
            let t_last = if pp == 2 {
                2 * (n + m).saturating_sub(2) + k
            } else {
                4 * m.saturating_sub(1) + (k - 1) * 65 + (4 * c_last + 65).max(4 * 31)
            };
            let sweep_b = sweep - 2 * (n + m) + 4 + t_last - usize::from(n > N_CELLS);
            let y = ends[0].len();
            let arrive = (y + 1) * w as usize;
            for (v, c) in [today, sweep.max(rest), sweep4 + rest, sweep4.max(rest), sweep_b + rest, sweep_b.max(rest)].into_iter().enumerate().map(|(c, v)| (v, c)) {
                sum[c] += v;
                free[c] = free[c].max(arrive) + v;
                ends[c].push(free[c]);
                let waiting = ends[c].iter().filter(|&&e| e > arrive).count();
                backlog[c] = backlog[c].max(waiting);
            }
        }
        let h = lines.len() as f64;
        let cols: Vec<String> = sum.iter().map(|&c| c as f64 / h).map(|c| format!("{c:5.0} ({:5.1} %)", 100.0 * c / w as f64)).collect();
        println!("{p:10} {w:6} {:6} {heavy:5} {n_max:6}   {}", lines.len(), cols.join("   "));
        println!("{:36}most lines in the matcher or waiting: {backlog:?}", "");
    }
    Ok(())
}
