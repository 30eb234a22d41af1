#!/bin/sh
# Whole stairs for the arms' trees (2026-12-04 night). PROBLEMS: the MotionBenchMaker Panda
# problems (pip download --no-deps vamp-planner; untar; tar xjf .../resources/panda/problems.tar.bz2);
# ROBOT: the sdist's resources/panda (for the OMPL peer); PEER: a built ../shared/ompl-peer.
# OLD: a viaroad binary of e05bf9e (the sliding stairs) for the workcell rows.
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=${VIAROAD:-target/release/viaroad}
R="--robot scenes/arms/panda --time 5"
export RAYON_NUM_THREADS=1
# all 700, one thread each, two side by side (one per core)
$V bench mbm $P $R --tree-balance false --out /tmp/mbm700-alternate-dc300 &
$V bench mbm $P $R --tree-balance false --direct-calls 0 --out /tmp/mbm700-alternate-dc0 &
wait
$V bench mbm $P $R --out /tmp/mbm700-balanced-dc300 &
$V bench mbm $P $R --direct-calls 0 --out /tmp/mbm700-balanced-dc0 &
wait
# the trees alone beside OMPL's RRTConnect (one per core)
$V bench mbm $P $R --direct-calls 0 --out /tmp/mbm700-side-by-side-dc0 &
for fam in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
  PROBLEMS=$P OUTDIR=/tmp/ompl-rrtconnect $PEER/arm_sweep.sh $ROBOT $fam 1 100 rrtconnect 5 > /dev/null
done
wait
# racing (two threads), alone
RAYON_NUM_THREADS=2 $V bench mbm $P $R --race --out /tmp/mbm700-balanced-race
# the workcell, before (OLD) and after, in turn side by side, then racing one at a time
W="--robot scenes/arms/panda --workcell --nodes 200 --query-time 5 --limit 30 --keep-answers"
$OLD bench mbm $P $W --out /tmp/workcell-turn-old &
$V bench mbm $P $W --out /tmp/workcell-turn-new &
wait
RAYON_NUM_THREADS=2 $OLD bench mbm $P $W --race 50 --out /tmp/workcell-race-old
RAYON_NUM_THREADS=2 $V bench mbm $P $W --race 50 --out /tmp/workcell-race-new
# rigid bodies, side by side: sh rigid.sh prefix > rigid-prefix.txt & sh rigid.sh whole > rigid-whole.txt
