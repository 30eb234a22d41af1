"""The problems VAMP and viaroad both call valid, and how many each solves there.

    python3 both_valid.py VAMP.jsonl[.gz] viaroad-ROBOT/problems.csv ROBOT

Two readings of "viaroad calls valid": its planner's oracle accepts the request's start and
goal (`oracle_valid`: the exact oracle, on the shapes that circumscribe big meshes), or the
independent checker does (`valid`, the true meshes). viaroad counts a problem solved when its
path is certified.
"""
import csv
import gzip
import json
import sys


def vamp_results(path):
    opened = gzip.open(path, "rt") if path.endswith(".gz") else open(path)
    with opened as f:
        rows = (json.loads(line) for line in f)
        return {(r["family"], r["index"]): r for r in rows if not r.get("meta")}


def main(vamp_path, viaroad_csv, robot):
    vamp = vamp_results(vamp_path)
    with open(viaroad_csv) as f:
        ours = list(csv.DictReader(f))
    readings = [
        ("VAMP valid, viaroad's oracle accepts the ends", lambda r: r["oracle_valid"] == "true"),
        ("VAMP valid, the independent checker valid", lambda r: True),
    ]
    for label, accepts in readings:
        both = vamp_solved = our_solved = 0
        only_vamp, only_ours = [], []
        for r in ours:
            key = (r["family"].removesuffix("_" + robot), int(r["id"]))
            v = vamp[key]
            if not (v["valid"] and r["valid"] == "true" and accepts(r)):
                continue
            both += 1
            solved = r["solved"] == "true" and r["certified"] == "true"
            vamp_solved += bool(v["solved"])
            our_solved += solved
            if v["solved"] and not solved:
                only_vamp.append("%s/%d" % key)
            if solved and not v["solved"]:
                only_ours.append("%s/%d" % key)
        print(f"{robot}: {label}: {both} problems; VAMP solves {vamp_solved}, viaroad {our_solved}")
        print(f"  VAMP only: {' '.join(only_vamp) or '-'}")
        print(f"  viaroad only: {' '.join(only_ours) or '-'}")


if __name__ == "__main__":
    main(*sys.argv[1:4])
