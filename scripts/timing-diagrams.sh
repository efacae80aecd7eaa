#!/usr/bin/env bash
# Regenerates the timing diagrams of docs/hardware/datasheet.md from a real simulated trace:
#
#   1. `declivity rtl depth` runs ten rows of tsukuba (384 px) through the line processor
#      (the rust-hdl model, clock by clock) with horizontal blanking and writes a VCD of every
#      signal, from the first pixel in to the last disparity out;
#   2. scripts/vcd2wavedrom.py cuts windows of it (a frame's start, a line's end and its
#      blanking, the first output line's start and end) into WaveJSON, docs/hardware/wave/*.json
#      (with trace-run.json, the run's summary);
#   3. yowasp-wavedrom renders each to docs/hardware/img/*.svg.
#
# Usage: scripts/timing-diagrams.sh [DECLIVITY]
#   DECLIVITY  the declivity binary (argument, or the environment variable DECLIVITY;
#              default target/release/declivity)
# Environment: PAIR (default data/stereo/tsukuba), ROWS (default 100..110), DISPMAX (15, the
# pair's dispmax + 1 as `declivity eval` uses), HBLANK (idle clocks after each line, 24),
# KEEP_VCD (a path: keep the VCD there instead of in a temporary folder), REUSE_VCD (a path:
# cut the diagrams from this VCD, written before by this script with KEEP_VCD, and skip the
# simulation, which takes about ten minutes and writes about 450 MB).
# Needs python3 and yowasp-wavedrom (python3 -m pip install --user yowasp-wavedrom).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
BIN=${1:-${DECLIVITY:-target/release/declivity}}
PAIR=${PAIR:-data/stereo/tsukuba}
ROWS=${ROWS:-100..110}
DISPMAX=${DISPMAX:-15}
HBLANK=${HBLANK:-24}
WAVE=docs/hardware/wave
IMG=docs/hardware/img

[ -n "${REUSE_VCD:-}" ] || [ -x "$BIN" ] || { echo "no declivity binary at $BIN (give its path as the argument or in DECLIVITY)" >&2; exit 1; }
command -v yowasp-wavedrom >/dev/null || { echo "yowasp-wavedrom missing: python3 -m pip install --user yowasp-wavedrom" >&2; exit 1; }

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
NROWS=$(( ${ROWS#*..} - ${ROWS%..*} ))

mkdir -p "$WAVE" "$IMG"
if [ -n "${REUSE_VCD:-}" ]; then
    VCD=$REUSE_VCD
    [ -f "$VCD" ] || { echo "REUSE_VCD: no file $VCD" >&2; exit 1; }
else
    VCD=${KEEP_VCD:-$WORK/stereo.vcd}
    echo "simulating rows $ROWS of $PAIR (hblank $HBLANK) with a VCD ..." >&2
    "$BIN" rtl depth "$PAIR/left_gray.png" "$PAIR/right_gray.png" --dispmax "$DISPMAX" --rows "$ROWS" \
        --hblank "$HBLANK" --vcd "$VCD" --lines "0..$NROWS" --out "$WORK/out" --json > "$WORK/run.json"
    # The run's summary beside the diagrams (the simulation's speed left out: it is not the design's).
    python3 - "$WORK/run.json" "$ROWS" "$WAVE/trace-run.json" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))
for k in ("sim_cycles_per_s", "seconds", "build_seconds"):
    run.pop(k, None)
run["rows"] = sys.argv[2]
run["command"] = "scripts/timing-diagrams.sh (declivity rtl depth ... --vcd)"
json.dump(run, open(sys.argv[3], "w"), indent=1)
open(sys.argv[3], "a").write("\n")
PY
fi

WIDTH=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['width'])" "$WAVE/trace-run.json")
V="python3 scripts/vcd2wavedrom.py $VCD --clock clock"
IN_L=(-s 'l_tvalid' -s 'l_tready' -s 'l_tuser' -s 'l_tlast' -s 'l_tdata=l_tdata')
IN_R=(-s 'r_tvalid' -s 'r_tready' -s 'r_tuser' -s 'r_tlast' -s 'r_tdata=r_tdata')
OUT=(-s 'm_tvalid' -s 'm_tuser' -s 'm_tlast' -s 'm_tdata[15:0]=m_tdata[15:0] disparity' -s 'm_tdata[31:16]=m_tdata[31:16] depth mm')

# A frame's start: the first pixel of both cameras, tuser on it (the trace starts there, cycle 0).
$V "${IN_L[@]}" "${IN_R[@]}" --anchor 'l_tuser=1' --before 3 --after 14 --max-run 1000 \
    --beats l_tdata --beats r_tdata --cycle-lane all --origin 0 \
    --title "Frame start: tuser with the first pixel of the frame's first line" -o "$WAVE/frame_start.json"
# A line's end and the horizontal blanking: tlast on the last pixel, tvalid low for HBLANK clocks.
$V "${IN_L[@]}" --anchor 'l_tlast=1' --before 5 --after $((HBLANK + 6)) --max-run 6 --keep 2 \
    --free l_tdata --beats l_tdata --cycle-lane all \
    --title "Line end (tlast) and horizontal blanking (tvalid low, $HBLANK clocks)" -o "$WAVE/line_end.json"
# The first output line: its first beats (tuser on the frame's first pixel), counted from the
# frame's first pixel in (the latency).
$V "${OUT[@]}" --anchor 'm_tvalid=1' --before 3 --after 12 --max-run 1000 --cycle-lane all --origin 0 --hscale 2 \
    --title "First output line: tuser with the frame's first disparity" -o "$WAVE/output_start.json"
# ... and its end (tlast), the wait, and the next output line's first beats.
$V "${OUT[@]}" --anchor 'm_tlast=1' --before 5 --after "$((WIDTH + HBLANK + 6))" --max-run 6 --keep 2 \
    --free 'm_tdata[15:0] disparity' --free 'm_tdata[31:16] depth mm' --cycle-lane all --hscale 2 \
    --title 'End of the first output line (tlast), the wait, the next line' -o "$WAVE/output_end.json"

for j in "$WAVE"/*.json; do
    case $j in *trace-run.json) continue ;; esac
    svg="$IMG/$(basename "${j%.json}").svg"
    yowasp-wavedrom "$j" "$svg"
    echo "$svg" >&2
done
