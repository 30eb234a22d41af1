#!/bin/sh
# The via-point planner's call budget before the trees, and racing the two (2026-12-04).
# PROBLEMS: the MotionBenchMaker Panda problems (pip download --no-deps vamp-planner; untar;
# tar xjf .../resources/panda/problems.tar.bz2).
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=${VIAROAD:-target/release/viaroad}
R="--robot scenes/arms/panda --time 5"
# the first 15 of each family, one budget at a time (first15-*)
for DC in 300 120 60 20 0; do
  $V bench mbm $P $R --limit 15 --direct-calls $DC --out /tmp/first15-dc$DC
done
# all 700: 60 alone, then 300 and 120 side by side (one per core)
$V bench mbm $P $R --direct-calls 60 --out /tmp/mbm700-dc60
$V bench mbm $P $R --direct-calls 300 --out /tmp/mbm700-dc300 &
$V bench mbm $P $R --direct-calls 120 --out /tmp/mbm700-dc120 &
wait
# racing (two threads), alone: the via-point planner beside one pair of trees, then beside two
$V bench mbm $P $R --direct-calls 300 --race --out /tmp/mbm700-race300
$V bench mbm $P $R --direct-calls 300 --race --tree-streams 2 --out /tmp/mbm700-race300-streams2
