#!/usr/bin/env bash
# The quick try of a query as yes/no questions (2026-12-03): before (OLD, the binary of 890fcd7)
# and after (NEW), back to back. PROBLEMS: MotionBenchMaker's problems/ (README: Robot arms).
set -euo pipefail
W=$(cd "$(dirname "$0")/../../.." && pwd)
OLD=${OLD:-/tmp/viaroad-old}; NEW=${NEW:-$W/target/release/viaroad}; OUT=${OUT:-/tmp/quick}
PROBLEMS=${PROBLEMS:-/tmp/vamp/mbm/problems}
mkdir -p "$OUT"
for v in old new; do
  b=$OLD; [ $v = new ] && b=$NEW
  "$b" bench mbm "$PROBLEMS" --robot "$W/scenes/arms/panda" --workcell --nodes 200 \
    --query-time 5 --limit 30 --keep-answers --out "$OUT/wc-$v" > "$OUT/wc-$v.log" 2>&1
done
# Home: the 50 shipped queries on a 10 000-node roadmap, one thread, alternating, then callgrind
SCENE=$W/scenes/ompl/3D/Home.cfg; Q=$W/scenes/ompl/queries/Home_seed1_50.txt; MAP=$OUT/home10k.bin
export RAYON_NUM_THREADS=1
[ -f "$MAP" ] || "$OLD" build "$SCENE" --nodes 10000 --seed 1 --output "$MAP" >/dev/null
for i in 1 2 3; do
  for v in old new; do
    b=$OLD; [ $v = new ] && b=$NEW
    "$b" query "$MAP" --scene "$SCENE" --queries "$Q" --shorten fast --json > "$OUT/home-$v-$i.jsonl"
  done
done
python3 "$W/benches/results/2026-12-02-home/stats.py" "$OUT"/home-old-*.jsonl "$OUT"/home-new-*.jsonl
for v in old new; do
  b=$OLD; [ $v = new ] && b=$NEW
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg-$v.out" "$b" query "$MAP" --scene "$SCENE" \
    --queries "$Q" --shorten fast --json 2>&1 >/dev/null | sed -n "s/.*I *refs: */$v callgrind instructions: /p"
done
