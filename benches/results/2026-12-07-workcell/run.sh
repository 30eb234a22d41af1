#!/usr/bin/env bash
# The workcell mode beside VAMP, back to back on one machine: VAMP's single queries (one
# thread), then `bench mbm --workcell` with RAYON_NUM_THREADS=1 and 2, on the same first
# LIMIT problems of each Panda family; each family's roadmap is learnt offline on its first
# scene and trained on the family's last TRAIN problems (held out: never asked).
#
#   LIMIT     first N problems of each family asked (default 20)
#   TRAIN     last N problems of each family learnt from (default 80; 0: none)
#   SHORTEN   the queries' shortening (default greedy; fast is `query`'s default)
#   NODES     sampled roadmap nodes (default 200)
#   BASE      1: also the workcell as the previous folder ran it (no training, fast shortening)
#   OUT       results folder (default: this folder's runs/)
#   VAMP_PY   VAMP's python (default /tmp/vamp-peer/venv/bin/python)
#   VAMP_PEER folder with run_mbm.py (default ../2026-12-06-vamp-peer)
#   MBM       folder holding panda/problems/<family>_panda (default /tmp/mbm)
#   VIAROAD   the viaroad binary (default target/release/viaroad)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
LIMIT="${LIMIT:-20}"
TRAIN="${TRAIN:-80}"
SHORTEN="${SHORTEN:-greedy}"
NODES="${NODES:-200}"
OUT="${OUT:-$HERE/runs}"
VAMP_PY="${VAMP_PY:-/tmp/vamp-peer/venv/bin/python}"
VAMP_PEER="${VAMP_PEER:-$ROOT/benches/results/2026-12-06-vamp-peer}"
MBM="${MBM:-/tmp/mbm}"
VIAROAD="${VIAROAD:-$ROOT/target/release/viaroad}"
mkdir -p "$OUT"
{
  echo "date: $(date -u +%FT%TZ)"
  echo "host: $(uname -n) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "viaroad: $(git -C "$ROOT" rev-parse --short HEAD)"
  echo "LIMIT=$LIMIT TRAIN=$TRAIN SHORTEN=$SHORTEN NODES=$NODES"
} > "$OUT/machine.txt"
echo "[run] VAMP panda" >&2
RAYON_NUM_THREADS=1 "$VAMP_PY" "$VAMP_PEER/run_mbm.py" panda --limit "$LIMIT" --out "$OUT/vamp-panda.jsonl"
echo "load after VAMP: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
workcell() { # name, threads, extra args
  local name=$1 threads=$2; shift 2
  echo "[run] viaroad workcell $name, $threads threads" >&2
  RAYON_NUM_THREADS=$threads "$VIAROAD" bench mbm "$MBM/panda/problems" --robot "$ROOT/scenes/arms/panda" \
    --workcell --nodes "$NODES" --race 2 --limit "$LIMIT" "$@" --out "$OUT/$name-$threads" \
    > "$OUT/$name-$threads.log" 2>&1
  echo "load after $name $threads: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
}
for threads in 1 2; do
  workcell workcell "$threads" --train "$TRAIN" --shorten "$SHORTEN"
  if [ "${BASE:-}" = 1 ]; then workcell base "$threads"; fi
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/machine.txt"
"$VAMP_PY" "$HERE/summarize.py" "$OUT" > "$OUT/summary.md"
cat "$OUT/summary.md"
