#!/usr/bin/env python3
"""Tables of this directory: the 700-problem runs against the sliding stairs of 2026-12-04
(../2026-12-04-direct-budget/), OMPL's RRTConnect of 2026-12-02 (../2026-12-02-mbm700/ompl/, another
VM) and, side by side on this one, RRTConnect again (ompl-rrtconnect/). python3 summary.py"""
import csv, json, glob, os, statistics as st

here = os.path.dirname(os.path.abspath(__file__))


def load(path):
    return {(r["family"], r["id"]): r for r in csv.DictReader(open(path))}


def row(name, rows):
    solved = [r for r in rows.values() if r["solved"] == "true"]
    t = sorted(float(r["time_s"]) * 1e3 for r in solved)
    cert = sum(r["certified"] == "true" for r in solved)
    p95 = t[int(0.95 * (len(t) - 1))]
    print(f"| {name} | {len(solved)} / {len(rows)} | {cert} | {st.mean(t):.0f} | {st.median(t):.0f} | {p95:.0f} |")


runs = {
    "sliding, alternating, in turn (300 calls; 2026-12-04 morning)": "../2026-12-04-direct-budget/mbm700-dc300.csv",
    "sliding, `--race` (2026-12-04 morning)": "../2026-12-04-direct-budget/mbm700-race300.csv",
    "whole, alternating, in turn (300 calls)": "mbm700-alternate-dc300.csv",
    "whole, alternating, trees alone (`--direct-calls 0`)": "mbm700-alternate-dc0.csv",
    "whole, balanced, in turn (300 calls): the default": "mbm700-balanced-dc300.csv",
    "whole, balanced, trees alone (`--direct-calls 0`)": "mbm700-balanced-dc0.csv",
    "whole, balanced, `--race`": "mbm700-balanced-race.csv",
}
print("| run | solved / total | certified | mean ms | p50 | p95 |")
print("|---|---|---|---|---|---|")
data = {k: load(os.path.join(here, v)) for k, v in runs.items()}
for k, v in data.items():
    row(k, v)
ompl = {}
for f in glob.glob(os.path.join(here, "../2026-12-02-mbm700/ompl/*_rrtconnect_t5.jsonl")):
    for line in open(f):
        r = json.loads(line)
        fam, pid = r["problem"].split("/")
        ompl[(fam, pid)] = r
t = sorted(r["time_s"] * 1e3 for r in ompl.values() if r["solved"])
print(f"| OMPL RRTConnect + FCL (2026-12-02) | {len(t)} / {len(ompl)} | – | {st.mean(t):.0f} | {st.median(t):.0f} | {t[int(0.95 * (len(t) - 1))]:.0f} |")

# per problem, where both solved: the new default and the trees alone against the morning's
before = data["sliding, alternating, in turn (300 calls; 2026-12-04 morning)"]
for k in ["whole, balanced, in turn (300 calls): the default", "whole, balanced, trees alone (`--direct-calls 0`)"]:
    both = [p for p, r in data[k].items() if r["solved"] == "true" and before[p]["solved"] == "true"]
    ratio = [float(data[k][p]["time_s"]) / float(before[p]["time_s"]) for p in both]
    gained = [p for p, r in data[k].items() if r["solved"] == "true" and before[p]["solved"] != "true"]
    lost = [p for p, r in data[k].items() if r["solved"] != "true" and before[p]["solved"] == "true"]
    print(f"\n{k}: {len(both)} solved by both, time ratio median {st.median(ratio):.2f}, "
          f"sum {sum(float(data[k][p]['time_s']) for p in both) / sum(float(before[p]['time_s']) for p in both):.2f}; "
          f"gained {len(gained)}, lost {len(lost)} {lost}")
# side by side on this machine (one per core, 2026-12-04 night): the trees alone and RRTConnect
side = load(os.path.join(here, "mbm700-side-by-side-dc0.csv"))
peer = {}
for f in glob.glob(os.path.join(here, "ompl-rrtconnect/*_rrtconnect_t5.jsonl")):
    for line in open(f):
        r = json.loads(line)
        fam, pid = r["problem"].split("/")
        peer[(fam, pid)] = r
print("\nSide by side: | family | viaroad solved | p50 ms | mean ms | RRTConnect solved | p50 ms | mean ms |")
print("|---|---|---|---|---|---|---|")
for fam in sorted({p[0] for p in side}) + ["all"]:
    a = [float(r["time_s"]) * 1e3 for p, r in side.items() if fam in (p[0], "all") and r["solved"] == "true"]
    b = [r["time_s"] * 1e3 for p, r in peer.items() if fam in (p[0], "all") and r["solved"]]
    print(f"| {fam} | {len(a)} | {st.median(a):.1f} | {st.mean(a):.0f} | {len(b)} | {st.median(b):.1f} | {st.mean(b):.0f} |")
