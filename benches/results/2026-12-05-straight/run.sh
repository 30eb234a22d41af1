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
