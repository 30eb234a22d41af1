#!/usr/bin/env python3
"""Per family: solved / valid / total, time mean / p50 / p95 (ms, solved problems), for viaroad's
`bench mbm` problems.csv and the OMPL peer's `arm` JSON lines, side by side.

usage: compare.py VIAROAD_PROBLEMS_CSV OMPL_DIR"""
import csv, glob, json, os, statistics, sys

def pct(xs, q):
    xs = sorted(xs)
    return xs[round(q * (len(xs) - 1))] if xs else float('nan')

def row(name, rows):
    solved = [r for r in rows if r['solved']]
    t = [r['ms'] for r in solved]
    valid = sum(r['valid'] for r in rows)
    mean = statistics.mean(t) if t else float('nan')
    return f"{len(solved)} / {valid} / {len(rows)} | {mean:.0f} | {pct(t, .5):.0f} | {pct(t, .95):.0f}"

def viaroad(path):
    out = {}
    for r in csv.DictReader(open(path)):
        out.setdefault(r['family'], []).append(dict(
            solved=r['solved'] == 'true', valid=r['valid'] == 'true', ms=1000 * float(r['time_s'])))
    return out

def ompl(d, planner):
    out = {}
    for f in sorted(glob.glob(os.path.join(d, f'*_{planner}_t*.jsonl'))):
        for l in open(f):
            if not l.startswith('{'):
                continue
            r = json.loads(l)
            out.setdefault(r['family'], []).append(dict(
                solved=bool(r['solved']), valid=bool(r.get('start_valid')) and bool(r.get('goal_valid')),
                ms=1000 * float(r['time_s'])))
    return out

v = viaroad(sys.argv[1])
peers = {p: ompl(sys.argv[2], p) for p in ('rrtconnect', 'prm')}
print("| family | viaroad solved / valid / total | mean ms | p50 | p95 | OMPL RRTConnect | mean ms | p50 | p95 | OMPL PRM | mean ms | p50 | p95 |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
fams = sorted(set(v) | set(peers['rrtconnect']) | set(peers['prm']))
for fam in fams + ['all']:
    cells = []
    for src in [v, peers['rrtconnect'], peers['prm']]:
        rows = [r for f in fams for r in src.get(f, [])] if fam == 'all' else src.get(fam, [])
        cells.append(row(fam, rows) if rows else "– | – | – | –")
    print(f"| {fam} | " + " | ".join(cells) + " |")
