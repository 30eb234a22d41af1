#!/usr/bin/env python3
"""Per Panda family: VAMP's median and 5× its p95 (total ms per solved problem) on the problems
asked, and each workcell run's (`workcell-1`, `workcell-2`, `base-1`, `base-2` in RUNS_DIR)
valid / solved / certified requests, query p50 / p95 ms and whether they meet the targets
(p50 ≤ VAMP's median, p95 ≤ 5× VAMP's p95), with the roadmap's nodes and learning time.

usage: summarize.py RUNS_DIR
"""
import json
import sys
from pathlib import Path

import numpy as np


def vamp(path):
    fams = {}
    for line in open(path):
        r = json.loads(line)
        d = fams.setdefault(r["family"], {"valid": 0, "solved": 0, "t": []})
        if r["valid"]:
            d["valid"] += 1
            if r["solved"]:
                d["solved"] += 1
                d["t"].append(r["total_ms"])
    return fams


def main():
    runs = Path(sys.argv[1])
    vp = vamp(runs / "vamp-panda.jsonl")
    names = [n for n in ("workcell-1", "workcell-2", "base-1", "base-2") if (runs / n / "workcell.json").exists()]
    print("| family | VAMP solved / valid | VAMP median / 5× p95 ms | run | nodes (sampled + trained on, kept) | learn s "
          "| valid | solved | certified | by trees | calls p50 / max | p50 / p95 ms | p50 ≤ VAMP median | p95 ≤ 5× VAMP p95 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in names:
        for r in json.load(open(runs / name / "workcell.json")):
            fam = r["family"].rsplit("_", 1)[0]
            v = vp.get(fam, {"valid": 0, "solved": 0, "t": []})
            vm, v95 = (np.percentile(v["t"], 50), np.percentile(v["t"], 95)) if v["t"] else (float("nan"),) * 2
            lat = r["latencies_ms"]
            p50, p95 = (np.percentile(lat, 50), np.percentile(lat, 95)) if lat else (float("nan"),) * 2
            ok50 = "yes" if p50 <= vm else f"no ({p50 / vm:.1f}×)"
            ok95 = "yes" if p95 <= 5 * v95 else f"no ({p95 / (5 * v95):.1f}×)"
            print(f"| {fam} | {v['solved']} / {v['valid']} | {vm:.3f} / {5 * v95:.2f} | {name} "
                  f"| {r['nodes']} ({r.get('sampled_nodes', r['nodes'])} + {r.get('train_valid', 0)}, {r.get('train_kept', 0)}) "
                  f"| {r['learn_s']:.1f} | {r['valid']} | {r['solved']} | {r['certified']} | {r['by_trees']} "
                  f"| {np.percentile(r['calls'], 50):.0f} / {max(r['calls'])} "
                  f"| {p50:.3f} / {p95:.2f} | {ok50} | {ok95} |")


if __name__ == "__main__":
    main()
