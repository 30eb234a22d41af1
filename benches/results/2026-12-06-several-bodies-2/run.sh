#!/bin/sh
# Several bodies, second part: (1) the `bodies` sampler (bodies placed one at a time) on the
# swaps in a corridor, k = 3, 4, 6: roadmaps learnt for 10 s with it and with `uniform`, the
# scene's query against each, and single queries; (2) the movers in a room
# (scenes/bodies/movers-room.toml): single queries in 10 s (solve's default, a roadmap grown
# with four local methods), a roadmap learnt for 10 s, and `bench local` against `straight` and
# `sampled` (every path re-checked by the independent checker). Every `--check` path is
# re-checked by the independent checker (raw and shortened).
# Run from the repository root: sh benches/results/2026-12-06-several-bodies-2/run.sh > OUT
set -u
V=target/release/viaroad
T=${TMPDIR:-/tmp}/several-bodies-2
mkdir -p "$T"
strip() {
  python3 -c 'import json,sys
for l in sys.stdin:
    d=json.loads(l); [d.pop(x,None) for x in ("path","shortened")]; print(json.dumps(d))'
}
for k in 3 4 6; do
  S=scenes/bodies/swap-corridor-$k.toml
  for sampler in uniform bodies; do
    echo "## k=$k build --time 10 --sampler $sampler + query --check --time 10"
    $V build "$S" -o "$T/swap$k-$sampler.bin" --time 10 --seed 1 --sampler $sampler
    $V query "$T/swap$k-$sampler.bin" --scene "$S" --check --time 10
  done
  echo "## k=$k solve --time 10 --check"
  $V solve "$S" --time 10 --check
  echo "## k=$k solve --roadmap --local viapoint --time 10 --check"
  $V solve "$S" --roadmap --local viapoint --time 10 --check
done
S=scenes/bodies/movers-room.toml
echo "## movers solve --time 10 --check"
$V solve "$S" --time 10 --check --json | strip
for local in straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint; do
  echo "## movers solve --roadmap --local $local --time 10 --check"
  $V solve "$S" --roadmap --time 10 --local "$local" --check --json | strip
done
echo "## movers solve --tree --time 10 --check"
$V solve "$S" --tree --time 10 --check
echo "## movers build --time 10 + query --check"
$V build "$S" -o "$T/movers.bin" --time 10 --seed 1
$V query "$T/movers.bin" --scene "$S" --check --time 10
echo "## movers bench local"
$V bench local "$S" \
  --methods straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint \
  --runs 3 --nodes 3000 --queries 20 --out "$T/movers-bench"
cat "$T/movers-bench"/*.md 2>/dev/null
