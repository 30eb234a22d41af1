#!/bin/sh
# `solve --json --time 10` (the default portfolio, seed 1) on single-body scenes and on the
# several-body scenes, one line per scene: solved, method, intersect calls, seconds, nodes.
# Run from the repository root with the binary to measure:
#   sh benches/results/2026-12-07-several-bodies-4/compare.sh target/release/viaroad > OUT
set -u
V=${1:-target/release/viaroad}
for S in scenes/discs-cluttered.toml scenes/se2-corridor.toml scenes/piano.toml \
  scenes/cube-into-box.toml scenes/ompl/2D/Maze_planar.cfg scenes/ompl/2D/BugTrap_planar.cfg \
  scenes/ompl/3D/Easy.cfg scenes/ompl/3D/cubicles.cfg \
  scenes/bodies/movers-room.toml scenes/bodies/swap-corridor-2.toml \
  scenes/bodies/swap-corridor-3.toml scenes/bodies/cubes-into-boxes-2.toml \
  scenes/bodies/cubes-into-boxes-3.toml; do
  $V solve "$S" --time 10 --json | python3 -c '
import json, sys
s = sys.argv[1]
for l in sys.stdin:
    d = json.loads(l)
    print("%-42s q%d solved=%-5s method=%-8s calls=%8d nodes=%6d s=%.3f" % (s, d["query"], d["solved"], d["method"], d["calls"], d["nodes"], d["seconds"]))
' "$S"
done
