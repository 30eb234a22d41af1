#!/usr/bin/env python3
"""Per robot and family: VAMP's and viaroad's solved counts and total times (mean, median, p95,
ms per problem) from run.sh's folder, with viaroad's ratio to VAMP. VAMP's time is its own
plan + simplify counter; viaroad's is `bench mbm`'s planning time (shortening included, scene
loading excluded). Means and percentiles are over each planner's solved problems.

usage: summarize.py RUNS_DIR ROBOT...
"""
import csv
import json
import sys
from pathlib import Path

import numpy as np


def stats(v):
    if not v:
        return (float("nan"),) * 3
    a = np.array(v)
    return a.mean(), np.percentile(a, 50), np.percentile(a, 95)


def viaroad(path):
    fams = {}
    if not path.exists():
        return fams
    for r in csv.DictReader(open(path)):
        fam = r["family"].rsplit("_", 1)[0]
        d = fams.setdefault(fam, {"valid": 0, "solved": 0, "certified": 0, "t": []})
        if r["valid"] == "true":
            d["valid"] += 1
        if r["solved"] == "true":
            d["solved"] += 1
            d["certified"] += r["certified"] == "true"
            d["t"].append(float(r["time_s"]) * 1e3)
    return fams


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
    for robot in sys.argv[2:]:
        vp = vamp(runs / f"vamp-{robot}.jsonl")
        sides = [("viaroad", viaroad(runs / f"viaroad-{robot}" / "problems.csv"))]
        before = viaroad(runs / f"before-{robot}" / "problems.csv")
        if before:
            sides.append(("before", before))
        print(f"\n### {robot}\n")
        print("| family | VAMP solved / valid | VAMP mean / p50 / p95 ms | planner | solved / valid (certified) "
              "| mean / p50 / p95 ms | mean ÷ VAMP | p50 ÷ VAMP | p95 ÷ VAMP |")
        print("|---|---|---|---|---|---|---|---|---|")
        fams = sorted(vp) + ["ALL"]
        for fam in fams:
            if fam == "ALL":
                v = {"valid": sum(d["valid"] for d in vp.values()),
                     "solved": sum(d["solved"] for d in vp.values()),
                     "t": sum((d["t"] for d in vp.values()), [])}
            else:
                v = vp[fam]
            vm = stats(v["t"])
            for name, side in sides:
                if fam == "ALL":
                    s = {k: sum(d[k] for d in side.values()) for k in ("valid", "solved", "certified")}
                    s["t"] = sum((d["t"] for d in side.values()), [])
                else:
                    s = side.get(fam)
                    if s is None:
                        continue
                m = stats(s["t"])
                label = f"**{fam}**" if fam == "ALL" else fam
                print(f"| {label} | {v['solved']} / {v['valid']} | {vm[0]:.3f} / {vm[1]:.3f} / {vm[2]:.3f} "
                      f"| {name} | {s['solved']} / {s['valid']} ({s['certified']}) "
                      f"| {m[0]:.2f} / {m[1]:.2f} / {m[2]:.2f} "
                      f"| {m[0] / vm[0]:.1f}× | {m[1] / vm[1]:.1f}× | {m[2] / vm[2]:.1f}× |")


if __name__ == "__main__":
    main()
