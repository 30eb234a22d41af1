#!/usr/bin/env bash
# Loading an arm's scene (2026-12-03 night): OLD = the binary of 2985385, NEW = this commit's.
# PROBLEMS: MotionBenchMaker's problems/ (README: Robot arms).
set -euo pipefail
W=$(cd "$(dirname "$0")/../../.." && pwd)
OLD=${OLD:-/tmp/viaroad-old}; NEW=${NEW:-$W/target/release/viaroad}; OUT=${OUT:-/tmp/load}
PROBLEMS=${PROBLEMS:-/tmp/vamp/mbm/problems}
S=$W/scenes/arms/panda-table_pick-1.toml
Q=$W/benches/results/2026-12-03-quick-yesno/keep-queries.txt
mkdir -p "$OUT"
"$NEW" build "$S" --nodes 200 --seed 1 -o "$OUT/tp200.bin" >/dev/null
head -1 "$Q" > "$OUT/one.txt"
export RAYON_NUM_THREADS=1
for v in old new; do
  b=$OLD; [ $v = new ] && b=$NEW
  # instructions of Scene::load, and of the 29 queries with answers kept
  valgrind --tool=callgrind --callgrind-out-file="$OUT/load-$v.out" --toggle-collect='*Scene*load*' \
    "$b" query "$OUT/tp200.bin" --scene "$S" --queries "$OUT/one.txt" --time 60 --json >/dev/null 2>&1
  valgrind --tool=callgrind --callgrind-out-file="$OUT/query-$v.out" --toggle-collect='*QueryPlanner*query_within*' \
    "$b" query "$OUT/tp200.bin" --scene "$S" --queries "$Q" --time 60 --json --keep-answers "$OUT/k-$v.bin" >/dev/null 2>&1
  echo "$v: load $(grep totals "$OUT/load-$v.out"), queries $(grep totals "$OUT/query-$v.out")"
done
# wall clock of a whole one-query `viaroad query`, 20 runs each, twice, alternating
python3 - "$OLD" "$NEW" "$OUT" "$S" <<'PY'
import subprocess, sys, time
old, new, out, scene = sys.argv[1:]
for name, b in [("old", old), ("new", new)] * 2:
    ts = []
    for _ in range(20):
        t = time.perf_counter()
        subprocess.run([b, "query", f"{out}/tp200.bin", "--scene", scene, "--queries", f"{out}/one.txt",
                        "--time", "5", "--json"], capture_output=True)
        ts.append((time.perf_counter() - t) * 1e3)
    ts.sort()
    print(f"{name}: process ms min {ts[0]:.1f} p50 {ts[len(ts) // 2]:.1f}")
PY
unset RAYON_NUM_THREADS
for v in new old; do
  b=$OLD; [ $v = new ] && b=$NEW
  "$b" bench mbm "$PROBLEMS" --robot "$W/scenes/arms/panda" --workcell --nodes 200 \
    --query-time 5 --limit 30 --keep-answers --out "$OUT/wc-$v" > "$OUT/wc-$v.log" 2>&1
done
