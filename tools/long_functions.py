#!/usr/bin/env python3
"""Functions of `src/` longer than a bound (120 lines by default), longest first.

A function's length runs from the line of its `fn` keyword to the line of its closing brace.
The source is tokenised by `import_graph.tokenize` (comments, literals and lifetimes dropped)
and braces matched, so functions inside `impl` blocks, with `where` clauses,
nested in other functions or written on one line are all found. Items under `#[cfg(test)]` are
skipped, and so are the files of modules declared `#[cfg(test)] mod x;`: test code may be long.

Usage: `tools/long_functions.py [--max N] [ROOT]`; exit code 1 when any function is over.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from import_graph import tokenize

IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def scan(path: Path, limit: int, test_files: set[Path], out: list):
    """Appends the functions of `path` over `limit` lines; collects its test-only module files."""
    toks = tokenize(path.read_text())
    mod_dir = path.parent if path.name in ("mod.rs", "lib.rs", "main.rs") else path.with_suffix("")

    def item_end(k: int) -> int:
        """Index of the token ending the item starting at `k` (its `;` or matching `}`)."""
        depth = 0
        while k < len(toks):
            t = toks[k][0]
            if t in "([":
                depth += 1
            elif t in ")]":
                depth -= 1
            elif t == ";" and depth == 0:
                return k
            elif t == "{" and depth == 0:
                return match(k)
            k += 1
        return k

    def match(k: int) -> int:
        depth = 0
        while k < len(toks):
            t = toks[k][0]
            if t == "{":
                depth += 1
            elif t == "}":
                depth -= 1
                if depth == 0:
                    return k
            k += 1
        return k

    k = 0
    while k < len(toks):
        t, line = toks[k]
        if t == "#" and k + 2 < len(toks) and toks[k + 1][0] == "[":
            close = k + 1
            depth = 0
            while close < len(toks):
                depth += {"[": 1, "]": -1}.get(toks[close][0], 0)
                if depth == 0:
                    break
                close += 1
            attr = [x for x, _ in toks[k + 2 : close]]
            if attr[:4] == ["cfg", "(", "test", ")"]:
                start = close + 1
                # Further attributes before the item, then the item itself.
                while start < len(toks) and toks[start][0] == "#":
                    start = item_end_attr(toks, start) + 1
                end = item_end(start)
                words = [x for x, _ in toks[start:end + 1]]
                if "mod" in words and words[-1] == ";":
                    name = words[words.index("mod") + 1]
                    test_files.add(mod_dir / f"{name}.rs")
                    test_files.add(mod_dir / name / "mod.rs")
                k = end + 1
                continue
            k = close + 1
            continue
        if t == "fn" and k + 1 < len(toks) and IDENT.fullmatch(toks[k + 1][0]):
            end = item_end(k)
            if toks[end][0] == "}" if end < len(toks) else False:
                length = toks[end][1] - line + 1
                if length > limit:
                    out.append((length, str(path), toks[k + 1][0], line))
            # Go on inside the body: nested functions count on their own too.
        k += 1


def item_end_attr(toks, k: int) -> int:
    """Index of the `]` closing the attribute starting at `k` (`#`)."""
    depth, j = 0, k + 1
    while j < len(toks):
        depth += {"[": 1, "]": -1}.get(toks[j][0], 0)
        if depth == 0:
            return j
        j += 1
    return j


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", nargs="?", default="src")
    parser.add_argument("--max", type=int, default=120, help="longest allowed, in lines")
    args = parser.parse_args()
    files = sorted(Path(args.root).rglob("*.rs"))
    found: list = []
    test_files: set[Path] = set()
    for path in files:
        scan(path, args.max, test_files, found)
    found = [f for f in found if Path(f[1]) not in test_files]
    for length, path, name, line in sorted(found, key=lambda f: (-f[0], f[1], f[3])):
        print(f"{length} {path}:{line} {name}")
    print(f"{len(found)} over {args.max} lines")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
