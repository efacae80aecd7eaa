//! `declivity rtl match`: the rows of a pair through the rtl matcher, on
//! parallel matchers, compared with golden line by line, with the matching
//! graph of one row.

use std::ops::Range;
use std::path::{Path, PathBuf};

use golden::{GreyImage, Params};
use rtl::matcher::declivity_matcher::{DeclivityMatcher, GainRule};
use serde::Serialize;

use crate::config::Config;
use crate::drive::matcher::{dequantize, golden_mode, image_lines_in, match_image_on, Agreement, HdMatcher, MatchLine, MatchReport};
use crate::error::SimError;
use crate::eval::pictures;
use crate::formats::{SearchArea, POSITION_UNIT};

/// What `rtl match` was asked for besides the pair.
#[derive(Debug, Clone)]
pub struct MatchJob {
    /// The configuration whose matcher runs (its `N_CELLS` cells).
    pub config: Config,
    /// The gain rule the matcher is generated for (golden runs the same).
    pub rule: GainRule,
    /// Eq. 6's area in `1/2^POS_FRAC_BITS` px ([`SearchArea::from_px`]).
    pub area: SearchArea,
    /// The rows to run.
    pub rows: Range<usize>,
    /// The row whose matching graph is drawn (in `rows`).
    pub graph_line: usize,
    /// Folder for the picture (created before the simulation).
    pub out: PathBuf,
    /// Matchers run in parallel, each on a run of rows.
    pub matchers: usize,
}

/// The report and what the job adds to it (one JSON object).
#[derive(Debug, Clone, Serialize)]
pub struct MatchOutcome {
    #[serde(flatten)]
    pub report: MatchReport,
    /// `[first, end)` of the rows run.
    pub rows: [usize; 2],
    /// Wall time of the simulation.
    pub seconds: f64,
    /// The matching graph's file.
    pub graph: String,
    /// How the graph's row compares with golden.
    #[serde(skip)]
    pub graph_agreement: Agreement,
}

/// Checks the rows of `job` against an image of `height` rows.
pub fn check_rows(job: &MatchJob, height: usize, image: &Path) -> Result<(), SimError> {
    let rows = &job.rows;
    if rows.is_empty() || rows.end > height {
        return Err(SimError::Argument(format!("--rows {}..{}: outside the image ({} has {height} rows)", rows.start, rows.end, image.display())));
    }
    if !rows.contains(&job.graph_line) {
        return Err(SimError::Argument(format!("--graph-line {}: outside the rows run ({}..{} of {height})", job.graph_line, rows.start, rows.end)));
    }
    Ok(())
}

/// Runs the rows of `left`/`right` through `job.matchers` matchers of
/// `job.config`'s `N_CELLS` cells and golden, and draws the graph of `job.graph_line` with
/// golden's gains and path and the rtl's path. `progress` is called after
/// every line, from any thread.
pub fn rtl_match(name: &str, left: &GreyImage, right: &GreyImage, job: &MatchJob, progress: &(dyn Fn() + Sync)) -> Result<MatchOutcome, SimError> {
    std::fs::create_dir_all(&job.out).map_err(|source| SimError::Io { path: job.out.clone(), source })?;
    let rows = job.rows.clone();
    let mut pairs = image_lines_in(left, right, job.config).drain(rows.clone()).collect::<Vec<_>>();
    if let Some(first) = pairs.first_mut() {
        (first.0.sof, first.1.sof) = (true, true);
    }
    let t0 = std::time::Instant::now();
    const SD: usize = rtl::params::N_CELLS;
    const HD: usize = rtl_hd::params::N_CELLS;
    let (mut report, outcomes) = match job.config {
        Config::Sd => match_image_on::<SD, DeclivityMatcher<SD>>(name, &pairs, job.rule, job.area, job.matchers, progress),
        Config::Hd => match_image_on::<HD, HdMatcher<HD>>(name, &pairs, job.rule, job.area, job.matchers, progress),
    };
    let seconds = t0.elapsed().as_secs_f64();
    report.max_cycles_line += rows.start;

    let k = job.graph_line - rows.start;
    let features = |line: &MatchLine| {
        let (declivities, dt) = dequantize(line);
        golden::line::LineFeatures { sigma: dt / golden::noise::THRESHOLD_FACTOR, dt, declivities }
    };
    let (fr, fo) = (features(&pairs[k].0), features(&pairs[k].1));
    let params = Params { dispmin: job.area.dispmin_px(), ..Params::with_mode(golden_mode(job.rule), job.area.dispmax as f64 / POSITION_UNIT)? };
    let line = &outcomes[k];
    let graph = job.out.join(format!("graph_rtl_line_{}.png", job.graph_line));
    let picture = pictures::matching_graph_two_paths(&fr, &fo, &params, &line.golden.table, &line.golden.nodes, &line.rtl.pairs());
    pictures::save_png(&picture, &graph)?;
    Ok(MatchOutcome { report, rows: [rows.start, rows.end], seconds, graph: graph.display().to_string(), graph_agreement: line.agreement })
}
