#!/bin/sh
# `viaroad query` on MotionBenchMaker's box: a 200-node roadmap of scene 1, then each of the
# family's first 30 requests alone (a fresh process each), with a grown copy (`--trees off`,
# as before) and with trees out of the roadmap (`--trees on`, the default for arms); every path
# found re-checked by the independent arm checker (`--check`, outside the query's time).
#   PROBLEMS=/path/to/vamp/problems V=target/release/viaroad sh query.sh
set -e
P=${PROBLEMS:-/tmp/vamp/mbm/problems}
V=$(realpath ${V:-target/release/viaroad})
HERE=$(pwd)/benches/results/2026-12-04-rooted-trees
W=${OUT:-/tmp/rooted-trees-query}
mkdir -p "$W" && cd "$W"
ln -sfn "$HERE/../../../scenes/arms/panda" panda
ln -sfn "$P/box_panda" fam
for i in $(seq -w 1 30); do
  cat > q$i.toml <<TOML
name = "box"
[space]
kind = "arm"
[robot]
urdf = "panda/panda.urdf"
srdf = "panda/panda.srdf"
group = "panda_arm"
[environment]
moveit_scene = "fam/scene0001.yaml"
[[query]]
moveit_request = "fam/request00$i.yaml"
TOML
done
$V build q01.toml --nodes 200 -o box.roadmap > build.log
for m in off on; do
  for i in $(seq -w 1 30); do
    # requests whose ends collide in scene 1 are refused with one error line: kept as data
    echo "$m $i $($V query --scene q$i.toml box.roadmap --time 5 --trees $m --json --check 2>&1 || true)"
  done
done > query-full.txt
# the record keeps each answer's figures, not its path (the paths are in query-full.txt)
python3 - query-full.txt "$HERE/query.txt" <<'PY'
import json, sys
with open(sys.argv[2], "w") as out:
    for line in open(sys.argv[1]):
        mode, i, rest = line.split(" ", 2)
        if rest.startswith("{"):
            v = json.loads(rest)
            v.pop("path", None)
            v.pop("shortened", None)
            rest = json.dumps(v, sort_keys=True) + "\n"
        out.write(f"{mode} {i} {rest}")
PY
