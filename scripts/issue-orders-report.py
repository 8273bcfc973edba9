#!/usr/bin/env python3
"""The issue-order table of docs/machine.md from scripts/issue-orders.sh.

Usage: issue-orders-report.py JSON_DIR > issue-orders.md

Each JSON_DIR/SCENE.ORDER.json (ORDER: lrr or gto) is the array `wasp
compare --policies baseline,WASP --json` writes: the baseline, then WaSP.
Speedups are baseline cycles / WaSP cycles - 1; "gto vs lrr" is lrr
cycles / gto cycles - 1 for the same policy; group means are arithmetic
means over the group's scenes. L0 hit rate is L0 hits / L0 accesses (a
secondary miss is no hit); L0 stalls the share of core-cycles the L0
refused an access (ports or MSHRs); L1 misses are summed over the cores.
"""
import json
import os
import sys

ORDERS = ["lrr", "gto"]
GROUPS = [("3D games", ("stk-", "oa-")), ("2D games", ("tw-", "fb-")),
          ("procedural", ("procedural-",))]


def load(d):
    runs = {}
    for f in sorted(os.listdir(d)):
        if f.endswith(".json"):
            scene, order, _ = f.rsplit(".", 2)
            with open(os.path.join(d, f)) as fh:
                base, wasp = json.load(fh)[:2]
            # A run under the default order names none.
            for r in (base, wasp):
                got = r.get("issue", "lrr")
                if got != order:
                    sys.exit(f"{f}: a run of issue order {got}, not {order}")
            runs[(scene, order)] = (base, wasp)
    return runs


def speedup(a, b):
    """Cycles a against b: a / b - 1, in percent."""
    return 100.0 * (a["cycles"] / b["cycles"] - 1.0)


def row(runs, scene):
    out = []
    for order in ORDERS:
        base, wasp = runs[(scene, order)]
        out.append({
            "base": base["cycles"], "wasp": wasp["cycles"],
            "speedup": speedup(base, wasp),
            "hit": 100.0 * base["l0"]["hits"] / max(base["l0"]["accesses"], 1),
            "stall": 100.0 * base["l0"]["stall_fraction"],
            "l1": base["l1"]["misses"],
            "prim": base["l0"]["misses"], "sec": base["l0"]["secondary_misses"],
            "wprim": wasp["l0"]["misses"], "wsec": wasp["l0"]["secondary_misses"],
            "whit": 100.0 * wasp["l0"]["hits"] / max(wasp["l0"]["accesses"], 1),
            "wstall": 100.0 * wasp["l0"]["stall_fraction"],
            "wl1": wasp["l1"]["misses"],
        })
    lrr, gto = out
    return lrr, gto, {"base": speedup(
        {"cycles": lrr["base"]}, {"cycles": gto["base"]}), "wasp": speedup(
        {"cycles": lrr["wasp"]}, {"cycles": gto["wasp"]})}


def mean(xs):
    return sum(xs) / len(xs) if xs else float("nan")


def main():
    runs = load(sys.argv[1])
    scenes = sorted({s for s, _ in runs})
    print("Per scene (cycles; baseline and WaSP under each order):\n")
    print("| scene | baseline lrr | baseline gto | gto vs lrr | WaSP lrr | WaSP gto | gto vs lrr "
          "| WaSP speedup lrr | WaSP speedup gto |")
    print("|---|---|---|---|---|---|---|---|---|")
    rows = {}
    for s in scenes:
        if (s, "lrr") not in runs or (s, "gto") not in runs:
            continue
        lrr, gto, d = rows[s] = row(runs, s)
        print(f"| {s} | {lrr['base']} | {gto['base']} | {d['base']:+.2f}% | {lrr['wasp']} "
              f"| {gto['wasp']} | {d['wasp']:+.2f}% | {lrr['speedup']:+.2f}% | {gto['speedup']:+.2f}% |")
    print("\nGroup means:\n")
    print("| group | scenes | baseline: gto vs lrr | WaSP: gto vs lrr | WaSP speedup, lrr "
          "| WaSP speedup, gto |")
    print("|---|---|---|---|---|---|")
    groups = []
    for name, prefixes in GROUPS:
        g = [rows[s] for s in rows if s.startswith(prefixes)]
        if g:
            groups.append((name, g))
    for name, g in groups:
        m = lambda f: mean([f(x) for x in g])
        print(f"| {name} | {len(g)} | {m(lambda x: x[2]['base']):+.2f}% "
              f"| {m(lambda x: x[2]['wasp']):+.2f}% | {m(lambda x: x[0]['speedup']):+.2f}% "
              f"| {m(lambda x: x[1]['speedup']):+.2f}% |")
    print("\nThe memory side, group means:\n")
    print("| group | policy | L0 hit rate, lrr / gto | L0 stalls, lrr / gto "
          "| L0 primary misses, gto vs lrr | L0 secondary misses, gto vs lrr "
          "| L1 misses, gto vs lrr |")
    print("|---|---|---|---|---|---|---|")
    for name, g in groups:
        m = lambda f: mean([f(x) for x in g])
        for policy, p in [("baseline", ""), ("WaSP", "w")]:
            ch = lambda k: m(lambda x: 100.0 * (x[1][p + k] / max(x[0][p + k], 1) - 1.0))
            print(f"| {name} | {policy} | {m(lambda x: x[0][p + 'hit']):.1f}% / "
                  f"{m(lambda x: x[1][p + 'hit']):.1f}% | {m(lambda x: x[0][p + 'stall']):.1f}% / "
                  f"{m(lambda x: x[1][p + 'stall']):.1f}% | {ch('prim'):+.1f}% | {ch('sec'):+.1f}% "
                  f"| {ch('l1'):+.2f}% |")

main()
