#!/usr/bin/env python3
"""The characterisation table of docs/scenes.md from `wasp characterize
--texture-format rgba8 --texture-format etc2 --json FILE`: per figure the
range over the study's game scenes (the procedural ones in parentheses),
for each format, beside the paper's. The study's scenes: a loader scene
with an engine twin (NAME-engine) counts through its twin. On stderr, the
scenes where the subsets do not rank as in the paper's Figure 11, and the
games' mean CF per format.

    scripts/characterisation-table.py chars.json > table.md
"""
import json
import sys

GAMES = {"tw": "Teeworlds", "fb": "Frozen Bubble", "st": "SuperTuxKart",
         "oa": "OpenArena", "pr": "procedural"}
GAME_ORDER = ["Teeworlds", "Frozen Bubble", "SuperTuxKart", "OpenArena"]
THREE_D = ("SuperTuxKart", "OpenArena")


def game(c):
    """A shipped scene's game, from its name's prefix."""
    return GAMES[c["scene"][:2]]


def footprint(c, subset):
    return next(f["footprint_ratio"] for f in c["footprints"] if f["subset"] == subset)


def span(values, digits):
    lo, hi = (f"{v:.{digits}f}" for v in (min(values), max(values)))
    return lo if lo == hi else f"{lo}-{hi}"


def cell(scenes, get, digits, per_game=False, by_dimension=False):
    games = [c for c in scenes if game(c) != "procedural"]
    procedural = [get(c) for c in scenes if game(c) == "procedural"]
    if per_game:
        parts = [f"{span([get(c) for c in games if game(c) == g], digits)} {g}" for g in GAME_ORDER]
        return ", ".join(parts) + f" ({span(procedural, digits)})"
    if by_dimension:
        d3 = [get(c) for c in games if game(c) in THREE_D]
        d2 = [get(c) for c in games if game(c) not in THREE_D]
        return f"{span(d3, digits)} 3D games, {span(d2, digits)} 2D games"
    return f"{span([get(c) for c in games], digits)} ({span(procedural, digits)})"


ROWS = [
    ("memory-instruction ratio", lambda c: c["mem_instr_ratio"], 3, {}, "0.07-0.26 (Table I)"),
    ("block reuse in tile", lambda c: c["reuse"], 1, {}, "3.3-22.9 (Table I)"),
    ("CF, blocks per warp", lambda c: c["cf"], 2, {"per_game": True}, "2.5 mean (III-B)"),
    ("Min_Estimate1", lambda c: c["min_estimate1"], 3, {}, "0.12 (III-B)"),
    ("Min_Estimate2", lambda c: c["min_estimate2"], 3, {}, "about 1/16 (III-B)"),
    ("footprint Top16th", lambda c: footprint(c, "top16"), 2, {}, "0.17 (Fig. 11)"),
    ("footprint hlines", lambda c: footprint(c, "hlines"), 2, {}, "0.30 (Fig. 11)"),
    ("footprint vlines", lambda c: footprint(c, "vlines"), 2, {}, "0.40 (Fig. 11)"),
    ("footprint Mesh2", lambda c: footprint(c, "mesh2"), 2, {}, "0.90 (Fig. 11)"),
    ("footprint Mesh4", lambda c: footprint(c, "mesh4"), 2, {"by_dimension": True},
     "0.59 (Fig. 11), 0.64 (V-D)"),
    ("footprint Mesh8", lambda c: footprint(c, "mesh8"), 2, {}, "lower than Mesh4"),
    ("footprint Mesh16", lambda c: footprint(c, "mesh16"), 2, {}, "lower than Mesh4"),
    ("footprint Random 1/16", lambda c: footprint(c, "random:1"), 2, {}, "0.56 (Fig. 11)"),
]

every = json.load(open(sys.argv[1]))
names = {c["scene"] for c in every}
by_format = {}
for c in every:
    if c["scene"] + "-engine" not in names:
        by_format.setdefault(c["texture_format"], []).append(c)

print("| figure | ours, rgba8 | ours, etc2 (shipped) | paper |\n|---|---|---|---|")
for name, get, digits, how, paper in ROWS:
    cells = [cell(by_format[f], get, digits, **how) for f in ("rgba8", "etc2")]
    print(f"| {name} | {cells[0]} | {cells[1]} | {paper} |")

for f, scenes in by_format.items():
    off = []
    for c in scenes:
        t, h, v, m2, m4, r = (footprint(c, s) for s in
                              ("top16", "hlines", "vlines", "mesh2", "mesh4", "random:1"))
        if not (t <= min(h, v) and r < m4 < m2):
            off.append(f"{c['scene']} (top16 {t:.2f}, lines {h:.2f}/{v:.2f}, random {r:.2f}, "
                       f"mesh4 {m4:.2f}, mesh2 {m2:.2f})")
    games = [c for c in scenes if game(c) != "procedural"]
    print(f"{f}: not in Figure 11's order: {', '.join(off) or 'none'}", file=sys.stderr)
    print(f"{f}: games' mean CF {sum(c['cf'] for c in games) / len(games):.2f}", file=sys.stderr)
