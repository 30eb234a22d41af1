#!/bin/sh
# criterion, polyhedra oracle on OMPL.app meshes: d7ab2ce (before issue 11) and main, alternating
D7=/work/wt-d7/target/release/deps/oracle_polyhedra-0a4931e950767691
MAIN=/work/main/target/release/deps/oracle_polyhedra-81442fcdff7a42cc
for i in 1 2; do
  for s in d7 main; do
    b=$D7; W=/work/wt-d7; [ $s = main ] && { b=$MAIN; W=/work/main; }
    echo "== $(date -u +%H:%M:%S) $s run $i, load $(cut -d' ' -f1-3 /proc/loadavg)"
    (cd $W && $b --bench 'ompl/exact_intervals/' --noplot 2>&1 | grep -E "^ompl|time:")
  done
done
