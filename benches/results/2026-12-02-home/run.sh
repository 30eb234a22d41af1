#!/bin/sh
# Home, the 50 shipped queries, --shorten fast, one thread: before (3f1de36) and after
# (branch home5), back to back, twice each, then callgrind (load independent).
# BEFORE / AFTER: the two release binaries; OUT: where the JSON lines go.
set -eu
W=$(cd "$(dirname "$0")/../../.." && pwd)
BEFORE=${BEFORE:-/tmp/home5/viaroad-before}
AFTER=${AFTER:-/tmp/home5/viaroad-after}
OUT=${OUT:-/tmp/home5/run}
mkdir -p "$OUT"
SCENE=$W/scenes/ompl/3D/Home.cfg
Q=$W/scenes/ompl/queries/Home_seed1_50.txt
export RAYON_NUM_THREADS=1
# the roadmap: both binaries learn the same file
for s in before after; do
    b=$BEFORE; [ $s = after ] && b=$AFTER
    /usr/bin/time -f "$s build: %e s wall, %U s user" \
        "$b" build "$SCENE" --nodes 10000 --seed 1 --output "$OUT/home10k-$s.bin" >/dev/null
done
cmp "$OUT/home10k-before.bin" "$OUT/home10k-after.bin" && echo "roadmaps identical"
MAP=$OUT/home10k-before.bin
for i in 1 2; do
    for s in before after; do
        b=$BEFORE; [ $s = after ] && b=$AFTER
        echo "$(date -u +%H:%M:%S) $s run $i, load: $(cut -d' ' -f1-3 /proc/loadavg)"
        "$b" query "$MAP" --scene "$SCENE" --queries "$Q" --shorten fast --json >"$OUT/$s-$i.jsonl"
    done
done
python3 "$W/benches/results/2026-12-02-home/stats.py" "$OUT"/before-*.jsonl "$OUT"/after-*.jsonl
for s in before after; do
    b=$BEFORE; [ $s = after ] && b=$AFTER
    valgrind --tool=callgrind --callgrind-out-file="$OUT/cg-$s.out" "$b" query "$MAP" \
        --scene "$SCENE" --queries "$Q" --shorten fast --json 2>&1 >/dev/null |
        sed -n "s/.*I *refs: */$s callgrind instructions: /p"
done
