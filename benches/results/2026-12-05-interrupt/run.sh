#!/bin/bash
# A long oracle call gives up at the via-point search's deadline (README here): the binary before
# (BASE) against the one under test (NEW), one at a time.
# 1. the Panda workcell of every family (`--nodes 200 --query-time 5 --limit 100 --keep-answers
#    --race 2`, the issue's judgement), BASE and NEW alternating twice, NEW twice more;
# 2. NEW with a shorter head start for the roadmap (`--race 0.5` three times, `--race 1` once);
# 3. all 700 problems one by one (`bench mbm --time 5`), once each.
# PROBLEMS: MBM's problems/ (vamp-planner 0.6.4 sdist); ROBOT: scenes/arms/panda. From the root.
set -e
: "${PROBLEMS:?}" "${BASE:?}" "${NEW:=target/release/viaroad}" "${ROBOT:=scenes/arms/panda}"
here=$(dirname "$0")
tsv=benches/results/2026-12-05-sure-test/workcell_tsv.py
work=${WORK:-/tmp/interrupt}
mkdir -p "$work"
: > "$here/workcell.tsv"
workcell() { # binary label rep race
  out=$work/workcell-$2-$3
  "$1" bench mbm "$PROBLEMS" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
    --limit 100 --keep-answers --race "$4" --out "$out" > "$out.log" 2>&1
  python3 "$tsv" "$out/workcell.json" "$2" "$3" >> "$here/workcell.tsv"
}
for rep in 1 2; do
  workcell "$BASE" base $rep 2
  workcell "$NEW" new $rep 2
done
for rep in 3 4; do workcell "$NEW" new $rep 2; done
for rep in 1 2 3; do workcell "$NEW" new-race0.5 $rep 0.5; done
workcell "$NEW" new-race1 1 1
for b in base new; do
  bin=$NEW
  [ "$b" = base ] && bin=$BASE
  out=$work/problems-$b
  "$bin" bench mbm "$PROBLEMS" --robot "$ROBOT" --time 5 --out "$out" > "$out.log" 2>&1
  python3 "$here/problems_summary.py" "$out/problems.csv" > "$here/problems-$b.txt"
done
