"""summary.md from workcell.tsv and problems-{base,new}.csv: per family the workcell's query p50
of each repetition (base → new), and the per-problem run's solved counts and times."""
import csv
import statistics as st
import sys
from collections import defaultdict

here = sys.argv[1]
rows = [l.rstrip("\n").split("\t") for l in open(f"{here}/workcell.tsv")]
by = defaultdict(lambda: defaultdict(list))
for r in rows:
    by[r[0]][r[1]].append(r)
print("## Workcell (query p50 ms of each repetition; found p50; solved / valid; certified)\n")
print("| family | base query p50 | new query p50 | base found p50 | new found p50 | solved / valid (base, new) | certified (new) | length p50 (base → new) |")
print("|---|---|---|---|---|---|---|---|")
for fam in sorted(by):
    b, n = by[fam]["base"], by[fam]["new"]
    q = lambda rs, i: " / ".join(r[i] for r in rs)
    print(f"| {fam} | {q(b, 6)} | **{q(n, 6)}** | {q(b, 8)} | {q(n, 8)} | "
          f"{b[0][4]}/{b[0][3]}, {n[0][4]}/{n[0][3]} | {q(n, 5)} | {q(b, 10)} → {q(n, 10)} |")
print("\n## All 700 problems one by one (`bench mbm --time 5`)\n")
print("| binary | solved | valid | certified | time p50 ms | mean ms | p95 ms | length p50 |")
print("|---|---|---|---|---|---|---|---|")
for b in ["base", "new"]:
    rs = list(csv.DictReader(open(f"{here}/problems-{b}.csv")))
    solved = [r for r in rs if r["solved"] == "true"]
    t = sorted(float(r["time_s"]) * 1e3 for r in rs if r["valid"] == "true")
    lens = [float(r["length"]) for r in solved if r["length"]]
    print(f"| {b} | {len(solved)} | {sum(r['valid'] == 'true' for r in rs)} | "
          f"{sum(r['certified'] == 'true' for r in rs)} | {st.median(t):.1f} | {st.mean(t):.1f} | "
          f"{t[int(0.95 * (len(t) - 1))]:.1f} | {st.median(lens):.2f} |")
