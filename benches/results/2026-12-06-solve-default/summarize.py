#!/usr/bin/env python3
"""The table of runs.jsonl: per problem and mode, runs solved and the median time of those."""
import json, os, statistics, sys
from collections import defaultdict

here = os.path.dirname(os.path.abspath(__file__))
runs = [json.loads(l) for l in open(os.path.join(here, sys.argv[1] if len(sys.argv) > 1 else "runs.jsonl"))]
problems = list(dict.fromkeys(r["problem"] for r in runs))
modes = ["default", "tree", "roadmap", "local-only"]
cell = defaultdict(list)
for r in runs:
    cell[(r["problem"], r["mode"])].append(r)
print("| problem | " + " | ".join(f"`{m}`" for m in modes) + " |")
print("|---|" + "---|" * len(modes))
tot = defaultdict(lambda: [0, 0])
for p in problems:
    row = []
    for m in modes:
        rs = cell[(p, m)]
        ok = [r for r in rs if r["solved"]]
        tot[m][0] += len(ok); tot[m][1] += len(rs)
        t = f", {statistics.median(r['wall'] for r in ok):.1f} s" if ok else ""
        won = ""
        if m == "default" and ok:
            ms = sorted({r["method"] for r in ok})
            won = " (" + ", ".join(ms) + ")"
        row.append(f"{len(ok)} / {len(rs)}{t}{won}")
    print(f"| {p} | " + " | ".join(row) + " |")
print("| **all** | " + " | ".join(f"**{tot[m][0]} / {tot[m][1]}**" for m in modes) + " |")
