#!/bin/sh
# The arm oracle's hot path (2026-12-04 evening): OLD (main 964df60) against NEW, one run at a
# time, alone, interleaved. PROBLEMS: the MotionBenchMaker Panda problems (pip download --no-deps
# vamp-planner; untar; tar xjf .../resources/panda/problems.tar.bz2).
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
OLD=${OLD:-/tmp/old-target/release/viaroad}
NEW=${NEW:-target/release/viaroad}
OUT=${OUT:-/tmp/hot-path}
W="--robot scenes/arms/panda --workcell --nodes 200 --query-time 5 --limit 30 --keep-answers"
for v in OLD NEW; do
  eval V=\$$v
  $V bench mbm $P $W --out $OUT/workcell-in-turn-$v
done
for v in OLD NEW; do
  eval V=\$$v
  $V bench mbm $P $W --race 50 --out $OUT/workcell-race50-$v
done
for v in OLD NEW; do
  eval V=\$$v
  $V bench mbm $P --robot scenes/arms/panda --time 5 --limit 20 --out $OUT/mbm140-$v
done
