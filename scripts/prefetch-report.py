#!/usr/bin/env python3
"""The prefetcher table of docs/machine.md from the JSON scripts/prefetch.sh writes.

Usage: prefetch-report.py JSON_DIR > prefetch.md

Each JSON_DIR/SCENE.RUN.json is `wasp run --json` of one scene under one
run (baseline, wasp, raster, wasp-raster, oracle, wasp-oracle, ideal).
Speedups are baseline cycles / run cycles - 1; group means are arithmetic
means of the per-scene speedups (as in scripts/machines-report.py). The
second table holds the instruments that say why a run is as fast as it is:
L1 stall share, mean L1 MSHRs outstanding, DRAM queue wait, and the
prefetches' fate (late share, useful share of prefetch misses).
"""
import json
import os
import sys

RUNS = ["baseline", "wasp", "raster", "wasp-raster", "oracle", "wasp-oracle", "ideal"]
LABELS = {"baseline": "baseline cycles", "wasp": "WaSP", "raster": "+raster", "wasp-raster": "WaSP+raster",
          "oracle": "+oracle", "wasp-oracle": "WaSP+oracle", "ideal": "ideal memory"}
GROUPS = [("3D games", ("stk-", "oa-")), ("2D games", ("tw-", "fb-")), ("procedural", ("procedural-",))]


def load(d):
    runs = {}
    for f in sorted(os.listdir(d)):
        if f.endswith(".json"):
            scene, run, _ = f.rsplit(".", 2)
            with open(os.path.join(d, f)) as fh:
                runs.setdefault(scene, {})[run] = json.load(fh)
    return runs


def sp(base, r):
    return 100.0 * (base["cycles"] / r["cycles"] - 1.0)


def group_of(scene):
    for name, prefixes in GROUPS:
        if scene.startswith(prefixes):
            return name
    return "other"


def main():
    runs = load(sys.argv[1])
    scenes = sorted(runs, key=lambda s: ([g for g, _ in GROUPS].index(group_of(s)), s))
    w = sys.stdout.write
    cols = RUNS[1:]
    w("| scene | " + " | ".join(LABELS[r] for r in RUNS) + " |\n")
    w("|---|" + "---:|" * len(RUNS) + "\n")
    per_group = {}
    for s in scenes:
        r = runs[s]
        if "baseline" not in r:
            continue
        b = r["baseline"]
        cells = [str(b["cycles"])]
        for c in cols:
            if c in r:
                v = sp(b, r[c])
                per_group.setdefault(group_of(s), {}).setdefault(c, []).append(v)
                cells.append(f"{v:+.1f}%")
            else:
                cells.append("")
        w(f"| {s} | " + " | ".join(cells) + " |\n")
    for g, _ in GROUPS + [("all", ())]:
        vals = {}
        for gg, d in per_group.items():
            if g in ("all", gg):
                for c, v in d.items():
                    vals.setdefault(c, []).extend(v)
        if not vals:
            continue
        n = len(vals.get("wasp", []))
        cells = [f"{n} scenes"] + [f"{sum(vals[c]) / len(vals[c]):+.1f}%" if c in vals else "" for c in cols]
        w(f"| **{g} mean** | " + " | ".join(cells) + " |\n")

    w("\n| scene | run | L1 stall | L1 MSHRs out | DRAM queue wait | DRAM latency | pf misses | useful | late share | reserve waits | dropped |\n")
    w("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    for s in scenes:
        for c in ["baseline", "wasp", "raster", "oracle", "wasp-oracle"]:
            x = runs[s].get(c)
            if x is None:
                continue
            p = x.get("prefetch") or {}
            pf = lambda k, f="{}": f.format(p[k]) if k in p else ""
            w(f"| {s} | {c} | {100 * x['l1']['stall_fraction']:.1f}% | {x['l1']['avg_outstanding_misses']:.2f} | "
              f"{x['dram']['avg_queue_wait']:.1f} | {x['dram']['avg_latency']:.1f} | {pf('misses')} | "
              f"{pf('accuracy', '{:.2f}') if p else ''} | {pf('late_share', '{:.2f}') if p else ''} | "
              f"{pf('reserve_waits')} | {pf('dropped')} |\n")


if __name__ == "__main__":
    main()
