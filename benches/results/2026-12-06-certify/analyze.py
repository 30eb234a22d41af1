#!/usr/bin/env python3
"""Compares `viaroad bench certify` with OMPL + FCL `armcheck` (../ompl-peer) on VAMP's paths.

usage: analyze.py ROBOT CERTIFY.jsonl [--sample N] [--seed S]

Reads the certify results (one JSON object per path), the mesh check's verdicts of the same
paths (vamp-peer results/check/, final paths at 1/1000), and runs armcheck on:
  A. nothing colliding called free: every path armcheck flags at 1/1000 must not be `free`;
  B. every path certify proves free, at 1/10000 (or a random sample of N of them);
  C. the witnesses of the paths only certify flags (one-state path files): armcheck must
     find each witness in collision;
  D. the repaired paths, at 1/1000.
Env: OMPL_PEER (the armcheck binary), VAMP_RES (the sdist's resources/), VAMP_PEER (vamp-peer).
"""
import argparse, json, os, random, subprocess, tempfile
from pathlib import Path

OMPL = Path(os.environ.get("OMPL_PEER", "/tmp/ompl-peer-certify/build/ompl_peer"))
RES = Path(os.environ.get("VAMP_RES", "/tmp/vamp-sdist/vamp_planner-0.6.4/resources"))
PEER = Path(os.environ.get("VAMP_PEER", "/work/shared/vamp-peer"))
CHECKS = {"panda": "panda_all.jsonl", "fetch": "fetch_all_final.jsonl",
          "ur5": "ur5_first10_final.jsonl"}


def armcheck(robot, family, index, path, resolution):
    d = RES / robot / "problems" / f"{family}_{robot}"
    with tempfile.NamedTemporaryFile("w", suffix=".path", delete=False) as f:
        for q in path:
            f.write(" ".join(repr(x) for x in q) + "\n")
    cmd = [str(OMPL), "armcheck", str(RES / robot / f"{robot}.urdf"), str(RES / robot / f"{robot}.srdf"),
           str(d / f"scene{index:04d}.yaml"), f.name, "--request", str(d / f"request{index:04d}.yaml"),
           "--resolution", str(resolution)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    os.unlink(f.name)
    line = out.stdout.strip().splitlines()[-1] if out.stdout.strip() else "{}"
    return json.loads(line)


def collides(check):
    """armcheck's verdict as a collision: not valid, and not only one waypoint a float32
    rounding outside a joint limit with no contact (the peer's "bounds-only" paths)."""
    if check.get("valid", True):
        return False
    bounds_only = (check.get("invalid_segments", 0) == 0 and check.get("invalid_states", 0) == 1
                   and check.get("first_invalid_state_out_of_bounds") and not check.get("first_invalid_state_collisions"))
    return not bounds_only


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("robot")
    ap.add_argument("certify")
    ap.add_argument("--sample", type=int, default=0)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rs = {(r["family"], r["index"]): r for r in map(json.loads, open(a.certify))}
    mesh = {}
    for line in open(PEER / "results" / "check" / CHECKS[a.robot]):
        c = json.loads(line)
        if c.get("kind") == "final" and c.get("resolution") == 0.001:
            mesh[(c["family"], c["index"])] = c["check"]
    flagged = {k for k, c in mesh.items() if collides(c)}
    out = {"robot": a.robot, "paths": len(rs), "armcheck_verdicts": len(mesh)}
    out["A_bounds_only"] = sum(1 for c in mesh.values() if not c.get("valid", True) and not collides(c))
    status = lambda k: rs[k]["status"] if k in rs else "missing"
    out["A_armcheck_flags"] = len(flagged)
    out["A_of_them_called_free"] = sorted(f"{f} {i}" for f, i in flagged if status((f, i)) == "free")
    out["A_of_them_collides"] = sum(status(k) == "collides" for k in flagged)
    out["A_of_them_undecided"] = sum(status(k) == "undecided" for k in flagged)
    free = [k for k, r in rs.items() if r["status"] == "free"]
    random.Random(a.seed).shuffle(free)
    sample = free[: a.sample] if a.sample else free
    bad = []
    for k in sample:
        c = armcheck(a.robot, k[0], k[1], path_of(a.robot, k), 0.0001)
        if collides(c):
            bad.append(f"{k[0]} {k[1]}")
    out["B_free_checked_at_1e-4"] = f"{len(sample)} of {len(free)}"
    out["B_failing"] = bad
    only = [k for k, r in rs.items() if r["status"] == "collides" and k not in flagged
            and r["witnesses"]]
    out["C_defects_only"] = sum(1 for k, r in rs.items() if r["status"] == "collides"
                                and k not in flagged and not r["witnesses"])
    conf, unconf = 0, []
    for k in only:
        w = rs[k]["witnesses"][0][2]
        c = armcheck(a.robot, k[0], k[1], [w], 0.001)
        if collides(c):
            conf += 1
        else:
            unconf.append(f"{k[0]} {k[1]}")
    out["C_only_certify_flags"] = len(only)
    out["C_witness_confirmed"] = conf
    out["C_witness_not_confirmed"] = unconf
    rep = [k for k, r in rs.items() if r.get("repaired") is not None]
    ok = [k for k in rep if rs[k]["repaired"]]
    failing = []
    for k in ok:
        c = armcheck(a.robot, k[0], k[1], rs[k]["fixed"], 0.001)
        if collides(c) or "valid" not in c:
            failing.append(f"{k[0]} {k[1]}")
    out["D_repairs_tried"] = len(rep)
    out["D_repairs_certified"] = len(ok)
    out["D_repaired_failing_armcheck_1e-3"] = failing
    # E. repairs refused because the path's own start or goal (the problem's) collides with
    # the true shapes: armcheck must find that configuration in collision too
    ends = {}
    for k in rep:
        if rs[k]["repaired"]:
            continue
        errs = " ".join(rs[k].get("repair_errors", []))
        if "collides (the true shapes)" not in errs:
            continue
        p = path_of(a.robot, k)
        hits = [collides(armcheck(a.robot, k[0], k[1], [q], 0.001)) for q in (p[0], p[-1])]
        ends[f"{k[0]} {k[1]}"] = {"start_collides": hits[0], "goal_collides": hits[1]}
    out["E_failed_with_an_end_colliding"] = len(ends)
    out["E_armcheck_confirms_an_end"] = sum(any(v.values()) for v in ends.values())
    out["E_ends"] = ends
    print(json.dumps(out, indent=1))


_PATHS = {}


def path_of(robot, key):
    if robot not in _PATHS:
        _PATHS[robot] = {(d["family"], d["index"]): d["path"]
                         for d in map(json.loads, open(PEER / "results" / f"{robot}.jsonl")) if d.get("path")}
    return _PATHS[robot][key]


if __name__ == "__main__":
    main()
