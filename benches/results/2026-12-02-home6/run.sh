#!/bin/sh
# Home, the 50 shipped queries, --shorten fast, one thread, on one 10 000-node roadmap: before
# (1773ee4) and after (attaching tries direct paths first), alternating, then callgrind.
set -eu
W=$(cd "$(dirname "$0")/../../.." && pwd)
BEFORE=${BEFORE:-/tmp/viaroad-1773}; AFTER=${AFTER:-$W/target/release/viaroad}; OUT=${OUT:-/tmp/home6}
mkdir -p "$OUT"
SCENE=$W/scenes/ompl/3D/Home.cfg; Q=$W/scenes/ompl/queries/Home_seed1_50.txt
export RAYON_NUM_THREADS=1
MAP=$OUT/home10k.bin
[ -f "$MAP" ] || "$BEFORE" build "$SCENE" --nodes 10000 --seed 1 --output "$MAP" >/dev/null
for i in 1 2 3; do
  for s in before after; do
    b=$BEFORE; [ $s = after ] && b=$AFTER
    echo "$(date -u +%H:%M:%S) $s run $i, load: $(cut -d' ' -f1-3 /proc/loadavg)"
    "$b" query "$MAP" --scene "$SCENE" --queries "$Q" --shorten fast --json >"$OUT/$s-$i.jsonl"
  done
done
python3 "$W/benches/results/2026-12-02-home/stats.py" "$OUT"/before-*.jsonl "$OUT"/after-*.jsonl
for s in before after; do
  b=$BEFORE; [ $s = after ] && b=$AFTER
  valgrind --tool=callgrind --callgrind-out-file="$OUT/cg-$s.out" "$b" query "$MAP" --scene "$SCENE" \
      --queries "$Q" --shorten fast --json 2>&1 >/dev/null | sed -n "s/.*I *refs: */$s callgrind instructions: /p"
done
