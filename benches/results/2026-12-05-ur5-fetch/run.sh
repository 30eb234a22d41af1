#!/bin/bash
# MotionBenchMaker's UR5 and Fetch problems (the first 20 of each family), side by side with the
# peer (README here): OMPL 1.5's RRTConnect (5 s, seed 1) on one core, viaroad's `bench mbm
# --time 5` on the other, robot by robot; then viaroad on the UR5 with `--exact-meshes` (every
# link mesh as it is, the planner before its envelopes) beside `ompl_peer armcheck` judging every
# returned path of both at 1/10 of OMPL's resolution. VAMP: the vamp-planner 0.6.4 sdist,
# unpacked (resources/{ur5,fetch} with problems.tar.bz2 unpacked into WORK/problems-ROBOT);
# PEER_DIR: a built copy of ../shared/ompl-peer; VIAROAD: the binary under test. Run from the
# repository's root.
set -e
: "${VAMP:?}" "${PEER_DIR:?}" "${VIAROAD:=target/release/viaroad}"
here=$(dirname "$0")
work=${WORK:-/tmp/ur5-fetch}
families="bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick"
mkdir -p "$work"
for robot in ur5 fetch; do
  problems=$work/problems-$robot
  if [ ! -d "$problems" ]; then
    mkdir -p "$work/unpack-$robot"
    tar xjf "$VAMP/resources/$robot/problems.tar.bz2" -C "$work/unpack-$robot"
    mv "$work/unpack-$robot/problems" "$problems"
  fi
  (
    for f in $families; do
      (cd "$PEER_DIR" && PROBLEMS=$problems OUTDIR=$work/json-$robot SAVE_PATHS=$work/peer-paths-$robot \
        SEED=1 RUNS=1 ./arm_sweep.sh "$VAMP/resources/$robot" $f 1 20 rrtconnect 5 > /dev/null \
        2>> "$work/sweep.err")
    done
  ) &
  "$VIAROAD" bench mbm "$problems" --robot "$VAMP/resources/$robot" --time 5 --limit 20 \
    --out "$work/viaroad-$robot" --paths-out "$work/paths-$robot" > /dev/null 2> "$work/viaroad-$robot.err"
  wait
  cat "$work"/json-$robot/*.jsonl > "$here/ompl-$robot.jsonl"
  cp "$work/viaroad-$robot/problems.csv" "$here/viaroad-$robot-problems.csv"
  cp "$work/viaroad-$robot/summary.md" "$here/viaroad-$robot-summary.md"
done
"$VIAROAD" bench mbm "$work/problems-ur5" --robot "$VAMP/resources/ur5" --time 5 --limit 20 \
  --exact-meshes --out "$work/exact-ur5" > /dev/null 2> "$work/exact-ur5.err" &
for robot in ur5 fetch; do
  for who in paths peer-paths; do
    PROBLEMS=$work/problems-$robot ROBOT=$VAMP/resources/$robot OMPL_PEER=$PEER_DIR/build/ompl_peer \
      benches/arm_peer_check.sh "$work/$who-$robot" "$work/check-$who-$robot.jsonl" 0.001
  done
done
wait
cp "$work/exact-ur5/problems.csv" "$here/viaroad-ur5-exact-meshes-problems.csv"
cp "$work/exact-ur5/summary.md" "$here/viaroad-ur5-exact-meshes-summary.md"
python3 "$here/summary.py" "$work"
