#!/usr/bin/env bash
# The trained workcell (as ../2026-12-07-workcell/run.sh runs it, without VAMP) with two
# binaries in turn, ROUNDS times, on 1 and 2 threads: the families' p50 and p95 of each run.
#
#   BASE=… NEW=… workcell_pairs.sh OUT
set -euo pipefail
OUT=$1 ROUNDS=${ROUNDS:-3} MBM=${MBM:-/tmp/mbm}
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
mkdir -p "$OUT"
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    for side in base new; do
      bin=$BASE; [ "$side" = new ] && bin=$NEW
      dir="$OUT/$side-$threads-$round"
      RAYON_NUM_THREADS=$threads "$bin" bench mbm "$MBM/panda/problems" --robot "$ROOT/scenes/arms/panda" \
        --workcell --nodes 200 --race 2 --limit 20 --train 80 --shorten greedy --out "$dir" > /dev/null 2>&1
      sed -n '3,9p' "$dir/workcell.md" | awk -F'|' -v s="$side" -v t="$threads" -v r="$round" \
        '{gsub(/ /,"",$2); printf "%s\t%s\t%s\t%s\tsolved %s/%s\ttrees %s\tp50 %s\tp95 %s\n", s, t, r, $2, $10, $9, $11, $14, $15}'
      rm -rf "$dir"/*.roadmap
    done
  done
done | tee "$OUT/pairs.tsv"
