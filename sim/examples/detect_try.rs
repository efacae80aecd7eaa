use sim::detector::*;
fn main() {
    let dir = sim::io::shared_stereo_dir().join(std::env::args().nth(1).unwrap_or("tsukuba".into()));
    let pair = sim::io::load_pair_dir(&dir).unwrap();
    let img = &pair.left;
    let lines: Vec<&[u8]> = (0..img.height()).map(|y| img.row(y)).collect();
    let mut s = DetectorSim::new();
    let t = std::time::Instant::now();
    let run = run_lines(&mut s, &lines, || false, |_| {}).unwrap();
    let secs = t.elapsed().as_secs_f64();
    let gold = golden_lines(&lines);
    let mut tot = LineComparison::default();
    for (y, (h, g)) in run.lines.iter().zip(&gold).enumerate() {
        let c = compare_line(h, g);
        if c.mismatches > 0 && tot.mismatches < 3 {
            println!("line {y}: {c:?} hw {} gold {}", h.records.len(), g.declivities.len());
            for (a, b) in h.records.iter().zip(&g.declivities).take(200) {
                let d = to_declivity(a);
                if (d.start, d.end, d.amplitude, d.left, d.right) != (b.start, b.end, b.amplitude, b.left, b.right) || (d.position - b.position).abs() >= 1.0/16.0 {
                    println!("  hw {:?}\n  gd {:?}", d, b);
                    break;
                }
            }
        }
        tot.common += c.common; tot.borderline += c.borderline; tot.mismatches += c.mismatches;
        tot.max_pos_err_lsb = tot.max_pos_err_lsb.max(c.max_pos_err_lsb);
        tot.dt_err_lsb = tot.dt_err_lsb.max(c.dt_err_lsb);
    }
    println!("{:?}", tot);
    println!("cycles {} input {} pixels {} px/clk {:.4} stalls {} sim {:.0} cycles/s", run.cycles, run.input_cycles, run.pixels, run.px_per_clk(), run.stall_cycles, run.cycles as f64 / secs);
    let l0 = &run.lines[0];
    println!("line0 marker at {} last px at {} → {}", l0.marker_cycle, run.last_pixel_cycle[0], l0.marker_cycle - run.last_pixel_cycle[0]);
}
