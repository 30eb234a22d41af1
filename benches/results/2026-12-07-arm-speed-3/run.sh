#!/usr/bin/env bash
# VAMP and viaroad on the MotionBenchMaker problems, back to back on one machine, one thread each;
# optionally the workcell mode with 1 and 2 threads.
#
#   ROBOTS    robots to run (default "panda"; "panda ur5 fetch" for all three)
#   LIMIT     first N problems of each family (default: all 100)
#   TIME      viaroad's seconds per problem (default 5)
#   WORKCELL  1: also `bench mbm --workcell --nodes 200 --race 2` with RAYON_NUM_THREADS=1 and 2
#   VAMP_SRC  unpacked vamp-planner sdist (default /tmp/vamp-peer/vamp_planner-0.6.4)
#   OUT       results folder (default: this folder's runs/)
#   VAMP_PY   VAMP's python (default /tmp/vamp-peer/venv/bin/python, as the vamp-peer folder's build.sh makes it)
#   VAMP_PEER folder with run_mbm.py (default ../2026-12-06-vamp-peer)
#   MBM       folder holding ROBOT/problems/<family>_ROBOT (default /tmp/mbm: VAMP's sdist's
#             resources/ROBOT/problems.tar.bz2 unpacked there)
#   VIAROAD   the viaroad binary (default target/release/viaroad)
#   PATHS     1: viaroad also writes every path (`--paths-out OUT/viaroad-ROBOT-paths`) for
#             benches/arm_peer_check.sh
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
ROBOTS="${ROBOTS:-panda}"
TIME="${TIME:-5}"
OUT="${OUT:-$HERE/runs}"
VAMP_PY="${VAMP_PY:-/tmp/vamp-peer/venv/bin/python}"
VAMP_PEER="${VAMP_PEER:-$ROOT/benches/results/2026-12-06-vamp-peer}"
MBM="${MBM:-/tmp/mbm}"
VIAROAD="${VIAROAD:-$ROOT/target/release/viaroad}"
export RAYON_NUM_THREADS=1
mkdir -p "$OUT"
limit_args=()
[ -n "${LIMIT:-}" ] && limit_args=(--limit "$LIMIT")
{
  echo "date: $(date -u +%FT%TZ)"
  echo "host: $(uname -n) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "viaroad: $(git -C "$ROOT" rev-parse --short HEAD)"
} > "$OUT/machine.txt"
# the Panda ships with viaroad; the UR5 and the Fetch come with VAMP's sdist
robot_dir() {
  if [ -d "$ROOT/scenes/arms/$1" ]; then echo "$ROOT/scenes/arms/$1"
  else echo "${VAMP_SRC:-/tmp/vamp-peer/vamp_planner-0.6.4}/resources/$1"; fi
}
for robot in $ROBOTS; do
  echo "[run] VAMP $robot" >&2
  "$VAMP_PY" "$VAMP_PEER/run_mbm.py" "$robot" "${limit_args[@]}" --out "$OUT/vamp-$robot.jsonl"
  echo "load after VAMP $robot: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
  echo "[run] viaroad $robot" >&2
  paths_args=()
  [ "${PATHS:-}" = 1 ] && paths_args=(--paths-out "$OUT/viaroad-$robot-paths")
  "$VIAROAD" bench mbm "$MBM/$robot/problems" --robot "$(robot_dir "$robot")" \
    --time "$TIME" "${limit_args[@]}" "${paths_args[@]}" --out "$OUT/viaroad-$robot" \
    > "$OUT/viaroad-$robot.log" 2>&1
  echo "load after viaroad $robot: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
  if [ "${WORKCELL:-}" = 1 ]; then
    for threads in 1 2; do
      echo "[run] viaroad $robot workcell, $threads threads" >&2
      RAYON_NUM_THREADS=$threads "$VIAROAD" bench mbm "$MBM/$robot/problems" --robot "$(robot_dir "$robot")" \
        --workcell --nodes 200 --race 2 "${limit_args[@]}" --out "$OUT/workcell-$robot-$threads" \
        > "$OUT/workcell-$robot-$threads.log" 2>&1
      echo "load after workcell $robot $threads: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
    done
  fi
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
"$VAMP_PY" "$HERE/../2026-12-06-arm-speed/summarize.py" "$OUT" $ROBOTS > "$OUT/summary.md"
cat "$OUT/summary.md"
