#!/usr/bin/env bash
# Planning instructions of one binary on 8 problems of each Panda family in DIR (callgrind,
# collecting only inside the portfolio's planning), as the README's tables count them.
#
#   instructions.sh BINARY NAME [DIR]
#
# DIR holds MotionBenchMaker family folders (default /tmp/mbm/panda6: the six families other
# than the cage, as symlinks into /tmp/mbm/panda/problems). Writes /tmp/prof/NAME.cg and
# /tmp/prof/NAME-out (problems.csv: calls, nodes and lengths to compare between binaries).
set -euo pipefail
BIN=$1 NAME=$2 DIR=${3:-/tmp/mbm/panda6}
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
mkdir -p /tmp/prof
RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="/tmp/prof/$NAME.cg" \
  --toggle-collect='*Portfolio*plan*' "$BIN" bench mbm "$DIR" --robot "$ROOT/scenes/arms/panda" \
  --time 50 --limit 8 --out "/tmp/prof/$NAME-out" > "/tmp/prof/$NAME.log" 2>&1
callgrind_annotate "/tmp/prof/$NAME.cg" | grep "PROGRAM TOTALS"
