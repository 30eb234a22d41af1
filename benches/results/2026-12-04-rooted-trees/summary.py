"""Tables of this directory's runs: python3 summary.py (after run.sh and query.sh)."""
import json
import os
import statistics

HERE = os.path.dirname(os.path.abspath(__file__))


def families(name):
    d = json.load(open(os.path.join(HERE, name)))
    return d if isinstance(d, list) else d["families"]


def workcell(names):
    print("| run | " + " | ".join(f["family"].replace("_panda", "") for f in families(names[0])) + " | all |")
    print("|---" * (len(families(names[0])) + 2) + "|")
    for n in names:
        fs = families(n)
        cells = [f"{f['solved']}/{f['valid']} ({f['certified']} cert.), p50 {f['query_ms']['p50']:.2f}, p95 {f['query_ms']['p95']:.0f}" for f in fs]
        total = sum(sum(f["latencies_ms"]) for f in fs) / 1e3
        solved = sum(f["solved"] for f in fs)
        valid = sum(f["valid"] for f in fs)
        cert = sum(f["certified"] for f in fs)
        print(f"| {n[9:-5]} | " + " | ".join(cells) + f" | {solved}/{valid} ({cert} cert.), sum {total:.1f} s |")


def query():
    rows = {}
    for line in open(os.path.join(HERE, "query.txt")):
        mode, i, rest = line.split(" ", 2)
        if rest.startswith("{"):
            rows.setdefault(mode, []).append((i, json.loads(rest)))
    print("| `--trees` | valid | solved | outcomes | p50 ms | mean ms | max ms |")
    print("|---|---|---|---|---|---|---|")
    for mode, r in rows.items():
        t = [v["query_ms"] for _, v in r]
        outcomes = {}
        for _, v in r:
            outcomes[v["outcome"]] = outcomes.get(v["outcome"], 0) + 1
        print(f"| {mode} | {len(r)} | {sum(v['solved'] for _, v in r)} | {outcomes} | {statistics.median(t):.0f} | {statistics.mean(t):.0f} | {max(t):.0f} |")


if __name__ == "__main__":
    workcell(["workcell-ends-1.json", "workcell-roadmap-1.json", "workcell-ends-2.json", "workcell-roadmap-2.json", "workcell-turn-ends.json", "workcell-turn-roadmap.json"])
    print()
    query()
