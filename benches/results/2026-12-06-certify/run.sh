#!/usr/bin/env bash
# Certify and repair VAMP's MotionBenchMaker paths (../vamp-peer/results/{panda,fetch,ur5}.jsonl)
# and certify OMPL's rigid-body paths, then compare with OMPL + FCL `armcheck` / `check`
# (../ompl-peer). See README.md.
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
  for r in panda fetch ur5; do (cd "$RES/$r" && tar xjf problems.tar.bz2); done
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
  --problems "$RES/fetch/problems" --repair 10 --time 5 --out "$OUT/fetch.jsonl" | tee "$OUT/fetch.md"
uptime
# the Fetch paths whose repair failed, again with 60 s each
python3 - "$PEER/results/fetch.jsonl" "$OUT/fetch.jsonl" > "$OUT/fetch_failed_input.jsonl" <<'PY'
import json, sys
failed = {(r["family"], r["index"]) for r in map(json.loads, open(sys.argv[2])) if r["repaired"] is False}
for line in open(sys.argv[1]):
    d = json.loads(line)
    if (d["family"], d["index"]) in failed:
        print(line, end="")
PY
target/release/viaroad bench certify "$OUT/fetch_failed_input.jsonl" --robot "$RES/fetch" \
  --problems "$RES/fetch/problems" --repair 60 --time 5 --out "$OUT/fetch_retry.jsonl" | tee "$OUT/fetch_retry.md"
python3 - "$OUT/fetch.jsonl" "$OUT/fetch_retry.jsonl" > "$OUT/fetch_final.jsonl" <<'PY'
import json, sys
retry = {(r["family"], r["index"]): r for r in map(json.loads, open(sys.argv[2]))}
for r in map(json.loads, open(sys.argv[1])):
    print(json.dumps(retry.get((r["family"], r["index"]), r)))
PY
uptime
# the UR5: the first 10 solved problems of each family (the paths the VAMP peer's armcheck covers)
: > "$OUT/ur5.jsonl"
for f in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
  target/release/viaroad bench certify "$PEER/results/ur5.jsonl" --robot "$RES/ur5" \
    --problems "$RES/ur5/problems" --family $f --limit 10 --repair 10 --time 5 --out "$OUT/ur5_$f.jsonl"
  cat "$OUT/ur5_$f.jsonl" >> "$OUT/ur5.jsonl"
done
uptime
# OMPL.app's rigid-body problems: OMPL's own paths (solve) certified, against OMPL's check
VIAROAD=target/release/viaroad OMPL_PEER=$OMPL_DIR/build/ompl_peer \
  python3 benches/results/2026-12-06-certify/rigid.py "$OUT" | tee "$OUT/rigid.md"
uptime
for r in panda fetch ur5; do
  f="$OUT/$r.jsonl"; [ "$r" = fetch ] && f="$OUT/fetch_final.jsonl"
  OMPL_PEER=$OMPL_DIR/build/ompl_peer VAMP_RES=$RES VAMP_PEER=$PEER \
    python3 benches/results/2026-12-06-certify/analyze.py $r "$f" | tee "$OUT/${r}_analysis.json"
done
