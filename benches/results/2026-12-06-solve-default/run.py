#!/usr/bin/env python3
"""`viaroad solve` by default against each single mode on OMPL.app's hard problems.

Every run gets the same time (--time, one thread: RAYON_NUM_THREADS=1, so the default's race
runs its sides in turn), and the modes run interleaved per problem and seed so that the
machine's load falls on all of them alike. Writes one JSON line per run to runs.jsonl.
Usage: run.py VIAROAD [--time 30] [--seeds 1 2 3]
"""
import argparse, json, os, subprocess, time

PROBLEMS = ["alpha-1.5", "bugtrap", "Abstract", "Twistycool", "Apartment", "Home", "cubicles"]
MODES = {"default": [], "tree": ["--tree"], "roadmap": ["--roadmap"]}

def run(viaroad, scene, args, secs):
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    began = time.monotonic()
    p = subprocess.run([viaroad, "solve", scene, "--json", "--time", str(secs)] + args,
                       capture_output=True, text=True, env=env, timeout=secs * 4 + 60)
    wall = time.monotonic() - began
    lines = [json.loads(l) for l in p.stdout.splitlines() if l.startswith("{")]
    q = lines[0] if lines else {}
    return {"exit": p.returncode, "solved": bool(q.get("solved")), "wall": wall,
            "calls": q.get("calls"), "length": q.get("length"), "method": q.get("method"),
            "error": p.stderr.strip().splitlines()[-1] if p.returncode else None}

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("viaroad")
    ap.add_argument("--time", type=float, default=30)
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--out", default="runs.jsonl")
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.abspath(os.path.join(here, "../../.."))
    with open(os.path.join(here, a.out), "w") as out:
        for prob in PROBLEMS:
            scene = os.path.join(root, "scenes/ompl/3D", prob + ".cfg")
            r = run(a.viaroad, scene, ["--local-only"], a.time)
            out.write(json.dumps(dict(problem=prob, mode="local-only", seed=None, **r)) + "\n")
            out.flush()
            for seed in a.seeds:
                for mode, args in MODES.items():
                    r = run(a.viaroad, scene, args + ["--seed", str(seed)], a.time)
                    out.write(json.dumps(dict(problem=prob, mode=mode, seed=seed, **r)) + "\n")
                    out.flush()
                    print(prob, mode, seed, r["solved"], round(r["wall"], 2), flush=True)

main()
