#!/usr/bin/env bash
# A step of the arm race (VIAROAD) beside the planner before this stop (BEFORE): the trained
# workcell beside VAMP, alternating, three times each (1 and 2 threads); then VAMP and VIAROAD on
# all 700 Panda problems. TAG prefixes the folders (the first step ran with TAG=first-).
#
#   VIAROAD   the viaroad binary of this step (binaries named after their commits)
#   BEFORE    the viaroad binary of the commit before
#   MBM       ROBOT/problems/ folders (default /tmp/mbm)
#   PANDA     0: the workcell runs only
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$HERE"
: "${VIAROAD:?the viaroad binary}" "${BEFORE:?the binary before}"
TAG="${TAG:-}"
export MBM="${MBM:-/tmp/mbm}"
WORKCELL=../2026-12-07-workcell/run.sh
for k in 1 2 3; do
  VIAROAD="$VIAROAD" OUT="$HERE/${TAG}workcell-$k" bash $WORKCELL
  echo "binary: $(basename "$VIAROAD")" >> "${TAG}workcell-$k/machine.txt"
  VIAROAD="$BEFORE" OUT="$HERE/${TAG}workcell-before-$k" bash $WORKCELL
  echo "binary: $(basename "$BEFORE")" >> "${TAG}workcell-before-$k/machine.txt"
done
if [ "${PANDA:-1}" != 0 ]; then
  VIAROAD="$VIAROAD" OUT="$HERE/${TAG}runs" bash ../2026-12-07-arm-speed-3/run.sh
fi
