#!/usr/bin/env python3
"""Compares two co-simulation traces (`# cosim trace v1`, vectors/README.md) clock by clock.

    python3 scripts/trace-diff.py OLD NEW [--ignore-input NAME ...] [--new-port NAME ...]
                                          [--only-where PORT:FLAG ...]

Expands the `*N` repeats, drops the named input columns of either trace (each must be 0 on
every clock of the trace that has it) and the new ports of NEW (inputs or outputs that OLD
lacks; it prints on how many clocks each is not 0), and reports the ports and clocks that
differ. `--only-where PORT:FLAG` lets PORT differ, but only on clocks where the port FLAG (of
the same side, in both traces) is not 0; it prints on how many clocks PORT changed. It exits 0 when both traces have the same ports, clocks and values, 1 when they differ.
Used to show that a re-blessed vector changed only by a new input held at 0 (the `reset`
port), or only by new ports (the matcher's `o_sof`, `r_unpaired`, `o_unpaired`), or only in a
field on a line's marker (the detector's `m_end` where `m_last` is set).
"""
import argparse
import sys


def read(path):
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f]
    if not lines or lines[0] != "# cosim trace v1":
        sys.exit(f"{path}: not a cosim trace v1")
    ins = [p.split(":") for p in lines[1].split()[1:]]
    outs = [p.split(":") for p in lines[2].split()[1:]]
    cycles = []
    for line in lines[4:]:
        if line.startswith("*"):
            cycles.extend([cycles[-1]] * int(line[1:]))
        elif line:
            i, o = line.split("|")
            cycles.append((i.split(), o.split()))
    declared = int(lines[3].split()[1])
    if declared != len(cycles):
        sys.exit(f"{path}: {len(cycles)} clocks, the header says {declared}")
    return ins, outs, cycles


def drop(path, ins, cycles, ignore):
    keep = [k for k, (name, _) in enumerate(ins) if name not in ignore]
    for k, (name, _) in enumerate(ins):
        if name in ignore and any(int(c[0][k], 16) != 0 for c in cycles):
            sys.exit(f"{path}: input {name} is not 0 on every clock")
    return [ins[k] for k in keep], [([i[k] for k in keep], o) for i, o in cycles]


def drop_new(path, ins, outs, cycles, new):
    """Drops the ports named in `new` from a trace; prints on how many clocks each is not 0."""
    ki = [k for k, (name, _) in enumerate(ins) if name not in new]
    ko = [k for k, (name, _) in enumerate(outs) if name not in new]
    for side, ports in ((0, ins), (1, outs)):
        for k, (name, _) in enumerate(ports):
            if name in new:
                n = sum(int(c[side][k], 16) != 0 for c in cycles)
                print(f"{path}: new {'input' if side == 0 else 'output'} {name} is not 0 on {n} of {len(cycles)} clocks")
    return [ins[k] for k in ki], [outs[k] for k in ko], [([i[k] for k in ki], [o[k] for k in ko]) for i, o in cycles]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--ignore-input", action="append", default=[], metavar="NAME")
    ap.add_argument("--new-port", action="append", default=[], metavar="NAME")
    ap.add_argument("--only-where", action="append", default=[], metavar="PORT:FLAG")
    a = ap.parse_args()
    (oi, oo, oc), (ni, no, nc) = read(a.old), read(a.new)
    oi, oc = drop(a.old, oi, oc, a.ignore_input)
    ni, nc = drop(a.new, ni, nc, a.ignore_input)
    ni, no, nc = drop_new(a.new, ni, no, nc, a.new_port)
    if (oi, oo) != (ni, no):
        print(f"ports differ: {oi} | {oo} against {ni} | {no}")
        return 1
    for spec in a.only_where:
        port, flag = spec.split(":")
        side = 0 if port in [n for n, _ in ni] else 1
        names = [n for n, _ in (ni if side == 0 else no)]
        kp, kf = names.index(port), names.index(flag)
        changed = outside = 0
        for x, y in zip(oc, nc):
            if x[side][kp] != y[side][kp]:
                changed += 1
                if int(x[side][kf], 16) == 0 or int(y[side][kf], 16) == 0:
                    outside += 1
                x[side][kp] = y[side][kp]
        print(f"{a.new}: {port} changed on {changed} clocks, {outside} of them where {flag} is 0")
        if outside:
            return 1
    ignored = ", ".join(a.ignore_input + a.new_port + [w.replace(":", " where ") for w in a.only_where]) or "nothing"
    diff = [k for k, (x, y) in enumerate(zip(oc, nc)) if x != y]
    if len(oc) != len(nc) or diff:
        print(f"{len(oc)} against {len(nc)} clocks; {len(diff)} differ, first {diff[:5]}")
        return 1
    print(f"{a.new}: {len(nc)} clocks, {len(ni)} inputs and {len(no)} outputs, every clock equal (ignoring {ignored})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
