#!/usr/bin/env bash
# The race after the head start with the trees on the caller's thread (VIAROAD) beside the
# planner before it (BEFORE): the workcell beside VAMP, alternating, twice each (1 and 2 threads).
#
#   VIAROAD=… BEFORE=… race.sh     (binaries named after their commits)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$HERE"
: "${VIAROAD:?the viaroad binary}" "${BEFORE:?the binary before}"
export MBM="${MBM:-/tmp/mbm}"
for k in 1 2; do
  VIAROAD="$VIAROAD" OUT="$HERE/race-$k" bash ../2026-12-07-workcell/run.sh
  echo "binary: $(basename "$VIAROAD")" >> "race-$k/machine.txt"
  VIAROAD="$BEFORE" OUT="$HERE/race-before-$k" bash ../2026-12-07-workcell/run.sh
  echo "binary: $(basename "$BEFORE")" >> "race-before-$k/machine.txt"
done
