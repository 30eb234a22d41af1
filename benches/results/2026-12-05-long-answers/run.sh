#!/bin/sh
# Long roadmap answers shortened by greedy passes alone (README here): the cage workcell (all
# 100 requests, answers kept) with head starts of 2 and 50 ms, box and bookshelf_thin with 2
# ms, before (BASE, 146dd60) and after (NEW), alternating, twice; then Home's 50 queries (3 000
# nodes, seed 1, one thread). PROBLEMS: MBM's problems/ (vamp-planner sdist); ROBOT: its
# resources/panda. Run from the repository's root.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${BASE:?}" "${NEW:=target/release/viaroad}"
here=$(dirname "$0")
out=${WORK:-/tmp/long-answers}
mkdir -p "$out"
: > "$here/runs.tsv"
for rep in 1 2; do
  for run in cage:2 cage:50 box:2 bookshelf_thin:2; do
    fam=${run%:*}; ms=${run#*:}
    for b in base new; do
      bin=$NEW
      [ "$b" = base ] && bin=$BASE
      dir=$(mktemp -d)
      ln -s "$PROBLEMS/${fam}_panda" "$dir/${fam}_panda"
      "$bin" bench mbm "$dir" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
        --limit 100 --keep-answers --race "$ms" --out "$out/$fam-$ms-$b-$rep" > /dev/null 2>&1
      rm -r "$dir"
      python3 benches/results/2026-12-05-shortening/stats.py "$out/$fam-$ms-$b-$rep/workcell.json" \
        "$fam/race-$ms" "$b" "$rep" >> "$here/runs.tsv"
    done
  done
done
"$NEW" build scenes/ompl/3D/Home.cfg --nodes 3000 --seed 1 -o "$out/home.roadmap" > /dev/null
: > "$here/home.tsv"
for rep in 1 2; do
  for b in base new; do
    bin=$NEW
    [ "$b" = base ] && bin=$BASE
    RAYON_NUM_THREADS=1 "$bin" query "$out/home.roadmap" --scene scenes/ompl/3D/Home.cfg \
      --queries scenes/ompl/queries/Home_seed1_50.txt --json 2> /dev/null > "$out/home-$b-$rep.jsonl"
    python3 benches/results/2026-12-05-greedy-per-group/home_stats.py "$out/home-$b-$rep.jsonl" \
      "$b" "$rep" >> "$here/home.tsv"
  done
done
