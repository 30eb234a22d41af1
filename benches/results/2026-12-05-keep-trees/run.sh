#!/bin/sh
# Workcell runs of 2026-12-05 (README there): answers kept, with and without the trees that
# found them. PROBLEMS: MBM's problems/ (vamp-planner sdist); ROBOT: its resources/panda.
# VIAROAD: the binary under test. LIMIT: requests per family (30; 100: all of them).
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${VIAROAD:=target/release/viaroad}" "${LIMIT:=30}"
here=$(dirname "$0")
mkdir -p "$here/out"
for mode in race turn; do
  for keep in answers trees; do
    out=$here/out/$mode-$keep-$LIMIT
    extra=""
    [ "$mode" = race ] && extra="--race 50"
    [ "$keep" = trees ] && extra="$extra --keep-trees"
    $VIAROAD bench mbm "$PROBLEMS" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
      --limit "$LIMIT" --keep-answers $extra --out "$out" > "$out.log" 2>&1
    cp "$out/workcell.md" "$here/$mode-$keep-$LIMIT.md"
    cp "$out/workcell.json" "$here/$mode-$keep-$LIMIT.json"
  done
done
