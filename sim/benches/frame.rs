//! One full frame of the golden model on Middlebury "cones" (450x375,
//! search bound 56), paper and robust modes, on one thread and on all cores,
//! and the robust mode in hardware parity (what the line processor computes,
//! bit for bit) beside it: the ratio of the two is parity's cost. Compare
//! with OpenCV StereoBM in the same run: `scripts/bench-vs-opencv.sh`.

use criterion::{criterion_group, criterion_main, Criterion};

// The allocator of the `declivity` binary, so that the bench measures what
// `declivity eval` reports.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use golden::{process_frame, Mode, Params, Threads};
use sim::eval::io::{load_pair_dir, stereo_data_dir};

fn frame(c: &mut Criterion) {
    let dir = stereo_data_dir().join("cones");
    let pair = load_pair_dir(&dir).unwrap_or_else(|e| panic!("bench needs the cones pair: {e}"));
    let mut g = c.benchmark_group("golden_frame_cones");
    g.sample_size(30);
    for mode in [Mode::Paper, Mode::Robust] {
        let params = Params::with_mode(mode, pair.dispmax + 1.0).expect("valid search bound");
        g.bench_function(format!("{}_one_thread", mode.name()), |b| {
            b.iter(|| process_frame(&pair.left, &pair.right, &params, Threads::One).unwrap())
        });
        g.bench_function(format!("{}_all_cores", mode.name()), |b| {
            b.iter(|| process_frame(&pair.left, &pair.right, &params, Threads::All).unwrap())
        });
    }
    let parity = Params { hardware: Some(sim::Config::Sd.limits()), ..Params::with_mode(Mode::Robust, pair.dispmax + 1.0).expect("valid search bound") };
    g.bench_function("robust_hardware_parity_one_thread", |b| {
        b.iter(|| process_frame(&pair.left, &pair.right, &parity, Threads::One).unwrap())
    });
    g.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
