#!/bin/sh
# The workcell's trees grown from the bare ends (`--trees-from ends`, as before) against trees
# grown out of the roadmap (`--trees-from roadmap`, the new default), every family, answers
# kept: racing with the roadmap's 50 ms head start (`--race 50`, two rounds, alternating), and
# in turn (one thread; out of the roadmap the query grows the trees itself after attaching).
#   PROBLEMS=/path/to/vamp/problems V=target/release/viaroad sh run.sh
set -e
HERE=$(dirname "$0")
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=${V:-target/release/viaroad}
OUT=${OUT:-/tmp/rooted-trees}
for round in 1 2; do
  for m in ends roadmap; do
    $V bench mbm "$P" --robot scenes/arms/panda --workcell --nodes 200 --query-time 5 \
      --limit 30 --keep-answers --race 50 --trees-from $m --out "$OUT/$m-$round" \
      > "$OUT-$m-$round.log" 2>&1
    cp "$OUT/$m-$round/workcell.md" "$HERE/workcell-$m-$round.md"
    cp "$OUT/$m-$round/workcell.json" "$HERE/workcell-$m-$round.json"
  done
done
for m in ends roadmap; do
  $V bench mbm "$P" --robot scenes/arms/panda --workcell --nodes 200 --query-time 5 \
    --limit 30 --keep-answers --trees-from $m --out "$OUT/turn-$m" > "$OUT-turn-$m.log" 2>&1
  cp "$OUT/turn-$m/workcell.md" "$HERE/workcell-turn-$m.md"
  cp "$OUT/turn-$m/workcell.json" "$HERE/workcell-turn-$m.json"
done
