#!/usr/bin/env bash
# Re-measures the figures that scripts/tables/results.py turns into the tables of README.md
# and docs/ (method, results, verification): writes docs/data/*.json[l] (docs/data/README.md
# lists them). Then run scripts/doc-tables.py.
#
# Usage: scripts/doc-data.sh [STEP...]    STEP: accuracy bench robustness rtl hd detect budget faults (default: all)
#        DECLIVITY=path/to/declivity       the binary (default target/release/declivity)
#
# Runs one thing at a time, under nice. The bench needs numpy and opencv-python-headless
# (installed if missing); rtl and faults need Verilator (faults: about 10 minutes); detect takes about ten seconds a pair.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${DECLIVITY:-target/release/declivity}
DATA=data/stereo
OUT=docs/data
MODES="paper relative one-sided consistent edges median edge-flag robust contour"
PAIRS="tsukuba venus sawtooth map cones teddy art motorcycle"
STEPS=${*:-accuracy bench robustness rtl hd detect budget faults}
run() { nice -n 10 "$@"; }
mkdir -p "$OUT"

# A folder of links to the pairs' files (the OpenCV script writes its CSV into the data
# folder). Its meta.txt keeps one scale: scripts/opencv_baseline.py reads the first number of
# `scale:`, and motorcycle's line is `1 (npz float) ; 256 (disp_gt.png)` while data/stereo has
# only its disp_gt.png.
links() {
  local dir=$1
  for p in $PAIRS; do
    mkdir "$dir/$p"
    for f in "$DATA/$p"/*; do
      [ "$(basename "$f")" = meta.txt ] || ln -s "$(cd "$(dirname "$f")" && pwd)/$(basename "$f")" "$dir/$p/"
    done
    sed -E 's/^scale: .*; *([0-9.]+) \(disp_gt\.png\).*/scale: \1/' "$DATA/$p/meta.txt" > "$dir/$p/meta.txt"
  done
}

for step in $STEPS; do
  case $step in
  accuracy)
    # Golden on the eight pairs in every mode, with the failure diagnosis.
    for mode in $MODES; do
      run "$BIN" eval --json --diagnose --mode "$mode" "$DATA" > "$OUT/eval-$mode.jsonl"
    done
    ;;
  bench)
    # OpenCV StereoBM/SGBM and golden, one thread each, on one machine in one run of this step.
    python3 -c "import cv2, numpy" 2>/dev/null || python3 -m pip install -q numpy opencv-python-headless==4.12.0.88
    # Five rounds; in each, pair by pair, OpenCV (the median of 5 runs) and then golden in
    # every mode (the median of 5 runs), so that the times compared are taken seconds apart
    # on a machine whose load drifts. Each time is then the median of its five rounds.
    work=$(mktemp -d)
    mkdir "$work/all"
    links "$work/all"
    for p in $PAIRS; do
      mkdir "$work/$p.dir"
      ln -s "$work/all/$p" "$work/$p.dir/$p"
    done
    for k in 1 2 3 4 5; do
      for p in $PAIRS; do
        run python3 scripts/opencv_baseline.py "$work/$p.dir" --threads 1 > "$work/$p.dir/opencv.txt"
        mv "$work/$p.dir/baseline_results_threads1.csv" "$work/$p.dir/opencv-$k.csv"
        for mode in $MODES; do
          run "$BIN" eval --json --runs 5 --mode "$mode" "$work/all/$p"
        done
      done
    done > "$work/golden.jsonl"
    python3 - "$work" "$OUT/bench.json" <<'PY'
import csv, glob, json, os, platform, statistics, sys
import cv2
work, out = sys.argv[1:]
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.machine())
pairs, times = {}, {}
for path in sorted(glob.glob(f"{work}/*.dir/opencv-*.csv")):
    for r in csv.DictReader(open(path)):
        a = pairs.setdefault(r["pair"], {}).setdefault(r["alg"], {})
        if r["region"] == "all":
            times.setdefault((r["pair"], r["alg"]), []).append(float(r["ms"]))
            a.update(bad1=float(r["bad1"]), bad2=float(r["bad2"]), bad2v=float(r["bad2v"]), density=float(r["density"]))
        else:
            a["nonocc_bad2"] = float(r["bad2"])
for (pair, alg), ms in times.items():
    pairs[pair][alg]["ms"] = statistics.median(ms)
gold = {}
for line in open(f"{work}/golden.jsonl"):
    g = json.loads(line)
    gold.setdefault((g["pair"], g["mode"]), []).append(g["ms"])
for (pair, mode), ms in gold.items():
    pairs[pair].setdefault("golden_ms", {})[mode] = statistics.median(ms)
json.dump({
    "command": "scripts/doc-data.sh bench",
    "machine": f"{cpu}, {os.cpu_count()} cores",
    "load_average": round(os.getloadavg()[0], 2),
    "opencv": cv2.__version__,
    "threads": 1,
    "runs": "the median over five rounds of the median of 5",
    "pairs": pairs,
}, open(out, "w"), indent=1)
PY
    rm -rf "$work"
    ;;
  robustness)
    # The right camera 10 grey levels brighter with 10 % more contrast, I' = 128 + 1.1 (I - 128) + 10;
    # Gaussian noise of sigma 3 on both images (numpy, seeded); rounded half up and clamped to 0..255,
    # as tests/beyond_the_paper.rs does (its noise comes from another generator).
    work=$(mktemp -d)
    python3 - "$DATA" "$work" $PAIRS <<'PY'
import os, sys
import numpy as np, cv2
data, work, pairs = sys.argv[1], sys.argv[2], sys.argv[3:]
rng = np.random.default_rng(3)
for variant in ("bright", "noise3"):
    for p in pairs:
        src, dst = os.path.join(data, p), os.path.join(work, variant, p)
        os.makedirs(dst)
        for f in os.listdir(src):
            if f not in ("left_gray.png", "right_gray.png"):
                os.symlink(os.path.abspath(os.path.join(src, f)), os.path.join(dst, f))
        for side in ("left", "right"):
            img = cv2.imread(os.path.join(src, f"{side}_gray.png"), cv2.IMREAD_GRAYSCALE).astype(np.float64)
            if variant == "bright" and side == "right":
                img = 128 + 1.1 * (img - 128) + 10
            elif variant == "noise3":
                img = img + rng.normal(0.0, 3.0, img.shape)
            cv2.imwrite(os.path.join(dst, f"{side}_gray.png"), np.clip(np.floor(img + 0.5), 0, 255).astype(np.uint8))
PY
    for variant in bright noise3; do
      for mode in paper robust; do
        run "$BIN" eval --json --mode "$mode" "$work/$variant"/*/ > "$OUT/eval-$variant-$mode.jsonl"
      done
    done
    rm -rf "$work"
    ;;
  rtl)
    # The whole line processor's Verilog under Verilator on the eight pairs, against golden.
    run "$BIN" eval --rtl --engine verilator --json "$DATA" > "$OUT/eval-rtl.jsonl"
    ;;
  hd)
    # The eight pairs up-scaled 2x (sim/examples/upscale_pairs.rs), golden and the hd line
    # processor's Verilog under Verilator.
    work=$(mktemp -d)
    run cargo run --release -q -p sim --example upscale_pairs -- "$work" 2 | grep -v "^written to" > "$OUT/upscale-2x.txt"
    run "$BIN" eval --json --mode robust "$work" > "$OUT/eval-2x-robust.jsonl"
    run "$BIN" eval --rtl --config hd --engine verilator --json "$work" > "$OUT/eval-rtl-hd-2x.jsonl"
    rm -rf "$work"
    ;;
  budget)
    # The latency budgets of the datasheet: sd examples at 125 MHz, and the HD video formats in
    # hd, each at its pixel clock with its horizontal blanking (name: budget-WxH-nN[-dispmaxD]
    # [-hblankC][-CONFIG-MHZ].json).
    b() { local name=$1; shift; run "$BIN" budget --json "$@" > "$OUT/$name.json"; }
    b budget-512x512-n56-dispmax60 --width 512 --height 512 --n-max 56 --dispmax 60 --clock-mhz 125
    b budget-512x512-n128 --width 512 --height 512 --n-max 128 --dispmax 64 --clock-mhz 125
    b budget-512x512-n128-hblank648 --width 512 --height 512 --n-max 128 --dispmax 64 --clock-mhz 125 --hblank 648
    b budget-1024x768-n128 --width 1024 --height 768 --n-max 128 --dispmax 64 --clock-mhz 125
    b budget-1024x768-n128-hblank320 --width 1024 --height 768 --n-max 128 --dispmax 64 --clock-mhz 125 --hblank 320
    # CEA-861 720p60 (1650 x 750, 74.25 MHz), CVT-RB 1280x800 at 120 Hz (1440 x 847, 146.25 MHz),
    # CEA-861 1080p30 (2200 x 1125, 74.25 MHz) and 1080p60 (2200 x 1125, 148.5 MHz), CVT-RB
    # 1080p60 (2080 x 1111, 138.5 MHz); N = 160 (the most declivities a line of the up-scaled
    # pairs has is 155) and N = N_MAX = 256.
    for n in 160 256; do
      b budget-1280x720-n$n-hblank370-hd-74.25 --config hd --width 1280 --height 720 --n-max $n --dispmax 128 --clock-mhz 74.25 --hblank 370
      b budget-1280x800-n$n-hblank160-hd-146.25 --config hd --width 1280 --height 800 --n-max $n --dispmax 128 --clock-mhz 146.25 --hblank 160
      b budget-1920x1080-n$n-hblank280-hd-74.25 --config hd --width 1920 --height 1080 --n-max $n --dispmax 128 --clock-mhz 74.25 --hblank 280
      b budget-1920x1080-n$n-hblank280-hd-148.5 --config hd --width 1920 --height 1080 --n-max $n --dispmax 128 --clock-mhz 148.5 --hblank 280
      b budget-1920x1080-n$n-hblank160-hd-138.5 --config hd --width 1920 --height 1080 --n-max $n --dispmax 128 --clock-mhz 138.5 --hblank 160
    done
    ;;
  detect)
    # The rtl detector (rust-hdl model) on every row of each pair's left view, against golden.
    work=$(mktemp -d)
    for p in $PAIRS; do
      run "$BIN" rtl detect "$DATA/$p/left_gray.png" --json --out "$work/$p"
    done > "$OUT/rtl-detect.jsonl"
    rm -rf "$work"
    ;;
  faults)
    # The fault campaign on sd's Verilog, 1 000 faulty frames per group of classes (the
    # datasheet's Verification).
    run "$BIN" rtl faults --frames 1000 --classes short_frame,sof_mid_frame,out_of_step,idle_clocks --json > "$OUT/faults-four.json"
    run "$BIN" rtl faults --frames 1000 --classes mixed_widths,missing_tlast --json > "$OUT/faults-widths.json"
    run "$BIN" rtl faults --frames 1000 --json > "$OUT/faults-all.json"
    ;;
  *) echo "unknown step $step" >&2; exit 2 ;;
  esac
done
