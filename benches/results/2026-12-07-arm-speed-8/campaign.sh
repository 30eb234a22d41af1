#!/usr/bin/env bash
# Everything this folder holds, back to back on one machine: the Panda's 700 problems beside
# VAMP (the new planner and the previous one, two pairs), the workcell beside VAMP (twice), the
# workcell with both planners in turn, and the UR5 and the Fetch beside VAMP.
#
#   NEW=… BASE=… campaign.sh      (the two viaroad binaries)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$HERE"
RUN=../2026-12-07-arm-speed-3/run.sh
for k in 1 2; do
  VIAROAD=$NEW OUT=$HERE/runs$k bash $RUN
  VIAROAD=$BASE OUT=$HERE/runs$k-base bash $RUN
done
VIAROAD=$NEW OUT=$HERE/workcell bash ../2026-12-07-workcell/run.sh
VIAROAD=$NEW OUT=$HERE/workcell-again bash ../2026-12-07-workcell/run.sh
BASE=$BASE NEW=$NEW ../2026-12-07-arm-speed-7/workcell_pairs.sh "$HERE/workcell-pairs"
ROBOTS="ur5 fetch" VIAROAD=$NEW OUT=$HERE/runs-ur5-fetch bash $RUN
