#!/usr/bin/env bash
# Arm paths judged by the peer's own checker at 1/10 of its resolution (the goal:
# "every returned path certified: zero collisions under a check at 1/10 of OMPL's default resolution; where a
# peer's path passes its own check and fails the finer one, show it"). Every `*.path` file of
# PATHS_DIR is handed to `ompl_peer armcheck` (OMPL 1.5 + FCL: every state, every segment at
# --resolution; it shares no code with viaroad) with its MotionBenchMaker scene and request.
#
#   benches/arm_peer_check.sh PATHS_DIR OUT.jsonl [RESOLUTION]
#
# File names: FAMILY_NNNN<kind>.path, FAMILY a problem directory of $PROBLEMS (table_pick_panda):
# `viaroad bench mbm --paths-out` writes FAMILY_NNNN.path / FAMILY_NNNN_raw.path, the peer's
# `arm_sweep.sh` with SAVE_PATHS FAMILY_NNNN_rrtconnect_run0[_simplified].path. Env: PROBLEMS
# (MBM's problems/), ROBOT (vamp-planner's resources/panda, or ur5, fetch: ROBOT/NAME.urdf and
# .srdf with NAME its folder's), OMPL_PEER (default
# /tmp/ompl-peer/build/ompl_peer). Writes one peer line per file, with "file" and "kind" added, and
# prints "checked N paths, M invalid".
set -euo pipefail
dir=${1:?usage: arm_peer_check.sh PATHS_DIR OUT.jsonl [RESOLUTION]}
out=${2:?usage: arm_peer_check.sh PATHS_DIR OUT.jsonl [RESOLUTION]}
res=${3:-0.001}
: "${PROBLEMS:?MBM problems/ directory}" "${ROBOT:?vamp-planner resources/panda}"
robot=$(basename "$ROBOT")
peer=${OMPL_PEER:-/tmp/ompl-peer/build/ompl_peer}
[ -x "$peer" ] || { echo "no OMPL peer at $peer (see ../shared/ompl-peer/build.sh)" >&2; exit 2; }
: > "$out"
n=0; bad=0
for f in "$dir"/*.path; do
  name=$(basename "$f" .path)
  if [[ ! $name =~ ^(.+)_([0-9]{4})(.*)$ ]]; then
    echo "skipping $f: not FAMILY_NNNN<kind>.path" >&2
    continue
  fi
  family=${BASH_REMATCH[1]}; id=${BASH_REMATCH[2]}; kind=${BASH_REMATCH[3]#_}
  line=$("$peer" armcheck "$ROBOT/$robot.urdf" "$ROBOT/$robot.srdf" "$PROBLEMS/$family/scene$id.yaml" \
    "$f" --resolution "$res" --request "$PROBLEMS/$family/request$id.yaml" 2>/dev/null || true)
  [ -n "$line" ] || line='{"valid": false, "error": "armcheck gave no answer"}'
  n=$((n + 1))
  case $line in *'"valid": true'*) ;; *) bad=$((bad + 1)) ;; esac
  printf '%s\n' "${line%\}}, \"file\": \"$name\", \"kind\": \"${kind:-returned}\"}" >> "$out"
done
echo "checked $n paths, $bad invalid"
