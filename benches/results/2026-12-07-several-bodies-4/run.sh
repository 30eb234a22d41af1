#!/bin/sh
# Several bodies, fourth part: what plain commands do on the shipped scenes of several bodies.
# BEFORE is a binary built at 33b5cf0 (the defaults before this change), AFTER this branch's.
# Run from the repository root:
#   BEFORE=/tmp/viaroad-base AFTER=target/release/viaroad \
#     sh benches/results/2026-12-07-several-bodies-4/run.sh > OUT
set -u
B=${BEFORE:?a binary built at 33b5cf0}
A=${AFTER:-target/release/viaroad}
D=benches/results/2026-12-07-several-bodies-4
S3=scenes/bodies/cubes-into-boxes-3.toml
T=${TMPDIR:-/tmp}/several-bodies-4
mkdir -p "$T"
summary() {
  python3 -c 'import json,sys
for l in sys.stdin:
    d=json.loads(l); print({k: d.get(k) for k in ("solved","method","calls","nodes","seconds","stop","certified")})'
}
echo "## 1. plain solve --time 10, three seeds, --check"
for v in "$B" "$A"; do
  for seed in 1 2 3; do
    echo "$v seed $seed: $($v solve $S3 --time 10 --seed $seed --check --json | summary)"
  done
done
echo "## 1. build --time 10 + query --check, default local method"
for v in "$B" "$A"; do
  echo "$v:"
  $v build $S3 -o "$T/cubes3.bin" --time 10 --seed 1 | head -1
  $v query "$T/cubes3.bin" --scene $S3 --check --time 10 | head -1
done
echo "## 1. the other scenes: solve --json --time 10"
for v in "$B" "$A"; do
  echo "$v:"
  sh $D/compare.sh "$v"
done
echo "## 2. node budgets: solve --roadmap --nodes N --local viapoint:max=3,calls=1000,split=true"
for v in "$B" "$A"; do
  for n in 100 1000 3000 4000; do
    echo "$v N=$n: $($v solve $S3 --roadmap --nodes $n --local viapoint:max=3,calls=1000,split=true --json | summary)"
  done
done
echo "## 3. solve --sampler (after only)"
for s in uniform bodies; do
  echo "movers-room --roadmap --sampler $s: $($A solve scenes/bodies/movers-room.toml --roadmap --nodes 3000 --sampler $s --json | summary)"
done
echo "## 5. the 3D still"
$A solve scenes/bodies/cubes-into-boxes-2.toml --check --path-out "$T/cubes-into-boxes-2.path"
