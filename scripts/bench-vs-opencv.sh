#!/usr/bin/env bash
# Golden model vs OpenCV StereoBM/SGBM, one thread each, on the same machine in the same run.
# Usage: scripts/bench-vs-opencv.sh [DATA_DIR]   (default data/stereo)
# Prints per pair: golden ms (median of 5), BM ms, SGBM ms (median of 5) and the ratios.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${1:-data/stereo}
python3 -c "import cv2, numpy" 2>/dev/null || pip install -q numpy opencv-python-headless
cargo build --release -q -p cli
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The baseline script writes its CSV into the data folder: give it one of ours.
for d in "$DATA"/*/; do [ -f "$d/meta.txt" ] && ln -s "$(cd "$d" && pwd)" "$work/$(basename "$d")"; done
python3 scripts/opencv_baseline.py "$work" --threads 1 > "$work/opencv.txt"
for mode in paper robust; do
  ./target/release/declivity eval --json --runs 5 --mode "$mode" "$work"/*/
done > "$work/golden.jsonl"
python3 - "$work" <<'PY'
import csv, json, sys, statistics
w = sys.argv[1]
cv = {}
for r in csv.DictReader(open(f"{w}/baseline_results_threads1.csv")):
    if r["region"] == "all":
        cv.setdefault(r["pair"], {})[r["alg"]] = r
gold = [json.loads(l) for l in open(f"{w}/golden.jsonl")]
print("| pair | mode | golden ms | BM ms | SGBM ms | golden/BM | golden/SGBM | golden bad2 | BM bad2 | SGBM bad2 | golden sparse_acc1 | golden density | BM density | SGBM density |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
ratios = {}
for g in gold:
    b, s = cv[g["pair"]]["BM"], cv[g["pair"]]["SGBM"]
    bm, sg = float(b["ms"]), float(s["ms"])
    ratios.setdefault(g["mode"], []).append(g["ms"] / bm)
    print(f"| {g['pair']} | {g['mode']} | {g['ms']:.2f} | {bm:.2f} | {sg:.2f} | {g['ms']/bm:.2f} | {g['ms']/sg:.2f} | {g['bad2']:.1f} | "
          f"{float(b['bad2']):.1f} | {float(s['bad2']):.1f} | {g['sparse_acc1']:.1f} | {g['density']:.1f} | {float(b['density']):.1f} | {float(s['density']):.1f} |")
for mode, r in ratios.items():
    print(f"golden ({mode}) / BM time ratio: mean {statistics.mean(r):.2f}, max {max(r):.2f} (target <= 0.5)")
PY
