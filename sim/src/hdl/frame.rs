//! The line processor's generated Verilog run on a whole frame under Icarus
//! or Verilator, with the cameras driven as [`StereoSim::run`] drives the
//! rust-hdl model; the result is the same [`StereoRun`], so the two compare
//! field by field (`declivity rtl depth --engine`, the `cosim_stereo`
//! tests).
//!
//! `sim::hdl::cosim` replays a recorded trace open loop; a frame of the line
//! processor is too long to record (over a hundred thousand clocks of the
//! rust-hdl model, slow per clock). Here the simulator holds the camera model
//! itself: it reads both images, offers a pixel per clock and camera,
//! advances a camera only when its `tready` took the pixel, idles `hblank`
//! clocks after each line, and writes every output beat with its clock.
//! The cycle semantics are `sim::hdl::cosim`'s (inputs with the clock low,
//! outputs sampled before the rising edge) and the stop rule is
//! [`StereoSim::run`]'s (every line out, or [`QUIET_CLOCKS`] without
//! activity after the inputs ended), so a correct Verilog gives the model's
//! run exactly: the same output words on the same clocks, the same stalls
//! and the same status counters.
//!
//! The camera model exists twice, with the same files and formats: as a
//! Verilog testbench for Icarus ([`frame_testbench`]) and as a C++ `main`
//! that drives Verilator's model of `top` directly ([`frame_driver`]: it
//! sets the inputs, toggles `clock` and calls `eval()` itself, without
//! Verilator's `--timing` coroutines).
//!
//! Verilator's build of the 32-cell processor takes minutes; the built
//! simulator is kept (keyed by a hash of the design, the driver, the
//! Verilator version and the build flags) in
//! `<work root>/declivity-frame-<hash>/` and reused, so later frames cost
//! only their run.
//!
//! [`StereoSim::run`]: crate::drive::stereo::StereoSim::run

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use golden::GreyImage;
use rtl::params::PIXEL_BITS;
use rtl::stereo_line_processor::{OUT_BITS, STATUS_BITS};

use crate::config::Config;
use crate::formats::SearchArea;

use crate::hdl::cosim::{io_err, log_of, run_tool, top_ports, verilator_build, CosimError, Options, Port, Simulator, VerilatorBuild, WorkDir, CLOCK_PORT, RESET_PORT, TOP_MODULE};
use crate::hdl::primitives::MODELS_FILE;
use crate::drive::stereo::{PendingLine, StereoRun, QUIET_CLOCKS};

/// Pixels an image may have in the testbench of `config`'s processor:
/// `W_MAX` columns of `2^HEIGHT_BITS` rows (its limits).
fn frame_pixels_max(config: Config) -> usize {
    config.sizes().w_max << config.sizes().height_bits
}

/// The files the testbench and the C++ driver read and write in their work
/// directory.
const FRAME_PARAMS_FILE: &str = "frame_params.txt";
const FRAME_LEFT_FILE: &str = "left.hex";
const FRAME_RIGHT_FILE: &str = "right.hex";
pub const FRAME_BEATS_FILE: &str = "beats.txt";
pub const FRAME_SUMMARY_FILE: &str = "summary.txt";
/// The C++ driver's source in Verilator's build directory.
const FRAME_DRIVER_FILE: &str = "frame_driver.cpp";
/// What the testbench and the driver print at the end (with the clocks
/// run), and at the start of a line when they stop on an error.
const FRAME_DONE: &str = "FRAME-DONE";
const FRAME_ERROR: &str = "FRAME-ERROR";

/// Verilator's arguments for the frame build, besides `--cc --exe`: `-O3`,
/// Verilator's highest optimisation of the model (a faster run than its
/// defaults; the comparison is in docs/timing-closure.md). No `--x-assign` or
/// `--x-initial`: the design has no X to assign (every register
/// and memory starts from its Verilog initial value); no `--noassert`: the
/// design has no assertion to remove. The C++ compiler's level is
/// [`Options::verilator_cxx_opt`] (see `FRAME_BUILD`).
const FRAME_VERILATOR_ARGS: &[&str] = &["-O3"];
/// The binary of the frame build.
pub(crate) const FRAME_BINARY: &str = "Vframe";

/// What a frame under a Verilog simulator gave, and what it cost.
#[derive(Debug, Clone)]
pub struct FrameRun {
    pub simulator: Simulator,
    pub run: StereoRun,
    /// Building the simulator (zero when Verilator's cached build served).
    pub compile: Duration,
    /// Running the frame.
    pub sim: Duration,
    /// Whether a cached Verilator build served.
    pub cached: bool,
    /// The work directory (the parameters, images, beats and summary
    /// files) if it was kept ([`Options::keep`]).
    pub work_dir: Option<PathBuf>,
}

impl FrameRun {
    /// Simulated clocks per second of wall time, build excluded.
    pub fn cycles_per_s(&self) -> f64 {
        self.run.cycles as f64 / self.sim.as_secs_f64().max(1e-9)
    }
}

/// The ports the testbench drives and reads, as `config`'s processor has
/// them (the formats of the pixels, the output and the counters are the
/// same in every configuration; `dispmin`, `dispmax` and `height` are its
/// widths).
pub(crate) fn expected_ports(config: Config) -> (Vec<Port>, Vec<Port>) {
    let sizes = config.sizes();
    let p = |name: &str, width: usize| Port { name: name.to_string(), width: width as u32 };
    let mut ins = vec![p(RESET_PORT, 1)];
    let mut outs = Vec::new();
    for side in ["l", "r"] {
        ins.push(p(&format!("{side}_tdata"), PIXEL_BITS));
        ins.push(p(&format!("{side}_tvalid"), 1));
        ins.push(p(&format!("{side}_tuser"), 1));
        ins.push(p(&format!("{side}_tlast"), 1));
        outs.push(p(&format!("{side}_tready"), 1));
    }
    ins.push(p("dispmin", sizes.dispmax_bits));
    ins.push(p("dispmax", sizes.dispmax_bits));
    ins.push(p("height", sizes.height_bits));
    for (name, width) in [("m_tvalid", 1), ("m_tdata", OUT_BITS), ("m_tuser", 1), ("m_tlast", 1)] {
        outs.push(p(name, width));
    }
    for name in STATUS_NAMES {
        outs.push(p(name, STATUS_BITS));
    }
    (ins, outs)
}

/// The status counters, in the order of the summary file.
pub(crate) const STATUS_NAMES: [&str; 6] = ["records_dropped", "lines_dropped", "pixels_dropped", "lines_full", "lines_wide", "lines_unpaired"];

/// Checks that `design`'s `top` has exactly the ports the testbench of
/// `config` connects (a design of another block or configuration is refused
/// before any build).
pub(crate) fn check_ports(design: &str, config: Config) -> Result<(), CosimError> {
    let (mut ins, outs) = top_ports(design)?;
    ins.retain(|p| p.name != CLOCK_PORT);
    let (want_ins, want_outs) = expected_ports(config);
    let key = |v: &[Port]| {
        let mut k: Vec<(String, u32)> = v.iter().map(|p| (p.name.clone(), p.width)).collect();
        k.sort();
        k
    };
    if key(&ins) != key(&want_ins) || key(&outs) != key(&want_outs) {
        return Err(CosimError::PortsDiffer(format!(
            "the frame testbench drives the {config} line processor's ports ({}), the design has inputs ({}) and outputs ({})",
            want_ins.iter().chain(&want_outs).map(|p| p.to_string()).collect::<Vec<_>>().join(", "),
            ins.iter().map(|p| p.to_string()).collect::<Vec<_>>().join(", "),
            outs.iter().map(|p| p.to_string()).collect::<Vec<_>>().join(", "),
        )));
    }
    Ok(())
}

/// The frame testbench (module `tb`): the camera model of
/// [`StereoSim::run`](crate::drive::stereo::StereoSim::run) in Verilog, for Icarus
/// 11 (Verilator runs [`frame_driver`], the same model in C++). It reads [`FRAME_PARAMS_FILE`] (width,
/// height, hblank, dispmin and dispmax in `1/2^POS_FRAC_BITS` px, quiet
/// clocks, clock limit, and the [`FrameReset`]'s cut, clocks and idle, 0 0
/// 0 for none; decimal), the images as one hex byte per line
/// ([`FRAME_LEFT_FILE`], [`FRAME_RIGHT_FILE`]), writes every output beat as
/// `clock tdata tuser tlast` ([`FRAME_BEATS_FILE`]) and at the end `clocks
/// stalls pixels_in first_in last_in` and the status counters
/// ([`FRAME_SUMMARY_FILE`]), then prints `FRAME-DONE <clocks>`.
fn frame_testbench(config: Config) -> String {
    let (ins, outs) = expected_ports(config);
    let pixels_max = frame_pixels_max(config);
    let decl = |w: u32| if w == 1 { String::new() } else { format!("[{}:0] ", w - 1) };
    let mut s = String::new();
    s.push_str("// Generated by sim::hdl::frame::frame_testbench: the camera model of\n");
    s.push_str("// sim::drive::stereo::StereoSim::run around the line processor.\n");
    s.push_str("module tb;\n  reg clock;\n");
    for p in &ins {
        let _ = writeln!(s, "  reg {}{};", decl(p.width), p.name);
    }
    for p in &outs {
        let _ = writeln!(s, "  wire {}{};", decl(p.width), p.name);
    }
    let conns: Vec<String> = std::iter::once("clock".to_string()).chain(ins.iter().chain(&outs).map(|p| p.name.clone())).map(|n| format!(".{n}({n})")).collect();
    let _ = writeln!(s, "  {TOP_MODULE} dut(\n    {}\n  );", conns.join(",\n    "));
    let _ = writeln!(s, "  reg [{}:0] left_img [0:{}];", PIXEL_BITS - 1, pixels_max - 1);
    let _ = writeln!(s, "  reg [{}:0] right_img [0:{}];", PIXEL_BITS - 1, pixels_max - 1);
    let _ = write!(
        s,
        "  integer fp, fb, fs, r, w, h, hblank, dmin, dmax, quiet, limit, cut, reset_clocks, reset_idle, k;
  integer lx, ly, lidle, rx, ry, ridle, rows;
  reg [63:0] cycle, stalls, pixels_in, first_in, last_in, last_activity;
  reg have_in, done, cutting, l_off, r_off, l_take, r_take;
  initial begin
    clock = 1'b0;
    {RESET_PORT} = 1'b0;
    fp = $fopen(\"{FRAME_PARAMS_FILE}\", \"r\");
    if (fp == 0) begin $display(\"{FRAME_ERROR} cannot open {FRAME_PARAMS_FILE}\"); $finish; end
    r = $fscanf(fp, \"%d %d %d %d %d %d %d %d %d %d\", w, h, hblank, dmin, dmax, quiet, limit, cut, reset_clocks, reset_idle);
    if (r != 10) begin $display(\"{FRAME_ERROR} bad {FRAME_PARAMS_FILE}\"); $finish; end
    $fclose(fp);
    $readmemh(\"{FRAME_LEFT_FILE}\", left_img, 0, w * h - 1);
    $readmemh(\"{FRAME_RIGHT_FILE}\", right_img, 0, w * h - 1);
    fb = $fopen(\"{FRAME_BEATS_FILE}\", \"w\");
    fs = $fopen(\"{FRAME_SUMMARY_FILE}\", \"w\");
    if (fb == 0 || fs == 0) begin $display(\"{FRAME_ERROR} cannot write the output files\"); $finish; end
    lx = 0; ly = 0; lidle = 0; rx = 0; ry = 0; ridle = 0; rows = 0;
    cycle = 0; stalls = 0; pixels_in = 0; first_in = 0; last_in = 0; last_activity = 0;
    have_in = 1'b0; done = 1'b0; cutting = cut > 0;
    while (!done) begin
      if (cutting && cycle == cut) begin
        // The frame cut short: reset, idle, then the frame anew from clock 0.
        l_tvalid = 1'b0; l_tdata = 0; l_tuser = 1'b0; l_tlast = 1'b0;
        r_tvalid = 1'b0; r_tdata = 0; r_tuser = 1'b0; r_tlast = 1'b0;
        for (k = 0; k < reset_clocks + reset_idle; k = k + 1) begin
          {RESET_PORT} = k < reset_clocks;
          #1;
          clock = 1'b1;
          #1;
          clock = 1'b0;
        end
        {RESET_PORT} = 1'b0;
        lx = 0; ly = 0; lidle = 0; rx = 0; ry = 0; ridle = 0; rows = 0;
        cycle = 0; stalls = 0; pixels_in = 0; first_in = 0; last_in = 0; last_activity = 0;
        have_in = 1'b0; cutting = 1'b0;
      end
      l_off = (ly < h) && (lidle == 0);
      r_off = (ry < h) && (ridle == 0);
      l_tvalid = l_off;
      l_tdata = l_off ? left_img[ly * w + lx] : 0;
      l_tuser = l_off && lx == 0 && ly == 0;
      l_tlast = l_off && lx == w - 1;
      r_tvalid = r_off;
      r_tdata = r_off ? right_img[ry * w + rx] : 0;
      r_tuser = r_off && rx == 0 && ry == 0;
      r_tlast = r_off && rx == w - 1;
      dispmin = dmin;
      dispmax = dmax;
      height = h;
      #1;
      l_take = l_off && l_tready;
      r_take = r_off && r_tready;
      if ((l_off && !l_take) || (r_off && !r_take)) stalls = stalls + 1;
      if (l_take) begin
        pixels_in = pixels_in + 1;
        if (!have_in) begin first_in = cycle; have_in = 1'b1; end
        last_in = cycle;
        last_activity = cycle;
      end
      if (m_tvalid && !cutting) begin
        last_activity = cycle;
        $fwrite(fb, \"%0d %h %0d %0d\\n\", cycle, m_tdata, m_tuser, m_tlast);
        if (m_tlast) rows = rows + 1;
      end
      clock = 1'b1;
      #1;
      clock = 1'b0;
      cycle = cycle + 1;
      if (lidle > 0) lidle = lidle - 1;
      else if (l_take) begin
        lx = lx + 1;
        if (lx == w) begin lx = 0; ly = ly + 1; lidle = hblank; end
      end
      if (ridle > 0) ridle = ridle - 1;
      else if (r_take) begin
        rx = rx + 1;
        if (rx == w) begin rx = 0; ry = ry + 1; ridle = hblank; end
      end
      if (!cutting && (rows >= h || (ly >= h && ry >= h && cycle - last_activity > quiet))) done = 1'b1;
      if (cycle >= limit) begin $display(\"{FRAME_ERROR} the clock limit was reached\"); done = 1'b1; end
    end
"
    );
    let _ = writeln!(
        s,
        "    $fwrite(fs, \"%0d %0d %0d %0d %0d{}\\n\", cycle, stalls, pixels_in, first_in, last_in, {});",
        " %0d".repeat(STATUS_NAMES.len()),
        STATUS_NAMES.join(", ")
    );
    let _ = writeln!(s, "    $fclose(fb);\n    $fclose(fs);\n    $display(\"{FRAME_DONE} %0d\", cycle);\n    $finish;\n  end\nendmodule");
    s
}

/// The C++ driver of Verilator's model of `top` (built `--cc --exe`
/// without `--timing`): the camera model of [`frame_testbench`], step for
/// step, with the same files and formats. Each clock `k`:
///
/// 1. with `clock` low, set the inputs from the cameras' state (a camera
///    offers its next pixel unless its frame is over or it is in its
///    `hblank` idle clocks) and `eval()`;
/// 2. sample the outputs: a camera took its pixel if it offered one and
///    its `tready` is high (a stall clock if one offered and was refused);
///    an output beat (`m_tvalid`) is written to [`FRAME_BEATS_FILE`] as
///    `k tdata tuser tlast` (`tdata` zero-padded hex, as Verilog's `%h`);
/// 3. raise `clock` and `eval()` (the rising edge), lower it (applied with
///    the next clock's inputs);
/// 4. advance each camera that took its pixel (after a line's last pixel
///    it idles `hblank` clocks), and stop when every line is out, or when
///    both cameras are done and nothing happened for more than the quiet
///    clocks; past the clock limit it stops with an error.
///
/// Registers start from their Verilog initial values (Verilator's
/// constructor and first `eval()` run the `initial` blocks), `reset` low.
/// With a [`FrameReset`] (`cut` > 0), the frame is cut at clock `cut`:
/// `reset` high for `clocks` clocks and low for `idle`, the cameras idle,
/// then the frame anew with the clocks counted from 0; nothing is written
/// for the clocks before.
/// It prints `FRAME-DONE <clocks>` at the end, or a line starting with
/// `FRAME-ERROR` and exits 1.
/// What the C++ drivers of the line processor ([`frame_driver`] and
/// `sim::hdl::beats`'s) share: the masks of the run-time inputs, the
/// output word's hex digits, the status counters' `printf` format and
/// arguments, the largest pixel, and the C++ text before and at the start
/// of `main`.
pub(crate) struct DriverParts {
    pub dispmin_mask: String,
    pub dispmax_mask: String,
    pub height_mask: String,
    pub hex_digits: usize,
    pub status_fmt: String,
    pub status_args: String,
    pub pixel_max: u32,
}

impl DriverParts {
    pub(crate) fn new(config: Config) -> Self {
        let (ins, _) = expected_ports(config);
        let width_of = |name: &str| ins.iter().find(|p| p.name == name).map_or(64, |p| p.width);
        let mask = |name: &str| format!("0x{:x}ULL", if width_of(name) >= 64 { u64::MAX } else { (1u64 << width_of(name)) - 1 });
        DriverParts {
            dispmin_mask: mask("dispmin"),
            dispmax_mask: mask("dispmax"),
            height_mask: mask("height"),
            hex_digits: OUT_BITS.div_ceil(4),
            status_fmt: " %llu".repeat(STATUS_NAMES.len()),
            status_args: STATUS_NAMES.iter().map(|n| format!(", (unsigned long long)top->{n}")).collect(),
            pixel_max: (1u32 << PIXEL_BITS) - 1,
        }
    }

    /// The includes and `fail`, which prints `error` and the message.
    pub(crate) fn head(error: &str) -> String {
        format!(
            r#"#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>
#include "verilated.h"
#include "V{TOP_MODULE}.h"

static int fail(const char* msg) {{
  std::printf("{error} %s\n", msg);
  return 1;
}}
"#
        )
    }

    /// `main`'s opening: the context and the model `top`.
    pub(crate) fn main_open() -> String {
        format!(
            r#"int main(int argc, char** argv) {{
  const std::unique_ptr<VerilatedContext> ctx{{new VerilatedContext}};
  ctx->commandArgs(argc, argv);
  const std::unique_ptr<V{TOP_MODULE}> top{{new V{TOP_MODULE}{{ctx.get()}}}};
"#
        )
    }
}

fn frame_driver(config: Config) -> String {
    let DriverParts { dispmin_mask, dispmax_mask, height_mask, hex_digits, status_fmt, status_args, pixel_max } = DriverParts::new(config);
    let (head, main_open) = (DriverParts::head(FRAME_ERROR), DriverParts::main_open());
    format!(
        r#"// Generated by sim::hdl::frame::frame_driver: the camera model of
// sim::drive::stereo::StereoSim::run around Verilator's model of the line processor,
// driven directly (inputs with the clock low, eval, sample, clock high, eval).
{head}
// Reads n pixels, one hex value per line (the files `$readmemh` reads).
static bool read_image(const char* path, std::vector<uint8_t>& img, long long n) {{
  FILE* f = std::fopen(path, "r");
  if (!f) return false;
  img.assign(n, 0);
  for (long long i = 0; i < n; ++i) {{
    unsigned v;
    if (std::fscanf(f, "%x", &v) != 1 || v > {pixel_max}u) {{ std::fclose(f); return false; }}
    img[i] = (uint8_t)v;
  }}
  std::fclose(f);
  return true;
}}

{main_open}  long long w, h, hblank, dmin, dmax, quiet, limit, cut, reset_clocks, reset_idle;
  FILE* fp = std::fopen("{FRAME_PARAMS_FILE}", "r");
  if (!fp) return fail("cannot open {FRAME_PARAMS_FILE}");
  int r = std::fscanf(fp, "%lld %lld %lld %lld %lld %lld %lld %lld %lld %lld", &w, &h, &hblank, &dmin, &dmax, &quiet, &limit, &cut, &reset_clocks, &reset_idle);
  std::fclose(fp);
  if (r != 10 || w <= 0 || h <= 0 || hblank < 0 || quiet < 0 || limit < 0 || cut < 0 || reset_clocks < 0 || reset_idle < 0) return fail("bad {FRAME_PARAMS_FILE}");
  std::vector<uint8_t> left, right;
  if (!read_image("{FRAME_LEFT_FILE}", left, w * h)) return fail("cannot read {FRAME_LEFT_FILE}");
  if (!read_image("{FRAME_RIGHT_FILE}", right, w * h)) return fail("cannot read {FRAME_RIGHT_FILE}");
  FILE* fb = std::fopen("{FRAME_BEATS_FILE}", "w");
  FILE* fs = std::fopen("{FRAME_SUMMARY_FILE}", "w");
  if (!fb || !fs) return fail("cannot write the output files");
  static char beats_buf[1 << 20];
  std::setvbuf(fb, beats_buf, _IOFBF, sizeof beats_buf);
  long long lx = 0, ly = 0, lidle = 0, rx = 0, ry = 0, ridle = 0, rows = 0;
  uint64_t cycle = 0, stalls = 0, pixels_in = 0, first_in = 0, last_in = 0, last_activity = 0;
  bool have_in = false, done = false, over_limit = false, cutting = cut > 0;
  top->{CLOCK_PORT} = 0;
  top->{RESET_PORT} = 0;
  top->dispmin = (uint64_t)dmin & {dispmin_mask};
  top->dispmax = (uint64_t)dmax & {dispmax_mask};
  top->height = (uint64_t)h & {height_mask};
  while (!done) {{
    if (cutting && cycle == (uint64_t)cut) {{
      // The frame cut short: reset, idle, then the frame anew from clock 0.
      top->l_tvalid = 0; top->l_tdata = 0; top->l_tuser = 0; top->l_tlast = 0;
      top->r_tvalid = 0; top->r_tdata = 0; top->r_tuser = 0; top->r_tlast = 0;
      for (long long k = 0; k < reset_clocks + reset_idle; ++k) {{
        top->{RESET_PORT} = k < reset_clocks;
        top->eval();
        top->{CLOCK_PORT} = 1;
        top->eval();
        top->{CLOCK_PORT} = 0;
      }}
      top->{RESET_PORT} = 0;
      lx = ly = lidle = rx = ry = ridle = rows = 0;
      cycle = stalls = pixels_in = first_in = last_in = last_activity = 0;
      have_in = false;
      cutting = false;
    }}
    const bool l_off = ly < h && lidle == 0;
    const bool r_off = ry < h && ridle == 0;
    top->l_tvalid = l_off;
    top->l_tdata = l_off ? left[ly * w + lx] : 0;
    top->l_tuser = l_off && lx == 0 && ly == 0;
    top->l_tlast = l_off && lx == w - 1;
    top->r_tvalid = r_off;
    top->r_tdata = r_off ? right[ry * w + rx] : 0;
    top->r_tuser = r_off && rx == 0 && ry == 0;
    top->r_tlast = r_off && rx == w - 1;
    top->eval();
    const bool l_take = l_off && top->l_tready;
    const bool r_take = r_off && top->r_tready;
    if ((l_off && !l_take) || (r_off && !r_take)) ++stalls;
    if (l_take) {{
      ++pixels_in;
      if (!have_in) {{ first_in = cycle; have_in = true; }}
      last_in = cycle;
      last_activity = cycle;
    }}
    if (top->m_tvalid && !cutting) {{
      last_activity = cycle;
      std::fprintf(fb, "%llu %0{hex_digits}llx %u %u\n", (unsigned long long)cycle, (unsigned long long)top->m_tdata, (unsigned)top->m_tuser, (unsigned)top->m_tlast);
      if (top->m_tlast) ++rows;
    }}
    top->{CLOCK_PORT} = 1;
    top->eval();
    top->{CLOCK_PORT} = 0;
    ++cycle;
    if (lidle > 0) --lidle;
    else if (l_take) {{
      if (++lx == w) {{ lx = 0; ++ly; lidle = hblank; }}
    }}
    if (ridle > 0) --ridle;
    else if (r_take) {{
      if (++rx == w) {{ rx = 0; ++ry; ridle = hblank; }}
    }}
    if (!cutting && (rows >= h || (ly >= h && ry >= h && cycle - last_activity > (uint64_t)quiet))) done = true;
    if (cycle >= (uint64_t)limit) {{ over_limit = true; done = true; }}
  }}
  std::fprintf(fs, "%llu %llu %llu %llu %llu{status_fmt}\n", (unsigned long long)cycle, (unsigned long long)stalls, (unsigned long long)pixels_in, (unsigned long long)first_in, (unsigned long long)last_in{status_args});
  top->final();
  if (std::fclose(fb) != 0 || std::fclose(fs) != 0) return fail("cannot write the output files");
  if (over_limit) return fail("the clock limit was reached");
  std::printf("{FRAME_DONE} %llu\n", (unsigned long long)cycle);
  return 0;
}}
"#
    )
}

/// One byte per line in hex, for `$readmemh`.
fn image_hex(image: &GreyImage) -> String {
    let mut s = String::with_capacity(image.width() * image.height() * 3);
    for y in 0..image.height() {
        for &v in image.row(y) {
            let _ = writeln!(s, "{v:02x}");
        }
    }
    s
}

/// A clock limit no correct run reaches: every pixel's clock and blanking
/// four times over, plus the quiet time and a line processor's worth of
/// latency.
fn clock_limit(width: usize, height: usize, hblank: usize) -> u64 {
    4 * ((width + hblank) * height) as u64 + 2 * QUIET_CLOCKS + 1_000_000
}

pub(crate) fn parse_err(what: &str, line: usize, msg: impl Into<String>) -> CosimError {
    CosimError::Parse { what: what.to_string(), line, msg: msg.into() }
}

/// A driver's summary line (`file`): five decimal numbers of the run, then
/// the status counters in [`STATUS_NAMES`]' order.
pub(crate) fn parse_summary(file: &str, summary: &str) -> Result<Vec<u64>, CosimError> {
    let v: Vec<u64> = summary
        .split_whitespace()
        .map(|t| t.parse::<u64>())
        .collect::<Result<_, _>>()
        .map_err(|_| parse_err(file, 1, format!("not decimal numbers: `{}`", summary.trim())))?;
    if v.len() != 5 + STATUS_NAMES.len() {
        return Err(parse_err(file, 1, format!("{} values, expected {}", v.len(), 5 + STATUS_NAMES.len())));
    }
    Ok(v)
}

/// The [`StereoRun`] the testbench's files describe (`width` the lines').
fn parse_frame(beats: &str, summary: &str, width: usize) -> Result<StereoRun, CosimError> {
    let mut run = StereoRun { width, ..StereoRun::default() };
    let mut pending = PendingLine::default();
    for (i, line) in beats.lines().enumerate() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let bad = || parse_err(FRAME_BEATS_FILE, i + 1, format!("expected `clock tdata tuser tlast`, got `{line}`"));
        if f.len() != 4 {
            return Err(bad());
        }
        let clock: u64 = f[0].parse().map_err(|_| bad())?;
        let word = u64::from_str_radix(f[1], 16).map_err(|_| parse_err(FRAME_BEATS_FILE, i + 1, format!("tdata `{}` is not hex (X or Z from the simulator?)", f[1])))?;
        run.push_beat(clock, word, f[2] == "1", f[3] == "1", &mut pending);
    }
    let v = parse_summary(FRAME_SUMMARY_FILE, summary)?;
    run.cycles = v[0];
    run.stall_cycles = v[1];
    run.pixels_in = v[2];
    run.first_in = v[3];
    run.last_in = v[4];
    run.records_dropped = v[5];
    run.lines_dropped = v[6];
    run.pixels_dropped = v[7];
    run.lines_full = v[8];
    run.lines_wide = v[9];
    run.lines_unpaired = v[10];
    Ok(run)
}

/// Verilator's frame build: `top` with the primitives' models and the C++
/// driver, no `--timing`, [`FRAME_VERILATOR_ARGS`]; the C++ compiled with
/// [`Options::verilator_cxx_opt`] (`-O1`: a higher level makes the build
/// much longer and the simulator no faster; the comparison is in
/// docs/timing-closure.md).
const FRAME_BUILD: VerilatorBuild<'static> = VerilatorBuild {
    top: TOP_MODULE,
    args: FRAME_VERILATOR_ARGS,
    timing: false,
    files: &["top.v", MODELS_FILE, FRAME_DRIVER_FILE],
    binary: FRAME_BINARY,
};

/// The cache directory of Verilator's build of `design` with the C++
/// driver `driver` under `opts`: a hash of the design, its primitives'
/// models, the driver, the build's flags, and the Verilator, compiler and
/// `-O` flag behind the runtime objects.
pub(crate) fn frame_cache_dir(design: &str, driver: &str, opts: &Options) -> PathBuf {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    design.hash(&mut h);
    driver.hash(&mut h);
    crate::hdl::primitives::models_for(design).hash(&mut h);
    FRAME_BUILD.args.hash(&mut h);
    // The Verilator and compiler behind the runtime cache key.
    crate::hdl::cosim::verilator_cache_dir(opts, FRAME_BUILD.timing).hash(&mut h);
    let root = opts.work_root.clone().unwrap_or_else(std::env::temp_dir);
    root.join(format!("declivity-frame-{:016x}", h.finish()))
}

/// Runs `left`/`right` (the same size, at most `config`'s `W_MAX` wide)
/// through `design` (the Verilog of `config`'s line processor, module
/// `top`) under `simulator`,
/// the cameras a line every `width + hblank` clocks at best, eq. 6's
/// search area `area`: Icarus runs [`frame_testbench`],
/// Verilator [`frame_driver`] (its build cached, see the module
/// documentation). The work directory is kept after a failure (its path is
/// in the error) or with [`Options::keep`] (its path is then in
/// [`FrameRun::work_dir`]).
#[allow(clippy::too_many_arguments)]
pub fn run_frame(simulator: Simulator, config: Config, design: &str, left: &GreyImage, right: &GreyImage, hblank: usize, area: SearchArea, opts: &Options) -> Result<FrameRun, CosimError> {
    run_frame_with(simulator, config, design, left, right, hblank, area, None, opts)
}

/// A frame cut short by a reset ([`run_frame_after_reset`]): the frame is
/// played for `cut` clocks, `reset` is held high for `clocks` clocks and
/// low for `idle` more, both cameras idle, and the frame is then played
/// anew from its first pixel. As [`StereoSim::run_cut`] and
/// [`StereoSim::reset`] do to the rust-hdl model.
///
/// [`StereoSim::run_cut`]: crate::drive::stereo::StereoSim::run_cut
/// [`StereoSim::reset`]: crate::drive::stereo::StereoSim::reset
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameReset {
    pub cut: u64,
    pub clocks: u64,
    pub idle: u64,
}

/// As [`run_frame`], with the frame first cut short by `reset`; the run
/// returned is the frame played after it, its clocks counted from the
/// clock it began.
#[allow(clippy::too_many_arguments)]
pub fn run_frame_after_reset(simulator: Simulator, config: Config, design: &str, left: &GreyImage, right: &GreyImage, hblank: usize, area: SearchArea, reset: FrameReset, opts: &Options) -> Result<FrameRun, CosimError> {
    if reset.cut == 0 {
        return Err(CosimError::Port("a reset cut at clock 0 cuts nothing: give a clock inside the frame".into()));
    }
    run_frame_with(simulator, config, design, left, right, hblank, area, Some(reset), opts)
}

#[allow(clippy::too_many_arguments)]
fn run_frame_with(simulator: Simulator, config: Config, design: &str, left: &GreyImage, right: &GreyImage, hblank: usize, area: SearchArea, reset: Option<FrameReset>, opts: &Options) -> Result<FrameRun, CosimError> {
    let (w, h) = (left.width(), left.height());
    if (right.width(), right.height()) != (w, h) {
        return Err(CosimError::Port(format!("the images differ in size: left {w}×{h}, right {}×{}", right.width(), right.height())));
    }
    let (w_max, height_bits) = (config.sizes().w_max, config.sizes().height_bits);
    if w == 0 || h == 0 || w > w_max || h >= 1 << height_bits {
        return Err(CosimError::Port(format!("a {w}×{h} frame: the {config} line processor takes 1 to {w_max} pixels per line and 1 to {} lines", (1usize << height_bits) - 1)));
    }
    check_ports(design, config)?;
    let mut dir = WorkDir::new(opts.work_root.as_deref(), &format!("frame-{}", simulator.name()))?;
    let result = frame_in(simulator, config, design, left, right, hblank, area, reset, opts, &dir);
    dir.keep = opts.keep || matches!(result, Err(CosimError::ToolFailed { .. } | CosimError::Parse { .. }));
    let mut run = result?;
    if dir.keep {
        run.work_dir = Some(dir.path.clone());
    }
    Ok(run)
}

#[allow(clippy::too_many_arguments)]
fn frame_in(simulator: Simulator, config: Config, design: &str, left: &GreyImage, right: &GreyImage, hblank: usize, area: SearchArea, reset: Option<FrameReset>, opts: &Options, dir: &WorkDir) -> Result<FrameRun, CosimError> {
    let (w, h) = (left.width(), left.height());
    let cut = reset.unwrap_or(FrameReset { cut: 0, clocks: 0, idle: 0 });
    dir.write(FRAME_PARAMS_FILE, &format!("{w} {h} {hblank} {} {} {QUIET_CLOCKS} {} {} {} {}\n", area.dispmin, area.dispmax, clock_limit(w, h, hblank), cut.cut, cut.clocks, cut.idle))?;
    dir.write(FRAME_LEFT_FILE, &image_hex(left))?;
    dir.write(FRAME_RIGHT_FILE, &image_hex(right))?;
    let t0 = Instant::now();
    let (out, compile, sim, cached) = match simulator {
        Simulator::Icarus => {
            dir.write_design(design)?;
            dir.write("tb.v", &frame_testbench(config))?;
            run_tool(&opts.iverilog, Command::new(&opts.iverilog).args(["-g2012", "-s", "tb", "-o", "tb.vvp", "tb.v", "top.v", MODELS_FILE]), dir)?;
            let compile = t0.elapsed();
            let t1 = Instant::now();
            let out = run_tool(&opts.vvp, Command::new(&opts.vvp).args(["-n", "tb.vvp"]), dir)?;
            (out, compile, t1.elapsed(), false)
        }
        Simulator::Verilator => {
            let driver = frame_driver(config);
            let cache = frame_cache_dir(design, &driver, opts);
            let binary = cache.join(FRAME_BINARY);
            let cached = binary.is_file();
            if !cached {
                build_verilator(design, &driver, opts, &cache)?;
            }
            let compile = t0.elapsed();
            let t1 = Instant::now();
            let out = run_tool(FRAME_BINARY, &mut Command::new(&binary), dir)?;
            (out, compile, t1.elapsed(), cached)
        }
    };
    let log = log_of(&out);
    if log.contains(FRAME_ERROR) || !log.contains(FRAME_DONE) {
        return Err(CosimError::ToolFailed { tool: simulator.name().to_string(), status: "the frame testbench did not finish".into(), log, dir: dir.path.clone() });
    }
    let read = |name: &str| {
        let p = dir.path.join(name);
        std::fs::read_to_string(&p).map_err(io_err(&p))
    };
    let run = parse_frame(&read(FRAME_BEATS_FILE)?, &read(FRAME_SUMMARY_FILE)?, w)?;
    Ok(FrameRun { simulator, run, compile, sim, cached, work_dir: None })
}

/// Builds the Verilator simulator of `design` with the C++ driver in a
/// directory of its own and moves the binary to `cache` (a directory made
/// atomically: a build racing another leaves one of the two).
pub(crate) fn build_verilator(design: &str, driver: &str, opts: &Options, cache: &Path) -> Result<(), CosimError> {
    let mut build = WorkDir::new(opts.work_root.as_deref(), "frame-build")?;
    build.write_design(design)?;
    build.write(FRAME_DRIVER_FILE, driver)?;
    let built = verilator_build(opts, &build, &FRAME_BUILD);
    if built.is_err() {
        build.keep = true;
    }
    built?;
    let staged = build.path.join("cache");
    std::fs::create_dir_all(&staged).map_err(io_err(&staged))?;
    let from = build.path.join("obj").join(FRAME_BINARY);
    std::fs::rename(&from, staged.join(FRAME_BINARY)).map_err(io_err(&from))?;
    match std::fs::rename(&staged, cache) {
        // Another build of the same design got there first.
        Err(_) if cache.join(FRAME_BINARY).is_file() => Ok(()),
        r => r.map_err(io_err(cache)),
    }
}

/// How `hdl` differs from `model` (two runs of one frame): each field that
/// differs, with the first row that does for the lines; empty when the runs
/// are the same clock for clock.
pub fn differences(model: &StereoRun, hdl: &StereoRun) -> Vec<String> {
    let mut out = Vec::new();
    let scalars = [
        ("cycles", model.cycles, hdl.cycles),
        ("stall_cycles", model.stall_cycles, hdl.stall_cycles),
        ("pixels_in", model.pixels_in, hdl.pixels_in),
        ("first_in", model.first_in, hdl.first_in),
        ("last_in", model.last_in, hdl.last_in),
        ("first_out", model.first_out.unwrap_or(u64::MAX), hdl.first_out.unwrap_or(u64::MAX)),
        ("last_out", model.last_out.unwrap_or(u64::MAX), hdl.last_out.unwrap_or(u64::MAX)),
        ("records_dropped", model.records_dropped, hdl.records_dropped),
        ("lines_dropped", model.lines_dropped, hdl.lines_dropped),
        ("pixels_dropped", model.pixels_dropped, hdl.pixels_dropped),
        ("lines_full", model.lines_full, hdl.lines_full),
        ("lines_wide", model.lines_wide, hdl.lines_wide),
        ("lines_unpaired", model.lines_unpaired, hdl.lines_unpaired),
        ("output lines", model.rows.len() as u64, hdl.rows.len() as u64),
    ];
    for (name, a, b) in scalars {
        if a != b {
            out.push(format!("{name}: model {a}, hdl {b}"));
        }
    }
    let first_row = |what: &str, differs: &dyn Fn(usize) -> bool, n: usize| (0..n).find(|&y| differs(y)).map(|y| format!("{what} differ from output line {y} on"));
    let n = model.rows.len().min(hdl.rows.len());
    out.extend(first_row("disparities", &|y| model.rows[y] != hdl.rows[y], n));
    out.extend(first_row("depths", &|y| model.depth_rows.get(y) != hdl.depth_rows.get(y), n));
    out.extend(first_row("start-of-frame flags", &|y| model.sof.get(y) != hdl.sof.get(y), n));
    out.extend(first_row("clocks of the lines' first and last beats", &|y| model.line_cycles.get(y) != hdl.line_cycles.get(y), n));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_testbench_connects_every_port_of_the_processor_once() {
        for config in Config::ALL {
            let tb = frame_testbench(config);
            let (ins, outs) = expected_ports(config);
            for p in ins.iter().chain(&outs) {
                assert_eq!(tb.matches(&format!(".{0}({0})", p.name)).count(), 1, "{}", p.name);
            }
            assert!(tb.contains(&format!("reg [{}:0] dispmax;", config.sizes().dispmax_bits - 1)));
            assert!(tb.contains(&format!("reg [{}:0] height;", config.sizes().height_bits - 1)));
        }
    }

    #[test]
    fn the_frame_driver_sets_every_input_and_reads_every_output_of_the_processor() {
        let driver = frame_driver(Config::Hd);
        let (ins, outs) = expected_ports(Config::Hd);
        // `top->name` as a whole word (not a prefix of a longer name).
        let uses = |name: &str| {
            let key = format!("top->{name}");
            driver.match_indices(&key).any(|(i, _)| driver[i + key.len()..].chars().next().is_some_and(|c| !c.is_alphanumeric() && c != '_'))
        };
        for p in ins.iter().chain(&outs) {
            assert!(uses(&p.name), "{}", p.name);
        }
        for p in &ins {
            assert!(driver.contains(&format!("top->{} = ", p.name)), "{} is set", p.name);
        }
        assert!(driver.contains(&format!("top->{CLOCK_PORT} = 1;")));
        // Both read and write the same files and print the same markers.
        for text in [&driver, &frame_testbench(Config::Hd)] {
            for name in [FRAME_PARAMS_FILE, FRAME_LEFT_FILE, FRAME_RIGHT_FILE, FRAME_BEATS_FILE, FRAME_SUMMARY_FILE, FRAME_DONE, FRAME_ERROR] {
                assert!(text.contains(name), "{name}");
            }
        }
        // tdata zero-padded to its width, as Verilog's %h writes it.
        assert!(driver.contains(&format!("%0{}llx", OUT_BITS.div_ceil(4))));
    }

    #[test]
    fn beats_and_summary_parse_into_lines_with_their_clocks() {
        let beats = "10 00100020 1 0\n11 00200030 0 1\n15 0 0 0\n16 ffff0001 0 1\n";
        let summary = "40 3 4 2 7 1 2 3 4 5 6\n";
        let run = parse_frame(beats, summary, 2).expect("parses");
        assert_eq!(run.rows, vec![vec![0x20, 0x30], vec![0, 1]]);
        assert_eq!(run.depth_rows, vec![vec![0x10, 0x20], vec![0, 0xffff]]);
        assert_eq!(run.sof, vec![true, false]);
        assert_eq!(run.line_cycles, vec![(10, 11), (15, 16)]);
        assert_eq!((run.first_out, run.last_out), (Some(10), Some(16)));
        assert_eq!((run.cycles, run.stall_cycles, run.pixels_in, run.first_in, run.last_in), (40, 3, 4, 2, 7));
        assert_eq!((run.records_dropped, run.lines_dropped, run.pixels_dropped, run.lines_full, run.lines_wide, run.lines_unpaired), (1, 2, 3, 4, 5, 6));
        assert!(matches!(parse_frame("3 xxxx 0 0\n", summary, 2), Err(CosimError::Parse { .. })));
        assert!(matches!(parse_frame(beats, "1 2 3", 2), Err(CosimError::Parse { .. })));
    }
}
