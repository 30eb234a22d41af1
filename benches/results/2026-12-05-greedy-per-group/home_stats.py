"""One line of home.tsv from `query --json` lines: binary, repetition, solved, query p50 ms,
shortening mean ms, summed length, intersect calls."""
import json
import statistics as st
import sys

path, binary, rep = sys.argv[1:4]
rows = [json.loads(l) for l in open(path) if l.startswith('{')]
print("\t".join([binary, rep, str(sum(r['solved'] for r in rows)),
                 "%.2f" % st.median(r['query_ms'] for r in rows),
                 "%.2f" % st.mean(r.get('shorten_ms', 0) for r in rows),
                 "%.0f" % sum(r['length'] for r in rows if r['solved']),
                 str(sum(r['calls'] for r in rows))]))
