"""One line of runs.tsv from a workcell.json: family, binary, repetition, query p50 and p95,
found p50, shortening p50 and sum (ms), length p50, intersect calls summed over the answers."""
import json
import statistics as st
import sys

path, fam, binary, rep = sys.argv[1:5]
d = json.load(open(path))[0]
s, lat = d["shorten_ms"], d["latencies_ms"]
print("\t".join([fam, binary, rep, "%.2f" % st.median(lat), "%.1f" % d["query_ms"]["p95"],
                 "%.2f" % d["found_ms"]["p50"], "%.2f" % st.median(s), "%.0f" % sum(s),
                 "%.2f" % d["length"]["p50"], str(sum(d["calls"]))]))
