//! The matcher's load on the eight Middlebury pairs: per pair, the clocks
//! the engine is busy per line (`rtl::matcher::declivity_matcher::line_period`, the
//! spacing of back-to-back lines: the longer of the sweep and the traceback,
//! which overlap), their mean and largest against the line's width `W`, and
//! the most lines waiting or in the matcher when lines arrive one per `W`
//! clocks (no blanking) and the engine follows its documented timing
//! (`rtl::matcher::declivity_matcher::schedule`): what the record queues must absorb.
//!
//! The lines are golden's hardware declivities of every row
//! (`sim::drive::matcher::image_lines`, at most `N_MAX` per line), with the
//! traceback at its bound (a walk to anti-diagonal 0 and `k = min(n, m)`
//! pairs) and each line's second marker taken `W` clocks after the one
//! before.
//!
//! `cargo run --release -p sim --example matcher_load [STEREO_DIR]`
use rtl::matcher::declivity_matcher::{line_period, schedule, sweep_cycles, EngineLine};
use rtl::params::{N_CELLS, N_MAX};
use rtl::matcher::traceback::traceback_cycles;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = std::env::args().nth(1).map(Into::into).unwrap_or_else(sim::eval::io::stereo_data_dir);
    println!("the matcher as built ({N_CELLS} cells of up to 4 rows, the traceback overlapping the next sweep), lines one per W clocks");
    println!("pair        width  lines  n>64  max n   mean clocks/line      max clocks/line   most lines waiting or in the matcher");
    for p in ["tsukuba", "cones", "motorcycle", "art", "map", "sawtooth", "teddy", "venus"] {
        let dir = root.join(p);
        let l = sim::eval::io::load_grey(&dir.join("left_gray.png"))?;
        let r = sim::eval::io::load_grey(&dir.join("right_gray.png"))?;
        let w = l.image.width() as u64;
        let lines = sim::drive::matcher::image_lines(&l.image, &r.image);
        let (mut heavy, mut n_max, mut sum, mut most) = (0, 0, 0u64, 0u64);
        let mut engine = Vec::with_capacity(lines.len());
        for (y, (a, b)) in lines.iter().enumerate() {
            let (n, m) = (a.records.len().min(N_MAX), b.records.len().min(N_MAX));
            n_max = n_max.max(n);
            heavy += usize::from(n > 2 * N_CELLS);
            let period = line_period(n, m, 0, n.min(m), N_CELLS) as u64;
            sum += period;
            most = most.max(period);
            engine.push(EngineLine {
                input_done: (y as u64 + 1) * w,
                sweep: sweep_cycles(n, m, N_CELLS) as u64,
                traceback: traceback_cycles(n, m, 0, n.min(m)) as u64,
            });
        }
        let times = schedule(&engine);
        // A line is waiting or in the matcher from its second marker to its
        // marker out.
        let backlog = engine
            .iter()
            .map(|e| times.iter().zip(&engine).filter(|(t, f)| f.input_done <= e.input_done && t.marker > e.input_done).count())
            .max()
            .unwrap_or(0);
        let h = lines.len() as f64;
        let mean = sum as f64 / h;
        println!(
            "{p:10} {w:6} {:6} {heavy:5} {n_max:6}   {mean:5.0} ({:5.1} %)    {most:5} ({:5.1} %)   {backlog}",
            lines.len(),
            100.0 * mean / w as f64,
            100.0 * most as f64 / w as f64
        );
    }
    Ok(())
}
