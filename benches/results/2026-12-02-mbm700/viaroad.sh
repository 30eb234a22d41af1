#!/usr/bin/env bash
# viaroad on all 700 MotionBenchMaker Panda problems (vamp-planner 0.6.4 sdist, unpacked outside
# the repository), 5 s per problem, then the side-by-side table with the OMPL peer's lines.
# VIAROAD: the release binary; PROBLEMS: the unpacked problems/; EXTRA: more `bench mbm` options.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
W=$(cd "$HERE/../../.." && pwd)
VIAROAD=${VIAROAD:-$W/target/release/viaroad}
PROBLEMS=${PROBLEMS:-/tmp/vamp/mbm/problems}
echo "$(date -u +%H:%M:%S) start, load $(cut -d' ' -f1-3 /proc/loadavg)"
# shellcheck disable=SC2086
/usr/bin/time -f "%e s wall, %U s user" "$VIAROAD" bench mbm "$PROBLEMS" --robot "$W/scenes/arms/panda" \
    --time 5 --direct-calls 300 ${EXTRA:-} --out "$HERE/viaroad" > "$HERE/viaroad.log" 2>&1
echo "$(date -u +%H:%M:%S) done, load $(cut -d' ' -f1-3 /proc/loadavg)"
python3 "$HERE/compare.py" "$HERE/viaroad/problems.csv" "$HERE/ompl" > "$HERE/compare.md"
