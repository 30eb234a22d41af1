#!/usr/bin/env python3
"""Records the OMPL peer's verdicts on the shipped Panda problems (scenes/arms/), for
tests/arm_checker.rs: start and goal validity of every problem (`ompl_peer arminfo`) and the
validity, with colliding pairs, of seeded uniform configurations in the first scene of each
family (`ompl_peer armcheck` on a one-state path).

    python3 tests/data/arms/peer_verdicts.py /tmp/ompl-peer/build/ompl_peer > tests/data/arms/peer_verdicts.json

The peer: ../shared/ompl-peer (OMPL 1.5.2 + FCL 0.7, urdfdom, assimp). Deterministic: the
configurations come from random.Random(SEED).
"""
import json, os, random, subprocess, sys, tempfile

SEED = 10
PER_FAMILY = 40
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scenes", "arms")
FAMILIES = ["table_pick", "table_under_pick", "box", "bookshelf_small", "bookshelf_tall",
            "bookshelf_thin", "cage"]

def run(peer, *args):
    out = subprocess.run([peer, *args], cwd=ROOT, capture_output=True, text=True, timeout=120)
    return json.loads(out.stdout.strip().splitlines()[-1])

def main():
    peer = sys.argv[1]
    urdf, srdf = "panda/panda.urdf", "panda/panda.srdf"
    problems, states = [], []
    lows = highs = None
    for fam in FAMILIES:
        for i in (1, 2, 3):
            scene, req = f"mbm/{fam}/scene{i:04}.yaml", f"mbm/{fam}/request{i:04}.yaml"
            info = run(peer, "arminfo", urdf, srdf, scene, req)
            lows, highs = info["bounds_low"], info["bounds_high"]
            problems.append({
                "scene": scene, "request": req,
                "start_valid": info["start_valid"], "start_collisions": info["start_collisions"],
                "goal_valid": info["goal_valid"], "goal_collisions": info["goal_collisions"],
            })
    rng = random.Random(SEED)
    with tempfile.TemporaryDirectory() as tmp:
        for fam in FAMILIES:
            scene = f"mbm/{fam}/scene0001.yaml"
            for k in range(PER_FAMILY):
                q = [round(rng.uniform(lo, hi), 6) for lo, hi in zip(lows, highs)]
                path = os.path.join(tmp, "q.path")
                with open(path, "w") as f:
                    f.write(" ".join(repr(v) for v in q) + "\n")
                r = run(peer, "armcheck", urdf, srdf, scene, path)
                states.append({"scene": scene, "q": q, "valid": r["valid"],
                               "collisions": r.get("first_invalid_state_collisions",
                                                   r.get("collisions", []))})
    json.dump({"peer": "ompl_peer (OMPL 1.5.2, FCL 0.7)", "seed": SEED,
               "problems": problems, "states": states}, sys.stdout, indent=1)
    print()

main()
