//! The line processor's generated Verilog under Verilator, driven beat by
//! beat: each camera plays a script of AXI4-Stream beats, each with its
//! `tdata`, `tuser`, `tlast` and the idle clocks (`tvalid` low) before it,
//! so that a camera can send anything a real one does: lines of any width,
//! a `tlast` missing or early, a start of frame anywhere, pauses, and the
//! two cameras out of step. The fault campaign (`sim::faults`) is built on
//! it.
//!
//! [`frame`](super::frame) plays a whole image pair as a well-formed frame,
//! in the same way as the rust-hdl model's driver, and compares the two;
//! here there is no model: the scripts are the input, every output beat and
//! the status counters are the result.
//!
//! The C++ driver ([`beat_driver`]) sets the inputs with the clock low,
//! calls `eval()`, samples the outputs, then raises and lowers the clock,
//! as [`frame`](super::frame)'s does, and shares its Verilator build
//! (cached by a hash of the design and the driver).

use std::fmt::Write as _;
use std::process::Command;
use std::time::{Duration, Instant};

use crate::config::Config;
use crate::formats::SearchArea;
use crate::hdl::cosim::{io_err, log_of, run_tool, CosimError, Options, WorkDir, CLOCK_PORT, RESET_PORT};
use crate::hdl::frame::{build_verilator, check_ports, frame_cache_dir, parse_err, parse_summary, DriverParts, FRAME_BINARY, STATUS_NAMES};

/// One beat a camera offers: `idle` clocks with `tvalid` low after the
/// beat before was taken, and not before clock `at`; then `tvalid` high
/// with `data`, `user` (`tuser`) and `last` (`tlast`) until the core takes
/// it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Beat {
    pub at: u64,
    pub idle: u32,
    pub data: u8,
    pub user: bool,
    pub last: bool,
}

/// One beat out of `m_*`, with the clock it left on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutBeat {
    pub clock: u64,
    pub data: u64,
    pub user: bool,
    pub last: bool,
}

/// What a run of two beat scripts gave.
#[derive(Debug, Clone, Default)]
pub struct BeatRun {
    /// Every output beat, in order.
    pub out: Vec<OutBeat>,
    /// The clock each camera's beats with `tuser` were taken on (left,
    /// right), with their index in the script.
    pub user_taken: [Vec<(usize, u64)>; 2],
    /// Clocks simulated, and clocks on which a camera offered a beat that
    /// was not taken.
    pub cycles: u64,
    pub stall_cycles: u64,
    /// Whether the run reached its clock limit with beats still to offer
    /// or output still coming (the core hung or never went quiet).
    pub hung: bool,
    /// Beats of each script taken before the end.
    pub taken: [usize; 2],
    /// The status counters at the end, named as the ports.
    pub status: Vec<(String, u64)>,
    /// Building the simulator (zero when the cached build served), and
    /// running it.
    pub compile: Duration,
    pub sim: Duration,
}

impl BeatRun {
    /// The status counter `name` at the end (0 if the core has none of
    /// that name).
    pub fn status(&self, name: &str) -> u64 {
        self.status.iter().find(|(n, _)| n == name).map_or(0, |&(_, v)| v)
    }
}

/// The files of the driver's work directory.
const BEATS_PARAMS_FILE: &str = "beats_params.txt";
const BEATS_LEFT_FILE: &str = "left.beats";
const BEATS_RIGHT_FILE: &str = "right.beats";
const BEATS_OUT_FILE: &str = "out.beats";
const BEATS_USER_FILE: &str = "user.txt";
const BEATS_SUMMARY_FILE: &str = "summary.txt";
const BEATS_DONE: &str = "BEATS-DONE";
const BEATS_ERROR: &str = "BEATS-ERROR";

/// A script as the driver reads it: the count, then `at idle data user
/// last` a line, decimal.
fn script_text(beats: &[Beat]) -> String {
    let mut s = String::with_capacity(beats.len() * 12 + 16);
    let _ = writeln!(s, "{}", beats.len());
    for b in beats {
        let _ = writeln!(s, "{} {} {} {} {}", b.at, b.idle, b.data, b.user as u8, b.last as u8);
    }
    s
}

/// The C++ driver of Verilator's model of `top`: reads
/// [`BEATS_PARAMS_FILE`] (`dispmin dispmax height quiet limit`) and the
/// two scripts, then each clock:
/// 1. with `clock` low, each camera offers its next beat unless it is in
///    the beat's idle clocks, before its clock `at`, or its script is over;
///    `eval()`;
/// 2. a camera's beat is taken if its `tready` is high; an output beat is
///    written to [`BEATS_OUT_FILE`] as `clock tdata tuser tlast`, and a
///    taken beat with `tuser` to [`BEATS_USER_FILE`] as `camera index
///    clock`;
/// 3. the rising edge, `eval()`, `clock` low again;
/// 4. a camera that took its beat moves to the next one (and its idle
///    clocks), one in its idle clocks counts them down.
///
/// It stops when both scripts are over and nothing was taken or sent for
/// more than `quiet` clocks, or at `limit` clocks (the summary then says
/// `hung`). [`BEATS_SUMMARY_FILE`]: `clocks stalls hung taken_left
/// taken_right` and the status counters.
fn beat_driver(config: Config) -> String {
    let DriverParts { dispmin_mask, dispmax_mask, height_mask, hex_digits, status_fmt, status_args, pixel_max } = DriverParts::new(config);
    let (head, main_open) = (DriverParts::head(BEATS_ERROR), DriverParts::main_open());
    format!(
        r#"// Generated by sim::hdl::beats::beat_driver: two cameras playing beat
// scripts into Verilator's model of the line processor.
{head}
struct Beat {{ unsigned long long at; unsigned idle, data, user, last; }};

static bool read_script(const char* path, std::vector<Beat>& beats) {{
  FILE* f = std::fopen(path, "r");
  if (!f) return false;
  long long n;
  if (std::fscanf(f, "%lld", &n) != 1 || n < 0) {{ std::fclose(f); return false; }}
  beats.resize(n);
  for (long long i = 0; i < n; ++i) {{
    Beat& b = beats[i];
    if (std::fscanf(f, "%llu %u %u %u %u", &b.at, &b.idle, &b.data, &b.user, &b.last) != 5 || b.data > {pixel_max}u || b.user > 1 || b.last > 1) {{ std::fclose(f); return false; }}
  }}
  std::fclose(f);
  return true;
}}

{main_open}  long long dmin, dmax, h, quiet, limit;
  FILE* fp = std::fopen("{BEATS_PARAMS_FILE}", "r");
  if (!fp) return fail("cannot open {BEATS_PARAMS_FILE}");
  int r = std::fscanf(fp, "%lld %lld %lld %lld %lld", &dmin, &dmax, &h, &quiet, &limit);
  std::fclose(fp);
  if (r != 5 || quiet < 0 || limit < 0) return fail("bad {BEATS_PARAMS_FILE}");
  std::vector<Beat> cam[2];
  if (!read_script("{BEATS_LEFT_FILE}", cam[0])) return fail("cannot read {BEATS_LEFT_FILE}");
  if (!read_script("{BEATS_RIGHT_FILE}", cam[1])) return fail("cannot read {BEATS_RIGHT_FILE}");
  FILE* fo = std::fopen("{BEATS_OUT_FILE}", "w");
  FILE* fu = std::fopen("{BEATS_USER_FILE}", "w");
  FILE* fs = std::fopen("{BEATS_SUMMARY_FILE}", "w");
  if (!fo || !fu || !fs) return fail("cannot write the output files");
  static char out_buf[1 << 20];
  std::setvbuf(fo, out_buf, _IOFBF, sizeof out_buf);
  size_t idx[2] = {{0, 0}};
  unsigned long long wait[2];
  for (int c = 0; c < 2; ++c) wait[c] = cam[c].empty() ? 0 : cam[c][0].idle;
  uint64_t cycle = 0, stalls = 0, last_activity = 0;
  bool hung = false;
  top->{CLOCK_PORT} = 0;
  top->{RESET_PORT} = 0;
  top->dispmin = (uint64_t)dmin & {dispmin_mask};
  top->dispmax = (uint64_t)dmax & {dispmax_mask};
  top->height = (uint64_t)h & {height_mask};
  for (;;) {{
    bool off[2];
    for (int c = 0; c < 2; ++c) off[c] = idx[c] < cam[c].size() && wait[c] == 0 && cycle >= cam[c][idx[c]].at;
    const Beat none = {{0, 0, 0, 0, 0}};
    const Beat& bl = off[0] ? cam[0][idx[0]] : none;
    const Beat& br = off[1] ? cam[1][idx[1]] : none;
    top->l_tvalid = off[0]; top->l_tdata = bl.data; top->l_tuser = bl.user; top->l_tlast = bl.last;
    top->r_tvalid = off[1]; top->r_tdata = br.data; top->r_tuser = br.user; top->r_tlast = br.last;
    top->eval();
    const bool take[2] = {{off[0] && top->l_tready, off[1] && top->r_tready}};
    if ((off[0] && !take[0]) || (off[1] && !take[1])) ++stalls;
    for (int c = 0; c < 2; ++c) {{
      if (!take[c]) continue;
      last_activity = cycle;
      if (cam[c][idx[c]].user) std::fprintf(fu, "%d %zu %llu\n", c, idx[c], (unsigned long long)cycle);
    }}
    if (top->m_tvalid) {{
      last_activity = cycle;
      std::fprintf(fo, "%llu %0{hex_digits}llx %u %u\n", (unsigned long long)cycle, (unsigned long long)top->m_tdata, (unsigned)top->m_tuser, (unsigned)top->m_tlast);
    }}
    top->{CLOCK_PORT} = 1;
    top->eval();
    top->{CLOCK_PORT} = 0;
    ++cycle;
    for (int c = 0; c < 2; ++c) {{
      if (take[c]) {{
        ++idx[c];
        wait[c] = idx[c] < cam[c].size() ? cam[c][idx[c]].idle : 0;
      }} else if (wait[c] > 0) {{
        --wait[c];
      }}
    }}
    const bool over = idx[0] >= cam[0].size() && idx[1] >= cam[1].size();
    if (over && cycle - last_activity > (uint64_t)quiet) break;
    if (cycle >= (uint64_t)limit) {{ hung = true; break; }}
  }}
  std::fprintf(fs, "%llu %llu %d %zu %zu{status_fmt}\n", (unsigned long long)cycle, (unsigned long long)stalls, hung ? 1 : 0, idx[0], idx[1]{status_args});
  top->final();
  if (std::fclose(fo) != 0 || std::fclose(fu) != 0 || std::fclose(fs) != 0) return fail("cannot write the output files");
  std::printf("{BEATS_DONE} %llu\n", (unsigned long long)cycle);
  return 0;
}}
"#
    )
}

/// The run the driver's files describe.
fn parse_run(out: &str, user: &str, summary: &str) -> Result<BeatRun, CosimError> {
    let mut run = BeatRun::default();
    for (i, line) in out.lines().enumerate() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let bad = || parse_err(BEATS_OUT_FILE, i + 1, format!("expected `clock tdata tuser tlast`, got `{line}`"));
        if f.len() != 4 {
            return Err(bad());
        }
        let clock = f[0].parse().map_err(|_| bad())?;
        let data = u64::from_str_radix(f[1], 16).map_err(|_| parse_err(BEATS_OUT_FILE, i + 1, format!("tdata `{}` is not hex", f[1])))?;
        run.out.push(OutBeat { clock, data, user: f[2] == "1", last: f[3] == "1" });
    }
    for (i, line) in user.lines().enumerate() {
        let v: Vec<u64> = line.split_whitespace().map(|t| t.parse::<u64>()).collect::<Result<_, _>>().map_err(|_| parse_err(BEATS_USER_FILE, i + 1, format!("not numbers: `{line}`")))?;
        match v[..] {
            [c @ (0 | 1), index, clock] => run.user_taken[c as usize].push((index as usize, clock)),
            _ => return Err(parse_err(BEATS_USER_FILE, i + 1, format!("expected `camera index clock`, got `{line}`"))),
        }
    }
    let v = parse_summary(BEATS_SUMMARY_FILE, summary)?;
    run.cycles = v[0];
    run.stall_cycles = v[1];
    run.hung = v[2] != 0;
    run.taken = [v[3] as usize, v[4] as usize];
    run.status = STATUS_NAMES.iter().zip(&v[5..]).map(|(n, &x)| (n.to_string(), x)).collect();
    Ok(run)
}

/// Plays `left` and `right` into `design` (the Verilog of `config`'s line
/// processor, module `top`) under Verilator, with eq. 6's search area
/// `area` and `height` rows a frame; stops `quiet` clocks after both
/// scripts are over and the output is quiet, or at `limit` clocks
/// ([`BeatRun::hung`]). The Verilator build is cached as
/// [`frame`](super::frame)'s is.
#[allow(clippy::too_many_arguments)]
pub fn run_beats(config: Config, design: &str, left: &[Beat], right: &[Beat], area: SearchArea, height: usize, quiet: u64, limit: u64, opts: &Options) -> Result<BeatRun, CosimError> {
    let height_bits = config.sizes().height_bits;
    if height == 0 || height >= 1 << height_bits {
        return Err(CosimError::Port(format!("height {height}: the {config} line processor takes 1 to {} rows", (1usize << height_bits) - 1)));
    }
    check_ports(design, config)?;
    let mut dir = WorkDir::new(opts.work_root.as_deref(), "beats")?;
    let result = beats_in(config, design, left, right, area, height, quiet, limit, opts, &dir);
    dir.keep = opts.keep || matches!(result, Err(CosimError::ToolFailed { .. } | CosimError::Parse { .. }));
    result
}

#[allow(clippy::too_many_arguments)]
fn beats_in(config: Config, design: &str, left: &[Beat], right: &[Beat], area: SearchArea, height: usize, quiet: u64, limit: u64, opts: &Options, dir: &WorkDir) -> Result<BeatRun, CosimError> {
    dir.write(BEATS_PARAMS_FILE, &format!("{} {} {height} {quiet} {limit}\n", area.dispmin, area.dispmax))?;
    dir.write(BEATS_LEFT_FILE, &script_text(left))?;
    dir.write(BEATS_RIGHT_FILE, &script_text(right))?;
    let t0 = Instant::now();
    let driver = beat_driver(config);
    let cache = frame_cache_dir(design, &driver, opts);
    let binary = cache.join(FRAME_BINARY);
    if !binary.is_file() {
        build_verilator(design, &driver, opts, &cache)?;
    }
    let compile = t0.elapsed();
    let t1 = Instant::now();
    let out = run_tool(FRAME_BINARY, &mut Command::new(&binary), dir)?;
    let sim = t1.elapsed();
    let log = log_of(&out);
    if log.contains(BEATS_ERROR) || !log.contains(BEATS_DONE) {
        return Err(CosimError::ToolFailed { tool: "verilator".into(), status: "the beat driver did not finish".into(), log, dir: dir.path.clone() });
    }
    let read = |name: &str| {
        let p = dir.path.join(name);
        std::fs::read_to_string(&p).map_err(io_err(&p))
    };
    let mut run = parse_run(&read(BEATS_OUT_FILE)?, &read(BEATS_USER_FILE)?, &read(BEATS_SUMMARY_FILE)?)?;
    run.compile = compile;
    run.sim = sim;
    Ok(run)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hdl::frame::expected_ports;

    #[test]
    fn the_beat_driver_sets_every_input_and_reads_every_output_of_the_processor() {
        for config in Config::ALL {
            let driver = beat_driver(config);
            let (ins, outs) = expected_ports(config);
            for p in &ins {
                assert!(driver.contains(&format!("top->{} = ", p.name)), "{config}: {} is set", p.name);
            }
            for p in &outs {
                assert!(driver.contains(&format!("top->{}", p.name)), "{config}: {} is read", p.name);
            }
            for name in [BEATS_PARAMS_FILE, BEATS_LEFT_FILE, BEATS_RIGHT_FILE, BEATS_OUT_FILE, BEATS_USER_FILE, BEATS_SUMMARY_FILE, BEATS_DONE, BEATS_ERROR] {
                assert!(driver.contains(name), "{name}");
            }
        }
    }

    #[test]
    fn scripts_and_results_round_trip_through_the_driver_formats() {
        let beats = [Beat { at: 9, idle: 3, data: 200, user: true, last: false }, Beat { at: 0, idle: 0, data: 7, user: false, last: true }];
        assert_eq!(script_text(&beats), "2\n9 3 200 1 0\n0 0 7 0 1\n");
        let summary = format!("40 3 1 2 1{}\n", " 9".repeat(STATUS_NAMES.len()));
        let run = parse_run("10 00100020 1 0\n11 00200030 0 1\n", "0 0 5\n1 0 6\n", &summary).expect("parses");
        assert_eq!(run.out.len(), 2);
        assert_eq!(run.out[1], OutBeat { clock: 11, data: 0x0020_0030, user: false, last: true });
        assert_eq!(run.user_taken, [vec![(0, 5)], vec![(0, 6)]]);
        assert_eq!((run.cycles, run.stall_cycles, run.hung, run.taken), (40, 3, true, [2, 1]));
        assert_eq!(run.status(STATUS_NAMES[0]), 9);
        assert!(parse_run("3 xxxx 0 0\n", "", &summary).is_err());
        assert!(parse_run("", "2 0 5\n", &summary).is_err());
        assert!(parse_run("", "", "1 2 3").is_err());
    }
}
