#!/bin/sh
# Straight shortcuts (the default) against staircases only (--no-straight), one after the other.
# PROBLEMS: MotionBenchMaker's problems/ from the vamp-planner 0.6.4 sdist; SUB15: the first 15
# problems of each family (symlinks).
set -e
V=${V:-target/release/viaroad}
OUT=${OUT:-/tmp/straight}
for mode in stairs straight; do
  flag=""; [ $mode = stairs ] && flag="--no-straight"
  $V bench mbm "$PROBLEMS" --robot scenes/arms/panda --workcell --nodes 200 --query-time 5 \
    --limit 100 --keep-answers --race 2 $flag --out "$OUT/workcell-$mode"
done
for mode in stairs straight; do
  flag=""; [ $mode = stairs ] && flag="--no-straight"
  $V bench mbm "$SUB15" --robot scenes/arms/panda --time 5 $flag --out "$OUT/problems-$mode"
done
# The final runs (after the second commit): /tmp/final/run.sh's order, summarised by sum.py.
W="--workcell --nodes 200 --query-time 5 --limit 100 --keep-answers --race 2"
for seed in 1 2 3; do
  $V bench mbm "$PROBLEMS" --robot scenes/arms/panda $W --seed $seed --out "$OUT/wc-s$seed"
done
$V bench mbm "$PROBLEMS" --robot scenes/arms/panda $W --no-straight --out "$OUT/wc-s1-stairs"
$V bench mbm "$PROBLEMS" --robot scenes/arms/panda --time 5 --out "$OUT/p700"
# The UR5 (UR5_PROBLEMS, UR5_ROBOT from the same sdist), both ways.
$V bench mbm "$UR5_PROBLEMS" --robot "$UR5_ROBOT" $W --out "$OUT/ur5"
$V bench mbm "$UR5_PROBLEMS" --robot "$UR5_ROBOT" $W --no-straight --out "$OUT/ur5-stairs"
