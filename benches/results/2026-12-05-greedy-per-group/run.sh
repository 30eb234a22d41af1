#!/bin/sh
# The greedy pass before the visibility graph counted per two DOF groups (README here): the
# workcell's three families above 1 ms, all 100 requests, racing, answers kept; and Home's 50
# queries on a 3 000-node roadmap (two groups: nothing may change). BASE0: 60035b2 (this
# morning's last commit), BASE: 6444175 (the trees' shortcut passes keeping their pieces), NEW:
# the change; one run at a time, alternating, twice. PROBLEMS: MBM's problems/ (vamp-planner
# sdist); ROBOT: its resources/panda. Run from the repository's root.
set -e
: "${PROBLEMS:?}" "${ROBOT:?}" "${BASE0:?}" "${BASE:?}" "${NEW:=target/release/viaroad}"
here=$(dirname "$0")
out=${WORK:-/tmp/greedy-per-group}
mkdir -p "$out"
: > "$here/runs.tsv"
for rep in 1 2; do
  for fam in bookshelf_thin box cage; do
    for b in base0 base new; do
      eval bin=\$$(echo $b | tr a-z A-Z)
      [ "$b" = new ] && bin=$NEW
      dir=$(mktemp -d)
      ln -s "$PROBLEMS/${fam}_panda" "$dir/${fam}_panda"
      "$bin" bench mbm "$dir" --robot "$ROBOT" --workcell --nodes 200 --query-time 5 \
        --limit 100 --keep-answers --race 50 --out "$out/$fam-$b-$rep" > /dev/null 2>&1
      rm -r "$dir"
      python3 benches/results/2026-12-05-shortening/stats.py "$out/$fam-$b-$rep/workcell.json" \
        "$fam" "$b" "$rep" >> "$here/runs.tsv"
    done
  done
done
# Home: two groups, the same rule as before
"$NEW" build scenes/ompl/3D/Home.cfg --nodes 3000 --seed 1 -o "$out/home.roadmap" > /dev/null
: > "$here/home.tsv"
for rep in 1 2; do
  for b in base new; do
    bin=$BASE
    [ "$b" = new ] && bin=$NEW
    RAYON_NUM_THREADS=1 "$bin" query "$out/home.roadmap" --scene scenes/ompl/3D/Home.cfg \
      --queries scenes/ompl/queries/Home_seed1_50.txt --json 2> /dev/null > "$out/home-$b-$rep.jsonl"
    python3 "$here/home_stats.py" "$out/home-$b-$rep.jsonl" "$b" "$rep" >> "$here/home.tsv"
  done
done
