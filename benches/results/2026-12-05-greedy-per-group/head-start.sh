#!/bin/sh
# The race's head start in the workcell (README here): every family, all 100 requests, answers
# kept, the roadmap's query alone for MS before the trees join (`--race MS`), MS = 50, 10, 2, 0;
# one run at a time. PROBLEMS, ROBOT as in run.sh; NEW: the binary.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${NEW:=target/release/viaroad}"
here=$(dirname "$0")
out=${WORK:-/tmp/greedy-per-group}
mkdir -p "$out"
: > "$here/head-start.tsv"
for fam in bookshelf_small bookshelf_tall bookshelf_thin box cage table_pick table_under_pick; do
  for ms in 50 10 2 0; do
    dir=$(mktemp -d)
    ln -s "$PROBLEMS/${fam}_panda" "$dir/${fam}_panda"
    "$NEW" bench mbm "$dir" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
      --limit 100 --keep-answers --race "$ms" --out "$out/hs-$fam-$ms" > /dev/null 2>&1
    rm -r "$dir"
    python3 benches/results/2026-12-05-shortening/stats.py "$out/hs-$fam-$ms/workcell.json" \
      "$fam" "race-$ms" 1 >> "$here/head-start.tsv"
  done
done
