//! The golden model's equations against small cases worked by hand.
//!
//! Every expected value below is derived in the comments from the paper's
//! equations (eq. 1–9) and the settled points of `DESIGN.md` §2, not taken
//! from the code's output. Numeric constants used to state expectations:
//! `Φ⁻¹(3/4) = 0.674 489 750 196 08` (the median of |N(0,1)|, a standard
//! table value), `0.6745·√2 = 0.953 872 552 4`, `1/√12 = 0.288 675 134 6`.

use declivity_tests::hand_declivity;
use golden::declivity::{
    all_declivities, amplitude, characteristic_declivities, declivity_bounds, describe, is_characteristic,
    neighbour_levels, position, position_sums,
};
use golden::disparity::{interpolate_line, Anchor};
use golden::dp::{banded_dp, best_path, literal_best_gain, literal_g, prefix_max_dp, BandRow, BandedGains, Choice, GainTable};
use golden::gain::{f_gmax, gmax, in_search_area, local_gain, lpd, node_gain, pair_disparity, rpd};
use golden::line::process_line;
use golden::noise::{abs_diff_histogram, interpolated_median, line_threshold, noise_sigma, sigma_from_histogram, threshold, HIST_BINS};
use golden::reconstruct::{depth, point, Camera};
use golden::{process_frame, EndRule, GreyImage, Mode, Params, RefView, Threads};

/// `0.6745·√2`, the median of |a - b| for a, b independent N(0, 1), written
/// from the standard table value of Φ⁻¹(3/4) (not the crate's constant).
const MAD_SQRT2: f64 = 0.674_489_750_196_08 * std::f64::consts::SQRT_2;

/// `1/√12`, the deviation of uniform quantization noise of one grey level.
const FLOOR: f64 = 0.288_675_134_594_813;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

macro_rules! assert_close {
    ($a:expr, $b:expr, $tol:expr) => {{
        let (a, b): (f64, f64) = ($a, $b);
        assert!(close(a, b, $tol), "{} = {a} but expected {} = {b} (tol {})", stringify!($a), stringify!($b), $tol);
    }};
    ($a:expr, $b:expr) => {
        assert_close!($a, $b, 1e-9)
    };
}

fn hist_of(pairs: &[(usize, u32)]) -> [u32; HIST_BINS] {
    let mut h = [0u32; HIST_BINS];
    for &(v, c) in pairs {
        h[v] = c;
    }
    h
}

// ===========================================================================
// Eq. 2: histogram, interpolated median, σ, floor, d_t = 5.6σ
// ===========================================================================

#[test]
fn eq2_histogram_counts_absolute_differences() {
    // [10, 12, 9, 9, 14]: |12-10| = 2, |9-12| = 3, |9-9| = 0, |14-9| = 5.
    let h = abs_diff_histogram(&[10, 12, 9, 9, 14]);
    let mut want = [0u32; HIST_BINS];
    want[0] = 1;
    want[2] = 1;
    want[3] = 1;
    want[5] = 1;
    assert_eq!(h, want);
    // The full range: |255 - 0| lands in the last bin.
    let h = abs_diff_histogram(&[0, 255, 0]);
    assert_eq!(h[255], 2);
    assert_eq!(h.iter().sum::<u32>(), 2);
    // Fewer than two pixels: no difference at all.
    assert_eq!(abs_diff_histogram(&[]), [0u32; HIST_BINS]);
    assert_eq!(abs_diff_histogram(&[77]), [0u32; HIST_BINS]);
}

#[test]
fn eq2_interpolated_median_inside_an_integer_bin() {
    // n = 5: bin 1 holds 1, bin 3 holds 3, bin 7 holds 1. n/2 = 2.5.
    // Cumulative: bin 1 -> 1 < 2.5; bin 3 -> 4 >= 2.5, so the median is in
    // bin 3 = [2.5, 3.5): c = 1 below, h = 3 inside:
    // m = 2.5 + 1·(2.5 - 1)/3 = 2.5 + 0.5 = 3.0.
    let m = interpolated_median(&hist_of(&[(1, 1), (3, 3), (7, 1)])).unwrap();
    assert_close!(m, 3.0);

    // n = 10: bin 0 holds 2, bin 2 holds 4, bin 4 holds 4. n/2 = 5.
    // Bin 0 -> 2 < 5; bin 2 -> 6 >= 5: bin 2 = [1.5, 2.5), c = 2, h = 4:
    // m = 1.5 + (5 - 2)/4 = 2.25.
    let m = interpolated_median(&hist_of(&[(0, 2), (2, 4), (4, 4)])).unwrap();
    assert_close!(m, 2.25);

    // n = 4: bins 0, 2, 3, 5 hold one each. n/2 = 2: bin 0 -> 1 < 2; bin 2 ->
    // 2 >= 2: m = 1.5 + (2 - 1)/1 = 2.5 (the top of bin 2).
    let m = interpolated_median(&hist_of(&[(0, 1), (2, 1), (3, 1), (5, 1)])).unwrap();
    assert_close!(m, 2.5);

    // Empty histogram: no median.
    assert_eq!(interpolated_median(&[0u32; HIST_BINS]), None);
}

#[test]
fn eq2_interpolated_median_bin_zero_is_half_wide() {
    // Bin 0 stands for [0, 0.5) (an absolute value is never negative).
    // n = 4: bin 0 holds 3, bin 1 holds 1. n/2 = 2 <= 3, so the median is in
    // bin 0: m = 0 + 0.5·(2 - 0)/3 = 1/3.
    let m = interpolated_median(&hist_of(&[(0, 3), (1, 1)])).unwrap();
    assert_close!(m, 1.0 / 3.0);
    // n = 4: bin 0 holds 2, bin 1 holds 2: m = 0.5·2/2 = 0.5 (the top of
    // bin 0, not 1.0 as a unit-wide bin 0 would give).
    let m = interpolated_median(&hist_of(&[(0, 2), (1, 2)])).unwrap();
    assert_close!(m, 0.5);
    // n = 4: bin 0 holds 1, bin 1 holds 3: bin 0 -> 1 < 2; bin 1 = [0.5, 1.5):
    // m = 0.5 + (2 - 1)/3 = 0.8333…
    let m = interpolated_median(&hist_of(&[(0, 1), (1, 3)])).unwrap();
    assert_close!(m, 0.5 + 1.0 / 3.0);
}

#[test]
fn eq2_sigma_is_median_over_0_6745_sqrt2() {
    // Line with |ΔI| = 0,0,2,2,2,2,4,4,4,4 (the n = 10 histogram above):
    // m = 2.25, σ = 2.25 / 0.953 872 552 = 2.358 806, d_t = 5.6σ = 13.209 31.
    let line = [100u8, 100, 100, 102, 100, 102, 100, 104, 100, 104, 100];
    assert_eq!(abs_diff_histogram(&line), hist_of(&[(0, 2), (2, 4), (4, 4)]));
    assert_close!(noise_sigma(&line), 2.25 / MAD_SQRT2);
    assert_close!(noise_sigma(&line), 2.358_806, 1e-6);
    assert_close!(line_threshold(&line), 13.209_31, 1e-5);

    // [10, 11, 14, 11, 14, 7]: |ΔI| = 1, 3, 3, 3, 7 -> m = 3.0 (above),
    // σ = 3 / 0.953 872 552 = 3.145 074, d_t = 17.612 42.
    let line = [10u8, 11, 14, 11, 14, 7];
    assert_close!(noise_sigma(&line), 3.0 / MAD_SQRT2);
    assert_close!(noise_sigma(&line), 3.145_074, 1e-6);
    assert_close!(line_threshold(&line), 17.612_42, 1e-5);

    // Median in bin 0 but above the floor: |ΔI| = 0, 0, 1, 1 -> m = 0.5,
    // σ = 0.5 / 0.953 872 552 = 0.524 18 > 1/√12 = 0.288 68.
    let line = [50u8, 50, 50, 51, 50];
    assert_close!(noise_sigma(&line), 0.524_18, 1e-5);
    // The same through an already built histogram.
    assert_close!(sigma_from_histogram(&hist_of(&[(0, 2), (1, 2)])), 0.5 / MAD_SQRT2);
}

#[test]
fn eq2_sigma_floor_on_flat_line_one_pixel_line_and_empty_line() {
    // A flat line of 50 pixels: 49 zero differences, m = 0.5·24.5/49 = 0.25,
    // σ = 0.25/0.953 87 = 0.262 < 1/√12 -> floored to 1/√12.
    assert_close!(noise_sigma(&[7u8; 50]), FLOOR);
    // A line of 1 pixel (and of 0): no difference at all -> the floor.
    assert_close!(noise_sigma(&[200u8]), FLOOR);
    assert_close!(noise_sigma(&[]), FLOOR);
    // Just above the floor: 20 zeros and 3 large steps of 23 differences:
    // m = 0.5·11.5/20 = 0.2875, σ = 0.2875/0.953 87 = 0.301 40 > 0.288 68.
    let mut line = vec![10u8; 24];
    line[5..].fill(60);
    line[12..].fill(20);
    line[20..].fill(90);
    assert_close!(noise_sigma(&line), 0.301_40, 1e-5);
    // Floor threshold: d_t = 5.6/√12 = 1.616 58.
    assert_close!(line_threshold(&[7u8; 50]), 1.616_58, 1e-5);
}

#[test]
fn eq2_threshold_is_5_6_sigma() {
    // d_t = 5.6σ: 5.6·2 = 11.2, 5.6·0.5 = 2.8, 5.6·10 = 56.
    assert_close!(threshold(2.0), 11.2, 1e-12);
    assert_close!(threshold(0.5), 2.8, 1e-12);
    assert_close!(threshold(10.0), 56.0, 1e-12);
}

// ===========================================================================
// Declivities: bounds (tight plateau rule), amplitudes, characteristic test
// ===========================================================================

fn bounds(line: &[u8]) -> Vec<(usize, usize)> {
    declivity_bounds(line)
}

#[test]
fn declivity_bounds_rise_plateau_fall_split_at_the_plateau_ends() {
    // [10, 20, 30, 30, 30, 15, 5]: g = +10, +10, 0, 0, -15, -10.
    // The rise starts at x = 0 and its last non-zero gradient is g(1), so it
    // ends at x = 2 (the plateau's first pixel). The fall starts at the
    // plateau's last pixel x = 4 and ends at x = 6.
    let line = [10u8, 20, 30, 30, 30, 15, 5];
    assert_eq!(bounds(&line), vec![(0, 2), (4, 6)]);
    // Amplitudes: I(2) - I(0) = +20, I(6) - I(4) = 5 - 30 = -25.
    assert_eq!(amplitude(&line, 0, 2), 20);
    assert_eq!(amplitude(&line, 4, 6), -25);
    let all = all_declivities(&line);
    assert_eq!(all.iter().map(|d| d.amplitude).collect::<Vec<_>>(), vec![20, -25]);
    assert_eq!(all.iter().map(|d| d.polarity()).collect::<Vec<_>>(), vec![1, -1]);
}

#[test]
fn declivity_bounds_plateau_inside_monotone_run_does_not_split_it() {
    // [10, 20, 20, 20, 35, 35]: g = +10, 0, 0, +15, 0. One rising run from
    // x = 0; last non-zero gradient g(3) -> end 4; the trailing flat 4..5
    // belongs to no declivity. Amplitude 35 - 10 = 25.
    let line = [10u8, 20, 20, 20, 35, 35];
    assert_eq!(bounds(&line), vec![(0, 4)]);
    assert_eq!(amplitude(&line, 0, 4), 25);
    // Eq. 3: Σg² = 100 + 225 = 325; Σg²(x+0.5) = 100·0.5 + 225·3.5 = 837.5;
    // X = 837.5/325 = 2.576 923.
    assert_close!(position(&line, 0, 4), 837.5 / 325.0);
    assert_close!(position(&line, 0, 4), 2.576_923, 1e-6);
    // The falling mirror image behaves the same way.
    assert_eq!(bounds(&[35u8, 35, 20, 20, 20, 10]), vec![(1, 5)]);
}

#[test]
fn declivity_bounds_flat_line_has_none() {
    assert!(bounds(&[9u8; 40]).is_empty());
    assert!(bounds(&[]).is_empty());
    assert!(bounds(&[3u8]).is_empty());
}

#[test]
fn declivity_bounds_leading_and_trailing_flat_runs_belong_to_no_declivity() {
    // [5, 5, 5, 9, 13, 13, 13]: g = 0, 0, +4, +4, 0, 0. The leading flat is
    // skipped: start at x = 2 (the last pixel of the flat run); last non-zero
    // gradient g(3) -> end 4. Amplitude 13 - 5 = 8.
    let line = [5u8, 5, 5, 9, 13, 13, 13];
    assert_eq!(bounds(&line), vec![(2, 4)]);
    assert_eq!(amplitude(&line, 2, 4), 8);
    // Eq. 3: g(2) = g(3) = 4: X = (16·2.5 + 16·3.5)/32 = 3.0.
    assert_close!(position(&line, 2, 4), 3.0);
}

#[test]
fn declivity_bounds_single_step_and_two_pixel_lines() {
    // Single step between x = 3 and 4.
    let line = [50u8, 50, 50, 50, 80, 80, 80, 80];
    assert_eq!(bounds(&line), vec![(3, 4)]);
    // 2-pixel lines: one declivity (0, 1) when the pixels differ, none when
    // equal.
    assert_eq!(bounds(&[3u8, 9]), vec![(0, 1)]);
    assert_eq!(bounds(&[9u8, 3]), vec![(0, 1)]);
    assert!(bounds(&[9u8, 9]).is_empty());
    let d = all_declivities(&[3u8, 9]);
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].amplitude, 6);
    assert_close!(d[0].position, 0.5);
    // Both attributes clamp to the two pixels: left = I(0), I(0), I(0);
    // right = I(1), I(1), I(1).
    assert_eq!(d[0].left, [3, 3, 3]);
    assert_eq!(d[0].right, [9, 9, 9]);
}

#[test]
fn declivity_bounds_zigzag_gives_one_declivity_per_step() {
    // Every gradient changes sign: [0, 5, 0, 5] -> (0,1), (1,2), (2,3), with
    // amplitudes +5, -5, +5.
    let line = [0u8, 5, 0, 5];
    assert_eq!(bounds(&line), vec![(0, 1), (1, 2), (2, 3)]);
    let a: Vec<i32> = all_declivities(&line).iter().map(|d| d.amplitude).collect();
    assert_eq!(a, vec![5, -5, 5]);
    // Consecutive declivities share their extremum: each one's end is the
    // next one's start when no plateau separates them.
    // With plateaus: [0, 5, 5, 0, 0, 5] -> (0,1), (2,3), (4,5).
    assert_eq!(bounds(&[0u8, 5, 5, 0, 0, 5]), vec![(0, 1), (2, 3), (4, 5)]);
}

#[test]
fn declivity_characteristic_test_is_strict() {
    // |a| > d_t, strictly.
    assert!(!is_characteristic(11, 11.0));
    assert!(is_characteristic(11, 10.999));
    assert!(!is_characteristic(-11, 11.0));
    assert!(is_characteristic(-12, 11.5));
    assert!(!is_characteristic(0, 0.0));
    // On a line: [0, 10, 10, 21, 21, 10]: declivities (0,3) amplitude +21 and
    // (4,5) amplitude -11. With d_t = 11: only the first (21 > 11; 11 is not
    // > 11). With d_t = 10.5: both. With d_t = 21: none.
    let line = [0u8, 10, 10, 21, 21, 10];
    assert_eq!(bounds(&line), vec![(0, 3), (4, 5)]);
    let c = |dt: f64| characteristic_declivities(&line, dt).iter().map(|d| (d.start, d.end)).collect::<Vec<_>>();
    assert_eq!(c(11.0), vec![(0, 3)]);
    assert_eq!(c(10.5), vec![(0, 3), (4, 5)]);
    assert_eq!(c(21.0), vec![]);
}

// ===========================================================================
// Eq. 3: positions
// ===========================================================================

#[test]
fn eq3_single_step_sits_between_its_pixels() {
    // One step between x = 3 and x = 4: only g(3) ≠ 0, X = 3 + 0.5 = 3.5.
    let line = [50u8, 50, 50, 50, 80, 80, 80, 80];
    assert_close!(position(&line, 3, 4), 3.5);
    // The integer sums: Σg² = 900, Σg²(2x+1) = 900·7 = 6300.
    assert_eq!(position_sums(&line, 3, 4), (900, 6300));
}

#[test]
fn eq3_two_equal_steps_average_their_midpoints() {
    // [0, 0, 10, 20, 20, 20]: g(1) = g(2) = 10: declivity (1, 3),
    // X = (100·1.5 + 100·2.5)/200 = 2.0.
    let line = [0u8, 0, 10, 20, 20, 20];
    assert_eq!(bounds(&line), vec![(1, 3)]);
    assert_close!(position(&line, 1, 3), 2.0);
}

#[test]
fn eq3_unequal_steps_are_weighted_by_squared_gradient() {
    // [0, 10, 40, 40]: g(0) = 10, g(1) = 30: declivity (0, 2),
    // X = (100·0.5 + 900·1.5)/(100 + 900) = 1400/1000 = 1.4
    // (a |g|-weighting would give (10·0.5 + 30·1.5)/40 = 1.25).
    let line = [0u8, 10, 40, 40];
    assert_eq!(bounds(&line), vec![(0, 2)]);
    assert_close!(position(&line, 0, 2), 1.4);
    // Falling: [200, 170, 160]: g = -30, -10: X = (900·0.5 + 100·1.5)/1000 = 0.6.
    assert_close!(position(&[200u8, 170, 160], 0, 2), 0.6);
    // With a zero gradient inside: [0, 20, 20, 30]: g = 20, 0, 10 ->
    // X = (400·0.5 + 0·1.5 + 100·2.5)/500 = 450/500 = 0.9.
    assert_close!(position(&[0u8, 20, 20, 30], 0, 3), 0.9);
}

// ===========================================================================
// Attributes
// ===========================================================================

#[test]
fn attributes_are_three_neighbours_clamped_at_the_line_ends() {
    // [40, 41, 42, 42, 90, 90, 70, 71]: g = +1, +1, 0, +48, 0, -20, +1.
    // Declivities: (0, 4) rising; from x = 4 skip the flat to x = 5, fall to
    // x = 6 (then g(6) = +1 turns back): (5, 6); then (6, 7).
    let line = [40u8, 41, 42, 42, 90, 90, 70, 71];
    assert_eq!(bounds(&line), vec![(0, 4), (5, 6), (6, 7)]);
    // (0, 4): left = I(0), I(-1)->I(0), I(-2)->I(0) = 40, 40, 40;
    //         right = I(4), I(5), I(6) = 90, 90, 70.
    assert_eq!(neighbour_levels(&line, 0, 4), ([40, 40, 40], [90, 90, 70]));
    // (5, 6): left = I(5), I(4), I(3) = 90, 90, 42;
    //         right = I(6), I(7), I(8)->I(7) = 70, 71, 71.
    assert_eq!(neighbour_levels(&line, 5, 6), ([90, 90, 42], [70, 71, 71]));
    // (6, 7): left = I(6), I(5), I(4) = 70, 90, 90;
    //         right = I(7), I(8)->I(7), I(9)->I(7) = 71, 71, 71.
    assert_eq!(neighbour_levels(&line, 6, 7), ([70, 90, 90], [71, 71, 71]));
    // describe() carries them with the amplitude and the position:
    // (5, 6): amplitude 70 - 90 = -20, X = 5.5.
    let d = describe(&line, 5, 6);
    assert_eq!((d.start, d.end, d.amplitude), (5, 6, -20));
    assert_close!(d.position, 5.5);
    assert_eq!(d.left, [90, 90, 42]);
    assert_eq!(d.right, [70, 71, 71]);
    // (1, 2) at one pixel from the start: left = I(1), I(0), I(-1)->I(0).
    assert_eq!(neighbour_levels(&line, 1, 2).0, [41, 40, 40]);
}

// ===========================================================================
// Eq. 6: the search area, for both reference views
// ===========================================================================

#[test]
fn eq6_search_area_is_open_at_both_ends() {
    assert!(!in_search_area(0.0, 0.0, 10.0));
    assert!(!in_search_area(10.0, 0.0, 10.0));
    assert!(!in_search_area(-0.5, 0.0, 10.0));
    assert!(!in_search_area(10.5, 0.0, 10.0));
    assert!(in_search_area(0.5, 0.0, 10.0));
    assert!(in_search_area(9.99, 0.0, 10.0));
    assert!(in_search_area(1e-9, 0.0, 10.0));
}

#[test]
fn eq6_lower_bound_dispmin_is_open_too() {
    // dispmin < d < dispmax: 3 and 10 are outside, just above 3 inside.
    assert!(!in_search_area(3.0, 3.0, 10.0));
    assert!(!in_search_area(2.5, 3.0, 10.0));
    assert!(in_search_area(3.0625, 3.0, 10.0));
    assert!(in_search_area(9.99, 3.0, 10.0));
    assert!(!in_search_area(10.0, 3.0, 10.0));
    // A pair 5 px apart is a node for dispmin 4.9, not for dispmin 5.
    let at = |x: f64| hand_declivity(x, [50, 50, 50], [90, 90, 90]);
    assert!(node_gain(&at(20.5), &at(15.5), 2.0, (4.9, 10.0), RefView::Left, Mode::Paper).is_some());
    assert!(node_gain(&at(20.5), &at(15.5), 2.0, (5.0, 10.0), RefView::Left, Mode::Paper).is_none());
}

/// A scene 6 px away throughout (the right view the left shifted by 6):
/// with `dispmin` 5 its matches stay at 6; with `dispmin` 6.5 no match is
/// at or below the bound. Bounds outside `0 ≤ dispmin < dispmax − 1` are
/// refused.
#[test]
fn eq6_dispmin_removes_every_match_at_or_below_it() {
    let mut rng = declivity_tests::seeded(61);
    let (w, h, d) = (240, 4, 6);
    let left: Vec<u8> = (0..h).flat_map(|_| declivity_tests::block_line(&mut rng, w)).collect();
    let right: Vec<u8> = left.chunks(w).flat_map(|l| declivity_tests::shift_left_to_right(l, d)).collect();
    let (l, r) = (GreyImage::new(w, h, left).unwrap(), GreyImage::new(w, h, right).unwrap());
    let matches = |dispmin: f64| -> Vec<f64> {
        let p = Params { dispmin, ..Params::paper(12.0).unwrap() };
        let f = process_frame(&l, &r, &p, Threads::One).unwrap();
        f.lines.iter().flat_map(|line| line.matches.iter().map(|m| m.disparity)).collect()
    };
    let base = matches(0.0);
    let at_six = |m: &[f64]| m.iter().filter(|&&x| (x - 6.0).abs() < 0.25).count();
    assert!(at_six(&base) > 20, "the shift is found: {base:?}");
    let above_five = matches(5.0);
    assert!(above_five.iter().all(|&x| x > 5.0), "{above_five:?}");
    assert!(at_six(&above_five) >= at_six(&base), "the true matches stay: {} < {}", at_six(&above_five), at_six(&base));
    let above = matches(6.5);
    assert!(above.iter().all(|&x| x > 6.5), "{above:?}");
    for dispmin in [-1.0, 11.0, 12.0, f64::NAN] {
        assert!(Params { dispmin, ..Params::paper(12.0).unwrap() }.validate().is_err(), "dispmin {dispmin}");
    }
}

#[test]
fn eq6_pair_disparity_is_x_left_minus_x_right_for_both_views() {
    // Left reference at 20.5, right at 15.5: d = 20.5 - 15.5 = 5.
    assert_close!(pair_disparity(20.5, 15.5, RefView::Left), 5.0);
    // Right reference at 15.5, left at 20.5: still d = x_left - x_right = 5.
    assert_close!(pair_disparity(15.5, 20.5, RefView::Right), 5.0);
}

#[test]
fn eq6_node_gain_excludes_d_zero_and_d_dispmax_for_both_views() {
    // Identical attributes: lpd = rpd = 0, so a node in range has gain
    // 3·gmax = 3·2 = 6 (eq. 7).
    let at = |x: f64| hand_declivity(x, [10, 10, 10], [90, 90, 90]);
    let g = |r: f64, o: f64, view| node_gain(&at(r), &at(o), 2.0, (0.0, 10.0), view, Mode::Paper);
    // Left reference: d = x_ref - x_other.
    assert_eq!(g(20.5, 20.5, RefView::Left), None); // d = 0
    assert_eq!(g(20.5, 10.5, RefView::Left), None); // d = 10 = dispmax
    assert_eq!(g(20.5, 23.0, RefView::Left), None); // d = -2.5
    assert_eq!(g(20.5, 11.0, RefView::Left), Some(6.0)); // d = 9.5
    assert_eq!(g(20.5, 20.0, RefView::Left), Some(6.0)); // d = 0.5
    // Right reference: d = x_other - x_ref.
    assert_eq!(g(10.5, 10.5, RefView::Right), None); // d = 0
    assert_eq!(g(10.5, 20.5, RefView::Right), None); // d = 10 = dispmax
    assert_eq!(g(10.5, 8.0, RefView::Right), None); // d = -2.5
    assert_eq!(g(10.5, 15.5, RefView::Right), Some(6.0)); // d = 5
    assert_eq!(g(10.5, 20.0, RefView::Right), Some(6.0)); // d = 9.5
}

// ===========================================================================
// Eq. 4, 5, 8, 7: photometric distances, gmax, f(gmax), gain
// ===========================================================================

#[test]
fn eq4_eq5_photometric_distances() {
    // lpd = |10-12| + |20-17| + |30-30| = 2 + 3 + 0 = 5.
    // rpd = |100-95| + |90-90| + |80-88| = 5 + 0 + 8 = 13.
    let r = hand_declivity(5.0, [10, 20, 30], [100, 90, 80]);
    let o = hand_declivity(3.0, [12, 17, 30], [95, 90, 88]);
    assert_eq!(lpd(&r, &o), 5);
    assert_eq!(rpd(&r, &o), 13);
    // Symmetric in the two declivities.
    assert_eq!(lpd(&o, &r), 5);
    assert_eq!(rpd(&o, &r), 13);
    // The extremes: 3·255 = 765.
    let a = hand_declivity(1.0, [0, 0, 0], [255, 255, 255]);
    let b = hand_declivity(1.0, [255, 255, 255], [0, 0, 0]);
    assert_eq!((lpd(&a, &b), rpd(&a, &b)), (765, 765));
}

#[test]
fn eq8_gmax_is_the_mean_of_the_two_thresholds() {
    // 0.5·(10 + 14) = 12; 0.5·(1.5 + 2.5) = 2.
    assert_close!(gmax(10.0, 14.0), 12.0, 1e-12);
    assert_close!(gmax(1.5, 2.5), 2.0, 1e-12);
}

#[test]
fn eq7_f_gmax_three_cases_and_equality_counts_as_not_below() {
    let gm = 12.0;
    // Both below: f = 3·12 = 36, gain = 36 - 5 - 6 = 25.
    assert_eq!(f_gmax(5.0, 6.0, gm, Mode::Paper), Some(36.0));
    assert_eq!(local_gain(5.0, 6.0, gm, Mode::Paper), Some(25.0));
    // Only lpd below: f = 12, gain = 12 - 5 - 13 = -6.
    assert_eq!(f_gmax(5.0, 13.0, gm, Mode::Paper), Some(12.0));
    assert_eq!(local_gain(5.0, 13.0, gm, Mode::Paper), Some(-6.0));
    // Only rpd below: f = 12, gain = 12 - 13 - 5 = -6.
    assert_eq!(local_gain(13.0, 5.0, gm, Mode::Paper), Some(-6.0));
    // lpd == gmax is not below: one-sided, f = 12, gain = 12 - 12 - 5 = -5.
    assert_eq!(f_gmax(12.0, 5.0, gm, Mode::Paper), Some(12.0));
    assert_eq!(local_gain(12.0, 5.0, gm, Mode::Paper), Some(-5.0));
    assert_eq!(local_gain(5.0, 12.0, gm, Mode::Paper), Some(-5.0));
    // Both equal to gmax: neither below -> rejected.
    assert_eq!(f_gmax(12.0, 12.0, gm, Mode::Paper), None);
    assert_eq!(local_gain(12.0, 12.0, gm, Mode::Paper), None);
    // Both above: rejected.
    assert_eq!(local_gain(13.0, 14.0, gm, Mode::Paper), None);
    // Just below on both sides: 36 - 11.999 - 11.999 = 12.002.
    assert_close!(local_gain(11.999, 11.999, gm, Mode::Paper).unwrap(), 12.002, 1e-9);
    // Zero distances: the largest gain, 3·gmax = 36.
    assert_eq!(local_gain(0.0, 0.0, gm, Mode::Paper), Some(36.0));
}

#[test]
fn eq4_to_eq8_node_gain_from_attributes() {
    // Thresholds 10 and 14 -> gmax = 12 (eq. 8). Reference at 30.0, other at
    // 25.0 (left reference: d = 5, inside 0 < d < 60).
    // lpd = |10-12| + |20-17| + |30-30| = 5, rpd = |100-97| + |90-90| + |80-81| = 4:
    // both < 12 -> gain = 36 - 5 - 4 = 27.
    let gm = gmax(10.0, 14.0);
    let r = hand_declivity(30.0, [10, 20, 30], [100, 90, 80]);
    let o = hand_declivity(25.0, [12, 17, 30], [97, 90, 81]);
    assert_eq!(node_gain(&r, &o, gm, (0.0, 60.0), RefView::Left, Mode::Paper), Some(27.0));
    // rpd = 13 (other right = 95, 90, 88): one-sided -> 12 - 5 - 13 = -6.
    let o2 = hand_declivity(25.0, [12, 17, 30], [95, 90, 88]);
    assert_eq!(node_gain(&r, &o2, gm, (0.0, 60.0), RefView::Left, Mode::Paper), Some(-6.0));
    // lpd = 12 = gmax (other left = 22, 20, 30: 12 + 0 + 0) and rpd = 13:
    // neither below -> rejected.
    let o3 = hand_declivity(25.0, [22, 20, 30], [95, 90, 88]);
    assert_eq!(node_gain(&r, &o3, gm, (0.0, 60.0), RefView::Left, Mode::Paper), None);
}

// ===========================================================================
// Eq. 9: a 3×3 table solved by hand, and the tie-break
// ===========================================================================

/// The hand table (rows i = reference, columns j = other view):
/// ```text
///         j=0  j=1  j=2
///   i=0    5    .    1
///   i=1    .    4    .
///   i=2    2    .    6
/// ```
fn hand_table() -> GainTable {
    let cells = [[Some(5.0), None, Some(1.0)], [None, Some(4.0), None], [Some(2.0), None, Some(6.0)]];
    GainTable::from_fn(3, 3, |i, j| cells[i][j])
}

#[test]
fn eq9_literal_g_on_the_hand_table() {
    // G(0,0) = 5 + max(0, ∅) = 5; G(0,2) = 1 + max(0, ∅) = 1 (no m < 0);
    // G(1,1) = 4 + max(0, G(0,0)) = 9; G(2,0) = 2 + max(0, ∅) = 2 (no n < 0);
    // G(2,2) = 6 + max(0, G(0,0)=5, G(1,1)=9) = 15. Best gain 15.
    let g = literal_g(&hand_table());
    let want = [Some(5.0), None, Some(1.0), None, Some(9.0), None, Some(2.0), None, Some(15.0)];
    assert_eq!(g, want.to_vec());
    assert_eq!(literal_best_gain(&hand_table()), 15.0);
}

#[test]
fn eq9_prefix_max_tables_and_choices_on_the_hand_table() {
    // 1-based P with the border at 0; choices (S start, N node, U up, L left):
    // row 1: j1 G=5+P(0,0)=5 -> N, P=5; j2 no node, up 0, left 5 -> L, P=5;
    //        j3 G=1+P(0,2)=1 -> N(1) then left 5 > 1 -> L, P=5.
    // row 2: j1 no node, up P(1,1)=5 -> U, P=5; j2 G=4+P(1,1)=9 -> N, P=9
    //        (up 5, left 5 lose); j3 no node, up P(1,3)=5, left P(2,2)=9 -> L, P=9.
    // row 3: j1 G=2+P(2,0)=2 -> N(2), then up P(2,1)=5 -> U, P=5;
    //        j2 no node, up P(2,2)=9 -> U, P=9 (left 5 loses);
    //        j3 G=6+P(2,2)=15 -> N, P=15 (up 9, left 9 lose).
    use Choice::*;
    let t = prefix_max_dp(&hand_table());
    let p: Vec<f64> = (1..=3).flat_map(|i| (1..=3).map(move |j| (i, j))).map(|(i, j)| t.p_at(i, j)).collect();
    assert_eq!(p, vec![5.0, 5.0, 5.0, 5.0, 9.0, 9.0, 5.0, 9.0, 15.0]);
    let c: Vec<Choice> = (1..=3).flat_map(|i| (1..=3).map(move |j| (i, j))).map(|(i, j)| t.choice_at(i, j)).collect();
    assert_eq!(c, vec![Node, Left, Left, Up, Node, Left, Up, Up, Node]);
    // Border row and column are zero.
    for k in 0..=3 {
        assert_eq!(t.p_at(0, k), 0.0);
        assert_eq!(t.p_at(k, 0), 0.0);
    }
    assert_eq!(t.best_gain(), 15.0);
    // G at nodes equals the literal G: (1,1)->5, (1,3)->1, (2,2)->9, (3,1)->2, (3,3)->15.
    let g_at = |i: usize, j: usize| t.g[i * 4 + j]; // 1-based, 4 columns
    assert_eq!(g_at(1, 1), Some(5.0));
    assert_eq!(g_at(1, 3), Some(1.0));
    assert_eq!(g_at(2, 2), Some(9.0));
    assert_eq!(g_at(3, 1), Some(2.0));
    assert_eq!(g_at(3, 3), Some(15.0));
    // No G where there is no node.
    assert_eq!(g_at(1, 2), None);
    assert_eq!(g_at(2, 1), None);
}

#[test]
fn eq9_best_path_on_the_hand_table() {
    // Traceback from (3,3): N -> take (2,2), go to (2,2): N -> take (1,1),
    // go to (1,1): N -> take (0,0), go to (0,0): border, stop.
    let p = best_path(&hand_table());
    assert_eq!(p.nodes, vec![(0, 0), (1, 1), (2, 2)]);
    assert_eq!(p.gain, 15.0);
}

#[test]
fn eq9_banded_dp_on_a_hand_banded_table() {
    // The hand table without node (2,0) (it is not banded: row 2 would have
    // to start before row 1). Bands: row 0 columns 0..3 = [5, -, 1];
    // row 1 columns 1..3 = [4, -]; row 2 columns 2..3 = [6].
    // Same best path (0,0),(1,1),(2,2) with gain 5 + 4 + 6 = 15.
    let b = BandedGains::from_rows(
        3,
        &[
            BandRow { lo: 0, gains: vec![Some(5.0), None, Some(1.0)] },
            BandRow { lo: 1, gains: vec![Some(4.0), None] },
            BandRow { lo: 2, gains: vec![Some(6.0)] },
        ],
    );
    let p = banded_dp(&b);
    assert_eq!(p.nodes, vec![(0, 0), (1, 1), (2, 2)]);
    assert_eq!(p.gain, 15.0);
    // With an empty band in the middle: row 0 = [5, -] at columns 0..2
    // (lo + len = 2), row 1 empty with lo = 2 (lo + len = 2), row 2 = [6] at
    // column 2 (lo + len = 3). The only chain of two nodes is (0,0), (2,2):
    // gain 5 + 6 = 11.
    let b = BandedGains::from_rows(
        3,
        &[
            BandRow { lo: 0, gains: vec![Some(5.0), None] },
            BandRow { lo: 2, gains: vec![] },
            BandRow { lo: 2, gains: vec![Some(6.0)] },
        ],
    );
    let p = banded_dp(&b);
    assert_eq!(p.nodes, vec![(0, 0), (2, 2)]);
    assert_eq!(p.gain, 11.0);
    // A path through the region right of a band (the tail T):
    // row 0 = [-, 7] at columns 0..2, row 1 = [3] at column 2 of m = 3:
    // (0,1)=7 then (1,2)=3 -> 10.
    let b = BandedGains::from_rows(
        3,
        &[BandRow { lo: 0, gains: vec![None, Some(7.0)] }, BandRow { lo: 2, gains: vec![Some(3.0)] }],
    );
    let p = banded_dp(&b);
    assert_eq!(p.nodes, vec![(0, 1), (1, 2)]);
    assert_eq!(p.gain, 10.0);
}

#[test]
fn eq9_tie_break_start_beats_zero_and_negative_nodes() {
    // A single node of gain 0: P = max(0 [start], 0 [node, not > 0]) -> Start,
    // empty path of gain 0. Same with a negative node.
    for g in [0.0, -3.0] {
        let t = GainTable::from_fn(1, 1, |_, _| Some(g));
        let p = best_path(&t);
        assert!(p.nodes.is_empty(), "gain {g}: {:?}", p.nodes);
        assert_eq!(p.gain, 0.0);
        assert_eq!(prefix_max_dp(&t).choice_at(1, 1), Choice::Start);
        assert_eq!(literal_best_gain(&t), 0.0);
    }
    // An isolated zero-gain node next to a positive one: (0,0) = 0,
    // (1,1) = 3. P(1,1) = 0 (S: the node's G = 0 is not > 0), so the path
    // is (1,1) alone, gain 3.
    let t = GainTable::from_fn(2, 2, |i, j| (i == j).then_some(if i == 0 { 0.0 } else { 3.0 }));
    let p = best_path(&t);
    assert_eq!(p.nodes, vec![(1, 1)]);
    assert_eq!(p.gain, 3.0);
}

#[test]
fn eq9_tie_break_zero_gain_node_extending_a_path_joins_it() {
    // Diagonal (0,0) = 2, (1,1) = 0, (2,2) = 2. The order start, node, up,
    // left with strict > gives at cell (2,2): node G = 0 + P(1,1) = 2 > 0
    // -> N; up P(1,2) = 2 and left P(2,1) = 2 are not > 2 -> stays N.
    // Cell (3,3): G = 2 + P(2,2) = 4 -> N. Traceback takes all three nodes:
    // (0,0), (1,1), (2,2), gain 2 + 0 + 2 = 4. (A zero-gain node joins a
    // path when its G ties with `up`/`left`; only an isolated one — G = 0
    // against start — is left out.)
    let t = GainTable::from_fn(3, 3, |i, j| (i == j).then_some(if i == 1 { 0.0 } else { 2.0 }));
    let tables = prefix_max_dp(&t);
    assert_eq!(tables.choice_at(2, 2), Choice::Node);
    let p = best_path(&t);
    assert_eq!(p.nodes, vec![(0, 0), (1, 1), (2, 2)]);
    assert_eq!(p.gain, 4.0);
}

#[test]
fn eq9_tie_break_node_beats_up() {
    // 2×1 table: (0,0) = 3, (1,0) = 3. Row 2, j1: G = 3 + P(1,0) = 3 (node),
    // up P(1,1) = 3 is not > 3 -> Node: the path takes (1,0).
    let t = GainTable::from_fn(2, 1, |_, _| Some(3.0));
    let tables = prefix_max_dp(&t);
    assert_eq!(tables.choice_at(2, 1), Choice::Node);
    let p = best_path(&t);
    assert_eq!(p.nodes, vec![(1, 0)]);
    assert_eq!(p.gain, 3.0);
    // 2×2: (0,0)=2, (0,1)=4, (1,1)=2. Cell (2,2): node G = 2 + P(1,1) = 4,
    // up P(1,2) = 4 -> Node: path (0,0),(1,1) rather than (0,1), both 4.
    let cells = [[Some(2.0), Some(4.0)], [None, Some(2.0)]];
    let t = GainTable::from_fn(2, 2, |i, j| cells[i][j]);
    let p = best_path(&t);
    assert_eq!(p.nodes, vec![(0, 0), (1, 1)]);
    assert_eq!(p.gain, 4.0);
}

#[test]
fn eq9_tie_break_node_beats_left() {
    // 1×2 table: (0,0) = 3, (0,1) = 3. Cell (1,2): node G = 3 + P(0,1) = 3,
    // left P(1,1) = 3 is not > 3 -> Node: the path takes (0,1).
    let t = GainTable::from_fn(1, 2, |_, _| Some(3.0));
    assert_eq!(prefix_max_dp(&t).choice_at(1, 2), Choice::Node);
    let p = best_path(&t);
    assert_eq!(p.nodes, vec![(0, 1)]);
    assert_eq!(p.gain, 3.0);
}

#[test]
fn eq9_tie_break_up_beats_left() {
    // 2×2 anti-diagonal: (0,1) = 4, (1,0) = 4.
    // P(1,1) = 0 (S), P(1,2) = 4 (N), P(2,1) = 4 (N). Cell (2,2): no node,
    // up P(1,2) = 4, left P(2,1) = 4 not > 4 -> Up. Traceback: (2,2) U ->
    // (1,2) N takes (0,1) -> (0,1) border: path (0,1), not (1,0).
    let cells = [[None, Some(4.0)], [Some(4.0), None]];
    let t = GainTable::from_fn(2, 2, |i, j| cells[i][j]);
    let tables = prefix_max_dp(&t);
    assert_eq!(tables.choice_at(1, 1), Choice::Start);
    assert_eq!(tables.choice_at(2, 2), Choice::Up);
    let p = best_path(&t);
    assert_eq!(p.nodes, vec![(0, 1)]);
    assert_eq!(p.gain, 4.0);
    // The anti-diagonal is not banded (lo would decrease), so check the same
    // tie in a banded layout: m = 2, row 0 = [4] at column 0, row 1 = [4] at
    // column 0. P(1,1) = 4 (N), P(1,2) = 4 (L: left 4 > 0);
    // P(2,1): G = 4 + P(1,0) = 4 (N), up P(1,1) = 4 not > 4 -> N;
    // P(2,2): no node, up P(1,2) = 4 -> U, left P(2,1) = 4 not > 4.
    // Traceback: (2,2) U -> (1,2) L -> (1,1) N takes (0,0). Path (0,0);
    // had left won at (2,2), it would have been (1,0).
    let b = BandedGains::from_rows(
        2,
        &[BandRow { lo: 0, gains: vec![Some(4.0)] }, BandRow { lo: 0, gains: vec![Some(4.0)] }],
    );
    let p = banded_dp(&b);
    assert_eq!(p.nodes, vec![(0, 0)]);
    assert_eq!(p.gain, 4.0);
    assert_eq!(best_path(&b.to_table()), p);
    let tables = prefix_max_dp(&b.to_table());
    assert_eq!(tables.choice_at(2, 1), Choice::Node);
    assert_eq!(tables.choice_at(2, 2), Choice::Up);
}

#[test]
fn eq9_empty_tables() {
    for (n, m) in [(0, 0), (0, 3), (3, 0)] {
        let t = GainTable::new(n, m);
        let p = best_path(&t);
        assert!(p.nodes.is_empty());
        assert_eq!(p.gain, 0.0);
        assert_eq!(literal_best_gain(&t), 0.0);
    }
    // No node at all in a 3×3 table.
    let p = best_path(&GainTable::new(3, 3));
    assert!(p.nodes.is_empty());
    assert_eq!(p.gain, 0.0);
    let p = banded_dp(&BandedGains::new(0));
    assert!(p.nodes.is_empty());
    assert_eq!(p.gain, 0.0);
}

// ===========================================================================
// Interpolation
// ===========================================================================

#[test]
fn interpolation_linear_between_anchors_with_hold_ends() {
    // Anchors (2.0, 10) and (6.0, 14): slope 1 per pixel.
    // x = 0, 1 -> hold 10; x = 2..6 -> 10, 11, 12, 13, 14; x = 7, 8 -> hold 14.
    let a = [Anchor { x: 2.0, d: 10.0 }, Anchor { x: 6.0, d: 14.0 }];
    let v = interpolate_line(&a, 9, EndRule::Hold);
    assert_eq!(v.len(), 9);
    let want = [10.0, 10.0, 10.0, 11.0, 12.0, 13.0, 14.0, 14.0, 14.0];
    for (x, (&got, &w)) in v.iter().zip(&want).enumerate() {
        assert_close!(got, w, 1e-12);
        let _ = x;
    }
}

#[test]
fn interpolation_empty_ends_leave_zero_outside_the_anchors() {
    // Same anchors, EndRule::Empty: x = 0, 1, 7, 8 -> 0.
    let a = [Anchor { x: 2.0, d: 10.0 }, Anchor { x: 6.0, d: 14.0 }];
    let v = interpolate_line(&a, 9, EndRule::Empty);
    let want = [0.0, 0.0, 10.0, 11.0, 12.0, 13.0, 14.0, 0.0, 0.0];
    for (&got, &w) in v.iter().zip(&want) {
        assert_close!(got, w, 1e-12);
    }
}

#[test]
fn interpolation_at_sub_pixel_anchors() {
    // Anchors (1.5, 4) and (3.5, 8): slope 2 per pixel.
    // x = 2: 4 + 4·(0.5/2) = 5; x = 3: 4 + 4·(1.5/2) = 7.
    // Hold: x = 0, 1 (< 1.5) -> 4; x = 4, 5 (> 3.5) -> 8.
    // Empty: x = 0, 1, 4, 5 -> 0.
    let a = [Anchor { x: 1.5, d: 4.0 }, Anchor { x: 3.5, d: 8.0 }];
    let hold = interpolate_line(&a, 6, EndRule::Hold);
    for (&got, &w) in hold.iter().zip(&[4.0, 4.0, 5.0, 7.0, 8.0, 8.0]) {
        assert_close!(got, w, 1e-12);
    }
    let empty = interpolate_line(&a, 6, EndRule::Empty);
    for (&got, &w) in empty.iter().zip(&[0.0, 0.0, 5.0, 7.0, 0.0, 0.0]) {
        assert_close!(got, w, 1e-12);
    }
    // Three anchors with a descent: (0, 6), (2, 2), (4, 3):
    // x = 1 -> 4; x = 3 -> 2.5.
    let a = [Anchor { x: 0.0, d: 6.0 }, Anchor { x: 2.0, d: 2.0 }, Anchor { x: 4.0, d: 3.0 }];
    let v = interpolate_line(&a, 5, EndRule::Empty);
    for (&got, &w) in v.iter().zip(&[6.0, 4.0, 2.0, 2.5, 3.0]) {
        assert_close!(got, w, 1e-12);
    }
}

#[test]
fn interpolation_with_no_anchor_or_one_anchor() {
    // No match: the line stays empty whatever the end rule.
    assert_eq!(interpolate_line(&[], 5, EndRule::Hold), vec![0.0; 5]);
    assert_eq!(interpolate_line(&[], 5, EndRule::Empty), vec![0.0; 5]);
    // One anchor at x = 3: Hold fills the line with its disparity; Empty
    // keeps only pixel 3.
    let a = [Anchor { x: 3.0, d: 7.5 }];
    assert_eq!(interpolate_line(&a, 6, EndRule::Hold), vec![7.5; 6]);
    assert_eq!(interpolate_line(&a, 6, EndRule::Empty), vec![0.0, 0.0, 0.0, 7.5, 0.0, 0.0]);
    // One anchor at x = 2.5 (between pixel centres): Empty leaves every
    // pixel empty ([2.5, 2.5] holds no pixel centre).
    let a = [Anchor { x: 2.5, d: 7.5 }];
    assert_eq!(interpolate_line(&a, 6, EndRule::Empty), vec![0.0; 6]);
    assert_eq!(interpolate_line(&a, 6, EndRule::Hold), vec![7.5; 6]);
}

// ===========================================================================
// Eq. 1: depth and 3-D point
// ===========================================================================

#[test]
fn eq1_depth_is_focal_times_baseline_over_disparity() {
    // f = 1000 px, b = 0.1 m, D = 20 px: Z = 1000·0.1/20 = 5 m.
    let cam = Camera { focal_px: 1000.0, baseline_m: 0.1, cx: 0.0, cy: 0.0 };
    assert_close!(depth(20.0, &cam).unwrap(), 5.0, 1e-12);
    // D = 40 -> 2.5 m; D = 0.5 -> 200 m.
    assert_close!(depth(40.0, &cam).unwrap(), 2.5, 1e-12);
    assert_close!(depth(0.5, &cam).unwrap(), 200.0, 1e-9);
    // No depth for D <= 0.
    assert_eq!(depth(0.0, &cam), None);
    assert_eq!(depth(-1.0, &cam), None);
    // The paper's rig: f = 8 mm on a 10 µm pitch = 800 px, b = 8 cm,
    // D = 16 px -> Z = 800·0.08/16 = 4 m.
    let rig = Camera { focal_px: 0.008 / 10e-6, baseline_m: 0.08, cx: 0.0, cy: 0.0 };
    assert_close!(depth(16.0, &rig).unwrap(), 4.0, 1e-9);
}

#[test]
fn eq1_point_from_pixel_and_disparity() {
    // A 641×481 image has its principal point at (320, 240).
    let cam = Camera::centred(1000.0, 0.1, 641, 481);
    assert_close!(cam.cx, 320.0, 1e-12);
    assert_close!(cam.cy, 240.0, 1e-12);
    // Pixel (420, 140), D = 20: X = (420-320)·0.1/20 = 0.5 m,
    // Y = (140-240)·0.1/20 = -0.5 m, Z = 5 m.
    let p = point(420.0, 140.0, 20.0, &cam).unwrap();
    assert_close!(p[0], 0.5, 1e-12);
    assert_close!(p[1], -0.5, 1e-12);
    assert_close!(p[2], 5.0, 1e-12);
    // The principal point lies on the optical axis.
    let p = point(320.0, 240.0, 10.0, &cam).unwrap();
    assert_close!(p[0], 0.0, 1e-12);
    assert_close!(p[1], 0.0, 1e-12);
    assert_close!(p[2], 10.0, 1e-12);
    assert_eq!(point(420.0, 140.0, 0.0, &cam), None);
}

// ===========================================================================
// A pair of short lines through the whole method
// ===========================================================================

/// Left line (24 px): 50 on x = 0..5, a two-pixel rise through 100 at x = 6
/// to 150 on x = 7..12, a step down to 60 on x = 13..23.
fn hand_left() -> Vec<u8> {
    let mut l = vec![50u8; 24];
    l[6] = 100;
    l[7..13].fill(150);
    l[13..].fill(60);
    l
}

/// Right line: the left one shifted by 4 (`right[x] = left[x + 4]`, the end
/// filled with 60), plus a bump to 200 at x = 20 that has no partner.
fn hand_right() -> Vec<u8> {
    let l = hand_left();
    let mut r: Vec<u8> = (0..24).map(|x| if x + 4 < 24 { l[x + 4] } else { 60 }).collect();
    r[20] = 200;
    r
}

#[test]
fn process_line_hand_pair_matches_the_shifted_edges() {
    let (left, right) = (hand_left(), hand_right());
    assert_eq!(&right[..12], &[50, 50, 100, 150, 150, 150, 150, 150, 150, 60, 60, 60]);
    // Left: g(5) = +50, g(6) = +50, g(12) = -90, the rest 0 (23 differences,
    // 20 zero). σ: m = 0.5·11.5/20 = 0.2875 -> σ = 0.301 40, d_t = 1.687 86.
    // Declivities: (5, 7) amplitude +100, X = (2500·5.5 + 2500·6.5)/5000 = 6.0,
    // left [50,50,50], right [150,150,150]; (12, 13) amplitude -90, X = 12.5,
    // left [150,150,150], right [60,60,60].
    // Right: g(1) = g(2) = +50, g(8) = -90, g(19) = +140, g(20) = -140
    // (23 differences, 18 zero). σ: m = 0.5·11.5/18 = 0.319 44 ->
    // σ = 0.334 89, d_t = 1.875 40. Declivities: (1, 3) X = 2.0,
    // (8, 9) X = 8.5, (19, 20) X = 19.5, (20, 21) X = 20.5.
    // gmax = 0.5·(1.687 86 + 1.875 40) = 1.781 63.
    // Nodes with dispmax = 10.5 (left reference, d = X_left - X_right):
    //   (0,0) d = 4 ✓ lpd = rpd = 0 -> gain 3·gmax = 5.344 88;
    //   (1,0) d = 10.5 = dispmax ✗; (1,1) d = 4 ✓ gain 3·gmax;
    //   every other pair has d <= 0 ✗.
    // Path (0,0), (1,1); gain 6·gmax = 10.689 76; both disparities 4.
    let mut params = Params::paper(10.5).unwrap();
    let res = process_line(&left, &right, &params);
    assert_close!(res.reference.sigma, 0.2875 / MAD_SQRT2);
    assert_close!(res.reference.dt, 1.687_86, 1e-5);
    assert_close!(res.other.dt, 1.875_40, 1e-5);
    let lpos: Vec<f64> = res.reference.declivities.iter().map(|d| d.position).collect();
    let rpos: Vec<f64> = res.other.declivities.iter().map(|d| d.position).collect();
    assert_eq!(lpos, vec![6.0, 12.5]);
    assert_eq!(rpos, vec![2.0, 8.5, 19.5, 20.5]);
    let pairs: Vec<(usize, usize)> = res.matches.iter().map(|m| (m.ref_index, m.other_index)).collect();
    assert_eq!(pairs, vec![(0, 0), (1, 1)]);
    let gm = 0.5 * 5.6 * (0.2875 + 0.5 * 11.5 / 18.0) / MAD_SQRT2;
    assert_close!(gm, 1.781_63, 1e-5);
    for m in &res.matches {
        assert_close!(m.disparity, 4.0);
        assert_close!(m.gain, 3.0 * gm);
    }
    assert_close!(res.path_gain, 6.0 * gm);

    // dispmax = 11: node (1,0) now exists (d = 10.5 < 11), but lpd =
    // 3·|150-50| = 300 and rpd = 3·|60-150| = 270 are both >= gmax: rejected.
    // Same path.
    params.dispmax = 11.0;
    let res = process_line(&left, &right, &params);
    let pairs: Vec<(usize, usize)> = res.matches.iter().map(|m| (m.ref_index, m.other_index)).collect();
    assert_eq!(pairs, vec![(0, 0), (1, 1)]);

    // dispmax = 4: d = 4 is not < 4, no node at all -> no match, gain 0.
    params.dispmax = 4.0;
    let res = process_line(&left, &right, &params);
    assert!(res.matches.is_empty());
    assert_eq!(res.path_gain, 0.0);
}

#[test]
fn process_line_hand_pair_with_right_reference() {
    // Reference = right line: its declivities X = 2.0, 8.5, 19.5, 20.5; other
    // = left: 6.0, 12.5. d = X_left - X_right: (0,0) 4 ✓; (0,1) 10.5 =
    // dispmax ✗; (1,1) 4 ✓; the rest have d <= 0 ✗.
    // Matches: right 0 <-> left 0, right 1 <-> left 1, both at d = 4.
    let mut params = Params::paper(10.5).unwrap();
    params.ref_view = RefView::Right;
    let res = process_line(&hand_left(), &hand_right(), &params);
    let pairs: Vec<(usize, usize)> = res.matches.iter().map(|m| (m.ref_index, m.other_index)).collect();
    assert_eq!(pairs, vec![(0, 0), (1, 1)]);
    for m in &res.matches {
        assert_close!(m.disparity, 4.0);
    }
    assert_eq!(res.matches[0].x_ref, 2.0);
    assert_eq!(res.matches[0].x_other, 6.0);
}

#[test]
fn process_frame_one_row_dense_disparity_of_the_hand_pair() {
    // Anchors (6.0, 4) and (12.5, 4): Hold gives 4 at every pixel; Empty gives
    // 4 on x = 6..12 and 0 elsewhere.
    let l = GreyImage::new(24, 1, hand_left()).unwrap();
    let r = GreyImage::new(24, 1, hand_right()).unwrap();
    let mut params = Params::paper(10.5).unwrap();
    let res = process_frame(&l, &r, &params, Threads::One).unwrap();
    assert_eq!(res.matches(), 2);
    assert_eq!(res.reference_declivities(), 2);
    assert_eq!(res.disparity, vec![4.0; 24]);
    params.ends = EndRule::Empty;
    let res = process_frame(&l, &r, &params, Threads::One).unwrap();
    let want: Vec<f64> = (0..24).map(|x| if (6..=12).contains(&x) { 4.0 } else { 0.0 }).collect();
    assert_eq!(res.disparity, want);
}

#[test]
fn params_and_frame_inputs_are_validated() {
    // eq. 6 needs room for 0 < d < dispmax: dispmax must exceed 1.
    assert!(Params::paper(1.0).is_err());
    assert!(Params::paper(f64::NAN).is_err());
    assert!(Params::paper(f64::INFINITY).is_err());
    assert!(Params::paper(1.5).is_ok());
    assert!(GreyImage::new(3, 2, vec![0; 5]).is_err());
    assert!(GreyImage::new(0, 0, vec![]).is_err());
    let a = GreyImage::new(3, 2, vec![0; 6]).unwrap();
    let b = GreyImage::new(2, 3, vec![0; 6]).unwrap();
    assert!(process_frame(&a, &b, &Params::paper(5.0).unwrap(), Threads::One).is_err());
}
