#!/bin/sh
# Which tree gets the next extend (2026-12-03). The policies other than alternating (the default)
# and `--tree-balance true` came from a temporary hook, `policies.patch` (VR_BAL=third|calls|trap),
# applied to main 2985385 for these runs only and not kept.
# PROBLEMS: the MotionBenchMaker Panda problems (pip download --no-deps vamp-planner; untar;
# tar xjf .../resources/panda/problems.tar.bz2).
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=${VIAROAD:-target/release/viaroad}
R="--robot scenes/arms/panda --time 5 --direct-calls 300"
# all 700, the two policies side by side (one per core)
$V bench mbm $P $R --out /tmp/a700-default &
VR_BAL=third $V bench mbm $P $R --out /tmp/a700-third &
wait
# the first 30 of each family
$V bench mbm $P $R --limit 30 --out /tmp/l30-default &
$V bench mbm $P $R --limit 30 --tree-balance true --out /tmp/l30-balance &
wait
VR_BAL=calls $V bench mbm $P $R --limit 30 --out /tmp/l30-calls &
VR_BAL=third $V bench mbm $P $R --limit 30 --out /tmp/l30-third &
wait
# twelve.md: a directory of symlinks to the twelve problems named there, each policy and seed
# (--seed 2, --seed 3), --tree-coarse true, --tree-restart 1000 / 2000
# two streams on two threads (the code of this commit)
$V bench mbm $P $R --tree-streams 2 --out /tmp/a700-streams2
