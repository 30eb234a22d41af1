#!/usr/bin/env python3
"""OMPL.app rigid-body paths (SE(2), SE(3)) certified by `viaroad certify`, held against the
OMPL peer's own sampled check (`ompl_peer check`, FCL on the real meshes).

For every non-control problem of ../shared/ompl-scenes: the OMPL peer's RRT-Connect solves it
RUNS times (`--save-path`: the raw and the simplified path of each run), and OMPL.app's shipped
`.path` where there is one. Each path is certified (`viaroad certify CFG PATH --json`) and
checked by `ompl_peer check` at 1/1000 of the space's extent (OMPL's default is 1/100). A path
certify proves free is checked again at 1/10 000; a witness of a path only certify flags is
checked as a one-state path (a state check, no sampling).

Usage: rigid.py OUT_DIR   (env: VIAROAD, OMPL_PEER, SCENES, RUNS, SOLVE_TIME, CERTIFY_TIME)
Writes OUT_DIR/rigid.jsonl (one object per path) and prints the summary table (markdown);
`rigid.py --summary RIGID.jsonl` prints the table again.
"""
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

VIAROAD = os.environ.get("VIAROAD", "target/release/viaroad")
PEER = os.environ.get("OMPL_PEER", "/tmp/ompl-peer-certify/build/ompl_peer")
SCENES = Path(os.environ.get("SCENES", "/work/shared/ompl-scenes"))
RUNS = int(os.environ.get("RUNS", "3"))
SOLVE_TIME = os.environ.get("SOLVE_TIME", "20")
CERTIFY_TIME = os.environ.get("CERTIFY_TIME", "30")
PROBLEMS = [
    "2D/Barriers", "2D/BugTrap_planar", "2D/Maze_planar", "2D/RandomPolygons_planar",
    "2D/UniqueSolutionMaze",
    "3D/Abstract", "3D/Apartment", "3D/Apartment_hard", "3D/Easy", "3D/Home",
    "3D/Twistycool", "3D/alpha-1.5", "3D/bugtrap", "3D/cubicles",
]


def run(cmd, timeout=600):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout


def last_json(text):
    lines = [l for l in text.splitlines() if l.startswith("{")]
    return json.loads(lines[-1]) if lines else None


def check(cfg, path, resolution):
    _, out = run([PEER, "check", str(cfg), str(path), "--resolution", str(resolution)])
    return last_json(out)


def one(cfg, path, kind, out_dir):
    rc, out = run([VIAROAD, "certify", str(cfg), str(path), "--json", "--time", CERTIFY_TIME],
                  timeout=int(float(CERTIFY_TIME)) * 4 + 60)
    c = json.loads(out) if out.strip().startswith("{") else None
    r = {"problem": cfg.stem, "path": str(path), "kind": kind, "exit": rc}
    if c is None:
        r["error"] = out[-300:]
        return r
    cert = c["certificate"]
    r["status"] = c["status"]
    verdicts = [s["verdict"] for s in cert["segments"]]
    r["segments"] = [verdicts.count(v) for v in ("free", "collides", "undecided")]
    r["defects"] = cert["defects"]
    r["certify_s"] = cert["seconds"]
    r["collides_at"] = [i for i, v in enumerate(verdicts) if v == "collides"]
    ch = check(cfg, path, 0.001)
    r["ompl_valid_1e-3"] = ch.get("valid") if ch else None
    r["ompl_first_invalid_segment"] = ch.get("first_invalid_segment") if ch else None
    r["ompl_invalid_states"] = ch.get("invalid_states") if ch else None
    if r["status"] == "free":
        ch4 = check(cfg, path, 0.0001)
        r["ompl_valid_1e-4"] = ch4.get("valid") if ch4 else None
    if r["status"] == "collides" and r["ompl_valid_1e-3"]:
        # certify alone flags it: each witness must be a collision for OMPL's own check
        confirmed = []
        for i, s in enumerate(cert["segments"]):
            if s["verdict"] != "collides":
                continue
            w = out_dir / "witness.path"
            w.write_text(" ".join(repr(x) for x in s["witness"]) + "\n")
            cw = check(cfg, w, 0.001)
            confirmed.append(bool(cw) and cw.get("invalid_states", 0) > 0)
        r["witnesses_confirmed"] = [sum(confirmed), len(confirmed)]
    return r


def main():
    out_dir = Path(sys.argv[1])
    paths_dir = out_dir / "rigid_paths"
    paths_dir.mkdir(parents=True, exist_ok=True)
    results = []
    with open(out_dir / "rigid.jsonl", "w") as f:
        for p in PROBLEMS:
            cfg = SCENES / f"{p}.cfg"
            name = cfg.stem
            prefix = paths_dir / name
            rc, out = run([PEER, "solve", str(cfg), "--planner", "rrtconnect", "--runs", str(RUNS),
                           "--seed", "1", "--time", SOLVE_TIME, "--save-path", str(prefix)],
                          timeout=RUNS * int(SOLVE_TIME) + 120)
            solves = [json.loads(l) for l in out.splitlines() if l.startswith("{")]
            todo = []
            shipped = SCENES / f"{p}.path"
            if shipped.exists():
                todo.append((shipped, "omplapp"))
            for s in solves:
                if not s.get("solved"):
                    continue
                k = s["run"]
                todo.append((Path(f"{prefix}_run{k}.path"), "raw"))
                todo.append((Path(f"{prefix}_run{k}_simplified.path"), "simplified"))
            for path, kind in todo:
                if not path.exists():
                    continue
                r = one(cfg, path, kind, out_dir)
                r["ompl_time_s"] = next((s["time_s"] for s in solves
                                         if f"_run{s['run']}" in path.name), None)
                results.append(r)
                f.write(json.dumps(r) + "\n")
                f.flush()
                print(json.dumps(r)[:200], file=sys.stderr)
    summary(results)


def summary(results):
    print("| problem | paths | certify free | collides | undecided | OMPL flags at 1/1000 | "
          "of those certify calls free | certify free, OMPL flags at 1/10 000 | only certify "
          "flags (witnesses confirmed) | defects only | certify s p50 |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    names = []
    for r in results:
        if r["problem"] not in names:
            names.append(r["problem"])
    for name in names + ["**ALL**"]:
        rs = [r for r in results if name == "**ALL**" or r["problem"] == name]
        rs = [r for r in rs if "status" in r]
        n = lambda s: sum(r["status"] == s for r in rs)
        flagged = [r for r in rs if r["ompl_valid_1e-3"] is False]
        missed = sum(r["status"] == "free" for r in flagged)
        free_bad = sum(r.get("ompl_valid_1e-4") is False for r in rs)
        only = [r for r in rs if r["status"] == "collides" and r["ompl_valid_1e-3"]
                and r["segments"][1] > 0]
        defect_only = sum(r["status"] == "collides" and r["segments"][1] == 0 for r in rs)
        conf = sum(r.get("witnesses_confirmed", [0, 0])[0] for r in only)
        tot = sum(r.get("witnesses_confirmed", [0, 0])[1] for r in only)
        med = statistics.median([r["certify_s"] for r in rs]) if rs else 0
        print(f"| {name} | {len(rs)} | {n('free')} | {n('collides')} | {n('undecided')} | "
              f"{len(flagged)} | {missed} | {free_bad} | {len(only)} ({conf}/{tot}) | {defect_only} | "
              f"{med:.3f} |")


if __name__ == "__main__":
    if sys.argv[1] == "--summary":
        summary([json.loads(l) for l in open(sys.argv[2])])
    else:
        main()
