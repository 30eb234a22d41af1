#!/bin/sh
# Swaps in a corridor (scenes/bodies/swap-corridor-K.toml, K = 2, 3, 4, 6): single queries
# with 10 s each, by a roadmap grown from start and goal with four local methods, by trees and
# by the portfolio; then a roadmap learnt for 20 s and the scene's query against it. Every
# path of `--check` runs is re-checked by the independent checker (raw and shortened).
# Run from the repository root: sh benches/results/2026-12-06-several-bodies/run.sh > OUT
set -u
V=target/release/viaroad
T=${TMPDIR:-/tmp}/several-bodies
mkdir -p "$T"
for k in 2 3 4 6; do
  S=scenes/bodies/swap-corridor-$k.toml
  for local in straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint; do
    echo "## k=$k solve --roadmap --local $local"
    $V solve "$S" --roadmap --time 10 --local "$local" --check --json \
      | python3 -c 'import json,sys
for l in sys.stdin:
    d=json.loads(l); [d.pop(x,None) for x in ("path","shortened")]; print(json.dumps(d))'
  done
  echo "## k=$k solve --tree"
  $V solve "$S" --tree --time 10
  echo "## k=$k solve --portfolio"
  $V solve "$S" --portfolio --time 10
  echo "## k=$k build --time 20 + query --check"
  $V build "$S" -o "$T/swap$k.bin" --time 20 --seed 1
  $V query "$T/swap$k.bin" --scene "$S" --check --time 10
done
