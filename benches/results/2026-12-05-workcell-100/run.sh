#!/bin/sh
# Workcell runs of 2026-12-05 (README there): all 100 requests of every family, answers kept,
# racing (`--race 50`) and in turn. PROBLEMS: MBM's problems/ (vamp-planner sdist); ROBOT: its
# resources/panda. BASE: the binary before the change (602ce91 with the length columns added),
# NEW: the binary under test.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${BASE:?}" "${NEW:=target/release/viaroad}"
here=$(dirname "$0")
mkdir -p "$here/out"
for mode in race turn; do
  for b in base new; do
    bin=$NEW
    [ "$b" = base ] && bin=$BASE
    extra=""
    [ "$mode" = race ] && extra="--race 50"
    out=$here/out/$mode-$b
    "$bin" bench mbm "$PROBLEMS" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
      --limit 100 --keep-answers $extra --out "$out" > "$out.log" 2>&1
    cp "$out/workcell.md" "$here/$mode-$b.md"
    cp "$out/workcell.json" "$here/$mode-$b.json"
  done
done
