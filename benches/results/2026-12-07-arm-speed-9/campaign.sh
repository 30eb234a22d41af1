#!/usr/bin/env bash
# The final arm planner beside VAMP, back to back on one machine, and every returned path under
# OMPL + FCL: the Panda's 700 problems (paths written), `ompl_peer armcheck` of those paths at
# 0.001, the workcell beside VAMP twice, the UR5 and the Fetch (paths written) and their armcheck.
#
#   VIAROAD=… OMPL_PEER=… campaign.sh
#   VAMP_SRC  unpacked vamp-planner sdist (default /tmp/vamp-peer/vamp_planner-0.6.4)
#   MBM       ROBOT/problems/ folders (default /tmp/mbm)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$HERE"
: "${VIAROAD:?the viaroad binary}" "${OMPL_PEER:?the OMPL peer (../../../../shared/ompl-peer/build.sh)}"
VAMP_SRC="${VAMP_SRC:-/tmp/vamp-peer/vamp_planner-0.6.4}"
MBM="${MBM:-/tmp/mbm}"
RUN=../2026-12-07-arm-speed-3/run.sh
CHECK=../../arm_peer_check.sh
check() { # robot, paths folder, out name
  mkdir -p armcheck
  echo "armcheck $1 start $(date -u +%T) load $(cut -d' ' -f1-3 /proc/loadavg)" >> armcheck/armcheck.log
  PROBLEMS="$MBM/$1/problems" ROBOT="$VAMP_SRC/resources/$1" OMPL_PEER="$OMPL_PEER" \
    bash "$CHECK" "$2" "armcheck/$3" 0.001 | tee -a armcheck/armcheck.log
  echo "armcheck $1 end $(date -u +%T)" >> armcheck/armcheck.log
}
PATHS=1 VIAROAD="$VIAROAD" OUT="$HERE/runs" bash $RUN
check panda runs/viaroad-panda-paths viaroad-panda-armcheck.jsonl
VIAROAD="$VIAROAD" OUT="$HERE/workcell" bash ../2026-12-07-workcell/run.sh
VIAROAD="$VIAROAD" OUT="$HERE/workcell-again" bash ../2026-12-07-workcell/run.sh
ROBOTS="ur5 fetch" PATHS=1 VIAROAD="$VIAROAD" OUT="$HERE/runs-ur5-fetch" bash $RUN
check ur5 runs-ur5-fetch/viaroad-ur5-paths viaroad-ur5-armcheck.jsonl
check fetch runs-ur5-fetch/viaroad-fetch-paths viaroad-fetch-armcheck.jsonl
