"""Learn a roadmap on a Ray cluster: W tasks learn shards, a reduction tree of merges joins
them, the driver saves the result.

    python python/examples/ray_learn.py scenes/ompl/3D/Home.cfg --workers 4 --time 60 -o home.bin
    python python/examples/ray_learn.py SCENE --workers 64 --nodes 200000 -o out.bin --address auto

Each task calls `viaroad.Roadmap.build(scene, shard=(i, W), ...)`: shard i of W draws from its
own random streams (derived from the seed, i and W), so the shards are independent samples of
the whole scene and a node budget (`--nodes`) is split between them. The shards come back to the
driver as Ray object references; a merge task takes two (or `--fan-in`) of them and returns
their merge, and the merges are merged again until one roadmap is left: ceil(log_k W) levels,
each level's merges running side by side. `Roadmap` objects pickle through their file's bytes
and their scene's path, so the scene file must be at the same path on every node of a cluster
(a shared file system, or the same checkout; or ship it with `runtime_env={"working_dir": ...}`
and give a relative path).

With `--nodes` and no `--time` the result is the same file on every run and every cluster size
for the same W: shards are reproducible, and a merge does not depend on the order its parts
arrive in. `--time` bounds each shard's learning (and `--merge-time` each merge), which is
faster to reason about on a cluster but not reproducible.

Local runtime: `ray.init()` (the default here); a running cluster: `--address auto` on one of
its nodes, or `--address ray://HEAD:10001` from outside (Ray Client).
"""

import argparse
import sys
import time

import ray

import viaroad


@ray.remote
def learn_shard(scene_path, index, count, seed, nodes, seconds):
    """Shard `index` of `count` (from 1), learnt on a worker."""
    scene = viaroad.Scene.load(scene_path)
    began = time.perf_counter()
    roadmap = viaroad.Roadmap.build(
        scene, shard=(index, count), seed=seed, nodes=nodes, time=seconds
    )
    return roadmap, time.perf_counter() - began


@ray.remote
def merge_parts(scene_path, seconds, *parts):
    """The merge of `parts` (Roadmaps, resolved by Ray before the call), on a worker."""
    scene = viaroad.Scene.load(scene_path)
    began = time.perf_counter()
    merged = viaroad.Roadmap.merge(list(parts), scene, time=seconds)
    return merged, time.perf_counter() - began


@ray.remote
def first(pair):
    """The roadmap of a (roadmap, seconds) pair."""
    return pair[0]


def reduction_tree(scene_path, refs, fan_in, seconds):
    """Merges `refs` (object references of Roadmaps) level by level, `fan_in` at a time;
    returns the reference of the last merge and the references of every merge's timing."""
    timings = []
    level = list(refs)
    while len(level) > 1:
        nxt = []
        for k in range(0, len(level), fan_in):
            group = level[k : k + fan_in]
            if len(group) == 1:
                nxt.append(group[0])
                continue
            pair = merge_parts.remote(scene_path, seconds, *group)
            timings.append(pair)
            nxt.append(first.remote(pair))
        level = nxt
    return level[0], timings


def run(args):
    """Learns, merges and saves; returns a summary dict (also printed)."""
    began = time.perf_counter()
    shards = [
        learn_shard.remote(args.scene, i, args.workers, args.seed, args.nodes, args.time)
        for i in range(1, args.workers + 1)
    ]
    roadmaps = [first.remote(s) for s in shards]
    top, merges = reduction_tree(args.scene, roadmaps, args.fan_in, args.merge_time)
    learnt = ray.get(shards)
    learn_wall = time.perf_counter() - began
    merged = ray.get(top)
    merge_times = [t for _, t in ray.get(merges)]
    merged.save(args.output)
    info = merged.info()
    summary = {
        "workers": args.workers,
        "nodes": info["nodes"],
        "edges": info["edges"],
        "components": info["components"],
        "largest": info["largest_component"],
        "shard_seconds": [round(t, 3) for _, t in learnt],
        "merge_seconds": [round(t, 3) for t in merge_times],
        "learn_wall_seconds": round(learn_wall, 3),
        "wall_seconds": round(time.perf_counter() - began, 3),
        "digest": merged.digest(),
        "output": args.output,
    }
    print(summary)
    return summary


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene", help="scene file (.toml, OMPL.app .cfg), at the same path on every node")
    p.add_argument("--workers", type=int, default=2, help="shards, one Ray task each")
    p.add_argument("--time", type=float, help="seconds each shard learns")
    p.add_argument("--nodes", type=int, help="nodes of all shards together (reproducible)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--fan-in", type=int, default=2, help="parts per merge of the reduction tree")
    p.add_argument("--merge-time", type=float, help="seconds each merge may connect parts")
    p.add_argument("--address", help="a Ray cluster's address (default: a local runtime)")
    p.add_argument("--cpus", type=int, help="CPUs of the local runtime (default: all)")
    p.add_argument("-o", "--output", required=True, help="where to save the merged roadmap")
    args = p.parse_args(argv)
    if args.workers < 1 or args.fan_in < 2:
        p.error("--workers must be at least 1 and --fan-in at least 2")
    if args.time is None and args.nodes is None:
        p.error("give --time, --nodes or both")
    if args.address:
        ray.init(address=args.address)
    else:
        ray.init(num_cpus=args.cpus)
    try:
        run(args)
    finally:
        ray.shutdown()


if __name__ == "__main__":
    sys.exit(main())
