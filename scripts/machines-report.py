#!/usr/bin/env python3
"""Tables of docs/results.md from the JSON that scripts/machines.sh writes.

Usage: machines-report.py JSON_DIR > machines.md

Each JSON_DIR/SCENE.DISPATCH.json is the array `wasp compare --with-ideal
--json` writes: baseline, fullpriority, freemshr:10, wasp:4, then the
baseline with ideal memory. Speedups are baseline cycles / policy cycles - 1.
"""
import json
import os
import sys

MODES = ["shared-tile", "per-core-tile"]
GROUPS = [("3D games", ("stk-", "oa-")), ("2D games", ("tw-", "fb-")), ("procedural", ("procedural-",))]


def load(d):
    runs = {}
    for f in sorted(os.listdir(d)):
        if not f.endswith(".json"):
            continue
        scene, mode, _ = f.rsplit(".", 2)
        with open(os.path.join(d, f)) as fh:
            runs[(scene, mode)] = json.load(fh)
    return runs


def sp(base, r):
    return 100.0 * (base["cycles"] / r["cycles"] - 1.0)


def pct(x):
    return f"{100.0 * x:.1f}%"


def change(a, b):
    return "n/a" if a == 0 else f"{100.0 * (b / a - 1.0):+.1f}%"


def group_of(scene):
    for name, prefixes in GROUPS:
        if scene.startswith(prefixes):
            return name
    return "other"


def main():
    runs = load(sys.argv[1])
    scenes = sorted({s for s, _ in runs})
    out = []
    w = out.append
    for mode in MODES:
        rows = [(s, runs[(s, mode)]) for s in scenes if (s, mode) in runs]
        if not rows:
            continue
        w(f"### {mode}\n")
        w("Speedup over the scanline baseline, and where the baseline's time goes:\n")
        w("| scene | baseline cycles | Fullpriority | Freemshr10 | WaSP | ideal memory | warps/core | <25% | <50% | fill | drain | rejected quads |")
        w("|---|---|---|---|---|---|---|---|---|---|---|---|")
        sums = {}
        for s, r in rows:
            b, fp, fm, wa, ideal = r
            o = b["occupancy"]
            t = b["tile_timing"]
            ra = b["raster"]
            vals = [sp(b, fp), sp(b, fm), sp(b, wa), sp(b, ideal)]
            g = sums.setdefault(group_of(s), [])
            g.append(vals + [o["mean"], o["below_quarter"], o["below_half"]])
            w(f"| {s} | {b['cycles']} | {vals[0]:+.2f}% | {vals[1]:+.2f}% | {vals[2]:+.2f}% | {vals[3]:+.2f}% | "
              f"{o['mean']:.1f} | {pct(o['below_quarter'])} | {pct(o['below_half'])} | {pct(t['fill_share'])} | "
              f"{pct(t['drain_share'])} | {ra['quads_rejected']} |")
        for name, _ in GROUPS:
            g = sums.get(name)
            if not g:
                continue
            m = [sum(v[i] for v in g) / len(g) for i in range(7)]
            w(f"| **mean, {name} ({len(g)})** | | {m[0]:+.2f}% | {m[1]:+.2f}% | {m[2]:+.2f}% | {m[3]:+.2f}% | "
              f"{m[4]:.1f} | {pct(m[5])} | {pct(m[6])} | | | |")
        w("")
        w("WaSP (`wasp:4`) against the baseline: lead of priority warps (raster position minus launch rank; "
          "positive = ahead of the quads rasterized before them), memory latency per warp, L0 stalls, misses:\n")
        w("| scene | measured CF (WaSP uses 2.5) | lead (mean) | ahead | after own subtile's regular | latency priority / regular | latency all, base -> WaSP | L0 stall base / WaSP | L1 misses | L2 misses | held cycles |")
        w("|---|---|---|---|---|---|---|---|---|---|---|")
        for s, r in rows:
            b, _, _, wa, _ = r
            lead = wa["priority_lead"]
            lat = wa["memory_latency"]
            st = lambda x: (x["l0"] or x["l1"])["stall_fraction"]
            w(f"| {s} | {b['cf']:.2f} | {lead['mean']:+.1f} | {pct(lead['ahead_share'])} | {pct(lead['after_subtile_regular_share'])} | "
              f"{lat['priority']:.1f} / {lat['regular']:.1f} | {b['memory_latency']['all']:.1f} -> {lat['all']:.1f} | "
              f"{pct(st(b))} / {pct(st(wa))} | {change(b['l1']['misses'], wa['l1']['misses'])} | "
              f"{change(b['l2']['misses'], wa['l2']['misses'])} | {wa['held_cycles']} |")
        w("")
    print("\n".join(out))


if __name__ == "__main__":
    main()
