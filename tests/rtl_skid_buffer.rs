//! The camera input's register slice (`rtl::stream::skid_buffer`), driven clock by
//! clock: every beat the camera hands over leaves toward the detector once,
//! in order, with its `tuser` and `tlast`, whatever the detector's `tready`
//! does; `s_tready` is a register (the detector's `tready` does not reach
//! the camera in the same clock); a beat takes `SKID_LAG` clocks through;
//! and with the detector always ready the camera is never held.
//!
//! The camera model obeys AXI4-Stream: once it raises `tvalid` it holds the
//! beat until the clock edge that takes it. Beats are generated and taken
//! from real Tsukuba rows.
//!
//! Run in release mode (`cargo test --release -p declivity-tests --test
//! rtl_skid_buffer`).

use proptest::collection::vec;
use proptest::prelude::*;
use rtl::params::PIXEL_BITS;
use rtl::rust_hdl::prelude::*;
use rtl::stream::skid_buffer::{SkidBuffer, SKID_LAG};

/// A beat: grey level, start of frame, end of line.
type Beat = (u8, bool, bool);

/// What a run saw: beats taken from the camera and given to the detector
/// (with the clock of each), and the clocks `s_tready` was low.
#[derive(Debug, Default)]
struct Run {
    taken: Vec<(u64, Beat)>,
    given: Vec<(u64, Beat)>,
    held_clocks: u64,
}

fn settle(uut: &mut SkidBuffer<PIXEL_BITS>) {
    assert!(simulate(uut, 100), "the block settles");
}

/// Runs `beats` through the slice. Clock `t`: the camera offers its next
/// beat when `offer[t % len]` (and holds an offered beat until taken), the
/// detector is ready when `ready[t % len]`. Stops when every beat has come
/// out (or after a bound, failing the caller's checks).
fn run(beats: &[Beat], offer: &[bool], ready: &[bool]) -> Run {
    let mut uut = SkidBuffer::<PIXEL_BITS>::default();
    uut.connect_all();
    let mut out = Run::default();
    let mut next = 0usize;
    let mut offering = false;
    let bound = 10 * (beats.len() as u64 + 10) * (1 + offer.len() as u64 + ready.len() as u64);
    let mut t = 0u64;
    while out.given.len() < beats.len() && t < bound {
        if !offering && next < beats.len() && offer[t as usize % offer.len()] {
            offering = true;
        }
        let (d, u, l) = if offering { beats[next] } else { (0, false, false) };
        uut.s_tdata.next = (d as u64).into();
        uut.s_tvalid.next = offering;
        uut.s_tuser.next = u;
        uut.s_tlast.next = l;
        uut.m_tready.next = ready[t as usize % ready.len()];
        settle(&mut uut);
        let s_ready = uut.s_tready.val();
        // A register: the detector's tready changing inside the clock does
        // not move it.
        uut.m_tready.next = !uut.m_tready.val();
        settle(&mut uut);
        assert_eq!(uut.s_tready.val(), s_ready, "clock {t}: s_tready follows m_tready in the same clock");
        uut.m_tready.next = ready[t as usize % ready.len()];
        settle(&mut uut);
        if !s_ready {
            out.held_clocks += 1;
        }
        if offering && s_ready {
            out.taken.push((t, beats[next]));
            next += 1;
            offering = false;
        }
        if uut.m_tvalid.val() && uut.m_tready.val() {
            let d: u64 = uut.m_tdata.val().index() as u64;
            out.given.push((t, (d as u8, uut.m_tuser.val(), uut.m_tlast.val())));
        }
        uut.clock.next = Clock::from(true);
        settle(&mut uut);
        uut.clock.next = Clock::from(false);
        settle(&mut uut);
        t += 1;
    }
    out
}

fn beats_of(row: &[u8], sof: bool) -> Vec<Beat> {
    row.iter().enumerate().map(|(x, &p)| (p, sof && x == 0, x + 1 == row.len())).collect()
}

fn tsukuba_rows(rows: std::ops::Range<usize>) -> Vec<Beat> {
    let pair = sim::eval::io::load_pair_dir(&sim::eval::io::stereo_data_dir().join("tsukuba"))
        .unwrap_or_else(|e| panic!("the test needs the tsukuba pair: {e}"));
    let first = rows.start;
    rows.flat_map(|y| beats_of(pair.left.row(y), y == first)).collect()
}

fn check_in_order(beats: &[Beat], r: &Run) -> Result<(), String> {
    let given: Vec<Beat> = r.given.iter().map(|g| g.1).collect();
    let taken: Vec<Beat> = r.taken.iter().map(|g| g.1).collect();
    if taken != beats {
        return Err(format!("{} of {} beats taken", taken.len(), beats.len()));
    }
    if given != beats {
        let first = given.iter().zip(beats).position(|(a, b)| a != b).unwrap_or(given.len().min(beats.len()));
        return Err(format!("{} beats given for {}; first difference at beat {first}", given.len(), beats.len()));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn every_beat_leaves_once_and_in_order_whatever_the_stalls(
        data in vec((any::<u8>(), any::<bool>(), any::<bool>()), 1..200),
        offer in vec(prop::bool::weighted(0.8), 0..40),
        ready in vec(prop::bool::weighted(0.6), 0..40),
    ) {
        // Each pattern repeats, and a camera that never offers or a
        // detector never ready passes nothing: each has a `true`.
        let (mut offer, mut ready) = (offer, ready);
        offer.push(true);
        ready.push(true);
        let r = run(&data, &offer, &ready);
        prop_assert!(check_in_order(&data, &r).is_ok(), "{:?}", check_in_order(&data, &r));
    }
}

#[test]
fn every_beat_of_real_rows_leaves_once_and_in_order_under_stall_patterns() {
    let beats = tsukuba_rows(100..104);
    let patterns: [(&[bool], &[bool]); 4] = [
        (&[true], &[true, false]),
        (&[true], &[false, false, true]),
        (&[true, true, false], &[true, true, true, false, false]),
        (&[true], &[true, true, true, true, true, true, true, false]),
    ];
    for (i, (offer, ready)) in patterns.iter().enumerate() {
        let r = run(&beats, offer, ready);
        check_in_order(&beats, &r).unwrap_or_else(|e| panic!("pattern {i}: {e}"));
        // The slice holds the camera only while its skid register holds a
        // beat the detector refused: with the camera offering back to back
        // and the detector ever not ready, some clocks.
        assert!(r.held_clocks > 0, "pattern {i}: never held");
    }
}

#[test]
fn a_real_row_passes_in_skid_lag_clocks_at_one_pixel_per_clock_never_held() {
    let beats = tsukuba_rows(200..203);
    let r = run(&beats, &[true], &[true]);
    check_in_order(&beats, &r).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.held_clocks, 0, "the camera held while the detector was ready");
    for ((t_in, _), (t_out, _)) in r.taken.iter().zip(&r.given) {
        assert_eq!(t_out - t_in, SKID_LAG as u64, "beat taken at {t_in} given at {t_out}");
    }
    // One pixel per clock: the beats taken on consecutive clocks.
    assert_eq!(r.taken.last().map(|t| t.0), Some(beats.len() as u64 - 1));
}
