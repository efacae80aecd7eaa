//! Regression of the paper mode on real Middlebury pairs from
//! `data/stereo` (beside the workspace; `DECLIVITY_DATA` overrides).
//! Thresholds sit just below the paper mode's figures on each pair
//! (`declivity eval --mode paper data/stereo/tsukuba`), so that a change of
//! its results fails here; the figures are in docs/timing-closure.md.

use golden::{process_frame, Mode, Params, Threads};
use sim::eval::scores::evaluate_pair;
use sim::eval::io::{load_pair_dir, stereo_data_dir, PairData};

fn pair(name: &str) -> PairData {
    let dir = stereo_data_dir().join(name);
    load_pair_dir(&dir).unwrap_or_else(|e| panic!("the regression needs {}: {e}", dir.display()))
}

#[test]
fn paper_mode_on_tsukuba_keeps_its_measured_accuracy() {
    let p = pair("tsukuba");
    let params = Params { mode: Mode::Paper, ..Params::paper(2.0).unwrap() };
    let (r, _) = evaluate_pair(&p, &params, 1).unwrap();
    assert_eq!((r.width, r.height), (384, 288));
    assert_eq!(r.search_bound, 15.0, "eval searches dispmax + 1");
    assert!(r.declivities > 11_500 && r.declivities < 12_600, "declivities {}", r.declivities);
    assert!(r.matches >= 4_800, "matches {}", r.matches);
    assert!(r.sparse_acc1.is_some_and(|v| v >= 94.5), "sparse_acc1 {:?}", r.sparse_acc1);
    assert!(r.bad2 <= 17.0, "bad2 {}", r.bad2);
    assert!(r.density >= 98.5, "density {}", r.density);
    let nonocc = r.nonocc_bad2.expect("tsukuba has a nonocc mask");
    assert!(nonocc <= 16.0 && nonocc < r.bad2, "nonocc bad2 {nonocc} vs bad2 {}", r.bad2);
}

#[test]
fn paper_mode_on_cones_keeps_its_measured_accuracy() {
    let p = pair("cones");
    let params = Params::paper(2.0).unwrap();
    let (r, _) = evaluate_pair(&p, &params, 1).unwrap();
    assert!(r.matches >= 7_300, "matches {}", r.matches);
    assert!(r.sparse_acc1.is_some_and(|v| v >= 87.5), "sparse_acc1 {:?}", r.sparse_acc1);
    assert!(r.bad2 <= 31.5, "bad2 {}", r.bad2);
    assert!(r.nonocc_bad2.is_some_and(|v| v <= 26.5), "nonocc bad2 {:?}", r.nonocc_bad2);
}

#[test]
fn frame_on_all_cores_equals_frame_on_one_thread_on_a_real_pair_in_every_mode() {
    let p = pair("venus");
    for mode in Mode::ALL {
        let params = Params::with_mode(mode, p.dispmax + 1.0).unwrap();
        let one = process_frame(&p.left, &p.right, &params, Threads::One).unwrap();
        let all = process_frame(&p.left, &p.right, &params, Threads::All).unwrap();
        assert!(one.matches() > 1000, "{mode:?}: a real pair gives matches");
        assert_eq!(one, all, "{mode:?}");
    }
}
