#!/bin/bash
# The per-problem pipeline with the trees first (README here), all 700 MotionBenchMaker problems,
# side by side with the peer: OMPL 1.5's RRTConnect (5 s, seed 1) on one core and viaroad's new
# default (`bench mbm --time 5`: the direct path, the trees for 20 % of the time, the via-point
# planner, the trees afresh) on the other; then the order before (`--trees-first 0`: the
# via-point planner first) beside the peer's checks; every path of both judged by `ompl_peer
# armcheck` at 1/10 of OMPL's resolution. PROBLEMS: MBM's problems/ (vamp-planner 0.6.4 sdist);
# ROBOT: its resources/panda; PEER_DIR: a built copy of ../shared/ompl-peer; VIAROAD: the binary
# under test. Run from the repository's root.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${PEER_DIR:?}" "${VIAROAD:=target/release/viaroad}"
here=$(dirname "$0")
work=${WORK:-/tmp/trees-first}
mkdir -p "$work"
(
  for f in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
    (cd "$PEER_DIR" && PROBLEMS=$PROBLEMS OUTDIR=$work/json SAVE_PATHS=$work/paths SEED=1 RUNS=1 \
      ./arm_sweep.sh "$ROBOT" $f 1 100 rrtconnect 5 > /dev/null 2>> "$work/sweep.err")
  done
) &
"$VIAROAD" bench mbm "$PROBLEMS" --robot "$ROBOT" --time 5 --out "$work/viaroad" \
  --paths-out "$work/viaroad-paths" > /dev/null 2> "$work/viaroad.err"
wait
cat "$work"/json/*.jsonl > "$here/ompl-sweep.jsonl"
cp "$work/viaroad/problems.csv" "$here/viaroad-problems.csv"
cp "$work/viaroad/summary.md" "$here/viaroad-summary.md"
# the order before, beside the checks of both planners' paths
"$VIAROAD" bench mbm "$PROBLEMS" --robot "$ROBOT" --time 5 --trees-first 0 \
  --out "$work/before" > /dev/null 2> "$work/before.err" &
OMPL_PEER=$PEER_DIR/build/ompl_peer benches/arm_peer_check.sh "$work/paths" "$work/ompl.jsonl" 0.001
OMPL_PEER=$PEER_DIR/build/ompl_peer benches/arm_peer_check.sh "$work/viaroad-paths" "$work/viaroad.jsonl" 0.001
wait
cp "$work/before/problems.csv" "$here/before-problems.csv"
cp "$work/before/summary.md" "$here/before-summary.md"
python3 "$here/summary.py" "$work/ompl.jsonl" "$work/viaroad.jsonl"
