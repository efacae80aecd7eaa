//! The optimal path through the matching graph (paper §IV, eq. 9).
//!
//! A path is a chain of nodes strictly increasing in both indices (the
//! non-reversal and uniqueness constraints), starting at any node; its gain is
//! the sum of its nodes' local gains. Eq. 9 gives the best gain of a partial
//! path ending at node `(i, j)`:
//! `G(i,j) = g(i,j) + max(0, max_{m<i, n<j} G(m,n))`.
//!
//! Three implementations, checked against each other by the tests:
//! - [`literal_g`]: eq. 9 as written, the quadrant maximum scanned cell by
//!   cell, `O(N²M²)` — the reference, for tests only;
//! - [`prefix_max_dp`]: the quadrant maximum is a prefix maximum, so the
//!   recurrence is local:
//!   `P(i,j) = max(0, G(i,j), P(i-1,j), P(i,j-1))`, `G(i,j) = g(i,j) + P(i-1,j-1)`,
//!   `P(0,·) = P(·,0) = 0`, with one 2-bit [`Choice`] per cell and a
//!   [`traceback`] from `P(N,M)`. This is the computation the systolic
//!   hardware mirrors;
//! - [`banded_dp`]: the same recurrence and the same choices, computed only in
//!   the band of columns that eq. 6 allows in each row (the frame pipeline's
//!   fast path).
//!
//! ## Tie-break (fixed; the hardware uses the same)
//! Candidates are taken in the order **start, node, up, left**, each replacing
//! the best so far only when *strictly* greater: `start` (value 0) wins every
//! tie, then the node, then `up` (`P(i-1,j)`), then `left` (`P(i,j-1)`).
//! Hence a path never starts with a node of gain ≤ 0 (`start` wins), but a
//! zero-gain node that extends a path ties with `up` and joins it; between
//! equal paths the traceback prefers matching the current pair, then
//! dropping the reference declivity.
//!
//! Indices: declivities are 0-based (`i` in `0..n` reference, `j` in `0..m`
//! other view); the tables are 1-based with row and column 0 as the border.

/// Which term gave `P(i,j)`: the 2-bit choice stored per cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Choice {
    /// `P(i,j) = 0`: no path ends at or before this cell.
    Start = 0,
    /// `P(i,j) = G(i,j)`: the path takes node `(i,j)`.
    Node = 1,
    /// `P(i,j) = P(i-1,j)`.
    Up = 2,
    /// `P(i,j) = P(i,j-1)`.
    Left = 3,
}

/// The local gains of an `n × m` graph (`None` where there is no node).
#[derive(Debug, Clone, PartialEq)]
pub struct GainTable {
    n: usize,
    m: usize,
    cells: Vec<Option<f64>>,
}

impl GainTable {
    /// A graph with no nodes.
    pub fn new(n: usize, m: usize) -> Self {
        GainTable { n, m, cells: vec![None; n * m] }
    }

    /// Builds the table from a function of the 0-based node indices.
    pub fn from_fn(n: usize, m: usize, mut f: impl FnMut(usize, usize) -> Option<f64>) -> Self {
        let mut t = GainTable::new(n, m);
        for i in 0..n {
            for j in 0..m {
                t.cells[i * m + j] = f(i, j);
            }
        }
        t
    }

    /// Rows (reference declivities).
    pub fn n(&self) -> usize {
        self.n
    }

    /// Columns (other-view declivities).
    pub fn m(&self) -> usize {
        self.m
    }

    /// The gain of node `(i, j)` (0-based), `None` where there is no node.
    pub fn get(&self, i: usize, j: usize) -> Option<f64> {
        self.cells[i * self.m + j]
    }

    /// Sets node `(i, j)` (0-based).
    fn set(&mut self, i: usize, j: usize, g: Option<f64>) {
        self.cells[i * self.m + j] = g;
    }
}

/// The best path: its gain and its nodes `(i, j)` (0-based) in increasing
/// order.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    /// Sum of the local gains of the path's nodes (0 for the empty path).
    pub gain: f64,
    /// Nodes, strictly increasing in both indices.
    pub nodes: Vec<(usize, usize)>,
}

/// Eq. 9 as written: `G(i,j) = g(i,j) + max(0, max_{m<i,n<j} G(m,n))` for
/// every node, scanning the whole quadrant (`O(N²M²)`, for tests). Returns the
/// table of `G` (0-based, `None` where there is no node).
pub fn literal_g(t: &GainTable) -> Vec<Option<f64>> {
    let (n, m) = (t.n, t.m);
    let mut g = vec![None; n * m];
    for i in 0..n {
        for j in 0..m {
            if let Some(local) = t.get(i, j) {
                let mut best = 0.0f64;
                for mi in 0..i {
                    for nj in 0..j {
                        if let Some(v) = g[mi * m + nj] {
                            best = best.max(v);
                        }
                    }
                }
                g[i * m + j] = Some(local + best);
            }
        }
    }
    g
}

/// The best path gain by eq. 9 literally: `max(0, max G(i,j))`.
pub fn literal_best_gain(t: &GainTable) -> f64 {
    literal_g(t).into_iter().flatten().fold(0.0, f64::max)
}

/// One step of the recurrence with the fixed tie-break order (module doc):
/// returns `(P(i,j), choice)` from `G(i,j)` (if a node), `P(i-1,j)` and
/// `P(i,j-1)`.
#[inline]
fn cell_step(g: Option<f64>, up: f64, left: f64) -> (f64, Choice) {
    cell_step_g(g.unwrap_or(NO_NODE), up, left)
}

/// [`cell_step`] with "no node" as `G = -∞`.
#[inline]
fn cell_step_g(g: f64, up: f64, left: f64) -> (f64, Choice) {
    // Selects rather than branches: the outcome is data-dependent and a
    // branch would be mispredicted often.
    use std::hint::select_unpredictable as pick;
    let (mut best, mut choice) = (0.0, Choice::Start);
    let take = g > best;
    best = pick(take, g, best);
    choice = pick(take, Choice::Node, choice);
    let take = up > best;
    best = pick(take, up, best);
    choice = pick(take, Choice::Up, choice);
    let take = left > best;
    best = pick(take, left, best);
    choice = pick(take, Choice::Left, choice);
    (best, choice)
}

/// The full tables of the prefix-max recurrence.
#[derive(Debug, Clone, PartialEq)]
pub struct PrefixMaxTables {
    /// Rows.
    pub n: usize,
    /// Columns.
    pub m: usize,
    /// `P(i,j)`, 1-based, `(n+1) × (m+1)` row-major, border zero.
    pub p: Vec<f64>,
    /// `G(i,j)` at nodes, 1-based like `p`; `None` elsewhere.
    pub g: Vec<Option<f64>>,
    /// The 2-bit choice of each cell, 1-based like `p` (border: `Start`).
    pub choice: Vec<Choice>,
}

impl PrefixMaxTables {
    /// `P(i,j)` (1-based).
    pub fn p_at(&self, i: usize, j: usize) -> f64 {
        self.p[i * (self.m + 1) + j]
    }

    /// The choice of cell `(i,j)` (1-based).
    pub fn choice_at(&self, i: usize, j: usize) -> Choice {
        self.choice[i * (self.m + 1) + j]
    }

    /// The best path gain `P(N,M)`.
    pub fn best_gain(&self) -> f64 {
        self.p_at(self.n, self.m)
    }
}

/// The prefix-max recurrence over the whole table, with choices (the
/// computation the systolic array mirrors; see the module doc).
pub fn prefix_max_dp(t: &GainTable) -> PrefixMaxTables {
    let (n, m) = (t.n, t.m);
    let w = m + 1;
    let mut p = vec![0.0; (n + 1) * w];
    let mut g = vec![None; (n + 1) * w];
    let mut choice = vec![Choice::Start; (n + 1) * w];
    for i in 1..=n {
        for j in 1..=m {
            let gij = t.get(i - 1, j - 1).map(|local| local + p[(i - 1) * w + j - 1]);
            let (pij, c) = cell_step(gij, p[(i - 1) * w + j], p[i * w + j - 1]);
            p[i * w + j] = pij;
            g[i * w + j] = gij;
            choice[i * w + j] = c;
        }
    }
    PrefixMaxTables { n, m, p, g, choice }
}

/// Walks the choices back from `(N, M)`: `node` takes `(i,j)` and moves to
/// `(i-1,j-1)`, `up` moves to `(i-1,j)`, `left` to `(i,j-1)`, `start` ends
/// the path. Returns the 0-based nodes in increasing order.
pub fn traceback(n: usize, m: usize, choice_at: impl Fn(usize, usize) -> Choice) -> Vec<(usize, usize)> {
    let (mut i, mut j) = (n, m);
    let mut nodes = Vec::new();
    while i > 0 && j > 0 && step_back(choice_at(i, j), &mut i, &mut j, &mut nodes) {}
    nodes.reverse();
    nodes
}

/// One move of the traceback from `(i, j)` (1-based) by `choice`, pushing
/// the node it takes (0-based); `false` when the path starts here.
#[inline]
fn step_back(choice: Choice, i: &mut usize, j: &mut usize, nodes: &mut Vec<(usize, usize)>) -> bool {
    match choice {
        Choice::Start => return false,
        Choice::Node => {
            nodes.push((*i - 1, *j - 1));
            *i -= 1;
            *j -= 1;
        }
        Choice::Up => *i -= 1,
        Choice::Left => *j -= 1,
    }
    true
}

/// The best path by the full prefix-max recurrence and its traceback.
pub fn best_path(t: &GainTable) -> Path {
    let tables = prefix_max_dp(t);
    let nodes = traceback(t.n, t.m, |i, j| tables.choice_at(i, j));
    Path { gain: tables.best_gain(), nodes }
}

/// The nodes allowed in one row: columns `lo .. lo + gains.len()` (0-based)
/// with their gains (`None` for a rejected node inside the band).
#[derive(Debug, Clone, PartialEq)]
pub struct BandRow {
    /// First column of the band (0-based); for an empty band, the column the
    /// band would start at, so that `lo` stays non-decreasing over the rows.
    pub lo: usize,
    /// Gains of the columns `lo ..`.
    pub gains: Vec<Option<f64>>,
}

/// The graph as one band of columns per row, stored flat. Both `lo` and
/// `lo + len` must be non-decreasing over the rows, as eq. 6 makes them for
/// sorted positions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BandedGains {
    m: usize,
    /// Per row: first column and offset of its gains in `gains`.
    rows: Vec<(usize, usize)>,
    /// Band cells' gains, [`NO_NODE`] where a node was rejected.
    gains: Vec<f64>,
}

/// The gain stored for a band cell without a node: the gain rule's value for
/// a rejected node (`-∞`), which never wins a comparison and stays `-∞` when
/// a path gain is added to it.
const NO_NODE: f64 = crate::gain::REJECTED;

impl BandedGains {
    /// A graph of `m` columns and no rows yet.
    pub fn new(m: usize) -> Self {
        BandedGains { m, rows: Vec::new(), gains: Vec::new() }
    }

    /// Room for `rows` rows and `cells` band cells.
    #[cfg(test)]
    pub(crate) fn with_capacity(m: usize, rows: usize, cells: usize) -> Self {
        BandedGains { m, rows: Vec::with_capacity(rows), gains: Vec::with_capacity(cells) }
    }

    /// The graph of `m` columns with the given rows.
    pub fn from_rows(m: usize, rows: &[BandRow]) -> Self {
        let mut b = BandedGains::new(m);
        for r in rows {
            b.push_row(r.lo, r.gains.iter().copied());
        }
        b
    }

    /// Appends the next row: its band starts at column `lo` (0-based).
    pub(crate) fn push_row(&mut self, lo: usize, gains: impl IntoIterator<Item = Option<f64>>) {
        let start = self.gains.len();
        self.gains.extend(gains.into_iter().map(|g| g.unwrap_or(NO_NODE)));
        debug_assert!(lo + (self.gains.len() - start) <= self.m, "band inside the table");
        self.rows.push((lo, start));
    }

    /// Rows (reference declivities).
    pub fn n(&self) -> usize {
        self.rows.len()
    }

    /// Columns (other-view declivities).
    pub fn m(&self) -> usize {
        self.m
    }

    /// Row `i` (0-based): the first column of its band and the band's gains
    /// ([`NO_NODE`] where there is no node).
    fn row(&self, i: usize) -> (usize, &[f64]) {
        let (lo, start) = self.rows[i];
        let end = self.rows.get(i + 1).map_or(self.gains.len(), |r| r.1);
        (lo, &self.gains[start..end])
    }

    /// The gain of node `(i, j)` (0-based), `None` where there is no node.
    pub fn get(&self, i: usize, j: usize) -> Option<f64> {
        let (lo, g) = self.row(i);
        j.checked_sub(lo).and_then(|k| g.get(k).copied()).filter(|&v| v != NO_NODE)
    }

    /// The same graph as a dense table.
    pub fn to_table(&self) -> GainTable {
        let mut t = GainTable::new(self.n(), self.m);
        for i in 0..self.n() {
            for j in 0..self.m {
                t.set(i, j, self.get(i, j));
            }
        }
        t
    }
}

/// The prefix-max recurrence restricted to the bands, with the same values
/// and choices as [`prefix_max_dp`] on the dense table, and its traceback.
///
/// Outside the bands no node exists, so with non-decreasing bands the table
/// is known without computing it: left of row `i`'s band, `P(i,j)` equals the
/// value of the latest row whose band starts at or before `j`; right of it,
/// `P(i,j) = T_i`, the best gain of rows `1 … i`. Only the band cells are
/// computed, in `O(band)` per row; the traceback derives the rest from the
/// tails.
pub fn banded_dp(b: &BandedGains) -> Path {
    let bands: Vec<(usize, usize)> = (0..b.n())
        .map(|i| {
            let (lo, g) = b.row(i);
            (lo, lo + g.len())
        })
        .collect();
    banded_dp_with(b.m, &bands, |i, j| b.gains[b.rows[i].1 + j - b.rows[i].0])
}

/// [`banded_dp`] on a graph given as its bands, `bands[i] = (lo, hi)`: the
/// columns `lo .. hi` (0-based) of row `i`, and a function giving the gain of
/// each band cell `(i, j)` ([`NO_NODE`] where there is no node). The gains
/// are asked for once each, row by row, left to right, so they can be
/// computed on the fly.
pub fn banded_dp_with(m: usize, bands: &[(usize, usize)], gain: impl FnMut(usize, usize) -> f64) -> Path {
    let mut buffers = DpBuffers::default();
    let gain = banded_dp_in(&mut buffers, m, bands, gain);
    Path { gain, nodes: buffers.nodes }
}

/// The working tables of [`banded_dp_in`], kept from one line to the next so
/// that their allocations are reused; `nodes` holds the last path found.
#[derive(Debug, Clone, Default)]
pub(crate) struct DpBuffers {
    offs: Vec<usize>,
    band_c: Vec<Choice>,
    tails: Vec<f64>,
    q: Vec<f64>,
    /// The nodes of the last path, in increasing order.
    pub nodes: Vec<(usize, usize)>,
}

/// [`banded_dp_with`] in reused tables: returns the path's gain and leaves
/// its nodes in `buffers.nodes`.
pub(crate) fn banded_dp_in(buffers: &mut DpBuffers, m: usize, bands: &[(usize, usize)], mut gain: impl FnMut(usize, usize) -> f64) -> f64 {
    let n = bands.len();
    let DpBuffers { offs, band_c, tails, q, nodes } = buffers;
    // Choices of the band cells, row after row; offs[i] = first of row i.
    // (Sized up front and written by index: no growth check in the loop.)
    offs.clear();
    let mut cells = 0usize;
    offs.extend(bands.iter().map(|&(lo, hi)| {
        let off = cells;
        cells += hi.saturating_sub(lo);
        off
    }));
    band_c.clear();
    band_c.resize(cells, Choice::Start);
    tails.clear();
    tails.resize(n, 0.0); // T_i
    // q[j] = P(current row, j) for j <= filled; beyond, the tail T.
    q.clear();
    q.resize(m + 1, 0.0);
    let mut filled = 0usize;
    let mut tail = 0.0f64;
    for (i, &(lo0, hi0)) in bands.iter().enumerate() {
        debug_assert!(hi0 <= m, "band inside the table");
        if hi0 > lo0 {
            // 1-based columns lo ..= hi.
            let (lo, hi) = (lo0 + 1, hi0);
            // q[j] for j > filled was never written: it stands for the tail
            // T of the rows above (read as such without a branch; q[lo - 1]
            // is written back, as the rows below may read it).
            let read = |qj: f64, j: usize| if j > filled { tail } else { qj };
            let start = read(q[lo - 1], lo - 1);
            q[lo - 1] = start;
            let mut diag = start;
            let mut left = start;
            let row_c = &mut band_c[offs[i]..][..hi - lo + 1];
            // Column j (0-based) is q[j + 1].
            for ((j, qj), c) in (lo0..).zip(&mut q[lo..hi + 1]).zip(row_c) {
                let up = read(*qj, j + 1);
                let (pij, choice) = cell_step_g(gain(i, j) + diag, up, left);
                diag = up;
                *qj = pij;
                left = pij;
                *c = choice;
            }
            filled = filled.max(hi);
            tail = tail.max(q[hi]);
        }
        tails[i] = tail;
    }

    // The traceback of `traceback`, with the choices outside the bands
    // derived from the tails and runs of equal moves taken at once. Right of
    // row i's band, P(i,j) = T_i and P(i-1,j) = T_{i-1}: the tie-break of
    // `cell_step` with no node gives start when T_i = 0, up when
    // T_{i-1} = T_i, and otherwise left all the way to the band. Left of the
    // band P(i,j) = P(i-1,j), so the walk goes up until a band reaches j; it
    // does so without looking at P: from a cell with P = 0 every cell the
    // walk can reach has P = 0 and holds no node, so the path's nodes are
    // those of `prefix_max_dp`'s traceback.
    // The nodes are written unconditionally into slot k, which only a node
    // move keeps (no branch on the choice); a path has at most min(n, m).
    nodes.clear();
    nodes.resize(n.min(m) + 1, (0, 0));
    let mut k = 0usize;
    let (mut i, mut j) = (n, m);
    while i > 0 && j > 0 {
        let (lo0, hi0) = bands[i - 1];
        if j <= lo0 {
            i -= 1;
            while i > 0 && j <= bands[i - 1].0 {
                i -= 1;
            }
        } else if j > hi0 {
            let t = tails[i - 1];
            let t_prev = if i >= 2 { tails[i - 2] } else { 0.0 };
            if t <= 0.0 {
                break;
            } else if t == t_prev {
                i -= 1;
            } else {
                j = hi0;
            }
        } else {
            // `step_back`'s move.
            let c = band_c[offs[i - 1] + j - 1 - lo0];
            if c == Choice::Start {
                break;
            }
            nodes[k] = (i - 1, j - 1);
            k += (c == Choice::Node) as usize;
            i -= matches!(c, Choice::Node | Choice::Up) as usize;
            j -= matches!(c, Choice::Node | Choice::Left) as usize;
        }
    }
    nodes.truncate(k);
    nodes.reverse();
    // P(N,M) = T_N: no column lies right of the last one.
    tails.last().copied().unwrap_or(0.0)
}
