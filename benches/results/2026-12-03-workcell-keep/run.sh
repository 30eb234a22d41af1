#!/usr/bin/env bash
# The workcell with and without answers kept, back to back (2026-12-03, binary of the commit
# that adds --keep-answers). PROBLEMS: MotionBenchMaker's problems/ (README: Robot arms).
set -euo pipefail
PROBLEMS=${PROBLEMS:-/tmp/vamp/mbm/problems}
for k in off on; do
  flag=""; [ "$k" = on ] && flag="--keep-answers"
  target/release/viaroad bench mbm "$PROBLEMS" --robot scenes/arms/panda --workcell --nodes 200 \
    --query-time 5 --limit 30 $flag --out "/tmp/wc/$k" > "/tmp/wc/$k.log" 2>&1
done
