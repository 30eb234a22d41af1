"""Sharded learning on Ray, measured: for each scene and worker count W, shards learn for T
seconds each (T from a ladder, stopping at the first that answers 99 % of a fixed query set),
a reduction tree of pairwise merges joins them; wall time, nodes, edges, merge time and its
share, Ray's overhead. Writes results.json beside this file.

    target/pyenv/bin/python benches/results/2026-12-06-shards/run.py [--scenes Home] [--workers 1]
                                                                     [--out results.json]
"""

import argparse

import importlib.util
import json
import sys
import time
from pathlib import Path

import ray

import viaroad

ROOT = Path(__file__).resolve().parents[3]
HERE = Path(__file__).resolve().parent
spec = importlib.util.spec_from_file_location("ray_learn", ROOT / "python/examples/ray_learn.py")
ray_learn = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ray_learn)

SCENES = {
    "Home": (ROOT / "scenes/ompl/3D/Home.cfg", [1, 2, 5, 10]),
    "panda-box": (ROOT / "scenes/arms/panda-box-1.toml", [1, 2, 5, 10]),
}
WORKERS = [1, 2, 4]
QUERIES = 100


@ray.remote
def noop():
    return None


def ray_overhead():
    """Seconds per task: one task's round trip, and 100 tasks' mean in a batch."""
    ray.get(noop.remote())
    began = time.perf_counter()
    for _ in range(20):
        ray.get(noop.remote())
    single = (time.perf_counter() - began) / 20
    began = time.perf_counter()
    ray.get([noop.remote() for _ in range(100)])
    batch = (time.perf_counter() - began) / 100
    return {"round_trip_s": round(single, 5), "batched_s": round(batch, 5)}


def one(scene_path, workers, seconds, starts, goals):
    began = time.perf_counter()
    shards = [
        ray_learn.learn_shard.remote(str(scene_path), i, workers, 1, None, seconds)
        for i in range(1, workers + 1)
    ]
    refs = [ray_learn.first.remote(s) for s in shards]
    top, merges = ray_learn.reduction_tree(str(scene_path), refs, 2, None)
    learnt = ray.get(shards)
    shards_done = time.perf_counter() - began
    merged = ray.get(top)
    wall = time.perf_counter() - began
    merge_times = [t for _, t in ray.get(merges)]
    info = merged.info()
    answers = merged.query_many(starts, goals, grow=False, time=10.0)
    solved = sum(r.solved for r in answers)
    shard_max = max(t for _, t in learnt)
    return {
        "workers": workers,
        "shard_time_budget_s": seconds,
        "nodes": info["nodes"],
        "edges": info["edges"],
        "components": info["components"],
        "largest": info["largest_component"],
        "shard_nodes": [r.info()["nodes"] for r, _ in learnt],
        "shard_s": [round(t, 3) for _, t in learnt],
        "merge_s": [round(t, 3) for t in merge_times],
        "shards_done_s": round(shards_done, 3),
        "wall_s": round(wall, 3),
        "merge_wall_s": round(wall - shards_done, 3),
        "merge_share": round((wall - shards_done) / wall, 3),
        "overhead_s": round(shards_done - shard_max, 3),
        "solved": solved,
        "queries": len(answers),
    }


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--scenes", nargs="*", default=list(SCENES))
    p.add_argument("--workers", nargs="*", type=int, default=WORKERS)
    p.add_argument("--out", default="results.json")
    args = p.parse_args()
    ray.init(num_cpus=2)
    out = {"ray": ray_overhead(), "runs": []}
    print(out["ray"], flush=True)
    for name in args.scenes:
        path, ladder = SCENES[name]
        scene = viaroad.Scene.load(path)
        ends = scene.sample_free(2 * QUERIES, seed=11)
        starts, goals = ends[:QUERIES], ends[QUERIES:]
        for w in args.workers:
            for t in ladder:
                r = one(path, w, t, starts, goals)
                r["scene"] = name
                out["runs"].append(r)
                print(json.dumps(r), flush=True)
                (HERE / args.out).write_text(json.dumps(out, indent=1))
                if r["solved"] >= 0.99 * r["queries"]:
                    break
    ray.shutdown()


if __name__ == "__main__":
    sys.exit(main())
