#!/bin/sh
# k cubes into k boxes (scenes/bodies/cubes-into-boxes-K.toml, K = 2, 3; SE(3)^K): single
# queries with 10 s each, by a roadmap grown from start and goal with five local methods, by
# the default solve, by trees and by the via-point planner alone; then a roadmap learnt for
# 20 s and the scene's query against it; then `bench local` on K = 2 (random queries, node
# budgets). Every path of `--check` runs is re-checked by the independent checker (raw and
# shortened). Run from the repository root:
#   sh benches/results/2026-12-06-several-bodies-3d/run.sh > OUT
set -u
V=target/release/viaroad
T=${TMPDIR:-/tmp}/several-bodies-3d
mkdir -p "$T"
strip() {
  python3 -c 'import json,sys
for l in sys.stdin:
    d=json.loads(l); [d.pop(x,None) for x in ("path","shortened")]; print(json.dumps(d))'
}
for k in 2 3; do
  S=scenes/bodies/cubes-into-boxes-$k.toml
  for local in straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint:max=3,calls=1000,split=true viapoint; do
    echo "## k=$k solve --roadmap --local $local"
    $V solve "$S" --roadmap --time 10 --local "$local" --check --json | strip
  done
  echo "## k=$k solve (default)"
  $V solve "$S" --time 10 --check --json | strip
  echo "## k=$k solve --tree"
  $V solve "$S" --tree --time 10
  echo "## k=$k solve --local-only (deep via-point planner)"
  $V solve "$S" --local-only --check --json | strip
  echo "## k=$k build --time 20 + query --check"
  $V build "$S" -o "$T/boxes$k.bin" --time 20 --seed 1
  $V query "$T/boxes$k.bin" --scene "$S" --check --time 10
done
echo "## bench local, k=2"
$V bench local scenes/bodies/cubes-into-boxes-2.toml \
  --methods straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint:max=3,calls=1000,split=true \
  --runs 3 --nodes 4000 --queries 20 --out "$T/bench2"
cp "$T/bench2/summary.md" benches/results/2026-12-06-several-bodies-3d/bench-local-2-summary.md
echo "## k=3 build --time 20 --local viapoint:max=3,calls=1000,split=true + query --check"
S=scenes/bodies/cubes-into-boxes-3.toml
$V build "$S" -o "$T/boxes3-split.bin" --time 20 --seed 1 --local viapoint:max=3,calls=1000,split=true
$V query "$T/boxes3-split.bin" --scene "$S" --check --time 10
echo "## bench local, k=3"
$V bench local "$S" \
  --methods straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint:max=3,calls=1000,split=true \
  --runs 3 --nodes 4000 --queries 20 --out "$T/bench3"
cp "$T/bench3/summary.md" benches/results/2026-12-06-several-bodies-3d/bench-local-3-summary.md
