#!/usr/bin/env python3
"""Turns a window of a VCD waveform into a WaveDrom timing diagram (WaveJSON).

The VCD is the one `declivity rtl depth ... --vcd FILE --lines A..B` writes (the rust-hdl
engine: every signal of the line processor, the clock low at time 10·k and high at 10·k + 5);
any VCD with a clock works. Each clock cycle becomes one column of the diagram, showing the
values the cycle's rising edge samples (the values just before the edge), drawn WaveDrom's
way: a `p` clock whose edge opens the column.

Signals are named by their full hierarchical VCD name or by a unique dotted suffix of it
(`m_tvalid`, `uut.l_tuser`), optionally with a bit slice and a label:

    --signal 'm_tdata[15:0]=disparity (1/16 px)'

The window is given in clock cycles around an anchor, the first cycle (or the N-th, `#N`) on
which a signal has a value:

    --anchor 'm_tvalid=1' --before 4 --after 24
    --anchor 'l_tlast=1#2'      (the second cycle with l_tlast high)
    --anchor 'cycle=1234'       (an absolute cycle)

Long stretches in which no signal changes are cut to a WaveDrom gap (`|`): every run of more
than --max-run unchanged cycles keeps --keep cycles on each side of one gap. Signals listed
with --free (by label) may change inside a stretch that is cut (a pixel stream's tdata): the
value after the gap is then a new segment. A bus listed with --beats is drawn as one segment
per cycle (a pixel stream's beats), not merged while its value repeats. --cycle-lane adds a
lane with the cycle number, counted from the anchor or from --origin N, on every column (all)
or at the window's start and after every gap (gaps), so the diagram stays quantitative.

Usage:
    scripts/vcd2wavedrom.py VCD --clock clock --signal ... --anchor ... [--before B]
        [--after A] [--max-run R] [--keep K] [--free LABEL ...] [--beats LABEL ...]
        [--cycle-lane [all|gaps]] [--origin N] [--radix dec|hex] [--title TEXT]
        [--foot TEXT] [--hscale S] [--out FILE.json]

The output is WaveJSON for WaveDrom (`yowasp-wavedrom FILE.json FILE.svg` renders it).
"""
import argparse
import json
import re
import sys


def parse_signal_spec(spec):
    """`path[hi:lo]=label` -> (path, (hi, lo) or None, label)."""
    name, _, label = spec.partition("=")
    m = re.fullmatch(r"(.+?)\[(\d+)(?::(\d+))?\]", name.strip())
    if m:
        path, hi = m.group(1), int(m.group(2))
        lo = int(m.group(3)) if m.group(3) is not None else hi
        sl = (hi, lo)
    else:
        path, sl = name.strip(), None
    return path, sl, (label.strip() or name.strip())


def parse_anchor(spec):
    """`name=value[#n]` or `cycle=N` -> (name or None, value, n)."""
    m = re.fullmatch(r"\s*([\w.\[\]]+)\s*=\s*(\w+)\s*(?:#(\d+))?\s*", spec)
    if not m:
        sys.exit(f"--anchor {spec!r}: expected NAME=VALUE[#N] or cycle=N")
    name, value, n = m.group(1), m.group(2), int(m.group(3) or 1)
    return (None if name == "cycle" else name), int(value, 0), n


class Vcd:
    """The header of a VCD file and the changes of a few of its signals."""

    def __init__(self, path):
        self.path = path
        self.vars = {}  # full name -> (id code, width)
        self.f = open(path, "r")
        self._read_header()

    def _read_header(self):
        scopes = []
        tokens = []
        for line in self.f:
            tokens.extend(line.split())
            while tokens:
                if "$end" not in tokens:
                    break
                end = tokens.index("$end")
                cmd, args = tokens[0], tokens[1:end]
                tokens = tokens[end + 1:]
                if cmd == "$scope":
                    scopes.append(args[1])
                elif cmd == "$upscope":
                    scopes.pop()
                elif cmd == "$var":
                    width, code, name = int(args[1]), args[2], args[3]
                    full = ".".join(scopes + [name])
                    self.vars[full] = (code, width)
                elif cmd == "$enddefinitions":
                    return
        sys.exit(f"{self.path}: no $enddefinitions")

    def resolve(self, name):
        """The full name of `name` (itself or the one name ending in `.name`)."""
        if name in self.vars:
            return name
        hits = [v for v in self.vars if v.endswith("." + name)]
        if len(hits) == 1:
            return hits[0]
        if not hits:
            sys.exit(f"{self.path}: no signal named {name!r}")
        # Prefer the shallowest (a port of the top over a sub-block's signal of the same name).
        hits.sort(key=lambda v: v.count("."))
        if hits[0].count(".") < hits[1].count("."):
            return hits[0]
        sys.exit(f"{self.path}: {name!r} is ambiguous: {', '.join(hits[:6])}")

    def changes(self, codes, stop):
        """Reads the value changes of the id `codes` up to the time `stop(time, changes)` says
        to stop at; returns {code: [(time, value), ...]} (values as ints, x/z as None).

        The file is scanned in large blocks with one regular expression that matches only
        timestamps and the changes of `codes` (a VCD of the whole line processor holds tens of
        thousands of signals, nearly all of them of no interest here)."""
        out = {c: [] for c in codes}
        alt = "|".join(re.escape(c) for c in sorted(codes, key=len, reverse=True))
        pat = re.compile(rf"^(?:#(\d+)|([01xzXZ])({alt})|[bB]([01xzXZ]+) ({alt}))[ \t\r]*$", re.M)
        time = 0
        rest = ""
        while True:
            block = self.f.read(1 << 24)
            if not block:
                text, rest = rest, ""
            else:
                text = rest + block
                cut = text.rfind("\n")
                if cut < 0:
                    rest = text
                    continue
                text, rest = text[:cut + 1], text[cut + 1:]
            for m in pat.finditer(text):
                t_, scalar, scode, vec, vcode = m.groups()
                if t_ is not None:
                    time = int(t_)
                    if stop(time, out):
                        return out
                elif scalar is not None:
                    out[scode].append((time, None if scalar in "xzXZ" else int(scalar)))
                else:
                    try:
                        v = int(vec, 2)
                    except ValueError:
                        v = None
                    out[vcode].append((time, v))
            if not block:
                return out


def value_at(changes, t):
    """The value of a change list at time t (after the changes at t)."""
    lo, hi = 0, len(changes)
    while lo < hi:
        mid = (lo + hi) // 2
        if changes[mid][0] <= t:
            lo = mid + 1
        else:
            hi = mid
    return changes[lo - 1][1] if lo else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("vcd")
    ap.add_argument("--clock", default="clock", help="the clock signal (default: clock)")
    ap.add_argument("--signal", "-s", action="append", default=[], help="PATH[hi:lo][=LABEL]; repeat")
    ap.add_argument("--anchor", default="cycle=0", help="NAME=VALUE[#N] or cycle=N (default cycle=0)")
    ap.add_argument("--before", type=int, default=4, help="cycles shown before the anchor")
    ap.add_argument("--after", type=int, default=28, help="cycles shown from the anchor on")
    ap.add_argument("--max-run", type=int, default=8, help="cut unchanged runs longer than this")
    ap.add_argument("--keep", type=int, default=2, help="cycles kept on each side of a gap")
    ap.add_argument("--free", action="append", default=[], help="LABEL of a signal that may change inside a gap")
    ap.add_argument("--cycle-lane", nargs="?", const="gaps", choices=["gaps", "all"],
                    help="add a lane of cycle numbers: at the start and after each gap (gaps), or on every column (all)")
    ap.add_argument("--origin", default="anchor", help="cycle the lane counts from: anchor (default) or a number")
    ap.add_argument("--beats", action="append", default=[], help="LABEL of a bus drawn as one segment per cycle")
    ap.add_argument("--radix", choices=["dec", "hex"], default="dec")
    ap.add_argument("--title", default=None)
    ap.add_argument("--foot", default=None)
    ap.add_argument("--hscale", type=int, default=1)
    ap.add_argument("--out", "-o", default="-")
    a = ap.parse_args()
    if not a.signal:
        sys.exit("no --signal given")

    vcd = Vcd(a.vcd)
    clock = vcd.resolve(a.clock)
    specs = []
    for s in a.signal:
        path, sl, label = parse_signal_spec(s)
        specs.append((vcd.resolve(path), sl, label))
    a_name, a_value, a_nth = parse_anchor(a.anchor)
    a_full = vcd.resolve(a_name) if a_name else None
    codes = {vcd.vars[clock][0]} | {vcd.vars[p][0] for p, _, _ in specs}
    if a_full:
        codes.add(vcd.vars[a_full][0])

    # Read the changes; the clock's rising edges are the cycles. Every few thousand
    # timestamps, stop if the window is complete (its anchor found, its last cycle past).
    ck = vcd.vars[clock][0]
    anchor_code = vcd.vars[a_full][0] if a_full else None
    progress = {"n": 0}

    def rising(changes):
        return [t for i, (t, v) in enumerate(changes) if v == 1 and (i == 0 or changes[i - 1][1] != 1)]

    def find_anchor(changes, edges):
        if a_full is None:
            return a_value if a_value < len(edges) else None
        seen = 0
        for k, t in enumerate(edges):
            if value_at(changes[anchor_code], t - 1) == a_value:
                seen += 1
                if seen == a_nth:
                    return k
        return None

    def stop(_t, changes):
        progress["n"] += 1
        if progress["n"] % 2000:
            return False
        edges = rising(changes[ck])
        k = find_anchor(changes, edges)
        return k is not None and len(edges) > k + a.after + 1

    ch = vcd.changes(codes, stop)
    edges = rising(ch[ck])
    if not edges:
        sys.exit(f"{a.vcd}: the clock {clock} never rises")
    # Cycle k is sampled just before edge k: at the last change before the edge's time.
    sample_t = [t - 1 for t in edges]

    def sample(code, k, sl=None):
        v = value_at(ch[code], sample_t[k])
        if v is not None and sl is not None:
            hi, lo = sl
            v = (v >> lo) & ((1 << (hi - lo + 1)) - 1)
        return v

    anchor = find_anchor(ch, edges)
    if anchor is None:
        sys.exit(f"{a.vcd}: no anchor {a.anchor!r} within the waveform")
    first = max(0, anchor - a.before)
    last = min(len(edges) - 1, anchor + a.after - 1)
    cycles = list(range(first, last + 1))

    lanes = []
    for path, sl, label in specs:
        code = vcd.vars[path][0]
        width = (sl[0] - sl[1] + 1) if sl else vcd.vars[path][1]
        lanes.append({"label": label, "width": width, "values": [sample(code, k, sl) for k in cycles]})

    # The runs to cut: cycles i where every non-free lane equals its value on cycle i - 1.
    free = set(a.free)
    unknown = free - {l["label"] for l in lanes}
    if unknown:
        sys.exit(f"--free {sorted(unknown)}: no such signal label")
    steady = [False] + [
        all(l["values"][i] == l["values"][i - 1] for l in lanes if l["label"] not in free) for i in range(1, len(cycles))
    ]
    cut = [False] * len(cycles)  # cycles left out (the gap stands for them)
    gap_at = set()  # index of the first cycle after a gap
    i = 0
    while i < len(cycles):
        if not steady[i]:
            i += 1
            continue
        j = i
        while j < len(cycles) and steady[j]:
            j += 1
        # cycles i-1 .. j-1 all hold the same values: a run of j - i + 1 cycles.
        if j - i + 1 > a.max_run:
            lo, hi = i - 1 + a.keep, j - a.keep  # keep [i-1, lo) and [hi, j)
            if hi > lo:
                for k in range(lo, hi):
                    cut[k] = True
                gap_at.add(hi)
        i = j

    beats = set(a.beats)
    unknown = beats - {l["label"] for l in lanes}
    if unknown:
        sys.exit(f"--beats {sorted(unknown)}: no such signal label")
    origin = anchor if a.origin == "anchor" else int(a.origin)

    def fmt(v, width):
        if v is None:
            return None
        return f"{v:x}" if a.radix == "hex" and width > 1 else str(v)

    signals = [{"name": "clock", "wave": ""}]
    shown = [k for k in range(len(cycles)) if not cut[k]]
    for k in shown:
        signals[0]["wave"] += "|" if k in gap_at else "p"
        # WaveDrom: a gap mark takes the place of a column, so the clock after a gap is '|'
        # followed by the column itself.
        if k in gap_at:
            signals[0]["wave"] += "."
    for lane in lanes:
        wave, data, prev = "", [], object()
        for k in shown:
            v = lane["values"][k]
            if k in gap_at:
                wave += "|"
            if lane["width"] == 1:
                ch_ = "x" if v is None else str(v)
                wave += "." if ch_ == prev else ch_
                prev = ch_
            else:
                s = fmt(v, lane["width"])
                if s is None:
                    wave += "." if prev == "x" else "x"
                    prev = "x"
                elif s == prev and k not in gap_at and lane["label"] not in beats:
                    wave += "."
                else:
                    wave += "="
                    data.append(s)
                    prev = s
        sig = {"name": lane["label"], "wave": wave}
        if data:
            sig["data"] = data
        signals.append(sig)
    if a.cycle_lane:
        wave, data = "", []
        for n, k in enumerate(shown):
            if k in gap_at:
                wave += "|"
            if a.cycle_lane == "all" or n == 0 or k in gap_at:
                wave += "="
                data.append(str(cycles[k] - origin))
            else:
                wave += "."
        name = "cycle" if a.origin != "anchor" and origin == 0 else ("cycle − anchor" if a.origin == "anchor" else f"cycle − {origin}")
        signals.append({"name": name, "wave": wave, "data": data})

    doc = {"signal": signals, "config": {"hscale": a.hscale}}
    if a.title:
        doc["head"] = {"text": a.title}
    if a.foot:
        doc["foot"] = {"text": a.foot}
    text = json.dumps(doc, indent=1, ensure_ascii=False) + "\n"
    if a.out == "-":
        sys.stdout.write(text)
    else:
        with open(a.out, "w") as f:
            f.write(text)
        print(f"{a.out}: cycles {first}..{last} of {a.vcd} (anchor {anchor}), {len(shown)} columns, {len(gap_at)} gaps", file=sys.stderr)


if __name__ == "__main__":
    main()
