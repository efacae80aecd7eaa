#!/usr/bin/env python3
"""The register endpoints near the critical path of a placed and routed design.

Usage: scripts/near-critical.py REPORT.json [MARGIN_NS]

REPORT.json is nextpnr's `--report` written with `--detailed-timing-report`
(scripts/synth-ecp5.sh passes both). nextpnr's log shows one critical path per
run; its report gives every endpoint's arrival time, so this lists, grouped by
register (the bit index and the primitive suffixes stripped), every endpoint
within MARGIN_NS (default 1.0) of the clock period that nextpnr achieved, the
worst first, with its port and the net's driver. An LSR (synchronous reset)
endpoint counts its 0.42 ns setup, which nextpnr leaves out of the arrival.
Arrivals above the period come from or go to the top-level ports (nextpnr
times them apart: there are no input or output constraints) and are left out;
those below it may still be port paths (an output pad's `I`, a register
loaded from a configuration input), to be read past.
"""
import collections
import json
import re
import sys

LSR_SETUP_NS = 0.42


def main() -> None:
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    report = json.load(open(sys.argv[1]))
    margin = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
    fmax = next(iter(report["fmax"].values()))["achieved"]
    period = 1000.0 / fmax
    groups = collections.defaultdict(list)
    for net in report.get("detailed_net_timings", []):
        for end in net["endpoints"]:
            arrival = end["delay"][1] + (LSR_SETUP_NS if end["port"] == "LSR" else 0.0)
            if period - margin <= arrival <= period + 0.05:
                reg = re.sub(r"(\$q|\.q|\.d|\.dff|\$d)?(_TRELLIS_FF_Q|_TRELLIS|\$).*", "", end["cell"])
                groups[reg].append((arrival, end["port"], net["driver"]))
    if not groups:
        sys.exit("no endpoint timings: was nextpnr run with --detailed-timing-report?")
    print(f"Fmax {fmax:.2f} MHz (period {period:.2f} ns); endpoints within {margin} ns of it")
    for reg, ends in sorted(groups.items(), key=lambda kv: -max(e[0] for e in kv[1])):
        ends.sort(reverse=True)
        arrival, port, driver = ends[0]
        print(f"{arrival:5.2f} ns  {reg:48s} {len(ends):4d} endpoints  {port:4s} <- {driver[:70]}")


if __name__ == "__main__":
    main()
