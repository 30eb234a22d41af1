#!/usr/bin/env python3
"""Circles of imports between the modules of `src/`.

Builds the graph "file A uses something defined in file B" from `use crate::…`, `use super::…`,
`use self::…`, paths written in code (`crate::a::b::f()`, `super::X`), `viaroad::…` in the
binary's files, and `use child::…` / `child::f()` where `child` is a submodule of the file's own
module. Each path resolves to the deepest existing module file (`crate::a::b::Item` ->
src/a/b.rs or src/a/b/mod.rs, else src/a.rs or src/a/mod.rs).

A circle: for some module, a strongly connected component among its submodules, each taken
whole (its file and all its descendants), e.g. `robot` uses `scene` and `scene` uses `robot`.
The module's own file takes no part at its level: its submodules may use it (`super::…`) and it
may use them, its parts. Circles are printed file by file, with the lines that make each edge,
and the exit code is 1 when there is any. `--strict` instead reports the strongly connected
components of the file graph itself, where a mod.rs and the children it calls do form circles.

Not edges, in both modes: `mod x;`, and a file's re-exports of its own descendants
(`pub use x::…`). Items under `#[cfg(test)]` or `#[cfg(doc)]` are skipped, and so are comments
(doc links included) and string literals.

`--all` lists every edge (to see one file's neighbours: `--all | grep robot/urdf`).
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict
from pathlib import Path

# --------------------------------------------------------------------------------- tokenizer


def tokenize(src: str) -> list[tuple[str, int]]:
    """Identifiers, `::` and single punctuation characters with their line numbers; comments,
    strings, chars, lifetimes and numbers are dropped."""
    toks: list[tuple[str, int]] = []
    i, n, line = 0, len(src), 1
    while i < n:
        c = src[i]
        if c == "\n":
            line += 1
            i += 1
        elif c.isspace():
            i += 1
        elif src.startswith("//", i):
            j = src.find("\n", i)
            i = n if j < 0 else j
        elif src.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if src.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif src.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    line += src[i] == "\n"
                    i += 1
        elif c in "rb" and _raw_string_at(src, i):
            j = i + (2 if src[i] == "b" else 1)
            hashes = 0
            while src[j] == "#":
                hashes, j = hashes + 1, j + 1
            end = src.find('"' + "#" * hashes, j + 1)
            end = n if end < 0 else end + 1 + hashes
            line += src.count("\n", i, end)
            i = end
        elif c == '"' or (c == "b" and src.startswith('b"', i)):
            j = i + (2 if c == "b" else 1)
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            line += src.count("\n", i, j)
            i = j + 1
        elif c == "'" or (c == "b" and src.startswith("b'", i)):
            j = i + (2 if c == "b" else 1)
            if j < n and src[j] == "\\":  # escaped char literal
                k = src.find("'", j + 2)
                i = n if k < 0 else k + 1
            elif j + 1 < n and src[j + 1] == "'":  # plain char literal
                i = j + 2
            else:  # lifetime or label
                while j < n and (src[j].isalnum() or src[j] == "_"):
                    j += 1
                i = j
        elif c.isalpha() or c == "_":
            j = i
            while j < n and (src[j].isalnum() or src[j] == "_"):
                j += 1
            word = src[i:j]
            if word == "r" and j < n and src[j] == "#":  # raw identifier r#type
                k = j + 1
                while k < n and (src[k].isalnum() or src[k] == "_"):
                    k += 1
                word, j = src[j + 1 : k], k
            toks.append((word, line))
            i = j
        elif c.isdigit():
            j = i
            while j < n and (src[j].isalnum() or src[j] in "_."):
                if src[j] == "." and not (j + 1 < n and src[j + 1].isdigit()):
                    break
                j += 1
            i = j
        elif src.startswith("::", i):
            toks.append(("::", line))
            i += 2
        else:
            toks.append((c, line))
            i += 1
    return toks


def _raw_string_at(src: str, i: int) -> bool:
    if i > 0 and (src[i - 1].isalnum() or src[i - 1] == "_"):
        return False
    j = i + 1 if src[i] == "r" else (i + 2 if src.startswith("br", i) else -1)
    if j < 0:
        return False
    while j < len(src) and src[j] == "#":
        j += 1
    return j < len(src) and src[j] == '"'


def is_ident(t: str) -> bool:
    return t[0].isalpha() or t[0] == "_"


# ------------------------------------------------------------------------------ module tree


class Crate:
    def __init__(self, name: str, root: Path):
        self.name = name
        self.root = root
        # module path (tuple) -> file, for file modules and inline modules alike
        self.modules: dict[tuple[str, ...], Path] = {}
        self.file_module: dict[Path, tuple[str, ...]] = {}


def child_file(parent_file: Path, parent_mod: tuple[str, ...], name: str) -> Path | None:
    """Where `mod name;` in parent_file lives."""
    if parent_file.name in ("mod.rs", "lib.rs", "main.rs"):
        base = parent_file.parent
    else:
        base = parent_file.parent / parent_file.stem
    for cand in (base / f"{name}.rs", base / name / "mod.rs"):
        if cand.exists():
            return cand
    return None


def skip_item(toks, i):
    """Index just past the item that starts at toks[i] (ends at `;` or its `{ … }` block)."""
    depth = 0
    n = len(toks)
    while i < n:
        t = toks[i][0]
        if t in "([{":
            depth += 1
        elif t in ")]}":
            depth -= 1
            if depth == 0 and t == "}":
                return i + 1
        elif t == ";" and depth == 0:
            return i + 1
        i += 1
    return n


def skip_attribute(toks, i):
    """toks[i] is `#`; returns (index past the attribute, its text)."""
    j = i + 1
    if j < len(toks) and toks[j][0] == "!":
        j += 1
    if j >= len(toks) or toks[j][0] != "[":
        return i + 1, ""
    depth, k = 0, j
    while k < len(toks):
        if toks[k][0] == "[":
            depth += 1
        elif toks[k][0] == "]":
            depth -= 1
            if depth == 0:
                break
        k += 1
    return k + 1, "".join(t for t, _ in toks[j + 1 : k])


SKIPPED_CFGS = ("cfg(test)", "cfg(doc)")


class Use:
    def __init__(self, path: list[str], line: int, kind: str, reexport: bool, scope: tuple[str, ...]):
        self.path = path  # segments as written, starting with crate/super/self/ident
        self.line = line
        self.kind = kind  # "use", "pub use", or "path" (written in code)
        self.reexport = reexport
        self.scope = scope  # module path the path is written in


def parse_file(toks, file_mod):
    """Returns (mods declared by file: list of (name, inline?)), uses, inline module paths)."""
    uses: list[Use] = []
    file_mods: list[str] = []
    inline_mods: list[tuple[str, ...]] = []
    # stack of (module path, brace depth at which its block closes)
    scope_stack: list[tuple[tuple[str, ...], int]] = [(file_mod, -1)]
    depth = 0
    i, n = 0, len(toks)
    pending_vis = False
    while i < n:
        t, line = toks[i]
        scope = scope_stack[-1][0]
        if t == "#":
            j, attr = skip_attribute(toks, i)
            if attr.replace(" ", "") in SKIPPED_CFGS and not (i + 1 < n and toks[i + 1][0] == "!"):
                # skip any further attributes, then the item
                while j < n and toks[j][0] == "#":
                    j, _ = skip_attribute(toks, j)
                i = skip_item(toks, j)
                continue
            i = j
            continue
        if t == "pub":
            pending_vis = True
            i += 1
            if i < n and toks[i][0] == "(":  # (crate), (super), (in path)
                while i < n and toks[i][0] != ")":
                    i += 1
                i += 1
            continue
        if t == "mod" and i + 1 < n and is_ident(toks[i + 1][0]) and (i == 0 or toks[i - 1][0] != "::"):
            name = toks[i + 1][0]
            nxt = toks[i + 2][0] if i + 2 < n else ""
            if nxt == ";":
                if len(scope_stack) == 1:
                    file_mods.append(name)
                i += 3
                pending_vis = False
                continue
            if nxt == "{":
                depth += 1
                inline = scope + (name,)
                inline_mods.append(inline)
                scope_stack.append((inline, depth - 1))
                i += 3
                pending_vis = False
                continue
        if t == "use" and (i == 0 or toks[i - 1][0] != "::"):
            end = i + 1
            while end < n and toks[end][0] != ";":
                end += 1
            kind = "pub use" if pending_vis else "use"
            for path in expand_use_tree([x for x, _ in toks[i + 1 : end]]):
                uses.append(Use(path, line, kind, pending_vis, scope))
            pending_vis = False
            i = end + 1
            continue
        pending_vis = False
        if t == "{":
            depth += 1
        elif t == "}":
            depth -= 1
            if len(scope_stack) > 1 and depth == scope_stack[-1][1]:
                scope_stack.pop()
        elif t in ("crate", "super", "self") and i + 1 < n and toks[i + 1][0] == "::":
            prev = toks[i - 1][0] if i > 0 else ""
            if prev != "::" or (i >= 2 and toks[i - 2][0] == "$"):
                path, j = [t], i
                while j + 2 < n and toks[j + 1][0] == "::" and is_ident(toks[j + 2][0]):
                    path.append(toks[j + 2][0])
                    j += 2
                uses.append(Use(path, line, "path", False, scope))
                i = j + 1
                continue
        elif is_ident(t) and i + 1 < n and toks[i + 1][0] == "::" and (i == 0 or toks[i - 1][0] not in ("::", ".")):
            # a relative path; kept only if its first segment is a submodule of the scope
            path, j = [t], i
            while j + 2 < n and toks[j + 1][0] == "::" and is_ident(toks[j + 2][0]):
                path.append(toks[j + 2][0])
                j += 2
            uses.append(Use(path, line, "path", False, scope))
            i = j + 1
            continue
        i += 1
    return file_mods, uses, inline_mods


def expand_use_tree(toks: list[str]) -> list[list[str]]:
    """`a::{b, c::{d, self}}` -> [[a,b], [a,c,d], [a,c]]; `as` renames and `*` are dropped."""
    out: list[list[str]] = []

    def tree(i: int, prefix: list[str]) -> int:
        path = list(prefix)
        if i < len(toks) and toks[i] == "::":  # leading `::`
            i += 1
        while i < len(toks):
            t = toks[i]
            if t == "{":
                i += 1
                while i < len(toks) and toks[i] != "}":
                    i = tree(i, path)
                    if i < len(toks) and toks[i] == ",":
                        i += 1
                return i + 1
            if t == "*":
                out.append(path)
                return i + 1
            if t == "self" and path:
                i += 1
            elif is_ident(t):
                path.append(t)
                i += 1
            else:
                i += 1
                continue
            if i < len(toks) and toks[i] == "as":
                i += 2
            if i < len(toks) and toks[i] == "::":
                i += 1
                continue
            out.append(path)
            return i
        if path:
            out.append(path)
        return i

    tree(0, [])
    return out


# -------------------------------------------------------------------------------- the graph


def build(src_dir: Path):
    """Parses every file reached from lib.rs and main.rs through `mod` declarations; returns
    (file -> (crate, module path)), and the edges file -> file -> [Use]."""
    crates: list[Crate] = []
    parsed: dict[Path, tuple] = {}
    for root_name in ("lib.rs", "main.rs"):
        root = src_dir / root_name
        if not root.exists():
            continue
        crate = Crate(root_name, root)
        crates.append(crate)
        todo = [(root, ())]
        while todo:
            f, mp = todo.pop()
            crate.modules[mp] = f
            crate.file_module[f] = mp
            file_mods, uses, inline_mods = parse_file(tokenize(f.read_text()), mp)
            parsed[f] = (crate, uses)
            for im in inline_mods:
                crate.modules[im] = f
            for name in file_mods:
                cf = child_file(f, mp, name)
                if cf is not None:
                    todo.append((cf, mp + (name,)))

    lib = next((c for c in crates if c.name == "lib.rs"), None)
    edges: dict[Path, dict[Path, list[Use]]] = defaultdict(lambda: defaultdict(list))
    where: dict[Path, tuple[str, ...]] = {}
    for f, (crate, uses) in parsed.items():
        fmod = crate.file_module[f]
        where[f] = (crate.name,) + fmod
        for u in uses:
            target = resolve(u, crate, lib)
            if target is None:
                continue
            tcrate, tmod = target
            tfile = deepest_file(tcrate, tmod)
            if tfile is None or tfile == f:
                continue
            # a parent's re-exports of its own descendants are not edges
            if u.reexport and tcrate is crate and tmod[: len(fmod)] == fmod:
                continue
            if all((v.line, v.path) != (u.line, u.path) for v in edges[f][tfile]):
                edges[f][tfile].append(u)
    return where, edges


def resolve(u: Use, crate: Crate, lib: Crate | None):
    p = u.path
    if not p:
        return None
    head = p[0]
    if head == "crate":
        return crate, tuple(p[1:])
    if head == "viaroad" and lib is not None and crate is not lib:
        return lib, tuple(p[1:])
    if head in ("super", "self"):
        base = list(u.scope)
        k = 0
        while k < len(p) and p[k] in ("super", "self"):
            if p[k] == "super":
                if not base:
                    return None
                base.pop()
            k += 1
        return crate, tuple(base) + tuple(p[k:])
    # relative path: only when it names a submodule of the scope
    if u.scope + (head,) in crate.modules:
        return crate, u.scope + tuple(p)
    return None


def deepest_file(crate: Crate, mod: tuple[str, ...]) -> Path | None:
    for k in range(len(mod), -1, -1):
        f = crate.modules.get(mod[:k])
        if f is not None:
            return f
    return None


def sccs(nodes, succ):
    """Tarjan's strongly connected components (iterative)."""
    index: dict = {}
    low: dict = {}
    on: set = set()
    stack: list = []
    out: list = []
    counter = 0
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(sorted(succ.get(start, ()))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(succ.get(w, ())))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                out.append(sorted(comp))
    return out


def sibling_circles(where, edges):
    """For every module, the circles among its submodules, each taken whole (its file and all
    its descendants). The module's own file is left out: a submodule may use its parent and the
    parent may use its parts. Yields (parent module path, [member module paths])."""
    # parent module path -> child name -> child name -> present
    levels: dict[tuple, dict[str, set[str]]] = defaultdict(lambda: defaultdict(set))
    for f, ts in edges.items():
        pf = where[f]
        for t in ts:
            pt = where[t]
            k = 0
            while k < min(len(pf), len(pt)) and pf[k] == pt[k]:
                k += 1
            if k < len(pf) and k < len(pt):
                levels[pf[:k]][pf[k]].add(pt[k])
    for parent in sorted(levels):
        succ = levels[parent]
        nodes = sorted(set(succ) | {c for cs in succ.values() for c in cs})
        for comp in sccs(nodes, succ):
            if len(comp) > 1:
                yield parent, [parent + (c,) for c in sorted(comp)]


def describe(uses: list[Use]) -> list[str]:
    """`line 14: use crate::space::{Change, Motion}` for the uses of one line."""
    out = []
    for line in sorted({u.line for u in uses}):
        here = [u for u in uses if u.line == line]
        paths = [u.path for u in here]
        k = 0
        while all(len(p) > k + 1 and p[k] == paths[0][k] for p in paths):
            k += 1
        rest = sorted({"::".join(p[k:]) for p in paths})
        tail = rest[0] if len(rest) == 1 else "{" + ", ".join(rest) + "}"
        how = "" if here[0].kind == "path" else here[0].kind + " "
        out.append(f"line {line}: {how}{'::'.join(paths[0][:k] + [tail])}")
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("src", nargs="?", default=str(Path(__file__).resolve().parent.parent / "src"))
    ap.add_argument("--all", action="store_true", help="print every edge, not only the circles")
    ap.add_argument(
        "--strict",
        action="store_true",
        help="circles of files, a module file's uses of its own submodules included",
    )
    args = ap.parse_args()
    src = Path(args.src)
    where, edges = build(src)

    def name(f: Path) -> str:
        return str(f.relative_to(src))

    if args.all:
        for f in sorted(edges, key=name):
            for t in sorted(edges[f], key=name):
                lines = ", ".join(str(n) for n in sorted({u.line for u in edges[f][t]}))
                print(f"{name(f)} -> {name(t)}  (line {lines})")
        return 0

    files = sorted(where, key=name)
    if args.strict:
        succ = {f: set(ts) for f, ts in edges.items()}
        groups = [(comp, {f: f for f in comp}) for comp in sccs(files, succ) if len(comp) > 1]
    else:
        groups = []
        for _, members in sibling_circles(where, edges):
            owner = {}
            for f in files:
                for m in members:
                    if where[f][: len(m)] == m:
                        owner[f] = m
            groups.append((sorted(owner, key=name), owner))
    groups.sort(key=lambda g: name(g[0][0]))

    for k, (comp, owner) in enumerate(groups, 1):
        print(f"circle {k}: {len(set(owner.values()))} modules ({len(comp)} files)")
        for f in comp:
            out = [
                (t, u)
                for t in sorted(edges.get(f, {}), key=name)
                if t in owner and owner[t] != owner[f]
                for u in edges[f][t]
            ]
            if not out:
                continue
            print(f"  {name(f)}")
            by_target: dict[Path, list[Use]] = defaultdict(list)
            for t, u in out:
                by_target[t].append(u)
            for t, us in by_target.items():
                print(f"    -> {name(t)}  ({'; '.join(describe(us))})")
    if groups:
        print(f"{len(groups)} circle(s) of imports in {src}")
        return 1
    print(f"no circles of imports in {src} ({len(files)} files)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
