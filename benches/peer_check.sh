#!/usr/bin/env bash
# The validity sweep's second opinion: answers random queries on OMPL.app
# problems with `viaroad bench validity`, keeps a sample of the solved paths (raw and shortened)
# as OMPL state files and re-checks every one with the OMPL peer's `check` (OMPL 1.5 + FCL, every
# state and every segment at OMPL's motion-check resolution: it shares no code with viaroad).
#
#   benches/peer_check.sh OUT_DIR [SAMPLE_PER_SCENE] [QUERIES_PER_SCENE] [CFG ...]
#
# Needs the peer built (../shared/ompl-peer/build.sh; OMPL_PEER=path/to/ompl_peer overrides the
# default /tmp/ompl-peer/build/ompl_peer). Writes OUT_DIR/sweep.txt, OUT_DIR/paths/*.path,
# OUT_DIR/checks.jsonl (one peer line per path) and prints "checked N paths, M invalid".
set -euo pipefail
out=${1:?usage: peer_check.sh OUT_DIR [SAMPLE] [QUERIES] [CFG ...]}
sample=${2:-20}
queries=${3:-500}
shift $(( $# < 3 ? $# : 3 ))
cfgs=("$@")
if [ ${#cfgs[@]} -eq 0 ]; then
  cfgs=(scenes/ompl/3D/Easy.cfg scenes/ompl/3D/cubicles.cfg scenes/ompl/3D/Home.cfg
        scenes/ompl/3D/Twistycool.cfg scenes/ompl/2D/Maze_planar.cfg
        scenes/ompl/2D/RandomPolygons_planar.cfg)
fi
peer=${OMPL_PEER:-/tmp/ompl-peer/build/ompl_peer}
[ -x "$peer" ] || { echo "no OMPL peer at $peer (see ../shared/ompl-peer/build.sh)" >&2; exit 2; }
cargo build --release --quiet
mkdir -p "$out/paths"
./target/release/viaroad bench validity "${cfgs[@]}" --nodes "${NODES:-1000}" \
  --queries "$queries" --sample "$sample" --paths-out "$out/paths" | tee "$out/sweep.txt"
: > "$out/checks.jsonl"
n=0; bad=0
while IFS=$'\t' read -r cfg file; do
  [ -n "$cfg" ] || continue
  n=$((n + 1))
  if ! "$peer" check "$cfg" "$file" >> "$out/checks.jsonl" 2>> "$out/checks.err"; then
    bad=$((bad + 1)); echo "INVALID by the peer: $file" >&2
  fi
done < "$out/paths/paths.tsv"
echo "checked $n paths with $peer, $bad invalid"
[ "$bad" -eq 0 ]
