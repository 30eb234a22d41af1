#!/usr/bin/env bash
# The workcell beside VAMP with this folder's planner and with the one before it, alternating
# (twice each, one and two threads), then the Panda's 700 single problems beside VAMP.
#
#   VIAROAD=… BEFORE=… campaign.sh
#   VIAROAD   the viaroad binary under test (named after its commit: its name goes into machine.txt)
#   BEFORE    the viaroad binary of the commit before (the same runs, for the side by side)
#   MBM       ROBOT/problems/ folders (default /tmp/mbm)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$HERE"
: "${VIAROAD:?the viaroad binary}" "${BEFORE:?the binary before}"
export MBM="${MBM:-/tmp/mbm}"
WORKCELL=../2026-12-07-workcell/run.sh
for k in 1 2; do
  VIAROAD="$VIAROAD" OUT="$HERE/workcell-$k" bash $WORKCELL
  echo "binary: $(basename "$VIAROAD")" >> "workcell-$k/machine.txt"
  VIAROAD="$BEFORE" OUT="$HERE/workcell-before-$k" bash $WORKCELL
  echo "binary: $(basename "$BEFORE")" >> "workcell-before-$k/machine.txt"
done
VIAROAD="$VIAROAD" OUT="$HERE/runs" bash ../2026-12-07-arm-speed-3/run.sh
