#!/usr/bin/env bash
# Profile viaroad with perf (Debian/Ubuntu: `apt-get install linux-perf`): one CLI command or
# one criterion bench, sampled with DWARF call graphs on the release build (Cargo.toml's
# release profile keeps line tables, so frames have file:line), then a flat and a call-graph
# report as text, and a flame graph if `inferno` (cargo install inferno) is on the PATH.
# See docs/profiling.md.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: benches/profile.sh [options] -- VIAROAD-ARGS…        profile `viaroad VIAROAD-ARGS…`
       benches/profile.sh [options] --bench NAME [FILTER]    profile a criterion bench
  --out DIR        where perf.data and the reports go (default: /tmp/viaroad-profile)
  --freq HZ        sampling frequency (default: 999)
  --threads N      RAYON_NUM_THREADS (default: 1: one thread reads best)
  --seconds S      for --bench: how long criterion runs the selected benches (default: 10)
  --no-build       use the binaries as they are
examples:
  benches/profile.sh -- bench discs --problems 1000 --out /tmp/discs
  benches/profile.sh -- query roadmaps/piano.bin scenes/piano.toml
  benches/profile.sh --bench local_discs connect_32_seed_problems
EOF
}

OUT=/tmp/viaroad-profile
FREQ=999
THREADS=1
SECONDS_BENCH=10
BUILD=1
BENCH=""
FILTER=""
ARGS=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) OUT="$2"; shift 2 ;;
    --freq) FREQ="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --seconds) SECONDS_BENCH="$2"; shift 2 ;;
    --no-build) BUILD=0; shift ;;
    --bench) BENCH="$2"; FILTER="${3:-}"; shift $(( $# >= 3 ? 3 : 2 )) ;;
    --) shift; ARGS=("$@"); break ;;
    -h|--help) usage; exit 0 ;;
    *) echo "unknown option $1" >&2; usage >&2; exit 2 ;;
  esac
done
if [ -z "$BENCH" ] && [ ${#ARGS[@]} -eq 0 ]; then usage >&2; exit 2; fi
command -v perf >/dev/null || { echo "perf not found: apt-get install linux-perf" >&2; exit 1; }

cd "$(dirname "$0")/.."
mkdir -p "$OUT"
if [ -n "$BENCH" ]; then
  if [ "$BUILD" = 1 ]; then cargo bench --bench "$BENCH" --no-run >&2; fi
  # the newest executable of that bench (cargo names it NAME-HASH)
  BIN=$(ls -t target/release/deps/"$BENCH"-* | grep -v '\.d$' | head -n 1)
  CMD=("$BIN" --bench --profile-time "$SECONDS_BENCH")
  if [ -n "$FILTER" ]; then CMD+=("$FILTER"); fi
else
  if [ "$BUILD" = 1 ]; then cargo build --release >&2; fi
  CMD=(target/release/viaroad "${ARGS[@]}")
fi

echo "profiling: ${CMD[*]}" >&2
RAYON_NUM_THREADS="$THREADS" perf record -F "$FREQ" -g --call-graph dwarf \
  -o "$OUT/perf.data" -- "${CMD[@]}" >"$OUT/stdout.txt"
# self time per function: where the cycles go
perf report -i "$OUT/perf.data" --no-children --stdio --percent-limit 0.5 -g none \
  --sort symbol >"$OUT/flat.txt" 2>/dev/null
# inclusive time with callers: which caller pays for it
perf report -i "$OUT/perf.data" --children --stdio --percent-limit 5 --max-stack 24 \
  -g caller,5,callee --sort symbol >"$OUT/callgraph.txt" 2>/dev/null
if command -v inferno-collapse-perf >/dev/null && command -v inferno-flamegraph >/dev/null; then
  perf script -i "$OUT/perf.data" 2>/dev/null | inferno-collapse-perf | inferno-flamegraph \
    >"$OUT/flamegraph.svg"
  echo "flame graph: $OUT/flamegraph.svg" >&2
fi
echo "reports: $OUT/flat.txt (self time), $OUT/callgraph.txt (with callers); perf report -i $OUT/perf.data to browse" >&2
grep -v '^#' "$OUT/flat.txt" | grep -v '^$' | head -n 25
