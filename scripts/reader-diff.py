#!/usr/bin/env python3
"""Compare how two `wasp` binaries read malformed traces.

    scripts/reader-diff.py OLD_BINARY NEW_BINARY [CASES] [SEED] [TRACE]

Mutates TRACE (default tests/traces/synthetic-small.trace; give one over
4 MB to exercise the reading in pieces on several threads) (inserted, deleted and replaced
bytes: line ends, tabs, commas, control and non-ASCII characters, stray
directives; some cases truncated), runs `wasp run --json -` on each with both
binaries, and reports every case where exit code, JSON or error message
differ. For changes to the trace reader that must not change what it
accepts or how it reports a malformed line. Exits 1 on any difference.
"""
import os
import random
import subprocess
import sys
import tempfile

old, new = sys.argv[1], sys.argv[2]
cases = int(sys.argv[3]) if len(sys.argv) > 3 else 400
rng = random.Random(int(sys.argv[4]) if len(sys.argv) > 4 else 11)
repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
base = sys.argv[5] if len(sys.argv) > 5 else os.path.join(repo, "tests/traces/synthetic-small.trace")
src = open(base, "rb").read()
pieces = [b"\r", b"\t", b" ", b",", b",,", b"\xc2\x85", b"\xc2\xa0", b"g", b"a0", b"t",
          b"q", b"\n", b"\x7f", b"\x00", b"\x1f", b"\xe3\x80\x80", b"f" * 18, b"\xff",
          b"\r\n", b"\t\xc2\xa0", b"tile 0 0\n", b"end\n", b"# c\n"]
diffs = errors = 0
with tempfile.TemporaryDirectory() as d:
    path = os.path.join(d, "m.trace")
    for i in range(cases):
        b = bytearray(src[:6000] if rng.random() < 0.3 else src)
        for _ in range(rng.randint(0, 2)):
            pos = rng.randrange(len(b))
            op = rng.random()
            if op < 0.4:
                b[pos:pos] = rng.choice(pieces)
            elif op < 0.7:
                del b[pos:pos + rng.randint(1, 3)]
            else:
                b[pos:pos + 1] = rng.choice(pieces)
        open(path, "wb").write(b)
        outs = []
        for binary in (old, new):
            r = subprocess.run([binary, "run", "-q", "--trace", path, "--json", "-"],
                               capture_output=True)
            outs.append((r.returncode, r.stdout, r.stderr.replace(path.encode(), b"TRACE")))
        if outs[0] != outs[1]:
            diffs += 1
            print(f"case {i}: old {outs[0][0]} {outs[0][2][:160]!r}\n        new {outs[1][0]} {outs[1][2][:160]!r}")
        errors += outs[0][0] != 0
print(f"reader-diff: {cases} cases ({errors} malformed), {diffs} differences")
sys.exit(1 if diffs else 0)
