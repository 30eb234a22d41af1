#!/bin/bash
# The 700-problem cross-check of 2026-12-05 (README here). PROBLEMS: MBM's problems/ (vamp-planner
# 0.6.4 sdist); ROBOT: its resources/panda; PEER_DIR: a built copy of ../shared/ompl-peer;
# VIAROAD: the binary under test. Run from the repository's root.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${PEER_DIR:?}" "${VIAROAD:=target/release/viaroad}"
here=$(dirname "$0")
work=${WORK:-/tmp/peer700}
mkdir -p "$work"
# OMPL's RRTConnect, 5 s, seed 1, paths saved (raw and simplifyMax'd)
for f in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
  (cd "$PEER_DIR" && PROBLEMS=$PROBLEMS OUTDIR=$work/json SAVE_PATHS=$work/paths SEED=1 RUNS=1 \
    ./arm_sweep.sh "$ROBOT" $f 1 100 rrtconnect 5 > /dev/null 2>> "$work/sweep.err")
done
cat "$work"/json/*.jsonl > "$here/ompl-sweep.jsonl"
# viaroad, the default per-problem pipeline, 5 s, paths saved
"$VIAROAD" bench mbm "$PROBLEMS" --robot "$ROBOT" --time 5 --out "$work/viaroad" \
  --paths-out "$work/viaroad-paths" > /dev/null 2> "$work/viaroad.err"
cp "$work/viaroad/report.json" "$here/viaroad-report.json"
cp "$work/viaroad/summary.md" "$here/viaroad-summary.md"
# every path of both, judged by the peer's armcheck at 1/10 of OMPL's resolution
OMPL_PEER=$PEER_DIR/build/ompl_peer benches/arm_peer_check.sh "$work/paths" "$work/ompl.jsonl" 0.001
OMPL_PEER=$PEER_DIR/build/ompl_peer benches/arm_peer_check.sh "$work/viaroad-paths" "$work/viaroad.jsonl" 0.001
python3 "$here/summary.py" "$work/ompl.jsonl" "$work/viaroad.jsonl"
