#!/usr/bin/env python3
"""Picks and report of scripts/calibrate.sh (see docs/calibration.md).

  calibrate-report.py pick OUT LEVEL N... [-- SUFFIX]
      The smallest N whose suite geomean baseline cycles (runs
      OUT/json/LEVEL-N{SUFFIX}.SCENE.json) are within KNEE (env, default
      0.01) of the best N's. Prints N.
  calibrate-report.py cf OUT BASE
      The suite mean of the scenes' measured CF (baseline runs
      OUT/json/BASE.SCENE.json), rounded to the datapath's quarter steps.
  calibrate-report.py report OUT BASE CF L0 L1 L2 L0_SET L1_SET L2_SET SCENES
      Writes OUT/calibration.md and OUT/calibration.json; prints the
      chosen threshold.

Every JSON file is the array `wasp compare --json` writes, the baseline
first. Every point runs on the same scenes; a missing one is an error.
"""
import json
import math
import os
import sys

GROUPS = [("3D games", ("stk-", "oa-")), ("2D games", ("tw-", "fb-")), ("procedural", ("procedural-",))]


def die(msg):
    print(f"calibrate-report.py: {msg}", file=sys.stderr)
    sys.exit(2)


def load_point(out, name):
    """{scene: [runs]} for every OUT/json/NAME.SCENE.json."""
    d = os.path.join(out, "json")
    prefix = name + "."
    runs = {}
    for f in sorted(os.listdir(d)):
        if f.startswith(prefix) and f.endswith(".json"):
            scene = f[len(prefix):-len(".json")]
            if "." in scene:  # a longer name sharing the prefix
                continue
            with open(os.path.join(d, f)) as fh:
                runs[scene] = json.load(fh)
    if not runs:
        die(f"no runs for point {name} in {d}")
    return runs


def geomean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs))


def group_of(scene):
    for name, prefixes in GROUPS:
        if scene.startswith(prefixes):
            return name
    return "other"


def knee():
    return float(os.environ.get("KNEE", "0.01"))


def sweep(out, level, ns, suffix):
    """[(n, geomean baseline cycles, {scene: cycles})] for one MSHR stage."""
    rows = []
    scenes = None
    for n in ns:
        pt = load_point(out, f"{level}-{n}{suffix}")
        if scenes is None:
            scenes = sorted(pt)
        elif sorted(pt) != scenes:
            die(f"{level}-{n}{suffix} ran on other scenes than {level}-{ns[0]}{suffix}")
        cyc = {s: pt[s][0]["cycles"] for s in scenes}
        rows.append((n, geomean(list(cyc.values())), cyc))
    return rows


def pick_n(rows):
    best = min(g for _, g, _ in rows)
    for n, g, _ in sorted(rows, key=lambda r: r[0]):
        if g <= best * (1.0 + knee()):
            return n
    raise AssertionError("the best point is within the knee of itself")


def split_suffix(args):
    if "--" in args:
        i = args.index("--")
        return args[:i], (args[i + 1] if i + 1 < len(args) else "")
    return args, ""


def quarter(x):
    return round(x * 4.0) / 4.0


def fmt_cf(x):
    return f"{x:g}"


def cmd_pick(out, level, rest):
    ns, suffix = split_suffix(rest)
    if not ns:
        die("pick: no counts given")
    print(pick_n(sweep(out, level, [int(n) for n in ns], suffix)))


def measured_cfs(out, base):
    pt = load_point(out, base)
    return {s: pt[s][0]["cf"] for s in sorted(pt)}


def cmd_cf(out, base):
    cfs = measured_cfs(out, base)
    print(fmt_cf(quarter(sum(cfs.values()) / len(cfs))))


def policy_speedups(pt):
    """{policy: {scene: speedup factor}} over the baseline of each file."""
    res = {}
    for s, runs in pt.items():
        b = runs[0]
        if b["policy"] != "baseline":
            die(f"{s}: the first run is {b['policy']}, not the baseline")
        for r in runs[1:]:
            res.setdefault(r["policy"], {})[s] = b["cycles"] / r["cycles"]
    return res


def pct(f):
    return f"{100.0 * (f - 1.0):+.2f}%"


def group_means(per_scene):
    """[(group, n, geomean factor)] for the groups present, then the suite."""
    out = []
    for name, _ in GROUPS:
        xs = [v for s, v in per_scene.items() if group_of(s) == name]
        if xs:
            out.append((name, len(xs), geomean(xs)))
    out.append(("suite", len(per_scene), geomean(list(per_scene.values()))))
    return out


def parse_wasp(name):
    # wasp:T or wasp:T:CF
    parts = name.split(":")
    t = int(parts[1])
    cf = float(parts[2]) if len(parts) > 2 else 2.5
    return t, cf


def cmd_report(out, base, cf, l0, l1, l2, l0_set, l1_set, l2_set, scenes):
    cf = float(cf)
    l0, l1, l2 = int(l0), int(l1), int(l2)
    stages = [
        ("L2", "l2", [int(n) for n in l2_set.split()], "", l2, "L0 31, L1 64"),
        ("L1", "l1", [int(n) for n in l1_set.split()], f".l2-{l2}", l1, f"L0 31, L2 {l2}"),
        ("L0", "l0", [int(n) for n in l0_set.split()], f".l1-{l1}.l2-{l2}", l0, f"L1 {l1}, L2 {l2}"),
    ]
    md = []
    w = md.append
    data = {"knee": knee(), "scenes": scenes.split(), "mshrs": {}, "cf": {}, "threshold": {}}
    w("# Calibration results\n")
    w(f"Scenes: {len(scenes.split())}. Knee: {100 * knee():g}% of the best suite geomean.\n")
    w("## A. MSHR counts (scanline baseline)\n")
    for label, level, ns, suffix, chosen, fixed in stages:
        rows = sweep(out, level, ns, suffix)
        best = min(g for _, g, _ in rows)
        w(f"### {label} MSHRs ({fixed})\n")
        w("| MSHRs | suite geomean cycles | vs best | |")
        w("|---|---|---|---|")
        for n, g, _ in rows:
            mark = "**chosen**" if n == chosen else ""
            w(f"| {n} | {g:.0f} | {100 * (g / best - 1):+.2f}% | {mark} |")
        w("")
        data["mshrs"][label] = {
            "chosen": chosen,
            "points": [{"mshrs": n, "geomean_cycles": g, "cycles": c} for n, g, c in rows],
        }
    cfs = measured_cfs(out, base)
    mean = sum(cfs.values()) / len(cfs)
    w("## B. CF: each scene's measured CF (unique blocks per warp)\n")
    w(f"Suite mean {mean:.3f}, in quarter steps {fmt_cf(quarter(mean))} (used: {fmt_cf(cf)}; the paper: 2.5).\n")
    w("| scene | group | measured CF |")
    w("|---|---|---|")
    for s, v in cfs.items():
        w(f"| {s} | {group_of(s)} | {v:.2f} |")
    for name, _ in GROUPS:
        xs = [v for s, v in cfs.items() if group_of(s) == name]
        if xs:
            w(f"| **mean, {name} ({len(xs)})** | | {sum(xs) / len(xs):.2f} |")
    w("")
    data["cf"] = {"chosen": cf, "suite_mean": mean, "per_scene": cfs}

    sp = policy_speedups(load_point(out, f"wasp.{base}"))
    by_cf = {}
    for name, per in sp.items():
        t, c = parse_wasp(name)
        by_cf.setdefault(c, {})[t] = per
    cands = []
    for c, ts in by_cf.items():
        for t, per in ts.items():
            cands.append((geomean(list(per.values())), -t, c, t))
    # Best suite geomean at the chosen CF; ties go to the lower threshold.
    at_cf = [x for x in cands if x[2] == cf]
    chosen_t = max(at_cf)[3]
    w(f"## C. WaSP threshold (MSHRs L0 {l0}, L1 {l1}, L2 {l2})\n")
    w("Geomean speedup of WaSP over the scanline baseline, per group and over the suite:\n")
    cfs_sorted = sorted(by_cf)
    groups = [g for g, _ in GROUPS if any(group_of(s) == g for s in cfs)] + ["suite"]
    head = "| threshold | " + " | ".join(f"CF {fmt_cf(c)}: {g}" for c in cfs_sorted for g in groups) + " |"
    w(head)
    w("|---" * (1 + len(cfs_sorted) * len(groups)) + "|")
    thresholds = sorted({t for ts in by_cf.values() for t in ts})
    rows_json = []
    for t in thresholds:
        cells = []
        for c in cfs_sorted:
            per = by_cf[c].get(t)
            gm = {g: f for g, _, f in group_means(per)} if per else {}
            for g in groups:
                cells.append(pct(gm[g]) if g in gm else "")
            if per:
                rows_json.append({"threshold": t, "cf": c, "speedup": {g: f - 1.0 for g, f in gm.items()},
                                  "per_scene": {s: f - 1.0 for s, f in per.items()}})
        mark = " **chosen**" if t == chosen_t else ""
        w(f"| {t}{mark} | " + " | ".join(cells) + " |")
    w("")
    best_any = max(cands)
    w(f"Chosen: threshold {chosen_t} at CF {fmt_cf(cf)} (suite geomean {pct(max(at_cf)[0])}); "
      f"best over both CFs: threshold {best_any[3]} at CF {fmt_cf(best_any[2])} ({pct(best_any[0])}).\n")
    data["threshold"] = {"chosen": chosen_t, "cf": cf, "points": rows_json}
    with open(os.path.join(out, "calibration.md"), "w") as fh:
        fh.write("\n".join(md) + "\n")
    with open(os.path.join(out, "calibration.json"), "w") as fh:
        json.dump(data, fh, indent=1, sort_keys=True)
        fh.write("\n")
    print(chosen_t)


def main():
    a = sys.argv[1:]
    if len(a) >= 3 and a[0] == "pick":
        cmd_pick(a[1], a[2], a[3:])
    elif len(a) == 3 and a[0] == "cf":
        cmd_cf(a[1], a[2])
    elif len(a) == 11 and a[0] == "report":
        cmd_report(*a[1:])
    else:
        die(__doc__.strip().splitlines()[2].strip() + " ... (see the script's docstring)")


if __name__ == "__main__":
    main()
