"""The tables of the hardware datasheet (docs/hardware/datasheet.md).

Every table reads JSON under docs/data/; each function names the command that writes its
files. Run as a script, this file also writes the port list of a generated Verilog top:

    declivity verilog --top stereo --out DIR
    python3 scripts/tables/hardware.py ports DIR/declivity_stereo.v > docs/data/ports-stereo.json
"""
import json
import pathlib
import re
import sys

if __name__ == "__main__":
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))

from tables import DATA, fmt, load_jsonl, markdown, table  # noqa: E402

# The ECP5-85K's LUT4s (nextpnr's TRELLIS_COMB sites), for the share of the device.
ECP5_85K_LUTS = 83_640

# ---------------------------------------------------------------------------------------
# Ports


def parse_ports(verilog_text, module="declivity_stereo"):
    """The ports of `module` in a rust-hdl Verilog file: [{name, direction, width}] in
    declaration order, and the module's localparams {name: value}."""
    m = re.search(rf"^module {re.escape(module)}\((.*?)\);(.*?)^endmodule", verilog_text, re.S | re.M)
    if not m:
        raise SystemExit(f"no module {module} in the Verilog")
    order = [p.strip() for p in m.group(1).split(",")]
    body = m.group(2)
    decl = {}
    for d in re.finditer(r"^\s*(input|output)\s+(?:wire|reg)?\s*(?:\[(\d+):(\d+)\])?\s*(\w+);", body, re.M):
        direction, hi, lo, name = d.groups()
        width = int(hi) - int(lo) + 1 if hi is not None else 1
        decl[name] = {"name": name, "direction": direction, "width": width}
    params = {}
    for p in re.finditer(r"^\s*localparam\s+(\w+)\s*=\s*(\d+)'([bhd])([0-9a-fA-F_]+);", body, re.M):
        name, _bits, base, digits = p.groups()
        params[name] = int(digits.replace("_", ""), {"b": 2, "h": 16, "d": 10}[base])
    return [decl[n] for n in order], params


# What each port of the top is, from rtl/src/stereo_line_processor.rs's "Ports" (the widths
# come from the Verilog: a port missing here, or described but not generated, fails).
PORT_GROUPS = [
    ("Clock and reset", {
        "clock": "The one clock; every register samples on its rising edge. Registers start "
                 "from their initial values (FPGA configuration).",
        "reset": "Synchronous, active high, one clock or more, at any clock: every register "
                 "back to its initial value, lines in flight forgotten, counters at zero. The "
                 "detectors then clear their histograms, one clock per grey level: `l_tready` "
                 "and `r_tready` are low until that is done ([Reset](#reset)).",
    }),
    ("Left camera, AXI4-Stream video in (the reference view)", {
        "l_tdata": "Grey level of the pixel.",
        "l_tvalid": "A pixel is offered.",
        "l_tuser": "Start of frame: high on the frame's first pixel (read on a line's first pixel).",
        "l_tlast": "End of line: high on the line's last pixel.",
        "l_tready": "The pixel is taken (`tvalid && tready`). A register (the input's register "
                    "slice): high except between lines shorter than `MIN_LINE_PERIOD`, a clock "
                    "after the detector's own ready.",
    }),
    ("Right camera, AXI4-Stream video in", {
        "r_tdata": "Grey level of the pixel.",
        "r_tvalid": "A pixel is offered.",
        "r_tuser": "Start of frame, as `l_tuser`.",
        "r_tlast": "End of line, as `l_tlast`.",
        "r_tready": "The pixel is taken; as `l_tready`.",
    }),
    ("Run-time inputs", {
        "dispmin": "Eq. 6's lower search bound: a node exists for `dispmin < d < dispmax` "
                   "(0: the paper's `0 < d`). Unsigned, 4 fraction bits (1/16 px). Hold it "
                   "during a frame.",
        "dispmax": "Eq. 6's search bound: a node exists for `dispmin < d < dispmax`. Unsigned, 4 "
                   "fraction bits (1/16 px). Hold it during a frame.",
        "height": "Rows of the frame: its last row ends the frame for the row check and the "
                  "median, which then flush it. Registered: set it before the frame and keep it "
                  "to the frame's last pixel out of the interpolator.",
    }),
    ("Output, AXI4-Stream video without back-pressure (one beat per reference pixel)", {
        "m_tvalid": "A beat: one disparity (and depth) of the left view. No `m_tready`: the "
                    "sink takes a beat on every clock it is offered.",
        "m_tdata": "Depth and disparity of the pixel (bit map below).",
        "m_tuser": "Start of frame: the frame's first pixel.",
        "m_tlast": "End of line: the line's last pixel. Every line of a frame has the frame's width: "
                   "that of the reference camera's first line of the frame.",
    }),
    ("Status: counters that wrap (each counts its event two clocks after it)", {
        "records_dropped": "Detector beats (records) that found a record queue full.",
        "lines_dropped": "Lines the row check had no room for (rows arriving faster than it "
                         "checks them), or the interpolator (ruled out by the limit on lines in "
                         "flight), and the last row of a frame cut short (dropped when the next "
                         "frame begins); their pixels are not sent.",
        "pixels_dropped": "Pixels that reached the vertical median while it flushed a frame's "
                          "last four rows (vertical blanking too short).",
        "lines_full": "Line pairs with more than `N_MAX` characteristic declivities on a side: "
                      "the first `N_MAX` are matched.",
        "lines_wide": "Line pairs with a side cut: wider than `W_MAX`, or a later line of a "
                      "frame wider than the frame's first (a late end of line, or a `tlast` "
                      "missing); the first pixels are processed, the rest dropped to `tlast`.",
        "lines_unpaired": "Lines of one camera dropped unpaired: the other camera's line at "
                          "their place starts a frame and they do not (the frame before had "
                          "more lines on their camera), or both start one more than "
                          "`SOF_SKEW_MAX` clocks apart and theirs is the older.",
    }),
]


def _ports(name="ports-stereo.json"):
    # docs/data/ports-stereo.json:
    #   declivity verilog --top stereo --out DIR
    #   python3 scripts/tables/hardware.py ports DIR/declivity_stereo.v > docs/data/ports-stereo.json
    return load_jsonl(name)[0]


@table("hw-ports")
def hw_ports():
    """The top's ports, grouped, with widths from the generated Verilog."""
    # docs/data/ports-stereo.json: declivity verilog --top stereo --out DIR;
    #   python3 scripts/tables/hardware.py ports DIR/declivity_stereo.v > docs/data/ports-stereo.json
    data = _ports()
    by_name = {p["name"]: p for p in data["ports"]}
    described = {n for _, g in PORT_GROUPS for n in g}
    missing = set(by_name) - described
    extra = described - set(by_name)
    if missing or extra:
        raise SystemExit(f"hw-ports: ports not described {sorted(missing)}, described but not generated {sorted(extra)}")
    rows = []
    for title, group in PORT_GROUPS:
        rows.append([f"**{title}**", "", "", ""])
        for name, text in group.items():
            p = by_name[name]
            rows.append([f"`{name}`", p["direction"], p["width"], text])
    return markdown(["port", "direction", "width", "description"], rows, ["---", "---", "--:", "---"])


@table("hw-tdata")
def hw_tdata():
    """The bit map of m_tdata, from the Verilog: the width of m_tdata, the top's shift of the
    depth (`sh_depth`) and the width of a disparity (`dispmax`'s, the position format)."""
    # docs/data/ports-stereo.json: declivity verilog --top stereo --out DIR;
    #   python3 scripts/tables/hardware.py ports DIR/declivity_stereo.v > docs/data/ports-stereo.json
    data = _ports()
    by_name = {p["name"]: p for p in data["ports"]}
    width = by_name["m_tdata"]["width"]
    shift = data["localparams"]["sh_depth"]
    pos_bits = by_name["dispmax"]["width"]
    rows = [
        [f"{width - 1}..{shift}", width - shift, "depth `Z` in mm, unsigned, rounded; 0 = no depth (disparity 0); "
         f"{(1 << (width - shift)) - 1} = that far or farther (saturated)"],
    ]
    if pos_bits < shift:
        rows.append([f"{shift - 1}..{pos_bits}", shift - pos_bits, "0"])
    rows.append([f"{pos_bits - 1}..0", pos_bits, "disparity `d = x_left − x_right`, unsigned, 4 fraction bits "
                 "(1/16 px: `d = value / 16`); 0 = no disparity"])
    return markdown(["bits", "width", "field"], rows, ["---", "--:", "---"])


# ---------------------------------------------------------------------------------------
# The simulated trace of the timing diagrams


@table("hw-trace")
def hw_trace():
    """The run the timing diagrams are cut from."""
    # docs/hardware/wave/trace-run.json: scripts/timing-diagrams.sh DECLIVITY (its summary of
    #   declivity rtl depth data/stereo/tsukuba/left_gray.png data/stereo/tsukuba/right_gray.png
    #     --dispmax 15 --rows 100..110 --hblank 24 --vcd FILE --lines 0..10 --json)
    r = json.loads((DATA.parent / "hardware" / "wave" / "trace-run.json").read_text())
    status = ", ".join(str(r[k]) for k in ("records_dropped", "lines_dropped", "pixels_dropped", "lines_full", "lines_wide"))
    rows = [[
        f"`{r['image']}`, rows {r['rows']}",
        f"{r['width']}×{r['height']}",
        f"{r['dispmax']:g}",
        r["hblank"],
        _n(r["cycles"]),
        f"{r['px_per_clk']:.4f}",
        r["stall_cycles"],
        _n(r["latency_cycles"]),
        r["lines_out"],
        f"{r['agree_quarter_px']:.4f}",
        status,
    ]]
    return markdown(["pair", "frame", "dispmax (px)", "hblank", "clocks", "px/clk (incl. blanking)", "stall clocks",
                     "latency, first pixel in → first out (clk)", "lines out", "within 1/4 px of golden",
                     "status counters (records, lines, pixels dropped; full, wide)"],
                    rows, ["---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "---"])


# ---------------------------------------------------------------------------------------
# Latency budget examples

# docs/data/budget-*.json, each written by
#   declivity budget --width W --height H --n-max N --dispmax D --clock-mhz 125 [--hblank C] --json
# with the values of its name (dispmax 64 unless the name says otherwise):
BUDGET_EXAMPLES = [
    ("budget-512x512-n56-dispmax60.json", "the paper's rig: 512×512, dispmax 60 px, N = 56"),
    ("budget-512x512-n128.json", "512×512, N = 128"),
    ("budget-512x512-n128-hblank648.json", "512×512, N = 128, input paced"),
    ("budget-1024x768-n128.json", "1024×768, N = 128"),
    ("budget-1024x768-n128-hblank320.json", "1024×768, N = 128, XGA timing"),
]


def _n(v):
    return fmt(v, ",")


def _esc(text):
    """A cell's text with its pipes escaped (`|ΔI|`)."""
    return str(text).replace("|", "\\|")


@table("hw-budget-examples")
def hw_budget_examples():
    """One row per budget example: the line period, latency, frame end, blanking, rate."""
    # docs/data/budget-*.json: declivity budget --width W --height H --n-max N --dispmax D
    #   --clock-mhz 125 [--hblank C] --json > docs/data/budget-WxH-nN[-dispmaxD][-hblankC].json
    #   (dispmax 64 unless the name says otherwise; see BUDGET_EXAMPLES)
    rows = []
    for name, title in BUDGET_EXAMPLES:
        b = load_jsonl(name)[0]
        matcher = next(s for s in b["stages"] if s["name"] == "matcher")
        check = next(s for s in b["stages"] if s["name"] == "row check")
        over = b["stall_cycles_per_line"]
        rows.append([
            title,
            b["hblank"],
            f"{_n(matcher['cycles_per_line'])} / {_n(check['cycles_per_line'])}",
            f"{_n(b['line_period_cycles'])} ({b['slowest_stage']})" if over else f"{_n(b['line_period_cycles'])} (the input)",
            f"{_n(over)} (hblank ≥ {_n(b['min_hblank_cycles'])} paces the input)" if over else "0",
            f"{_n(b['latency_cycles'])} clk = {b['latency_us']:.2f} µs",
            _n(b["flush_cycles"]),
            f"{b['vblank_lines']} ({b['vblank_lines_any_rows']})",
            f"{b['frame_time_ms']:.3f} ms",
            f"{b['fps']:.1f}",
        ])
    return markdown(
        ["example (125 MHz, 32 cells)", "hblank", "matcher / row check, worst clk per line", "line period P",
         "slowest stage over W + hblank, clk per line", "latency (first pixel in → first disparity out)", "flush (last pixel in → last out)",
         "vertical blanking, lines (any rows)", "frame", "frames/s"],
        rows,
        ["---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:"],
    )


# The HD video formats in the hd configuration, each at its pixel clock: (format, timing,
# total pixels per line, total lines, pixel clock MHz, budget file stem with {n} for N).
# docs/data/budget-WxH-nN-hblankC-hd-MHZ.json, each written by
#   declivity budget --config hd --width W --height H --n-max N --dispmax 128
#     --clock-mhz MHZ --hblank C --json
# (scripts/doc-data.sh budget).
HD_FORMATS = [
    ("1280×720 at 60 fps", "CEA-861 720p60", 1650, 750, 74.25, "budget-1280x720-n{n}-hblank370-hd-74.25.json"),
    ("1280×800 at 120 fps", "CVT-RB", 1440, 847, 146.25, "budget-1280x800-n{n}-hblank160-hd-146.25.json"),
    ("1920×1080 at 30 fps", "CEA-861 1080p30", 2200, 1125, 74.25, "budget-1920x1080-n{n}-hblank280-hd-74.25.json"),
    ("1920×1080 at 60 fps", "CEA-861 1080p60", 2200, 1125, 148.5, "budget-1920x1080-n{n}-hblank280-hd-148.5.json"),
    ("1920×1080 at 60 fps", "CVT-RB", 2080, 1111, 138.5, "budget-1920x1080-n{n}-hblank160-hd-138.5.json"),
]
HD_N = [160, 256]


@table("hw-budget-hd")
def hw_budget_hd():
    """The HD formats in hd at their pixel clocks: line period against the line's clocks, the
    vertical blanking needed against the format's, and whether the format fits."""
    rows = []
    for title, timing, htotal, vtotal, mhz, stem in HD_FORMATS:
        for n in HD_N:
            b = load_jsonl(stem.format(n=n))[0]
            assert b["config"] == "hd" and b["hblank"] == htotal - b["width"] and b["clock_mhz"] == mhz
            vblank = vtotal - b["height"]
            line_ok = b["line_period_cycles"] <= htotal
            frame_ok = b["vblank_lines"] <= vblank
            slowest = b["slowest_stage"] if b["stall_cycles_per_line"] else "the input"
            rows.append([
                title if n == HD_N[0] else "",
                f"{timing}: {htotal} × {vtotal}, {mhz} MHz" if n == HD_N[0] else "",
                n,
                f"{_n(b['line_period_cycles'])} ({slowest})",
                f"{b['vblank_lines']} of {vblank}",
                f"{b['latency_cycles'] / mhz:.1f} µs",
                "**fits**" if line_ok and frame_ok else f"no: P over {htotal} by {_n(b['line_period_cycles'] - htotal)} clk" if not line_ok else "no: vertical blanking",
            ])
    return markdown(["format", "timing (total pixels × lines, pixel clock = the processor's clock)", "N per line",
                     "line period P, clk (slowest stage)", "vertical blanking needed, lines", "latency", "fits"],
                    rows, ["---", "---", "--:", "--:", "--:", "--:", "---"])


@table("hw-configurations")
def hw_configurations():
    """The configurations: their sizes (the budgets' `hardware`) and memories as generated."""
    # docs/data/budget-512x512-n128.json (sd) and budget-1920x1080-n256-hblank280-hd-148.5.json
    # (hd): declivity budget [--config hd] ... --json (scripts/doc-data.sh budget)
    rows = []
    for name in ["budget-512x512-n128.json", "budget-1920x1080-n256-hblank280-hd-148.5.json"]:
        b = load_jsonl(name)[0]
        h, r = b["hardware"], b["resources"]
        rows.append([
            f"`{h['config']}`", _n(h["w_max"]), h["n_max"], f"{h['cells']} × {h['rows_per_cell']}",
            h["pos_bits"], h["dispmax_bits"], f"{h['height_bits']} (up to {_n((1 << h['height_bits']) - 1)} rows)",
            _n(h["sof_skew_max"]), _n(r["memory_bits"]), r["dp16kd_instances"], _n(r["reference_row_dpr16x4"]),
        ])
    return markdown(["`--config`", "`W_MAX`, px", "`N_MAX`", "gain cells × rows", "disparity and position bits (`m_tdata`, 4 fraction)",
                     "`dispmax` bits", "`height` bits", "`SOF_SKEW_MAX`, clk", "memory bits", "DP16KD instantiated", "TRELLIS_DPR16X4"],
                    rows, ["---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:"])


@table("hw-budget-stages")
def hw_budget_stages():
    """The stages of one example (512×512, N = 128): clocks per line and latency terms."""
    # docs/data/budget-512x512-n128.json: declivity budget --width 512 --height 512 --n-max 128
    #   --dispmax 64 --clock-mhz 125 --json
    b = load_jsonl("budget-512x512-n128.json")[0]
    rows = []
    for s in b["stages"]:
        inst = f" ×{s['instances']}" if s["instances"] > 1 else ""
        rows.append([
            s["name"] + inst,
            _n(s["cycles_per_line"]),
            _n(s["latency_cycles"]),
            _esc(s["latency_span"]),
            "`" + s["latency_formula"] + "`",
        ])
    rows.append(["**scanline**", f"**P = {_n(b['line_period_cycles'])}**", f"**{_n(b['latency_cycles'])}**",
                 "a row's first pixel in → its first disparity out", ""])
    return markdown(["stage", "clk per worst line", "latency, clk", "from → to", "latency formula = values"],
                    rows, ["---", "--:", "--:", "---", "---"])


@table("hw-memories")
def hw_memories():
    """The memories as generated (the same in every budget: generation-time sizes)."""
    # docs/data/budget-512x512-n128.json: declivity budget --width 512 --height 512 --n-max 128
    #   --dispmax 64 --clock-mhz 125 --json
    b = load_jsonl("budget-512x512-n128.json")[0]
    r = b["resources"]
    rows = []
    for m in r["memories"]:
        dp = m.get("dp16kd")
        rows.append([
            m["stage"], _esc(m["name"]),
            f"{m['copies']} × {m['banks']} × {_n(m['words_per_bank'])} × {m['word_bits']}",
            _n(m["bits"]),
            dp if dp is not None else "inferred (LUT RAM / logic)",
        ])
    rows.append(["**all of the above**", "", "", f"**{_n(r['memory_bits'])}**", f"**{r['dp16kd_instances']}**"])
    per_row = r["reference_row_bits"] // (r["pe_count"] * r["rows_per_cell"])
    rows.append(["matcher", "gain cells' reference rows", f"{r['pe_count']} × 1 × {r['rows_per_cell']} × {per_row}",
                 _n(r["reference_row_bits"]), f"— (LUT RAM: {r['reference_row_dpr16x4']} TRELLIS_DPR16X4)"])
    return markdown(["stage", "memory", "copies × banks × words × bits", "bits", "DP16KD"], rows,
                    ["---", "---", "--:", "--:", "--:"])


# ---------------------------------------------------------------------------------------
# Synthesis

# docs/data/synth-<top>-seed<N>.json, each written (from the repository's root) by
#   declivity synth --top <top> --seed <N> --json > docs/data/synth-<top>-seed<N>.json
# (Yosys synth_ecp5 + nextpnr-ecp5 for the LFE5U-85F-6, 125 MHz asked, placer timing weight 25).
SYNTH_BLOCKS = [
    ("detector", "declivity detector (one camera)"),
    ("matcher", "matcher (32 gain cells × 4 rows, traceback)"),
    ("interpolator", "interpolator"),
    ("stereo", "**line processor (the top)**"),
]


def _synth(top, seed):
    return load_jsonl(f"synth-{top}-seed{seed}.json")[0]


def _lut_share(r):
    return f"{_n(r['luts'])} ({100 * r['luts'] / ECP5_85K_LUTS:.1f} %)"


@table("hw-synth-blocks")
def hw_synth_blocks():
    """Each block alone and the top, placer seed 1."""
    # docs/data/synth-<top>-seed1.json: declivity synth --top <top> --seed 1 --json
    #   (top: detector, matcher, interpolator, stereo)
    rows = []
    for top, title in SYNTH_BLOCKS:
        r = _synth(top, 1)
        rows.append([
            title, f"`{top}`", _lut_share(r), _n(r["ffs"]), _n(r["lutram"]), r["brams"], r["dsps"],
            f"**{r['fmax_mhz']:.1f} MHz**" if r["meets_target"] else f"{r['fmax_mhz']:.1f} MHz",
            r["io_mode"],
            _short_path(r.get("critical_path") or []),
        ])
    return markdown(["block", "--top", "LUT4 (of 83 640)", "FF", "LUT RAM", "DP16KD", "MULT18X18D", "Fmax", "IOs",
                     "critical path"],
                    rows, ["---", "---", "--:", "--:", "--:", "--:", "--:", "--:", "---", "---"])


# The Artix-7 XC7A100T's resources, for the shares of the estimate (DS180: 63 400 LUTs,
# 126 800 flip-flops, 135 RAMB36 = 270 RAMB18, 240 DSP48E1).
XC7A100T = {"luts": 63_400, "ffs": 126_800, "ramb36": 135, "dsps": 240}


@table("hw-synth-artix7")
def hw_synth_artix7():
    """Each block and the top of the generic target, Yosys synth_xilinx (xc7) beside the ECP5's
    place-and-route figures of the ecp5 target (seed 1)."""
    # docs/data/synth-artix7-<top>.json: declivity synth --family artix7 --top <top> --json
    #   (top: detector, matcher, interpolator, stereo)
    rows = []
    for top, title in SYNTH_BLOCKS:
        x = load_jsonl(f"synth-artix7-{top}.json")[0]
        e = _synth(top, 1)
        bram36 = x["ramb36"] + x["ramb18"] / 2
        rows.append([
            title, f"`{top}`",
            f"{_n(x['luts'])} ({100 * x['luts'] / XC7A100T['luts']:.1f} %)", _n(x["lut_memory"]), _n(x["ffs"]),
            f"{x['ramb18']} + {x['ramb36']} ({100 * bram36 / XC7A100T['ramb36']:.1f} %)", x["dsps"],
            _n(e["luts"]), e["brams"], e["dsps"],
        ])
    return markdown(["block", "--top", "Artix-7 LUT6 (of XC7A100T's 63 400)", "LUT as memory", "FF",
                     "RAMB18 + RAMB36", "DSP48E1", "ECP5 LUT4", "ECP5 DP16KD", "ECP5 MULT18X18D"],
                    rows, ["---", "---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:"])


@table("hw-synth-stereo")
def hw_synth_stereo():
    """The top on placer seeds 1, 2, 3 (the same netlist), with each run's critical path."""
    # docs/data/synth-stereo-seed<N>.json: declivity synth --top stereo --seed N --json (N = 1, 2, 3)
    rows = []
    for seed in (1, 2, 3):
        r = _synth("stereo", seed)
        path = r.get("critical_path") or []
        rows.append([
            seed, _lut_share(r), _n(r["ffs"]), _n(r["lutram"]), r["brams"], r["dsps"],
            f"**{r['fmax_mhz']:.1f} MHz**" if r["meets_target"] else f"{r['fmax_mhz']:.1f} MHz",
            f"{r['seconds'] / 60:.0f} min",
            _short_path(path),
        ])
    return markdown(["seed", "LUT4 (of 83 640)", "FF", "LUT RAM", "DP16KD", "MULT18X18D", "Fmax", "run time", "critical path"],
                    rows, ["--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "---"])


@table("hw-synth-hd")
def hw_synth_hd():
    """The hd top (64 gain cells x 4 rows) on each speed grade and placer seed measured, with
    its target clock and critical path."""
    # docs/data/synth-hd-stereo-speed<S>-seed<N>.json:
    #   declivity synth --config hd --top stereo --speed S --seed N --mhz F --json
    runs = _hd_runs()
    if not runs:
        return "No run of the design and flow as they are yet (the earlier runs are in\n[`docs/timing-closure.md`](../timing-closure.md))."
    rows = []
    for speed, seed, r in runs:
        if not r["device"].startswith(f"LFE5U-85F-{speed} "):
            raise SystemExit(f"hw-synth-hd: synth-hd-stereo-speed{speed}-seed{seed}.json is of {r['device']}")
        rows.append([
            speed, seed, f"{r['target_mhz']:g} MHz", _lut_share(r), _n(r["ffs"]), _n(r["lutram"]), r["brams"], r["dsps"],
            f"**{r['fmax_mhz']:.1f} MHz**" if r["meets_target"] else f"{r['fmax_mhz']:.1f} MHz",
            f"{r['seconds'] / 60:.0f} min",
            _short_path(r.get("critical_path") or []),
        ])
    return markdown(["speed", "seed", "target", "LUT4 (of 83 640)", "FF", "LUT RAM", "DP16KD", "MULT18X18D", "Fmax", "run time", "critical path"],
                    rows, ["--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "---"])


def _short_path(path):
    """The critical path in one line: its delay (logic, routing) from the report's summary,
    and the register it starts from and the one it ends on (the cells of its first and last
    steps, without nextpnr's suffixes)."""
    if not path:
        return "—"
    m = re.match(r"\s*([\d.]+ ns).*\(logic ([\d.]+ ns), routing ([\d.]+ ns)\)", path[0])
    head = f"{m.group(1)} ({m.group(2)} logic, {m.group(3)} routing)" if m else path[0].strip()
    steps = [re.split(r"\s{2,}", s.strip()) for s in path[1:]]
    cells = [s[-1].split()[0] for s in steps if len(s) >= 3]
    if len(cells) >= 2:
        def reg(c):
            return re.sub(r"(_TRELLIS_FF_Q|_LUT4|_DP16KD|_MULT18X18D)\S*$", "", c.rsplit(".", 1)[0] if c.endswith((".Q", ".DI", ".CE", ".LSR", ".M")) else c)
        head += f": `{reg(cells[0])}` → `{reg(cells[-1])}`"
    return head.replace("|", "\\|")


def _hd_runs():
    """The hd top's runs: (speed, seed, report) of each docs/data/synth-hd-stereo-speed<S>-seed<N>.json."""
    runs = []
    for f in sorted(DATA.glob("synth-hd-stereo-speed*-seed*.json")):
        m = re.fullmatch(r"synth-hd-stereo-speed(\d)-seed(\d+)\.json", f.name)
        if m:
            runs.append((int(m.group(1)), int(m.group(2)), load_jsonl(f.name)[0]))
    return runs


def _carry_outs(r):
    """How the run gave nextpnr the carry outputs nothing reads (reports from before the
    flow disconnected them have no such field)."""
    n = r.get("carry_outs_detached")
    return "kept" if n is None or n == 0 else "disconnected"


@table("hw-synth-tools")
def hw_synth_tools():
    """The flow's tools and options as the reports record them, one row per distinct set."""
    # docs/data/synth-<top>-seed<N>.json: declivity synth --top <top> --seed N --json
    # docs/data/synth-hd-stereo-speed<S>-seed<N>.json: declivity synth --config hd --top stereo ...
    groups = {}
    for top, _ in SYNTH_BLOCKS:
        for seed in (1, 2, 3):
            if not (DATA / f"synth-{top}-seed{seed}.json").exists():
                continue
            r = _synth(top, seed)
            key = (r["tools"], r["device"], f"{r['target_mhz']:.0f} MHz", r["timing_weight"], _carry_outs(r))
            groups.setdefault(key, []).append(f"`{top}` seed {seed}")
    for speed, seed, r in _hd_runs():
        key = (r["tools"], r["device"], f"{r['target_mhz']:.0f} MHz", r["timing_weight"], _carry_outs(r))
        groups.setdefault(key, []).append(f"`hd` `stereo` speed {speed} seed {seed}")
    rows = [[*key, ", ".join(runs)] for key, runs in groups.items()]
    return markdown(["tools", "device", "target", "placer timing weight", "unread carry outs", "runs"], rows)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "ports":
        ports, params = parse_ports(pathlib.Path(sys.argv[2]).read_text())
        doc = {
            "source": "declivity verilog --top stereo --out DIR; DIR/declivity_stereo.v, module declivity_stereo",
            "module": "declivity_stereo",
            "ports": ports,
            "localparams": params,
        }
        print(json.dumps(doc, indent=1))
    else:
        sys.exit(__doc__)


@table("hw-faults")
def hw_faults():
    """The fault campaign, 1 000 faulty frames per class group, on `sd`'s Verilog."""
    # docs/data/faults-*.json: declivity rtl faults --frames 1000 [--classes ...] --json
    # (scripts/doc-data.sh faults)
    rows = []
    for name in ["faults-four.json", "faults-widths.json", "faults-all.json"]:
        f = load_jsonl(name)[0]
        injected = ", ".join(f"{k} {_n(v)}" for k, v in sorted(f["injected"].items()))
        status = dict(f["status"])
        violated = f["violated"]
        rows.append([
            "all six" if len(f["classes"]) == 6 else ", ".join(f"`{c}`" for c in f["classes"]),
            _n(f["faulty_frames"]), injected,
            f"{_n(f['clean_exact'])} of {_n(f['clean_frames'])}", _n(f["clean_unchecked"]),
            _n(violated.get("hang", 0)), _n(violated.get("malformed_line", 0)),
            _n(violated.get("misaligned_line", 0)), _n(violated.get("clean_frame_inexact", 0)),
            _n(status["lines_unpaired"]), _n(status["lines_wide"]), _n(status["lines_dropped"]),
            f"{f['sim_seconds']:.0f}",
        ])
    return markdown(["classes", "faulty frames", "injected (frames with the class)", "clean frames exact",
                     "unchecked", "hangs", "malformed lines", "misaligned lines", "inexact clean frames",
                     "`lines_unpaired`", "`lines_wide`", "`lines_dropped`", "Verilator, s"],
                    rows, ["---", "--:", "---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:"])
