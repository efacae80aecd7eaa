"""Tables of README.md, docs/method.md, docs/results.md and docs/verification.md.

Each reads files under docs/data/ that `scripts/doc-data.sh STEP` writes (docs/data/README.md
names the command of every file):

- eval-<mode>.jsonl          `declivity eval --json --diagnose --mode MODE data/stereo` (accuracy)
- eval-{bright,noise3}-<mode>.jsonl  the same on changed copies of the pairs (robustness)
- bench.json                 OpenCV StereoBM/SGBM and golden, one thread, one run (bench)
- eval-rtl.jsonl             `declivity eval --rtl --engine verilator --json data/stereo` (rtl)
- rtl-detect.jsonl           `declivity rtl detect PAIR/left_gray.png --json` per pair (detect)
- synth-stereo-seed{1,2,3}.json  `declivity synth --top stereo --seed N --json` (written by
                             the hardware datasheet's measurements)
"""
import statistics

from tables import DATA, fmt, load_jsonl, markdown, table

PAIRS = ["tsukuba", "venus", "sawtooth", "map", "cones", "teddy", "art", "motorcycle"]
MODES = ["paper", "relative", "one-sided", "consistent", "edges", "median", "edge-flag", "robust", "contour"]
DEVICE_LUTS = 83_640  # LFE5U-85F


def evals(name):
    """The per-pair reports of docs/data/NAME (eval --json), by pair."""
    return {r["pair"]: r for r in load_jsonl(name) if "mode" in r}


def diagnoses(name):
    """The per-pair diagnoses of docs/data/NAME (eval --json --diagnose), by pair."""
    return {r["pair"]: r["diagnosis"] for r in load_jsonl(name) if "diagnosis" in r}


def bench():
    return load_jsonl("bench.json")[0]["pairs"]


def mean(xs):
    xs = [x for x in xs if x is not None]
    return statistics.mean(xs) if xs else None


def opencv(alg):
    """OpenCV's per-pair scores (all pixels with ground truth), by pair."""
    b = bench()
    return {p: b[p][alg] for p in PAIRS}


def time_ratio(mode, alg):
    """golden's time in `mode` over OpenCV `alg`'s, per pair (one run)."""
    b = bench()
    return {p: b[p]["golden_ms"][mode] / b[p][alg]["ms"] for p in PAIRS}


def synth_runs():
    """`declivity synth --top stereo --seed N --json` for the seeds that have a file."""
    runs = []
    for seed in (1, 2, 3):
        if (DATA / f"synth-stereo-seed{seed}.json").exists():
            runs.append((seed, load_jsonl(f"synth-stereo-seed{seed}.json")[0]))
    return runs


def bold(s, on=True):
    return f"**{s}**" if on else s


# ---------------------------------------------------------------------------
# README


@table("readme-results")
def readme_results():
    paper, robust = evals("eval-paper.jsonl"), evals("eval-robust.jsonl")
    bm, sgbm = opencv("BM"), opencv("SGBM")
    rtl = evals_rtl()
    runs = synth_runs()
    mean_ratio = lambda mode: mean(time_ratio(mode, "BM").values())
    sgbm_ratio = mean(sgbm[p]["ms"] / bm[p]["ms"] for p in PAIRS)
    if runs:
        luts = runs[0][1]["luts"]
        fmax = " / ".join(fmt(r["fmax_mhz"], ".1f") for _, r in runs)
        seeds = ", ".join(str(s) for s, _ in runs)
        which = f"placer seed{'s' if len(runs) > 1 else ''} {seeds}"
        hw_speed = f"{fmt(min(r['px_per_clk'] for r in rtl.values()), '.2f')} px/clk; Fmax {fmax} MHz ({which})"
        hw_size = f"{fmt(luts, ',')} LUTs ({100 * luts / DEVICE_LUTS:.1f} % of an ECP5-85K)"
    else:
        hw_speed = f"{fmt(min(r['px_per_clk'] for r in rtl.values()), '.2f')} px/clk; Fmax —"
        hw_size = "—"
    rows = [
        ["golden, `robust` mode (default)", fmt(mean(r["sparse_acc1"] for r in robust.values()), ".1f"),
         fmt(mean(r["bad2"] for r in robust.values()), ".1f"), f"{mean_ratio('robust'):.2f} × StereoBM's time", "—"],
        ["golden, `paper` mode", fmt(mean(r["sparse_acc1"] for r in paper.values()), ".1f"),
         fmt(mean(r["bad2"] for r in paper.values()), ".1f"), f"{mean_ratio('paper'):.2f} × StereoBM's time", "—"],
        ["OpenCV StereoBM", "—", fmt(mean(bm[p]["bad2"] for p in PAIRS), ".1f"), "1 (the reference)", "—"],
        ["OpenCV StereoSGBM", "—", fmt(mean(sgbm[p]["bad2"] for p in PAIRS), ".1f"), f"{sgbm_ratio:.2f} × StereoBM's time", "—"],
        ["hardware line processor (`robust` mode)", "—", fmt(mean(r["bad2"] for r in rtl.values()), ".1f"), hw_speed, hw_size],
    ]
    return markdown(["", "sparse_acc1 (%)", "bad2 (%)", "speed", "size"], rows, ["---", "---:", "---:", "---", "---"])


# ---------------------------------------------------------------------------
# method.md


@table("method-diagnosis")
def method_diagnosis():
    d = diagnoses("eval-paper.jsonl")
    rows = [[p] + [fmt(d[p][k], ".1f") for k in
                   ("with_partner", "partner_both_sides", "partner_one_side", "partner_rejected",
                    "partner_matched", "partner_level_offset", "bad2_between_correct")] for p in PAIRS]
    header = ["pair", "declivities with a true partner (%)", "… passing both photometric tests (%)",
              "… one side only (%)", "… rejected (%)", "… matched to it (%)", "level offset (grey levels)",
              "bad2 pixels between two correct matches (%)"]
    return markdown(header, rows, ["---"] + ["---:"] * 7)


@table("method-ablation")
def method_ablation():
    bm = opencv("BM")
    b = bench()
    rows = []
    for mode in MODES:
        e = evals(f"eval-{mode}.jsonl")
        # A mode measured after the last bench run has no time in it.
        timed = all(mode in b[p]["golden_ms"] for p in PAIRS)
        ratio = mean(b[p]["golden_ms"][mode] / b[p]["golden_ms"]["paper"] for p in PAIRS) if timed else None
        below = sum(e[p]["bad2"] < bm[p]["bad2"] for p in PAIRS)
        on = mode == "robust"
        rows.append([bold(f"`{mode}`", on)] + [bold(c, on) for c in (
            fmt(mean(e[p]["sparse_acc1"] for p in PAIRS), ".1f"),
            fmt(mean(e[p]["match_frac"] for p in PAIRS), ".3f"),
            fmt(mean(e[p]["bad2"] for p in PAIRS), ".1f"),
            fmt(mean(e[p]["nonocc_bad2"] for p in PAIRS), ".1f"),
            f"{below}/8")] + [fmt(ratio, ".2f")])
    return markdown(["mode", "sparse_acc1 (%)", "match_frac", "bad2 (%)", "nonocc bad2 (%)",
                     "pairs with bad2 below StereoBM's", "time / paper mode's"], rows, ["---"] + ["---:"] * 6)


@table("method-contour")
def method_contour():
    """Inter-scanline support (the contour mode) against the robust and paper modes, per pair, and
    the contour mode's time over the robust mode's: eval's times (one thread) from one run of
    `scripts/doc-data.sh accuracy`."""
    modes = ("paper", "robust", "contour")
    e = {mode: evals(f"eval-{mode}.jsonl") for mode in modes}
    keys = (("sparse_acc1", ".2f"), ("match_frac", ".3f"), ("bad2", ".1f"), ("nonocc_bad2", ".1f"))
    trio = lambda value, spec: " / ".join(fmt(value(mode), spec) for mode in modes)
    ratio = {p: e["contour"][p]["ms"] / e["robust"][p]["ms"] for p in PAIRS}
    rows = []
    for p in PAIRS:
        below = " (below paper)" if e["contour"][p]["match_frac"] < e["paper"][p]["match_frac"] else ""
        rows.append([p] + [trio(lambda mode: e[mode][p][k], spec) + (below if k == "match_frac" else "")
                           for k, spec in keys] + [f"{ratio[p]:.2f}"])
    rows.append(["**mean**"] + [trio(lambda mode: mean(e[mode][p][k] for p in PAIRS), spec) for k, spec in keys]
                + [f"{mean(ratio.values()):.2f}"])
    return markdown(["pair"] + [f"{k} (paper / robust / contour)" for k, _ in keys] + ["time contour / robust"],
                    rows, ["---"] + ["---:"] * 5)


# ---------------------------------------------------------------------------
# results.md


@table("results-accuracy")
def results_accuracy():
    paper, robust = evals("eval-paper.jsonl"), evals("eval-robust.jsonl")
    bm, sgbm = opencv("BM"), opencv("SGBM")
    trio = lambda r: f"{r['sparse_acc1']:.1f} / {r['match_frac']:.3f} / {r['bad2']:.1f}"
    rows = [[p, trio(paper[p]), trio(robust[p]), fmt(robust[p]["nonocc_bad2"], ".1f"),
             fmt(bm[p]["bad2"], ".1f"), fmt(sgbm[p]["bad2"], ".1f")] for p in PAIRS]
    m = lambda e, k: mean(e[p][k] for p in PAIRS)
    mtrio = lambda e: f"{m(e, 'sparse_acc1'):.1f} / {m(e, 'match_frac'):.3f} / {m(e, 'bad2'):.1f}"
    rows.append(["**mean**", mtrio(paper), bold(mtrio(robust)), fmt(m(robust, "nonocc_bad2"), ".1f"),
                 fmt(mean(bm[p]["bad2"] for p in PAIRS), ".1f"), fmt(mean(sgbm[p]["bad2"] for p in PAIRS), ".1f")])
    return markdown(["pair", "paper: sparse_acc1 / match_frac / bad2", "robust: sparse_acc1 / match_frac / bad2",
                     "robust nonocc bad2", "StereoBM bad2", "StereoSGBM bad2"], rows, ["---"] + ["---:"] * 5)


def detail(mode):
    e, d = evals(f"eval-{mode}.jsonl"), diagnoses(f"eval-{mode}.jsonl")
    keys = ("declivities", "matches", "match_frac", "sparse_acc1", "edge_tolerant", "bad1", "bad2", "bad2v",
            "density", "nonocc_bad2")
    specs = (",", ",", ".3f", ".1f", ".1f", ".1f", ".1f", ".1f", ".1f", ".1f")

    def cell(p, k, spec):
        v = d[p]["sparse_acc1_edge_tolerant"] if k == "edge_tolerant" else e[p][k]
        return fmt(v, spec)

    rows = [[p] + [cell(p, k, s) for k, s in zip(keys, specs)] for p in PAIRS]
    rows.append(["**mean**"] + [fmt(mean(d[p]["sparse_acc1_edge_tolerant"] if k == "edge_tolerant" else e[p][k]
                                         for p in PAIRS), ".3f" if k == "match_frac" else ".1f")
                                if k not in ("declivities", "matches") else "" for k in keys])
    return markdown(["pair", "declivities", "matches", "match_frac", "sparse_acc1", "sparse_acc1 edge-tolerant",
                     "bad1", "bad2", "bad2v", "density", "nonocc bad2"], rows, ["---"] + ["---:"] * 10)


@table("results-paper")
def results_paper():
    return detail("paper")


@table("results-robust")
def results_robust():
    return detail("robust")


@table("results-opencv")
def results_opencv():
    bm, sgbm = opencv("BM"), opencv("SGBM")
    keys = ("bad1", "bad2", "bad2v", "density", "nonocc_bad2")
    rows = [[p] + [fmt(a[p].get(k), ".1f") for a in (bm, sgbm) for k in keys] for p in PAIRS]
    rows.append(["**mean**"] + [fmt(mean(a[p].get(k) for p in PAIRS), ".1f") for a in (bm, sgbm) for k in keys])
    header = ["pair"] + [f"{n} {k.replace('_', ' ')}" for n in ("BM", "SGBM") for k in keys]
    return markdown(header, rows, ["---"] + ["---:"] * 10)


@table("results-robustness")
def results_robustness():
    cols = []
    for variant, mode in (("bright", "paper"), ("bright", "robust"), ("noise3", "paper"), ("noise3", "robust")):
        base, changed = evals(f"eval-{mode}.jsonl"), evals(f"eval-{variant}-{mode}.jsonl")
        cols.append({p: (changed[p]["sparse_acc1"] - base[p]["sparse_acc1"], changed[p]["bad2"] - base[p]["bad2"])
                     for p in PAIRS})
    rows = [[p] + [f"{c[p][0]:+.1f} / {c[p][1]:+.1f}" for c in cols] for p in PAIRS]
    return markdown(["pair", "brighter right camera, paper", "brighter right camera, robust",
                     "noise σ = 3, paper", "noise σ = 3, robust"], rows, ["---"] + ["---:"] * 4)


@table("results-speed")
def results_speed():
    cols = [time_ratio("paper", "BM"), time_ratio("robust", "BM"), time_ratio("robust", "SGBM"),
            {p: bench()[p]["SGBM"]["ms"] / bench()[p]["BM"]["ms"] for p in PAIRS}]
    rows = [[p] + [f"{c[p]:.2f}" for c in cols] for p in PAIRS]
    rows.append(["**mean**"] + [f"**{mean(c.values()):.2f}**" for c in cols])
    rows.append(["largest"] + [f"{max(c.values()):.2f}" for c in cols])
    return markdown(["pair", "paper / BM", "robust / BM", "robust / SGBM", "SGBM / BM"], rows, ["---"] + ["---:"] * 4)


@table("results-speed-machine")
def results_speed_machine():
    b = load_jsonl("bench.json")[0]
    return (f"Measured on {b['machine']} (load average {b['load_average']} at the end of the run), "
            f"OpenCV {b['opencv']}, {b['threads']} thread; times: {b['runs']} runs.\n")


@table("results-rtl")
def results_rtl():
    rtl = evals_rtl()
    rows = []
    for p in PAIRS:
        r = run = rtl[p]
        dropped = f"{run['records_dropped']}, {run['lines_dropped']}, {run['pixels_dropped']}"
        rows.append([p, f"{run['width']}×{run['height']}", f"{run['exact_px']:.4f}", f"{run['exact_depth_px']:.4f}",
                     f"{run['agree_quarter_px']:.4f}", f"{run['px_per_clk']:.4f}",
                     fmt(run["stall_cycles"], ","), fmt(run["latency_cycles"], ","), fmt(r["bad2"], ".2f"),
                     fmt(r["golden_bad2"], ".2f"), fmt(r["nonocc_bad2"], ".2f"), dropped, fmt(run["cycles"], ",")])
    return markdown(["pair", "size", "exact_px", "exact_depth_px", "agree_quarter_px", "px_per_clk", "stall clocks",
                     "latency (clocks, first pixel in → first disparity out)", "bad2 rtl (%)",
                     "bad2 golden, same stages (%)", "nonocc bad2 rtl (%)", "dropped (records, lines, pixels)", "clocks"],
                    rows, ["---", "---"] + ["---:"] * 11)


def evals_rtl(name="eval-rtl.jsonl"):
    return {r["pair"]: r for r in load_jsonl(name)}


@table("results-rtl-hd")
def results_rtl_hd():
    """The hd configuration on the pairs up-scaled 2x."""
    # docs/data/eval-rtl-hd-2x.jsonl: declivity eval --rtl --config hd --engine verilator --json
    #   on the folders of sim/examples/upscale_pairs.rs OUT 2 (scripts/doc-data.sh hd)
    rtl = evals_rtl("eval-rtl-hd-2x.jsonl")
    rows = []
    for p in PAIRS:
        r = run = rtl[p]
        assert run["config"] == "hd"
        dropped = f"{run['records_dropped']}, {run['lines_dropped']}, {run['pixels_dropped']}"
        rows.append([p, f"{run['width']}×{run['height']}", f"{run['exact_px']:.4f}", f"{run['exact_depth_px']:.4f}",
                     f"{run['px_per_clk']:.4f}", fmt(run["stall_cycles"], ","), fmt(run["latency_cycles"], ","),
                     fmt(r["bad2"], ".2f"), fmt(r["golden_bad2"], ".2f"), dropped, fmt(run["cycles"], ",")])
    return markdown(["pair (2×)", "size", "exact_px", "exact_depth_px", "px_per_clk", "stall clocks",
                     "latency (clocks)", "bad2 rtl (%)", "bad2 golden, same stages (%)", "dropped (records, lines, pixels)", "clocks"],
                    rows, ["---", "---"] + ["---:"] * 9)


# ---------------------------------------------------------------------------
# verification.md


@table("verification-detector")
def verification_detector():
    det = {}
    for r in load_jsonl("rtl-detect.jsonl"):
        det[r["image"].replace("\\", "/").split("/")[-2]] = r
    rows = [[p, f"{r['width']}×{r['lines']}", fmt(r["cycles"], ","), f"{r['px_per_clk']:.2f}",
             fmt(r["declivities_rtl"], ","), fmt(r["declivities_golden"], ","), fmt(r["borderline"], ","),
             fmt(r["mismatches"], ","), f"{r['max_pos_err_lsb']:.4f}", f"{r['max_dt_err_lsb']:.3f}"]
            for p, r in ((p, det[p]) for p in PAIRS if p in det)]
    return markdown(["pair", "size", "clocks", "px/clk", "records rtl", "golden", "borderline", "mismatches",
                     "max position error (LSB)", "max d_t error (LSB)"], rows, ["---", "---"] + ["---:"] * 8)
