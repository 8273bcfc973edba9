#!/usr/bin/env python3
"""Tables of docs/results.md from the JSON that scripts/machines.sh writes.

Usage: machines-report.py JSON_DIR > machines.md

Each JSON_DIR/SCENE.DISPATCH.json is the array `wasp compare --with-ideal
--json` writes: the scanline baseline first, then the other policies, then
the baseline with ideal memory. Runs are found by their policy name
(fullpriority, freemshr:N, wasp:..., wasp-m:...), so a missing policy only
leaves its column empty. Speedups are baseline cycles / policy cycles - 1;
group means are arithmetic means of the per-scene speedups.
"""
import json
import os
import sys

MODES = ["shared-tile", "per-core-tile"]
GROUPS = [("3D games", ("stk-", "oa-")), ("2D games", ("tw-", "fb-")), ("procedural", ("procedural-",))]
COLUMNS = [("Fullpriority", "fullpriority"), ("Freemshr", "freemshr:"), ("WaSP", "wasp:"),
           ("WaSP-m", "wasp-m:"), ("ideal memory", None)]


def load(d):
    runs = {}
    for f in sorted(os.listdir(d)):
        if not f.endswith(".json"):
            continue
        scene, mode, _ = f.rsplit(".", 2)
        with open(os.path.join(d, f)) as fh:
            runs[(scene, mode)] = json.load(fh)
    return runs


def by_policy(runs):
    """{column: run} for one scene's array."""
    out = {"baseline": runs[0]}
    for r in runs[1:]:
        if r.get("ideal_memory"):
            out["ideal memory"] = r
            continue
        for col, prefix in COLUMNS:
            if prefix and (r["policy"] == prefix or r["policy"].startswith(prefix)) and col not in out:
                if prefix == "wasp:" and r["policy"].startswith("wasp-m"):
                    continue
                out[col] = r
                break
    return out


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


def fmt(v, spec):
    return "" if v is None else format(v, spec)


def stall(x):
    return (x["l0"] or x["l1"])["stall_fraction"]


def detail_table(w, rows, col, label):
    present = [(s, p) for s, p in rows if col in p]
    if not present:
        return
    w(f"{label} (`{present[0][1][col]['policy']}`) against the baseline: lead of priority warps (raster position "
      "minus launch rank; positive = ahead of the quads rasterized before them), memory latency per warp, "
      "L0 stalls, misses, energy, core-cycles held by the launch rule:\n")
    pol = present[0][1][col]["policy"]
    used = pol.split(":")[2] if pol.startswith("wasp:") and pol.count(":") == 2 else (
        "2.5" if pol.startswith("wasp:") else "its meter's")
    w(f"| scene | measured CF (the policy uses {used}) | lead (mean) | ahead | after own subtile's regular | latency priority / regular | "
      "latency all, base -> policy | L0 stall base / policy | L1 misses | L2 misses | energy | held cycles |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s, p in present:
        b, r = p["baseline"], p[col]
        lead = r["priority_lead"]
        lat = r["memory_latency"]
        meter = r.get("measured_cf_mean")
        cf = f"{b['cf']:.2f}" + (f" (meter {meter:.2f})" if meter is not None else "")
        w(f"| {s} | {cf} | {lead['mean']:+.1f} | {pct(lead['ahead_share'])} | "
          f"{pct(lead['after_subtile_regular_share'])} | {lat['priority']:.1f} / {lat['regular']:.1f} | "
          f"{b['memory_latency']['all']:.1f} -> {lat['all']:.1f} | {pct(stall(b))} / {pct(stall(r))} | "
          f"{change(b['l1']['misses'], r['l1']['misses'])} | {change(b['l2']['misses'], r['l2']['misses'])} | "
          f"{change(b['energy']['total_nj'], r['energy']['total_nj'])} | {r['held_cycles']} |")
    w("")


def group_summary(w, rows, cols):
    """Per group: mean speedup per policy, latency change, priority and
    regular latency, L1/L2 miss and energy change of WaSP."""
    w("Group means (arithmetic over the scenes; latency and misses of WaSP against the baseline):\n")
    w("| group | scenes | " + " | ".join(cols) + " | WaSP latency change | priority / regular latency | "
      "L1 misses | L2 misses | energy |")
    w("|---|---|" + "---|" * len(cols) + "---|---|---|---|---|")
    for name, _ in GROUPS:
        g = [p for s, p in rows if group_of(s) == name]
        if not g:
            continue
        cells = []
        for c in cols:
            xs = [sp(p["baseline"], p[c]) for p in g if c in p]
            cells.append(f"{sum(xs) / len(xs):+.2f}%" if xs else "")
        wa = [p for p in g if "WaSP" in p]

        def mean(f):
            xs = [f(p) for p in wa]
            return sum(xs) / len(xs) if xs else None

        def rel(f):
            return mean(lambda p: 100.0 * (f(p["WaSP"]) / f(p["baseline"]) - 1.0) if f(p["baseline"]) else 0.0)

        lat = rel(lambda r: r["memory_latency"]["all"])
        lp = mean(lambda p: p["WaSP"]["memory_latency"]["priority"])
        lr = mean(lambda p: p["WaSP"]["memory_latency"]["regular"])
        w(f"| {name} | {len(g)} | " + " | ".join(cells) + f" | {fmt(lat, '+.1f')}% | {fmt(lp, '.1f')} / {fmt(lr, '.1f')} | "
          f"{fmt(rel(lambda r: r['l1']['misses']), '+.2f')}% | {fmt(rel(lambda r: r['l2']['misses']), '+.2f')}% | "
          f"{fmt(rel(lambda r: r['energy']['total_nj']), '+.2f')}% |")
    w("")


def main():
    runs = load(sys.argv[1])
    scenes = sorted({s for s, _ in runs})
    out = []
    w = out.append
    for mode in MODES:
        rows = [(s, by_policy(runs[(s, mode)])) for s in scenes if (s, mode) in runs]
        if not rows:
            continue
        cols = [c for c, _ in COLUMNS if any(c in p for _, p in rows)]
        w(f"### {mode}\n")
        w("Speedup over the scanline baseline, and where the baseline's time goes:\n")
        w("| scene | baseline cycles | " + " | ".join(cols) +
          " | warps/core | <25% | <50% | fill | drain | rejected quads |")
        w("|---|---|" + "---|" * len(cols) + "---|---|---|---|---|---|")
        for s, p in rows:
            b = p["baseline"]
            o = b["occupancy"]
            t = b["tile_timing"]
            cells = [f"{sp(b, p[c]):+.2f}%" if c in p else "" for c in cols]
            w(f"| {s} | {b['cycles']} | " + " | ".join(cells) + f" | {o['mean']:.1f} | {pct(o['below_quarter'])} | "
              f"{pct(o['below_half'])} | {pct(t['fill_share'])} | {pct(t['drain_share'])} | "
              f"{b['raster']['quads_rejected']} |")
        w("")
        group_summary(w, rows, cols)
        detail_table(w, rows, "WaSP", "WaSP")
        detail_table(w, rows, "WaSP-m", "WaSP with the measured CF")
    print("\n".join(out))


if __name__ == "__main__":
    main()
