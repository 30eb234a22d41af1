#!/bin/sh
# Instructions spent inside QueryPlanner::query_within (callgrind; they do not depend on the
# machine's load) for every bookshelf_thin request valid in the family's first scene, each
# asked alone (`viaroad query`, one process per request) of the 200-node workcell roadmap as
# learnt (not kept). Usage: V=path/to/viaroad ROADMAP=.../bookshelf_thin_panda.roadmap sh instructions.sh
# (the roadmap: `viaroad bench mbm $PROBLEMS/bookshelf_thin_panda --robot scenes/arms/panda
# --workcell --nodes 200 --limit 30 --out DIR`, either binary: the same file).
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=${V:-target/release/viaroad}
W=${WORK:-/tmp/thin-instructions}
mkdir -p $W
ln -sfn "$(pwd)/scenes/arms/panda" $W/panda
ln -sfn $P/bookshelf_thin_panda $W/fam
tot=0
for i in $(seq -w 1 30); do
  printf 'name = "thin"\n[space]\nkind = "arm"\n[robot]\nurdf = "panda/panda.urdf"\nsrdf = "panda/panda.srdf"\ngroup = "panda_arm"\n[environment]\nmoveit_scene = "fam/scene0001.yaml"\n[[query]]\nmoveit_request = "fam/request00%s.yaml"\n' $i > $W/q$i.toml
  # requests whose start or goal collide in scene 1 are refused: skipped
  $V query --scene $W/q$i.toml $ROADMAP --time 50 >/dev/null 2>&1 || continue
  valgrind --tool=callgrind --callgrind-out-file=$W/cg.$i.out --toggle-collect='*QueryPlanner*query_within*' \
    $V query --scene $W/q$i.toml $ROADMAP --json --time 50 > $W/answer.$i.json 2>/dev/null
  n=$(grep -m1 "^summary:" $W/cg.$i.out | awk '{print $2}')
  echo "request $i: $n"
  tot=$((tot+n))
done
echo "total $tot"
