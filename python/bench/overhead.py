"""Python overhead per `Roadmap.query` call: the wall time of the Python call
against the time of the Rust call inside it (`QueryResult.ms`, measured around
`QueryPlanner::query`), on the discs demo roadmap and, if `cargo bench --bench serve` has
learnt it, OMPL.app's Home. The difference is what Python adds: reading start and goal,
building the planner, releasing and taking back the interpreter, making the numpy paths.

    python python/bench/overhead.py [QUERIES]
"""

import statistics
import sys
import time
from pathlib import Path

import viaroad

ROOT = Path(__file__).resolve().parents[2]
# no time limit and no growing: a query the roadmap cannot answer fails fast instead of
# growing a copy of it for 10 s, which would decide the batch figure alone
OPTS = dict(time=None, grow=False)


def measure(name, scene, roadmap, n):
    free = scene.sample_free(2 * n, seed=12)
    starts, goals = free[:n], free[n:]
    for s, g in zip(starts[:20], goals[:20]):  # warm-up
        roadmap.query(s, g, **OPTS)
    wall, rust = [], []
    for s, g in zip(starts, goals):
        t0 = time.perf_counter()
        r = roadmap.query(s, g, **OPTS)
        wall.append((time.perf_counter() - t0) * 1e3)
        rust.append(r.ms)
    over = [(w - r) * 1e3 for w, r in zip(wall, rust)]
    t0 = time.perf_counter()
    roadmap.query_many(starts, goals, **OPTS)
    batch = (time.perf_counter() - t0) * 1e3 / n
    print(
        f"| {name} | {n} | {statistics.median(rust):.3f} | {statistics.median(wall):.3f} "
        f"| {statistics.median(over):.1f} | {statistics.mean(over):.1f} | {batch:.3f} |"
    )


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    print("| roadmap | queries | Rust call p50 ms | Python call p50 ms | overhead p50 µs | overhead mean µs | query_many ms/query |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    discs = viaroad.Scene.load(ROOT / "scenes" / "discs-cluttered.toml")
    measure("discs-cluttered", discs, viaroad.Roadmap.load(ROOT / "roadmaps" / "discs-cluttered.bin", discs), n)
    home_map = ROOT / "target" / "bench-serve" / "home.bin"
    if home_map.exists():
        home = viaroad.Scene.load(ROOT / "scenes" / "ompl" / "3D" / "Home.cfg")
        measure("OMPL.app Home", home, viaroad.Roadmap.load(home_map, home), max(20, n // 10))


if __name__ == "__main__":
    main()
