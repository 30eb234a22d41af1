#!/bin/sh
# Off-segment borderlines (viapoint:sidestep=F, CHS Fig 1.4) against the plain planner on
# motions restricted to the axes (split=true): (1) the local method alone on every query of
# the cluttered disc scene and of the 2-square swap; (2) inside the learner (bench local,
# node budgets: the same counts on any machine). Run from the repository root.
set -u
V=target/release/viaroad
O=${1:-/tmp/several-bodies/sidestep}
mkdir -p "$O"
for S in scenes/discs-cluttered.toml scenes/bodies/swap-corridor-2.toml; do
  for m in viapoint:split=true viapoint:split=true,sidestep=0.25 viapoint:split=true,sidestep=0.5 viapoint:split=true,sidestep=1; do
    echo "## solve $S --local $m"
    $V solve "$S" --local "$m" --check --time 10 --json | python3 -c 'import json,sys
rows=[json.loads(l) for l in sys.stdin]
ok=[r for r in rows if r["solved"]]
print("solved", len(ok), "of", len(rows), "calls total", sum(r["calls"] for r in rows),
      "calls of solved (mean)", round(sum(r["calls"] for r in ok)/max(1,len(ok)),1),
      "certified", sum(1 for r in ok if r.get("certified")))'
  done
done
$V bench local scenes/discs-cluttered.toml \
  --methods viapoint:max=3,calls=1000,split=true viapoint:max=3,calls=1000,split=true,sidestep=0.5 \
  --runs 3 --nodes 2000 --queries 100 --out "$O/discs"
$V bench local scenes/bodies/swap-corridor-2.toml \
  --methods straight sampled:res=0.01 viapoint:max=3,calls=1000 viapoint:max=3,calls=1000,split=true viapoint:max=3,calls=1000,split=true,sidestep=0.5 \
  --runs 3 --nodes 8000 --queries 20 --out "$O/swap2"
