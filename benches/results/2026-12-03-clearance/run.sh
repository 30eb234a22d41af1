#!/usr/bin/env bash
# Conservative advancement ahead of the exact arm sweep (2026-12-03 evening): before (OLD, the
# binary of 7f5e76b) and after (NEW), back to back. PROBLEMS: MotionBenchMaker's problems/
# (README: Robot arms).
set -euo pipefail
W=$(cd "$(dirname "$0")/../../.." && pwd)
OLD=${OLD:-/tmp/viaroad-old}; NEW=${NEW:-$W/target/release/viaroad}; OUT=${OUT:-/tmp/clearance}
PROBLEMS=${PROBLEMS:-/tmp/vamp/mbm/problems}
mkdir -p "$OUT"
# the workcell: one 200-node roadmap per family, 30 requests each, answers kept
for v in old new; do
  b=$OLD; [ $v = new ] && b=$NEW
  "$b" bench mbm "$PROBLEMS" --robot "$W/scenes/arms/panda" --workcell --nodes 200 \
    --query-time 5 --limit 30 --keep-answers --out "$OUT/wc-$v" > "$OUT/wc-$v.log" 2>&1
done
# single queries: the first 15 problems of each family, 5 s each
for v in old new; do
  b=$OLD; [ $v = new ] && b=$NEW
  "$b" bench mbm "$PROBLEMS" --robot "$W/scenes/arms/panda" --time 5 --direct-calls 300 \
    --limit 15 --out "$OUT/single-$v" > "$OUT/single-$v.log" 2>&1
done
# table_pick's workcell from the CLI, one thread: latencies, then callgrind of the batch
SCENE=$W/scenes/arms/panda-table_pick-1.toml; Q=$W/benches/results/2026-12-03-quick-yesno/keep-queries.txt
MAP=$OUT/tp200.bin
[ -f "$MAP" ] || "$OLD" build "$SCENE" --nodes 200 --seed 1 -o "$MAP" >/dev/null
export RAYON_NUM_THREADS=1
for i in 1 2 3; do
  for v in old new; do
    b=$OLD; [ $v = new ] && b=$NEW
    rm -f "$OUT/kept-$v.bin"
    "$b" query "$MAP" --scene "$SCENE" --queries "$Q" --time 5 --json \
      --keep-answers "$OUT/kept-$v.bin" > "$OUT/tp-$v-$i.jsonl" 2>/dev/null
  done
done
for v in old new; do
  b=$OLD; [ $v = new ] && b=$NEW
  rm -f "$OUT/kept-$v.bin"
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg-$v.out" "$b" query "$MAP" --scene "$SCENE" \
    --queries "$Q" --time 50 --json --keep-answers "$OUT/kept-$v.bin" 2>&1 >/dev/null \
    | sed -n "s/.*I *refs: */$v callgrind instructions: /p"
  callgrind_annotate --inclusive=yes "$OUT/cg-$v.out" | grep -E "=> .*QueryPlanner::query_within " | head -1
done
