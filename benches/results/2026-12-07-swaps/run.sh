#!/bin/sh
# Swaps in a corridor (scenes/bodies/swap-corridor-{2,3,4,6}.toml) with the body-aware walks:
# before (BEFORE: a build of main without them) and after (AFTER: this branch).
# (1) solve's default, --time 10 --check, seeds 1..5 (before: 1..3);
# (2) build --time 10, then the scene's query against the roadmap (query --check --time 10);
# (3) a roadmap grown from start and goal with the local methods straight, sampled and the
#     roadmap default (viapoint:max=3,calls=1000), --time 10 --check (after only);
# (4) the other scenes of several bodies and a few single-body scenes, before and after
#     (solve --time 10 and solve --roadmap --nodes 3000, --check);
# (5) the certified path of the swap of six (solve, seed 1), drawn by render.
# Every `--check` path is re-checked (raw and shortened) by the independent checker.
# Run from the repository root:
#   BEFORE=/path/to/main/viaroad sh benches/results/2026-12-07-swaps/run.sh > OUT
set -u
AFTER=${AFTER:-target/release/viaroad}
BEFORE=${BEFORE:?a viaroad binary built from main}
R=benches/results/2026-12-07-swaps
T=${TMPDIR:-/tmp}/swaps-bench
mkdir -p "$T"
row() {
  python3 -c 'import json,sys
label=sys.argv[1]
for l in sys.stdin:
    if not l.startswith("{"):
        continue
    d=json.loads(l)
    f=lambda x: "-" if x is None else (f"{x:.2f}" if isinstance(x,float) else str(x))
    secs=d.get("seconds", (d.get("query_ms") or 0)/1000)
    print(label, "| solved", f(d.get("solved")), "| by", f(d.get("method") or d.get("outcome")),
          "| s", f(secs), "| calls", f(d.get("calls")),
          "| nodes", f(d.get("nodes", d.get("grown_nodes"))), "| length", f(d.get("length")),
          "| certified", f(d.get("certified")), f(d.get("check_error") or ""))' "$1"
}
echo "# $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg)"
for k in 2 3 4 6; do
  S=scenes/bodies/swap-corridor-$k.toml
  for s in 1 2 3; do
    $BEFORE solve "$S" --time 10 --seed $s --check --json | row "k=$k before solve seed=$s"
  done
  for s in 1 2 3 4 5; do
    $AFTER solve "$S" --time 10 --seed $s --check --json | row "k=$k after  solve seed=$s"
  done
done
echo "# $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg)"
for k in 2 3 4 6; do
  S=scenes/bodies/swap-corridor-$k.toml
  for side in before after; do
    if [ $side = before ]; then V=$BEFORE; else V=$AFTER; fi
    echo "## k=$k $side build --time 10"
    $V build "$S" -o "$T/swap$k-$side.bin" --time 10 --seed 1 2>&1 | grep -E "^learnt|^oracle"
    $V query "$T/swap$k-$side.bin" --scene "$S" --check --time 10 --json | row "k=$k $side build+query"
  done
done
echo "# $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg)"
for k in 2 3 4 6; do
  S=scenes/bodies/swap-corridor-$k.toml
  for local in straight sampled:res=0.01 viapoint:max=3,calls=1000; do
    $AFTER solve "$S" --roadmap --local "$local" --time 10 --check --json | row "k=$k after  roadmap --local $local"
  done
done
echo "# $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg)"
for f in bodies/movers-room bodies/cubes-into-boxes-2 bodies/cubes-into-boxes-3 se2-corridor piano cube-into-box; do
  for side in before after; do
    if [ $side = before ]; then V=$BEFORE; else V=$AFTER; fi
    $V solve scenes/$f.toml --time 10 --check --json | row "$f $side solve"
    $V solve scenes/$f.toml --roadmap --nodes 3000 --check --json | row "$f $side roadmap --nodes 3000"
  done
done
echo "# $(date -u) load: $(cut -d' ' -f1-3 /proc/loadavg)"
$AFTER solve scenes/bodies/swap-corridor-6.toml --time 10 --seed 1 --check --path-out "$R/swap-corridor-6.path" --json | row "k=6 after solve (drawn)"
$AFTER render scenes/bodies/swap-corridor-6.toml --path "$R/swap-corridor-6.path" -o "$R/swap-corridor-6.svg"
