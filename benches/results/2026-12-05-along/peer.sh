cd /work/main
P=/tmp/vamp/mbm/problems
ROBOT=/tmp/vamp/vamp_planner-0.6.4/resources/panda
rm -rf /tmp/r/ompl; mkdir -p /tmp/r/ompl
date -u +%T > /tmp/r/peer-start
for f in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
  (cd /tmp/ompl-peer && PROBLEMS=$P OUTDIR=/tmp/r/ompl SEED=1 RUNS=1 ./arm_sweep.sh $ROBOT $f 1 100 rrtconnect 5 > /dev/null 2>> /tmp/r/ompl/sweep.err)
done
date -u +%T > /tmp/r/peer-mid
target/release/viaroad bench mbm $P --robot scenes/arms/panda --time 5 --out /tmp/r/p700-final > /dev/null 2>&1
date -u +%T > /tmp/r/peer-end
