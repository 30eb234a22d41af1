#!/usr/bin/env bash
# The Panda's cage workcell on one and two rayon threads, before (a binary of 72a4a25) and
# after the race runs its sides in turn when no pool thread is free; and two cage queries in
# one batch through `viaroad query`.
# PROBLEMS: the MotionBenchMaker problems of the vamp-planner 0.6.4 sdist (resources/panda/problems).
set -euo pipefail
P=${PROBLEMS:?set PROBLEMS to the sdist's resources/panda/problems}
BEFORE=${BEFORE:?a viaroad binary built at 72a4a25}
AFTER=${AFTER:-target/release/viaroad}
OUT=${OUT:-/tmp/race-in-turn}
run() { # binary threads label
  echo "== $3, RAYON_NUM_THREADS=$2, $(date +%T), load $(cut -d' ' -f1 /proc/loadavg)"
  RAYON_NUM_THREADS=$2 "$1" bench mbm "$P/cage_panda" --robot scenes/arms/panda --workcell \
    --nodes 200 --query-time 5 --limit 100 --keep-answers --race 2 --seed 1 --out "$OUT/$3-$2" | tail -1
}
run "$AFTER" 1 after
run "$AFTER" 2 after
run "$BEFORE" 1 before
