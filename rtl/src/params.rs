//! Generation-time parameters of the hardware and the fixed-point formats
//! derived from them.
//!
//! rust-hdl widths are const generics, and stable Rust cannot compute one
//! const generic from another, so the sizes are constants here, derived
//! from the two of the crate's configuration ([`crate::config`]: `W_MAX`
//! and `N_MAX`): every width below follows from them. The same sources
//! build one crate per configuration (`rtl` is `sd`, `rtl-hd` is `hd`).

/// Bits of a grey level (8-bit images).
pub const PIXEL_BITS: usize = 8;

/// The configuration's name (`sd`, `hd`).
pub const CONFIG: &str = crate::config::NAME;

/// log2 of the maximum line width `W_MAX`.
pub(crate) const W_MAX_BITS: usize = crate::config::W_MAX_BITS;
/// `W_MAX`: the widest line the detector stores (pixels beyond it are
/// dropped and the line is flagged; see [`crate::detector::declivity_detector`]).
pub const W_MAX: usize = 1 << W_MAX_BITS;
/// Bits of a pixel index `x < W_MAX`.
pub(crate) const X_BITS: usize = W_MAX_BITS;
/// Address bits of the ping-pong line buffer: one bank bit above `x`.
pub const LINE_BUF_ADDR_BITS: usize = W_MAX_BITS + 1;

/// `N_MAX`: characteristic declivities kept per line; the later ones of a
/// line are dropped and the line is flagged. A line of the eight Middlebury
/// pairs has at most 117 (motorcycle, 741 px wide), so `sd`'s 128 covers
/// every row with room to spare; up-scaled 2x (1482 px) the most is 155, in
/// `hd`'s 256.
pub const N_MAX: usize = 1 << crate::config::N_MAX_BITS;
/// Bits of a per-line declivity count `0 ..= N_MAX`.
pub(crate) const COUNT_BITS: usize = crate::config::N_MAX_BITS + 1;

/// Bins of the |ΔI| histogram (one per grey-level difference).
pub(crate) const HIST_BINS: usize = 1 << PIXEL_BITS;
/// Address bits of the histogram.
pub const HIST_ADDR_BITS: usize = PIXEL_BITS;
/// Bits of a histogram count or a running sum of counts: up to
/// `W_MAX - 1` differences per line, doubled in the median test.
pub const HIST_COUNT_BITS: usize = W_MAX_BITS + 2;

/// Fraction bits of the median's in-bin interpolation `(n/2 - below)/h`.
pub const MEDIAN_FRAC_BITS: usize = 15;
/// Bits of that fraction: it can be exactly 1.
pub(crate) const MEDIAN_Q_BITS: usize = MEDIAN_FRAC_BITS + 1;

/// Fraction bits of `d_t` (the threshold is within one LSB, 1/32 grey level,
/// of golden's f64 value).
pub const DT_FRAC_BITS: usize = 5;
/// Bits of `d_t`: it reaches `5.6/(0.6745·√2) · 255.5 ≈ 1500` grey levels.
pub(crate) const DT_BITS: usize = 16;
/// Bits of the integer threshold `⌊d_t⌋`.
pub(crate) const DT_INT_BITS: usize = DT_BITS - DT_FRAC_BITS;

/// The factor from the median of |ΔI| to `d_t`: `5.6 / (0.6745·√2)`
/// (eq. 2 with the MAD estimator of `DESIGN.md` §2.1).
pub const THRESHOLD_PER_MEDIAN: f64 = 5.6 / (0.674_489_750_196_081_7 * std::f64::consts::SQRT_2);
/// Fraction bits of `d_t` inside the threshold engine before rounding.
pub const DT_ACC_FRAC_BITS: usize = 20;
/// Bits of the threshold engine's accumulator (`d_t · 2^20 < 2^31`).
pub(crate) const DT_ACC_BITS: usize = 32;
/// `round(K · 2^19)`: `K·(v - ½)·2^20 = (2v - 1)·K_HALF`, added twice per bin
/// during the histogram scan.
pub const K_HALF: u64 = 3_077_993;
/// Fraction bits of [`K_FRAC`].
pub const K_FRAC_BITS: usize = 13;
/// `round(K · 2^13)`: multiplies the in-bin fraction (16×16 product).
pub const K_FRAC: u64 = 48_094;
/// The σ floor of eq. 2's estimator (`1/√12`) as a `d_t` in fixed point:
/// `round(5.6/√12 · 2^5)`.
pub const DT_FLOOR: u64 = 52;

/// Fraction bits of a declivity position `X_i` (eq. 3).
pub const POS_FRAC_BITS: usize = 4;
/// Bits of a position `X_i < W_MAX`.
pub const POS_BITS: usize = W_MAX_BITS + POS_FRAC_BITS;
/// Bits of a signed amplitude `a_i ∈ [-255, 255]` (two's complement).
pub(crate) const AMP_BITS: usize = PIXEL_BITS + 1;
/// Bits of `Σ g²` over one declivity: its gradients share a sign and add up
/// to at most 255, so `Σ g² ≤ 255²`.
pub(crate) const S0_BITS: usize = 2 * PIXEL_BITS;
/// Bits of `Σ g²·(2x + 1)`: `Σ g² · (2 W_MAX - 1)`.
pub(crate) const S1_BITS: usize = S0_BITS + W_MAX_BITS + 1;
/// Bits of the eq. 3 dividend `Σ g²(2x+1) · 2^(POS_FRAC_BITS-1)`.
pub(crate) const DIVIDEND_BITS: usize = S1_BITS + POS_FRAC_BITS - 1;

// ---- The matcher (paper §III–IV, eq. 4–9).

/// Bits of a declivity index `0 .. N_MAX` in a line (row `i`, column `j`).
pub const INDEX_BITS: usize = crate::config::N_MAX_BITS;
/// Bits of an anti-diagonal index `i + j ≤ 2 (N_MAX - 1)` of the matching
/// table.
pub const DIAG_BITS: usize = INDEX_BITS + 1;
/// Bits of a neighbour level as the matcher compares it: `2·I - e + 512`,
/// where `e` is the declivity's end-level sum `I(x_i) + I(x_{i+1})` in the
/// offset-compensated rule and 0 in the paper's. Doubling keeps the
/// compensated levels integers; the offset makes them non-negative
/// (`[2, 1022]`), so that a distance is a plain unsigned difference.
pub const LEVEL_BITS: usize = PIXEL_BITS + 2;
/// The offset of [`LEVEL_BITS`] levels.
pub(crate) const LEVEL_OFFSET: u64 = 1 << (PIXEL_BITS + 1);
/// Bits of a doubled photometric distance `2·lpd` or `2·rpd` (eq. 4–5):
/// three differences of at most `2·510`.
pub(crate) const DIST_BITS: usize = 12;
/// Bits of the doubled distances subtracted from `f(gmax)` (at most both
/// sides).
pub(crate) const DIST_SUM_BITS: usize = DIST_BITS + 1;
/// Fraction bits of `d_t` as the matcher uses it: the detector's `d_t`
/// rounded down to 1/2 grey level. (A threshold of typically 20–100 grey
/// levels moves by less than half a level; golden's hardware-parity matcher
/// rounds the same way. Four fraction bits fewer narrow every gain and path
/// register of the array by four bits.)
pub const MATCH_DT_FRAC_BITS: usize = 1;
/// Integer bits of that `d_t`: it saturates at `2^PIXEL_BITS - 1/2` grey
/// levels. A line whose `d_t` is 255 or more has no declivity (eq. 1:
/// `|a_i| > d_t`, and an amplitude of 8-bit pixels is at most 255), so no
/// node of its pair exists and the saturation changes no match; it bounds
/// `gmax`, and with it every gain and path register of the array.
const MATCH_DT_INT_BITS: usize = PIXEL_BITS;
/// Bits of that `d_t`.
pub const MATCH_DT_BITS: usize = MATCH_DT_INT_BITS + MATCH_DT_FRAC_BITS;
/// Fraction bits of a gain: the unit is `2^-(MATCH_DT_FRAC_BITS + 1)` grey
/// levels, so `2·gmax = d_t,ref + d_t,other` (eq. 8) is exact and every
/// local gain of eq. 7 is an integer in this unit.
pub(crate) const GAIN_FRAC_BITS: usize = MATCH_DT_FRAC_BITS + 1;
/// Bits of the largest local gain, `3·gmax < 3·2^MATCH_DT_INT_BITS` grey
/// levels (unsigned).
const GAIN_MAX_BITS: usize = MATCH_DT_INT_BITS + 2 + GAIN_FRAC_BITS;
/// Bits of a local gain (two's complement): below `2^GAIN_MAX_BITS` above,
/// `-(2·lpd + 2·rpd)/2 > -2^DIST_BITS` grey levels below.
pub(crate) const GAIN_BITS: usize = max_usize(GAIN_MAX_BITS, DIST_BITS + GAIN_FRAC_BITS) + 1;
/// Bits of a path gain `P(i, j) ≥ 0`: at most `N_MAX` nodes of the largest
/// gain.
pub(crate) const PATH_BITS: usize = GAIN_MAX_BITS + INDEX_BITS;
/// Bits of `G(i, j) = g + P(i-1, j-1)` (two's complement).
pub(crate) const SCORE_BITS: usize = PATH_BITS + 1;
/// A line's marker carries to the matcher the clock it left its detector
/// on, in ticks of `2^STAMP_SHIFT` clocks: the matcher pairs two frame
/// starts only when they are close in time (its Pairing).
pub const STAMP_SHIFT: usize = 6;
/// Bits of the time stamp: it wraps every `2^(STAMP_BITS + STAMP_SHIFT)`
/// clocks (4 M, 34 ms at 125 MHz, two frames at 60 Hz), and two stamps are
/// compared modulo that.
pub const STAMP_BITS: usize = 16;
/// `SOF_SKEW_MAX`: two frame starts whose markers left their detectors at
/// most this many clocks apart (two lines of `W_MAX`) are paired; more than
/// `SOF_SKEW_MAX + 2^STAMP_SHIFT` apart, the older is dropped (in between,
/// either, by the ticks they fall in).
pub const SOF_SKEW_MAX: usize = 2 * W_MAX;
/// [`SOF_SKEW_MAX`] in ticks.
pub(crate) const SKEW_TICKS: usize = SOF_SKEW_MAX >> STAMP_SHIFT;
const _: () = assert!(SKEW_TICKS << STAMP_SHIFT == SOF_SKEW_MAX && 2 * SKEW_TICKS < 1 << STAMP_BITS);

/// Bits of the search bound `dispmax` of eq. 6, in the position format
/// ([`POS_FRAC_BITS`] fraction bits); larger bounds are clamped to the
/// largest, which no disparity inside a line reaches.
pub const DISPMAX_BITS: usize = POS_BITS;

/// The larger of two widths (for constants).
const fn max_usize(a: usize, b: usize) -> usize {
    if a > b {
        a
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_are_the_rounded_reals() {
        let k = THRESHOLD_PER_MEDIAN;
        assert_eq!(K_HALF, (k * (1u64 << (DT_ACC_FRAC_BITS - 1)) as f64).round() as u64);
        assert_eq!(K_FRAC, (k * (1u64 << K_FRAC_BITS) as f64).round() as u64);
        assert_eq!(DT_FLOOR, (5.6 / 12f64.sqrt() * (1u64 << DT_FRAC_BITS) as f64).round() as u64);
        // The widths hold their worst cases.
        // The accumulator at the top bin plus the largest fraction term, and
        // the 16×16 product of the fraction.
        let top = (2 * (HIST_BINS as u64 - 1) - 1) * K_HALF;
        let frac = (1u64 << MEDIAN_FRAC_BITS) * K_FRAC;
        assert!(frac < 1 << 32);
        assert!(top + (frac >> (MEDIAN_FRAC_BITS + K_FRAC_BITS - DT_ACC_FRAC_BITS)) < 1u64 << (DT_ACC_BITS - 1));
        assert!((k * 255.5 * (1u64 << DT_FRAC_BITS) as f64) < (1u64 << DT_BITS) as f64);
        assert!(255u64 * 255 < 1 << S0_BITS);
        assert!(255u64 * 255 * (2 * W_MAX as u64 - 1) < 1 << S1_BITS);
        assert!(DIVIDEND_BITS <= 32 && POS_BITS <= 32);
        assert!(N_MAX < 1 << COUNT_BITS);
        // The matcher's formats hold their worst cases.
        assert_eq!(N_MAX, 1 << INDEX_BITS);
        assert!(2 * (N_MAX - 1) < 1 << DIAG_BITS);
        assert!(LEVEL_OFFSET + 2 * 255 < 1 << LEVEL_BITS && LEVEL_OFFSET >= 2 * 255);
        assert!(3 * 2 * 510 < 1 << DIST_BITS);
        // f(gmax) at most 3·gmax = 3·(d_t,ref + d_t,other)/2 in gain units,
        // each d_t at most the largest of MATCH_DT_BITS.
        let gain_max = 3 * 2 * ((1u64 << MATCH_DT_BITS) - 1);
        // The saturated d_t is at least 255 grey levels: no amplitude of
        // 8-bit pixels exceeds it, so a line at it has no declivity.
        assert!((1u64 << MATCH_DT_BITS) - 1 >= 255 << MATCH_DT_FRAC_BITS);
        assert_eq!(GAIN_FRAC_BITS, MATCH_DT_FRAC_BITS + 1);
        assert!(MATCH_DT_FRAC_BITS <= DT_FRAC_BITS);
        let gain_min = (1u64 << GAIN_FRAC_BITS) / 2 * 2 * 3 * 2 * 510;
        assert!(gain_max < 1 << (GAIN_BITS - 1) && gain_min <= 1 << (GAIN_BITS - 1));
        assert!(N_MAX as u64 * gain_max < 1 << PATH_BITS);
    }
}

/// Bits of a line width `1 ..= W_MAX` or of a pixel boundary `0 ..= W_MAX`
/// (the first pixel centre at or after a position).
pub const WIDTH_BITS: usize = W_MAX_BITS + 1;
/// The edge jump of golden's default mode (`golden::params::EDGE_JUMP`,
/// 6 px) in [`POS_FRAC_BITS`] fixed point: the interpolator does not bridge
/// two matches whose disparities differ by more.
pub const EDGE_JUMP_LSB: u64 = 6 << POS_FRAC_BITS;
/// Fraction bits of the interpolator's weight `t = (x - X_a) / (X_b - X_a)`
/// between two matches.
pub const WEIGHT_FRAC_BITS: usize = 16;
/// Index bits of the interpolator's reciprocal table: `1 / (X_b - X_a)` from
/// the distance's [`RECIP_INDEX_BITS`] bits after its leading one (relative
/// error below `2^-(RECIP_INDEX_BITS + 1) + 2^-15`).
pub const RECIP_INDEX_BITS: usize = 9;
/// Bits of a reciprocal table entry.
pub const RECIP_BITS: usize = 16;
/// A table entry is `2^RECIP_SHIFT / m` for a distance `m` normalised to
/// `[2^(POS_BITS-1), 2^POS_BITS)`: between `2^(RECIP_BITS-1)` and
/// `2^RECIP_BITS`.
pub const RECIP_SHIFT: usize = POS_BITS - 1 + RECIP_BITS;
/// Address bits of the interpolator's segment memory (`2^SEG_ADDR_BITS`
/// = `8·N_MAX` entries, 1024 in `sd`): with a full line queue, the other
/// `LINE_QUEUE - 1` lines' segments, at most `N_MAX - 1` each (889 in
/// `sd`), leave a line's reserve
/// ([`SEG_RESERVE`](crate::post::interpolator::SEG_RESERVE),
/// `N_MAX - 1 + 4` = 131 in `sd`) free, so a line the queue has room for is
/// never dropped for want of segments. In `sd` one `DP16KD` per field (1024
/// words of 18 bits), in `hd` one per 9 bits (2048 words).
pub const SEG_ADDR_BITS: usize = INDEX_BITS + 3;
/// Address bits of the interpolator's line queue (8 lines,
/// [`LINE_QUEUE`](crate::post::interpolator::LINE_QUEUE)). Lines reach the
/// interpolator in bursts when the matcher catches up on a backlog, while
/// it sends one per `W` clocks and so never catches up itself: after a
/// busy stretch of lines the queue holds several lines at once. The line
/// processor keeps at most this many lines between the matcher's input and
/// the interpolator's output (`rtl::stereo_line_processor`, "Lines in
/// flight"), so the interpolator never drops one there.
pub(crate) const LINE_QUEUE_BITS: usize = 3;

/// Reference declivities per gain cell, at most: cell `c` of `C` holds rows
/// `c`, `c + C`, `c + 2C` and `c + 3C` of the matching table, one per
/// *phase* of the column stream (the other view's declivities pass the
/// array once per phase, interleaved), so one datapath serves four rows. A
/// line of at most `2C` reference declivities uses two phases and sweeps an
/// anti-diagonal every two clocks; a longer one uses up to four and sweeps
/// one every four (see `crate::matcher::systolic_matcher`).
pub const ROWS_PER_CELL: usize = 4;
/// Bits of a phase `0 .. ROWS_PER_CELL`.
pub(crate) const PHASE_BITS: usize = 2;
/// Gain cells of the sensor's matcher: `N_MAX / ROWS_PER_CELL`.
pub const N_CELLS: usize = N_MAX / ROWS_PER_CELL;
/// Bits of a sweep clock count: up to `4·N_MAX + 3·(2·N_CELLS + 1) +
/// 4·(N_CELLS - 1)` and a few of pipeline, 844 for `n = m = N_MAX`
/// (`crate::matcher::declivity_matcher::sweep_cycles`).
pub(crate) const SWEEP_BITS: usize = DIAG_BITS + 2;
/// Bits of a reference's or a column's six neighbour levels side by side,
/// level `k` (left 0–2, then right 0–2) at bit `k·LEVEL_BITS`.
pub const LEVELS_BITS: usize = 6 * LEVEL_BITS;
/// Bits of a word of the choice memory: the 2-bit choices of
/// [`CELLS_PER_CHOICE_WORD`] cells, one anti-diagonal's worth of them. (32:
/// rust-hdl simulates wider values as big integers.)
pub const CHOICE_WORD_BITS: usize = 32;
/// Cells whose choices share one memory word.
pub const CELLS_PER_CHOICE_WORD: usize = CHOICE_WORD_BITS / 2;
/// Memory words of the choice memory per anti-diagonal: the row groups of
/// [`N_MAX`] rows (`r / CELLS_PER_CHOICE_WORD`), one block RAM each.
pub const CHOICE_WORDS: usize = N_MAX / CELLS_PER_CHOICE_WORD;
/// Bits of a row's group `r / CELLS_PER_CHOICE_WORD`: the choice memory
/// holds each group's choices of an anti-diagonal in one word.
pub(crate) const ROW_GROUP_BITS: usize = INDEX_BITS - CELLS_PER_CHOICE_WORD.trailing_zeros() as usize;
/// Bits of a choice's offset `2·(c mod CELLS_PER_CHOICE_WORD)` in its word.
pub(crate) const PAIR_BITS: usize = 5;
/// Words of 16 choices (32 bits) of a gain cell's skew delay: with four
/// phases, cell `c`'s choices wait `2c` clocks, so that every cell writes
/// one anti-diagonal together (`crate::matcher::gain_cell`); `2·(N_CELLS - 1)`
/// choices at most.
pub(crate) const SKEW_WORDS: usize = (2 * (N_CELLS - 1)).div_ceil(CELLS_PER_CHOICE_WORD);

// ---- The depth stage (paper eq. 1, `rtl::post::depth_stage`).

/// Bits of a depth in millimetres: `0` is "no depth" (disparity 0), and
/// depths from [`DEPTH_MAX_MM`] on read as it (saturation).
pub const DEPTH_BITS: usize = 16;
/// The largest depth the stage outputs, millimetres (65.535 m).
pub const DEPTH_MAX_MM: u64 = (1 << DEPTH_BITS) - 1;
/// Index bits of the depth table: the normalised disparity's bits after its
/// leading one (512 entries).
pub const DEPTH_INDEX_BITS: usize = 9;
/// Bits of the normalised disparity below the table's index: the
/// linear interpolation's weight between two entries (sixteenths).
pub const DEPTH_WEIGHT_BITS: usize = POS_BITS - 1 - DEPTH_INDEX_BITS;
/// Bits of a depth table entry `round(K / m)` for a normalised disparity
/// `m ∈ [2^(POS_BITS-1), 2^POS_BITS)`: the numerator `K` is below
/// [`DEPTH_K_LIMIT`], so an entry lies in `(2^16 - 1, 2^18)`.
pub const DEPTH_TABLE_BITS: usize = 18;
/// Bits of an entry's slope, the difference to the next entry (at most
/// `2^18 / 512 ≈ 512`).
pub const DEPTH_SLOPE_BITS: usize = 10;
/// Bits of a depth table word: the entry above its slope.
pub const DEPTH_WORD_BITS: usize = DEPTH_TABLE_BITS + DEPTH_SLOPE_BITS;
/// The numerator `K = round(f_px · b_mm · 2^POS_FRAC_BITS · 2^s)` of
/// `Z_mm = K / (D_lsb · 2^s)` is scaled (the exponent `s` chosen) to lie
/// below this bound and at least half of it: every entry `round(K / m)`
/// then fits [`DEPTH_TABLE_BITS`] bits and has at least 16 significant ones.
pub const DEPTH_K_LIMIT: u64 = (1 << (POS_BITS - 1 + DEPTH_TABLE_BITS)) - (1 << (POS_BITS - 1));
/// Bits of the depth stage's shift amounts (`s - 1 - lz`, `0 ..= 15`).
pub const DEPTH_SHIFT_BITS: usize = 4;
/// The smallest scale exponent `s` of a camera: `s = 0` would saturate
/// every depth (`Z ≥ 2^30 / 2^14 = 65536` mm at the largest disparity).
pub const DEPTH_SCALE_MIN: u32 = 1;
/// The largest scale exponent `s` (a shift of `s - 1` must fit
/// [`DEPTH_SHIFT_BITS`]); it makes the smallest depth, at the largest
/// disparity, at least 1 mm, so that 0 only ever means "no depth".
pub const DEPTH_SCALE_MAX: u32 = 1 << DEPTH_SHIFT_BITS;

// ---------------------------------------------------------------------------
// The vertical median (`rtl::post::vertical_median`)

/// Rows of the vertical median of the default mode (golden's
/// `MEDIAN_ROWS`): the taps of `rtl::post::vertical_median`'s network.
pub const MEDIAN_TAPS: usize = 9;
/// Rows on each side of the median's centre row, `MEDIAN_TAPS / 2`: output
/// row `y` waits for row `y + MEDIAN_HALF`, and the flush after a frame's
/// last row sends its last `MEDIAN_HALF` rows.
pub const MEDIAN_HALF: usize = MEDIAN_TAPS / 2;
/// Line buffers of the vertical median: the rows above the incoming one
/// that its taps reach, `MEDIAN_TAPS - 1`, each of `W_MAX` disparities of
/// `POS_BITS` (one `DP16KD`).
pub const MEDIAN_LINE_BUFFERS: usize = MEDIAN_TAPS - 1;

// ---- The row check (golden's `confirmed_matches`, the default mode's
// consistency check across neighbouring rows).

/// golden's `CONSISTENT_DX` (3 px) in [`POS_FRAC_BITS`] fixed point: a
/// match of a neighbouring row at most this far in position confirms
/// (inclusive).
pub const CONSISTENT_DX_LSB: u64 = 3 << POS_FRAC_BITS;
/// golden's `CONSISTENT_DD` (1 px) in [`POS_FRAC_BITS`] fixed point: the
/// confirming match's disparity differs by at most this (inclusive).
pub const CONSISTENT_DD_LSB: u64 = 1 << POS_FRAC_BITS;
/// Bits of a row-check bank index: four banks of [`N_MAX`] matches (the
/// rows above, at and below the one checked, and the incoming one).
pub const ROW_BANK_BITS: usize = 2;
/// Address bits of a row-check memory: the bank, then the match's index.
pub const ROW_ADDR_BITS: usize = ROW_BANK_BITS + INDEX_BITS;
/// Bits of a stored match: `X` above the disparity, both [`POS_BITS`].
pub const ROW_ENTRY_BITS: usize = 2 * POS_BITS;
/// Bits of a slot index of a neighbour's window ring.
pub(crate) const ROW_WINDOW_BITS: usize = 3;
/// Slots of a neighbour's window ring: the matches of the neighbouring row
/// from the first one not left of the checked match's window on. A window
/// `[X - 3 px, X + 3 px]` holds at most 7 matches at least a pixel apart
/// (as declivities are, so their positions at least 16 LSB apart), and
/// the eighth slot takes the first match right of it.
pub(crate) const ROW_WINDOW: usize = 1 << ROW_WINDOW_BITS;
