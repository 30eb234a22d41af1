#!/usr/bin/env bash
# OMPL 1.5 + FCL (../shared/ompl-peer, `arm` mode) on all 700 MotionBenchMaker Panda problems,
# 5 s per problem, seed 1, one run each, sequential; one JSON line per problem in ompl/.
# PROBLEMS: the unpacked problems/ of the vamp-planner 0.6.4 sdist; ROBOT: its resources/panda.
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
PEER=${PEER:-/work/shared/ompl-peer}
ROBOT=${ROBOT:-/tmp/vamp/vamp_planner-0.6.4/resources/panda}
export PROBLEMS=${PROBLEMS:-/tmp/vamp/mbm/problems} OUTDIR=$HERE/ompl
for pl in ${PLANNERS:-rrtconnect prm}; do
  for fam in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
    "$PEER/arm_sweep.sh" "$ROBOT" "$fam" 1 100 "$pl" 5 >/dev/null 2>>"$HERE/ompl/sweep.log"
  done
done
