#!/usr/bin/env python3
"""Summary of the 700-problem run with the trees first (README here): both viaroad orders and the
peer, every path of the peer and of viaroad's new default judged by the peer's `armcheck` at
1/10 of OMPL's resolution, beside each planner's own verdict (from ../2026-12-05-peer700).

Reads ompl-sweep.jsonl (the peer's `arm` lines, trimmed: solved, time, its own `path_valid` /
`simplified_valid` at its resolution), viaroad-problems.csv (`bench mbm`: solved, time,
`certified` by ArmChecker at 1/10 of OMPL's resolution) and checks-*.tsv (made here from the
armcheck JSON lines when given as arguments: `summary.py ompl.jsonl viaroad.jsonl`). Writes
summary.md."""
import csv, json, os, re, statistics, sys

here = os.path.dirname(os.path.abspath(__file__))

def tsv_from(jsonl, name):
    rows = [json.loads(l) for l in open(jsonl) if l.startswith('{')]
    with open(os.path.join(here, name), 'w') as f:
        f.write('file\tkind\tvalid\tinvalid_states\tinvalid_segments\tfirst_invalid_segment\tt\tcollisions\n')
        for r in rows:
            f.write('\t'.join(str(x) for x in [
                r['file'], r['kind'], r.get('valid'), r.get('invalid_states', ''),
                r.get('invalid_segments', ''), r.get('first_invalid_segment', ''),
                r.get('first_invalid_segment_t', ''),
                ' '.join(r.get('first_invalid_segment_collisions', [])
                         or r.get('first_invalid_state_collisions', []))]) + '\n')

if len(sys.argv) == 3:
    tsv_from(sys.argv[1], 'checks-ompl.tsv')
    tsv_from(sys.argv[2], 'checks-viaroad.tsv')

def read_tsv(name):
    lines = open(os.path.join(here, name)).read().splitlines()
    head = lines[0].split('\t')
    return [dict(zip(head, l.split('\t'))) for l in lines[1:]]

def pct(xs, q):
    xs = sorted(xs)
    k = (len(xs) - 1) * q
    lo = int(k)
    hi = min(lo + 1, len(xs) - 1)
    return xs[lo] + (xs[hi] - xs[lo]) * (k - lo)

ompl = [json.loads(l) for l in open(os.path.join(here, 'ompl-sweep.jsonl')) if l.startswith('{')]
ours = list(csv.DictReader(open(os.path.join(here, 'viaroad-problems.csv'))))
before = list(csv.DictReader(open(os.path.join(here, 'before-problems.csv'))))
for r in ours + before:
    r['solved'] = r['solved'] == 'true'
    r['valid'] = r['valid'] == 'true'
    r['certified'] = {'true': True, 'false': False}.get(r['certified'])
    r['time_s'] = float(r['time_s'])
    r['length'] = float(r['length'])
co = read_tsv('checks-ompl.tsv')
cv = read_tsv('checks-viaroad.tsv')

out = []
out.append('| planner | solved / valid / total | time p50 ms | mean ms | p95 ms | length p50 (returned) |')
out.append('|---|---|---|---|---|---|')
t = [1e3 * r['time_s'] for r in ompl if r['solved']]
ln = [r['simplified_length'] for r in ompl if r['solved']]
out.append(f"| OMPL RRTConnect (+ simplifyMax) | {sum(r['solved'] for r in ompl)} / "
           f"{sum(r['start_valid'] and r['goal_valid'] for r in ompl)} / {len(ompl)} | "
           f"{pct(t, .5):.1f} | {statistics.mean(t):.1f} | {pct(t, .95):.1f} | {pct(ln, .5):.2f} |")
t = [1e3 * (r['time_s'] + r.get('simplify_time_s', 0.0)) for r in ompl if r['solved']]
out.append(f"| OMPL, time including simplifyMax (viaroad's time includes its shortening) | | "
           f"{pct(t, .5):.1f} | {statistics.mean(t):.1f} | {pct(t, .95):.1f} | |")
t = [1e3 * r['time_s'] for r in ours if r['solved']]
ln = [r['length'] for r in ours if r['solved']]
out.append(f"| viaroad (`bench mbm --time 5`) | {sum(r['solved'] for r in ours)} / "
           f"{sum(r['valid'] for r in ours)} / {len(ours)} | "
           f"{pct(t, .5):.1f} | {statistics.mean(t):.1f} | {pct(t, .95):.1f} | {pct(ln, .5):.2f} |")
t = [1e3 * r['time_s'] for r in before if r['solved']]
ln = [r['length'] for r in before if r['solved']]
out.append(f"| viaroad, the order before (`--trees-first 0`) | {sum(r['solved'] for r in before)} / "
           f"{sum(r['valid'] for r in before)} / {len(before)} | "
           f"{pct(t, .5):.1f} | {statistics.mean(t):.1f} | {pct(t, .95):.1f} | {pct(ln, .5):.2f} |")
out.append('')
out.append('Per family, time p50 / mean ms of the solved (OMPL | viaroad | the order before):')
out.append('')
out.append('| family | OMPL | viaroad | before |')
out.append('|---|---|---|---|')
def fam_times(rows, fam, key):
    t = [1e3 * r['time_s'] for r in rows if r['solved'] and key(r) == fam]
    return f"{pct(t, .5):.1f} / {statistics.mean(t):.1f}" if t else '–'
ompl_fam = lambda r: r['family']
for fam in sorted({r['family'] for r in ours}):
    out.append(f"| {fam} | {fam_times(ompl, fam, ompl_fam)} | "
               f"{fam_times(ours, fam, ompl_fam)} | {fam_times(before, fam, ompl_fam)} |")
out.append('')
out.append("| paths | own check (its resolution) | `armcheck` at 1/10 of OMPL's resolution: valid / checked |")
out.append('|---|---|---|')
def fails(rows, kind):
    rs = [r for r in rows if r['kind'] == kind]
    return rs, [r for r in rs if r['valid'] != 'True']
raw, raw_bad = fails(co, 'rrtconnect_run0')
simp, simp_bad = fails(co, 'rrtconnect_run0_simplified')
own_raw = sum(1 for r in ompl if r['solved'] and r.get('path_valid') is False)
own_simp = sum(1 for r in ompl if r['solved'] and r.get('simplified_valid') is False)
out.append(f"| OMPL RRTConnect, raw | {own_raw} of {len(raw)} fail | {len(raw) - len(raw_bad)} / {len(raw)} |")
out.append(f"| OMPL RRTConnect, simplified (returned) | {own_simp} of {len(simp)} fail | {len(simp) - len(simp_bad)} / {len(simp)} |")
vraw, vraw_bad = fails(cv, 'raw')
vret, vret_bad = fails(cv, 'returned')
own_v = sum(1 for r in ours if r['solved'] and r.get('certified') is not True)
out.append(f"| viaroad, raw | – | {len(vraw) - len(vraw_bad)} / {len(vraw)} |")
out.append(f"| viaroad, shortened (returned) | ArmChecker at 1/10: {own_v} of {sum(r['solved'] for r in ours)} fail | {len(vret) - len(vret_bad)} / {len(vret)} |")
out.append('')
def family(r):
    return re.match(r'^(.+)_[0-9]{4}', r['file']).group(1)
own = {(r['family'], r['problem'].split('/')[1]): r for r in ompl}
def own_valid(r, field):
    m = re.match(r'^(.+)_([0-9]{4})', r['file'])
    return own[(m.group(1), m.group(2))].get(field) is True
passed_own = [r for r in raw_bad if own_valid(r, 'path_valid')] + \
    [r for r in simp_bad if own_valid(r, 'simplified_valid')]
out.append(f"Of OMPL's {len(raw_bad) + len(simp_bad)} paths failing at 1/10 of its resolution, "
           f"{len(passed_own)} pass its own check. Per family (raw / simplified failing):")
out.append('')
for fam in sorted({family(r) for r in co}):
    nr = sum(1 for r in raw_bad if family(r) == fam)
    ns = sum(1 for r in simp_bad if family(r) == fam)
    out.append(f"- {fam}: {nr} / {ns}")
out.append('')
bad = raw_bad + simp_bad + vraw_bad + vret_bad
out.append(f"The first 20 of the {len(bad)} failing paths (first invalid segment, t along it, "
           "colliding pair there; all of them in checks-*.tsv):")
out.append('')
for r in bad[:20]:
    out.append(f"- {r['file']}: segment {r['first_invalid_segment']} at t = {r['t']}, {r['collisions']}")
open(os.path.join(here, 'summary.md'), 'w').write('\n'.join(out) + '\n')
print('\n'.join(out[:24]))
