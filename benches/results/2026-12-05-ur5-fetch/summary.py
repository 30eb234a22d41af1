#!/usr/bin/env python3
"""Summary of run.sh (README here): per robot and family, the peer's RRTConnect and viaroad
(enveloped meshes; for the UR5 also --exact-meshes): solved / valid and time p50, p95; and the
verdicts of `ompl_peer armcheck` at 1/10 of OMPL's resolution on every path both returned.
Argument: run.sh's work directory (its check-*.jsonl become checks-*.tsv here). Writes
summary.md."""
import csv, json, os, statistics, sys

here = os.path.dirname(os.path.abspath(__file__))
work = sys.argv[1] if len(sys.argv) > 1 else None
families = ['bookshelf_small', 'bookshelf_tall', 'bookshelf_thin', 'box', 'cage', 'table_pick',
            'table_under_pick']

def pct(xs, q):
    if not xs:
        return float('nan')
    xs = sorted(xs)
    k = (len(xs) - 1) * q
    lo = int(k)
    hi = min(lo + 1, len(xs) - 1)
    return xs[lo] + (xs[hi] - xs[lo]) * (k - lo)

def peer(robot):
    rows = [json.loads(l) for l in open(os.path.join(here, f'ompl-{robot}.jsonl')) if l.startswith('{')]
    return [dict(family=r['family'], valid=bool(r.get('start_valid') and r.get('goal_valid')),
                 solved=bool(r['solved']), ms=1e3 * r['time_s']) for r in rows]

def ours(name):
    path = os.path.join(here, name)
    if not os.path.exists(path):
        return None
    return [dict(family=r['family'], valid=r['valid'] == 'true', solved=r['solved'] == 'true',
                 ms=1e3 * float(r['time_s'])) for r in csv.DictReader(open(path))]

def cell(rows):
    valid = [r for r in rows if r['valid']]
    solved = [r['ms'] for r in valid if r['solved']]
    return f"{len(solved)} / {len(valid)} | {pct(solved, 0.5):.1f} | {pct(solved, 0.95):.1f}"

def checks(kind, robot):
    if work:
        src = os.path.join(work, f'check-{kind}-{robot}.jsonl')
        rows = [json.loads(l) for l in open(src) if l.startswith('{')]
        with open(os.path.join(here, f'checks-{kind}-{robot}.tsv'), 'w') as f:
            f.write('file\tkind\tvalid\n')
            for r in rows:
                f.write(f"{r['file']}\t{r['kind']}\t{r.get('valid')}\n")
    lines = open(os.path.join(here, f'checks-{kind}-{robot}.tsv')).read().splitlines()[1:]
    by = {}
    for l in lines:
        _, k, v = l.split('\t')
        by.setdefault(k, [0, 0])
        by[k][0] += 1
        by[k][1] += v != 'True'
    return ', '.join(f"{k}: {n} checked, {bad} invalid" for k, (n, bad) in sorted(by.items()))

out = []
for robot in ['ur5', 'fetch']:
    columns = [('OMPL RRTConnect', peer(robot)), ('viaroad', ours(f'viaroad-{robot}-problems.csv'))]
    exact = ours(f'viaroad-{robot}-exact-meshes-problems.csv')
    if exact:
        columns.append(('viaroad --exact-meshes', exact))
    out.append(f'### {robot}\n')
    out.append('| family | ' + ' | '.join(f'{n}: solved / valid | p50 ms | p95 ms' for n, _ in columns) + ' |')
    out.append('|---|' + '---|---|---|' * len(columns))
    for f in families + ['all']:
        cells = []
        for _, rows in columns:
            sel = [r for r in rows if f == 'all' or r['family'] == f'{f}_{robot}']
            cells.append(cell(sel))
        name = f'**{f}**' if f == 'all' else f
        out.append(f'| {name} | ' + ' | '.join(cells) + ' |')
    out.append('')
    out.append(f'`ompl_peer armcheck` at 1/10 of OMPL\'s resolution: viaroad {checks("paths", robot)}; '
               f'the peer {checks("peer-paths", robot)}.\n')
open(os.path.join(here, 'summary.md'), 'w').write('\n'.join(out))
print('\n'.join(out))
