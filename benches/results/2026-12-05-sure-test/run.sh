#!/bin/bash
# The sure collision test and the shortening changes of 2026-12-05 afternoon (README here), the
# binary before (BASE) against the one under test (NEW), one at a time, alternating:
# 1. the Panda workcell of every family (`--nodes 200 --query-time 5 --limit 100 --keep-answers
#    --race 2`, as in 2026-12-05-workcell-100 and the issue's judgement), three repetitions;
# 2. all 700 problems one by one (`bench mbm --time 5`, the default pipeline), once each;
# 3. the static test at 40 000 configurations of box 1 (`ARM_MOVES=states`, NEW's bench).
# PROBLEMS: MBM's problems/ (vamp-planner 0.6.4 sdist); ROBOT: scenes/arms/panda (the same
# files as the sdist's resources/panda). Run from the repository's root.
set -e
: "${PROBLEMS:?}" "${BASE:?}" "${NEW:=target/release/viaroad}" "${ROBOT:=scenes/arms/panda}"
here=$(dirname "$0")
work=${WORK:-/tmp/sure-test}
mkdir -p "$work"
: > "$here/workcell.tsv"
for rep in 1 2 3; do
  for b in base new; do
    bin=$NEW
    [ "$b" = base ] && bin=$BASE
    out=$work/workcell-$b-$rep
    "$bin" bench mbm "$PROBLEMS" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
      --limit 100 --keep-answers --race 2 --out "$out" > "$out.log" 2>&1
    python3 "$here/workcell_tsv.py" "$out/workcell.json" "$b" "$rep" >> "$here/workcell.tsv"
  done
done
for b in base new; do
  bin=$NEW
  [ "$b" = base ] && bin=$BASE
  out=$work/problems-$b
  "$bin" bench mbm "$PROBLEMS" --robot "$ROBOT" --time 5 --out "$out" > "$out.log" 2>&1
  cp "$out/summary.md" "$here/problems-$b.md"
  cp "$out/problems.csv" "$here/problems-$b.csv"
done
cargo bench --bench arm --no-run > /dev/null 2>&1
ARM_MOVES=states "$(ls -t target/release/deps/arm-* | grep -v '\.d$' | head -1)" --bench \
  > "$here/states.txt" 2>&1
python3 "$here/summary.py" "$here" > "$here/summary.md"
