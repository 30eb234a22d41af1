#!/usr/bin/env python3
"""p50/p95/mean of query_ms, calls and path lengths of `viaroad query --json` lines.

p50/p95: nearest rank on the sorted times (index round(q*(n-1))), as in earlier rounds."""
import json, sys

def pct(xs, q):
    xs = sorted(xs)
    return xs[round(q * (len(xs) - 1))]

for f in sys.argv[1:]:
    rows = [json.loads(l) for l in open(f) if l.startswith('{')]
    t = [r['query_ms'] for r in rows]
    c = [r['calls'] for r in rows]
    L = [r['length'] for r in rows if r.get('solved')]
    print(f"{f}: n={len(rows)} solved={sum(bool(r.get('solved')) for r in rows)} "
          f"p50={pct(t,.5):.2f} ms p95={pct(t,.95):.2f} ms mean={sum(t)/len(t):.2f} ms "
          f"calls/query={sum(c)/len(c):.1f} length mean={sum(L)/len(L):.1f} p95={pct(L,.95):.1f}")
