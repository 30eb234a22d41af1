#!/bin/sh
# Shortening's corner test and unchecked-pair weight, and the faster static face test
# (README here): the three workcell families whose query p50 was above 1 ms, all 100 requests,
# racing, before (BASE, 16f792a) and after (NEW), alternating, twice. PROBLEMS: MBM's
# problems/ (vamp-planner sdist); ROBOT: its resources/panda.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${BASE:?}" "${NEW:=target/release/viaroad}"
here=$(dirname "$0")
mkdir -p "$here/out"
for rep in 1 2; do
  for fam in bookshelf_thin box cage; do
    for b in base new; do
      bin=$NEW
      [ "$b" = base ] && bin=$BASE
      dir=$(mktemp -d)
      ln -s "$PROBLEMS/${fam}_panda" "$dir/${fam}_panda"
      out=$here/out/$fam-$b-$rep
      "$bin" bench mbm "$dir" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
        --limit 100 --keep-answers --race 50 --out "$out" > "$out.log" 2>&1
      rm -r "$dir"
      python3 "$here/stats.py" "$out/workcell.json" "$fam" "$b" "$rep" >> "$here/runs.tsv"
    done
  done
done
