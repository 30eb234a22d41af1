#!/bin/sh
# Every several-body scene shipped, on the merged tree: `solve --time 10 --check` with seeds
# 1-3, then `build --time 10` and `query --check --time 10` for the swaps. From the repository
# root: sh benches/results/2026-12-07-several-bodies-final/run.sh > …/run-output.txt
set -u
V=${VIAROAD:-target/release/viaroad}
T=${TMPDIR:-/tmp}
echo "# $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg) commit: $(git rev-parse --short HEAD)"
for s in swap-corridor-2 swap-corridor-3 swap-corridor-4 swap-corridor-6 \
         cubes-into-boxes-2 cubes-into-boxes-3 movers-room; do
  for seed in 1 2 3; do
    echo "## solve $s --seed $seed"
    $V solve scenes/bodies/$s.toml --time 10 --check --seed $seed 2>&1 | grep -E "query|certif|warning"
  done
done
for k in 2 3 4 6; do
  echo "## build swap-corridor-$k --time 10, then query"
  $V build scenes/bodies/swap-corridor-$k.toml --time 10 -o "$T/swap-$k.roadmap" 2>&1 | head -1
  $V query "$T/swap-$k.roadmap" --scene scenes/bodies/swap-corridor-$k.toml --check --time 10 2>&1 | tail -1
done
for k in 4 6; do
  echo "## query swap-corridor-$k --keep-answers, then the kept roadmap asked again"
  $V query "$T/swap-$k.roadmap" --scene scenes/bodies/swap-corridor-$k.toml --check --time 10 \
    --keep-answers "$T/swap-$k-kept.roadmap" 2>&1 | tail -1
  $V query "$T/swap-$k-kept.roadmap" --scene scenes/bodies/swap-corridor-$k.toml --check --time 10 2>&1 | tail -2
done
echo "# done $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg)"
