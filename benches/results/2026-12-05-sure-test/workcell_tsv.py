"""Lines of workcell.tsv from a workcell.json: family, binary, repetition, valid, solved,
certified, query p50 / p95 ms, found p50 ms, shortening p50 ms, length p50 rad, intersect calls
summed over the answers."""
import json
import statistics as st
import sys

path, binary, rep = sys.argv[1:4]
for d in json.load(open(path)):
    print("\t".join([d["family"], binary, rep, str(d["valid"]), str(d["solved"]),
                     str(d["certified"]), "%.2f" % d["query_ms"]["p50"],
                     "%.1f" % d["query_ms"]["p95"], "%.2f" % d["found_ms"]["p50"],
                     "%.2f" % st.median(d["shorten_ms"]), "%.2f" % d["length"]["p50"],
                     str(sum(d["calls"]))]))
