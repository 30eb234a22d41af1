#!/bin/sh
# The workcell's roadmap and trees in turn, or racing (2026-12-04), one run at a time, alone.
# PROBLEMS: the MotionBenchMaker Panda problems (pip download --no-deps vamp-planner; untar;
# tar xjf .../resources/panda/problems.tar.bz2).
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=${VIAROAD:-target/release/viaroad}
W="--robot scenes/arms/panda --workcell --nodes 200 --query-time 5 --limit 30 --keep-answers"
$V bench mbm $P $W --out /tmp/wc-in-turn
# in-turn-no-grow: a flag of the session's intermediate binary (`--no-grow`, no copy of the
# roadmap grown before the trees), dropped after this run showed no difference
$V bench mbm $P $W --race --out /tmp/wc-race0
$V bench mbm $P $W --race 50 --out /tmp/wc-race50
$V bench mbm $P $W --race 200 --out /tmp/wc-race200
