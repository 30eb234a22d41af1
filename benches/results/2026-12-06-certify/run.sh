#!/usr/bin/env bash
# Certify and repair VAMP's MotionBenchMaker paths (../vamp-peer/results/{panda,fetch}.jsonl),
# then compare with OMPL + FCL `armcheck` (../ompl-peer). See README.md.
set -euo pipefail
cd "$(dirname "$0")/../../.."
export CARGO_PROFILE_RELEASE_DEBUG=false
cargo build --release
PEER=${VAMP_PEER:-/work/shared/vamp-peer}
SDIST=${SDIST:-/tmp/vamp-sdist}
RES=$SDIST/vamp_planner-0.6.4/resources
if [ ! -d "$RES/panda/problems" ]; then
  pip download --no-deps vamp-planner==0.6.4 -d "$SDIST"
  (cd "$SDIST" && tar xzf vamp_planner-0.6.4.tar.gz)
  for r in panda fetch; do (cd "$RES/$r" && tar xjf problems.tar.bz2); done
fi
# the OMPL peer, built in a copy (its build.sh installs the Debian packages it needs)
OMPL_DIR=${OMPL_DIR:-/tmp/ompl-peer-certify}
mkdir -p "$OMPL_DIR" && cp "${OMPL_PEER_SRC:-/work/shared/ompl-peer}"/{build.sh,ompl_peer.cpp} "$OMPL_DIR"/
(cd "$OMPL_DIR" && bash build.sh)
OUT=${OUT:-/tmp/certify-results}
mkdir -p "$OUT"
export RAYON_NUM_THREADS=1
uptime
target/release/viaroad bench certify "$PEER/results/panda.jsonl" --robot scenes/arms/panda \
  --problems "$RES/panda/problems" --repair 10 --time 5 --out "$OUT/panda.jsonl" | tee "$OUT/panda.md"
uptime
target/release/viaroad bench certify "$PEER/results/fetch.jsonl" --robot "$RES/fetch" \
  --problems "$RES/fetch/problems" --repair 3 --time 3 --out "$OUT/fetch.jsonl" | tee "$OUT/fetch.md"
uptime
OMPL_PEER=$OMPL_DIR/build/ompl_peer VAMP_RES=$RES VAMP_PEER=$PEER \
  python3 benches/results/2026-12-06-certify/analyze.py panda "$OUT/panda.jsonl" | tee "$OUT/panda_analysis.json"
OMPL_PEER=$OMPL_DIR/build/ompl_peer VAMP_RES=$RES VAMP_PEER=$PEER \
  python3 benches/results/2026-12-06-certify/analyze.py fetch "$OUT/fetch.jsonl" --sample 100 | tee "$OUT/fetch_analysis.json"
