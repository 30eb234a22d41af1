#!/usr/bin/env bash
# The workcell (as ../2026-12-07-workcell/run.sh runs it, without VAMP) with two binaries in
# turn, ROUNDS times, on 1 and 2 threads: each family's solved, tree requests, p50 and p95.
#
#   BASE=… NEW=… workcell_pairs.sh OUT
#
#   DIR     the families (default $MBM/panda/problems: all seven)
#   LIMIT   requests asked per family (default 20)
#   TRAIN   requests learnt from per family, held out (default 80; 0: the sampled roadmap alone,
#           every request asked with LIMIT=100)
#   ROUNDS  default 3
set -euo pipefail
OUT=$1 ROUNDS=${ROUNDS:-3} MBM=${MBM:-/tmp/mbm}
DIR=${DIR:-$MBM/panda/problems} LIMIT=${LIMIT:-20} TRAIN=${TRAIN:-80}
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
mkdir -p "$OUT"
{
  echo "date: $(date -u +%FT%TZ)"
  echo "host: $(uname -n) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "BASE=$BASE NEW=$NEW DIR=$DIR LIMIT=$LIMIT TRAIN=$TRAIN ROUNDS=$ROUNDS"
} > "$OUT/machine.txt"
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    for side in base new; do
      bin=$BASE; [ "$side" = new ] && bin=$NEW
      dir="$OUT/$side-$threads-$round"
      RAYON_NUM_THREADS=$threads "$bin" bench mbm "$DIR" --robot "$ROOT/scenes/arms/panda" \
        --workcell --nodes 200 --race 2 --limit "$LIMIT" --train "$TRAIN" --shorten greedy \
        --out "$dir" > /dev/null 2>&1
      sed -n '3,9p' "$dir/workcell.md" | awk -F'|' -v s="$side" -v t="$threads" -v r="$round" \
        '{gsub(/ /,"",$2); printf "%s\t%s\t%s\t%s\tsolved %s/%s\ttrees %s\tp50 %s\tp95 %s\n", s, t, r, $2, $10, $9, $11, $14, $15}'
      rm -rf "$dir"/*.roadmap
    done
  done
done | tee "$OUT/pairs.tsv"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
