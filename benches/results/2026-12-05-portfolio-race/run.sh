#!/bin/bash
# The arm benchmark's stages as a library (viaroad::portfolio, `solve`), the workcell's race as a
# query option (QueryOptions::race, `query`/`serve --race`), and shortening's lazy A* setting
# known-blocked pairs aside on expansion (README here). One at a time, nothing else running.
# PROBLEMS: MBM's problems/ (vamp-planner 0.6.4 sdist); OLD, NEW: the binaries compared.
# 1. the Panda workcell of every family, OLD and NEW alternating, seeds 1-3
#    (`--nodes 200 --query-time 5 --limit 100 --keep-answers --race 2`, the issue's judgement);
# 2. the box and bookshelf_thin families alone, seeds 4-10 (the seed moves their p50 around 1 ms);
# 3. all 700 problems one by one (`bench mbm --time 5`), NEW once.
set -e
: "${PROBLEMS:?}" "${OLD:?}" "${NEW:=target/release/viaroad}" "${ROBOT:=scenes/arms/panda}"
work=${WORK:-/tmp/portfolio-race}
mkdir -p "$work"
workcell() { # binary label seed dir
  out=$work/wc-$2-$3-$(basename "$4")
  "$1" bench mbm "$4" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 --limit 100 \
    --keep-answers --race 2 --seed "$3" --out "$out" > "$out.log" 2>&1
  grep "^| " "$out/workcell.md" | grep -v "family\|---" | sed "s/^/$2 $3 /"
}
for seed in 1 2 3; do
  workcell "$OLD" old $seed "$PROBLEMS"
  workcell "$NEW" new $seed "$PROBLEMS"
done
for family in box_panda bookshelf_thin_panda; do
  mkdir -p "$work/$family" && ln -sfn "$PROBLEMS/$family" "$work/$family/$family"
  for seed in 4 5 6 7 8 9 10; do
    workcell "$OLD" old $seed "$work/$family"
    workcell "$NEW" new $seed "$work/$family"
  done
done
"$NEW" bench mbm "$PROBLEMS" --robot "$ROBOT" --time 5 --out "$work/problems" > "$work/problems.log" 2>&1
python3 "$(dirname "$0")/../2026-12-05-interrupt/problems_summary.py" "$work/problems/problems.csv"
