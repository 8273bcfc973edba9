#!/usr/bin/env python3
"""No import cycle between the modules of any crate.

For every crate root (`*/src/lib.rs`, `*/src/main.rs`, `src/main.rs`) the
script builds the module tree from the files, reads every `crate::`,
`super::` and `self::` path in code (use lines and paths written inline,
test and Kani modules left out), and draws an arrow from module A to its
sibling B when code in A (or below it) names something in B (or below it).
A cycle among the siblings of any module is an error; each arrow of it is
shown with the first line that makes it.

    scripts/import-cycles.py [REPO]       check every crate of REPO
    scripts/import-cycles.py --self-test  check that a planted cycle fails

Run by scripts/layering.sh.
"""
import os
import re
import sys
import tempfile

PATH_RE = re.compile(r"(?<![\w:])((?:crate|super|self)(?:::\w+)+)")
TEST_ATTR = re.compile(r"#\[cfg\((test|kani)\)\]")
MOD_DECL = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*([;{])")


def strip_code(line):
    """The line without its comment and string literals (roughly)."""
    out, i, in_str = [], 0, False
    while i < len(line):
        c = line[i]
        if in_str:
            if c == "\\":
                i += 2
                continue
            if c == '"':
                in_str = False
            i += 1
            continue
        if c == '"':
            in_str = True
        elif line.startswith("//", i):
            break
        else:
            out.append(c)
        i += 1
    return "".join(out)


def expand_use(tree):
    """`a::{b, c::{d, e}}` -> ["a::b", "a::c::d", "a::c::e"]."""
    tree = tree.strip()
    depth, start = 0, None
    for i, c in enumerate(tree):
        if c == "{":
            if depth == 0:
                start = i
            depth += 1
        elif c == "}":
            depth -= 1
    if start is None:
        return [re.sub(r"\s+as\s+\w+$", "", tree)]
    prefix, inner = tree[:start], tree[start + 1 : tree.rindex("}")]
    parts, depth, cur = [], 0, ""
    for c in inner:
        if c == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        depth += c == "{"
        depth -= c == "}"
        cur += c
    parts.append(cur)
    out = []
    for p in parts:
        if p.strip():
            out += [prefix + x for x in expand_use(p)]
    return out


class Crate:
    def __init__(self, root_file):
        self.root = root_file
        self.src = os.path.dirname(root_file)
        self.modules = {()}  # module paths (tuples)
        self.files = []  # (file, module path, is_dir_module)
        self._walk(root_file, (), True)

    def _walk(self, path, module, dir_module):
        self.files.append((path, module, dir_module))
        base = self.src if module == () else (
            os.path.dirname(path) if dir_module else path[: -len(".rs")]
        )
        lines = open(path, encoding="utf-8").read().splitlines()
        for i, line in enumerate(lines):
            m = MOD_DECL.match(line)
            if not m:
                continue
            name, kind = m.groups()
            test_only = i > 0 and TEST_ATTR.search(lines[i - 1])
            child = module + (name,)
            if kind == "{":
                if not test_only:
                    self.modules.add(child)
                continue
            if test_only:
                continue
            for cand, is_dir in ((f"{base}/{name}.rs", False), (f"{base}/{name}/mod.rs", True)):
                if os.path.exists(cand):
                    self.modules.add(child)
                    self._walk(cand, child, is_dir)
                    break

    def references(self):
        """(from module, to path, file, line number, text) for every path."""
        for path, module, _ in self.files:
            lines = open(path, encoding="utf-8").read().splitlines()
            stmt, stmt_line = None, 0
            for n, raw in enumerate(lines, 1):
                if TEST_ATTR.search(raw) and n < len(lines) and MOD_DECL.match(lines[n]) \
                        and lines[n].rstrip().endswith("{"):
                    break  # the test module: to the end of the file
                code = strip_code(raw)
                if stmt is None and re.match(r"^\s*(pub(\([^)]*\))?\s+)?use\s", code):
                    stmt, stmt_line = "", n
                    code = re.sub(r"^\s*(pub(\([^)]*\))?\s+)?use\s", "", code)
                if stmt is not None:
                    stmt += code
                    if ";" in stmt:
                        for p in expand_use(stmt[: stmt.index(";")]):
                            yield module, p, path, stmt_line, raw.strip()
                        stmt = None
                    continue
                for m in PATH_RE.finditer(code):
                    yield module, m.group(1), path, n, raw.strip()

    def resolve(self, module, text):
        parts = [p for p in text.split("::") if p]
        if parts[0] == "crate":
            at, parts = (), parts[1:]
        else:
            at = module
            while parts and parts[0] in ("super", "self"):
                if parts.pop(0) == "super":
                    at = at[:-1]
        return at + tuple(parts)

    def edges(self):
        """{parent: {(a, b): (file, line, text)}} for sibling arrows."""
        out = {}
        for module, text, path, n, raw in self.references():
            target = self.resolve(module, text)
            k = 0
            while k < len(module) and k < len(target) and module[k] == target[k]:
                k += 1
            if k >= len(module) or k >= len(target):
                continue  # into an ancestor or a descendant
            parent = module[:k]
            if parent + (target[k],) not in self.modules:
                continue  # an item of the parent, not a module
            arrow = (module[k], target[k])
            out.setdefault(parent, {}).setdefault(arrow, (path, n, raw))
        return out


def cycles(arrows):
    """The strongly connected components with more than one node."""
    graph = {}
    for a, b in arrows:
        graph.setdefault(a, []).append(b)
        graph.setdefault(b, [])
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def roots(repo):
    found = []
    for d in sorted(os.listdir(repo)):
        for f in ("lib.rs", "main.rs"):
            p = os.path.join(repo, d, "src", f)
            if os.path.exists(p):
                found.append(p)
    for f in ("lib.rs", "main.rs"):
        p = os.path.join(repo, "src", f)
        if os.path.exists(p):
            found.append(p)
    return found


def check(repo, quiet=False):
    bad, modules = 0, 0
    for root in roots(repo):
        crate = Crate(root)
        modules += len(crate.modules)
        name = os.path.relpath(root, repo)
        for parent, arrows in sorted(crate.edges().items()):
            for comp in cycles(arrows):
                bad += 1
                if quiet:
                    continue
                where = "::".join(("crate",) + parent)
                print(f"import cycle in {name}, among the modules of {where}: "
                      f"{' <-> '.join(comp)}", file=sys.stderr)
                for (a, b), (path, n, raw) in sorted(arrows.items()):
                    if a in comp and b in comp:
                        print(f"  {a} -> {b}: {os.path.relpath(path, repo)}:{n}: {raw}",
                              file=sys.stderr)
    return bad, modules


def self_test():
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(f"{d}/c/src/a")
        files = {
            "c/src/lib.rs": "mod a;\nmod b;\n",
            "c/src/a/mod.rs": "mod x;\nmod y;\nuse crate::b::B;\n",
            "c/src/a/x.rs": "pub fn f() -> super::y::Y { todo!() }\n",
            "c/src/a/y.rs": "use super::{Item, z};\n#[cfg(test)]\nmod tests {\n"
                            "    use crate::b::Test;\n}\n",
            "c/src/b.rs": "// crate::a::Nope in a comment\nconst S: &str = \"crate::a::no\";\n",
        }
        for f, text in files.items():
            with open(f"{d}/{f}", "w") as fh:
                fh.write(text)
        bad, _ = check(d, quiet=True)
        assert bad == 0, "no cycle yet: comments, strings and tests do not count"
        with open(f"{d}/c/src/b.rs", "a") as fh:
            fh.write("use crate::a::{x::f};\n")
        bad, _ = check(d, quiet=True)
        assert bad == 1, "a <-> b"
        with open(f"{d}/c/src/a/y.rs", "w") as fh:
            fh.write("use super::{x::f as g};\n")
        bad, _ = check(d, quiet=True)
        assert bad == 2, "and x <-> y inside a"
    print("import-cycles: the self-test finds its planted cycles", file=sys.stderr)


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        sys.exit(0)
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    bad, modules = check(os.path.abspath(repo))
    if bad:
        sys.exit(1)
    print(f"import-cycles: no cycle among the {modules} modules of the crates", file=sys.stderr)
