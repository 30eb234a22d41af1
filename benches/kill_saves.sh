#!/usr/bin/env bash
# Issue 15, part 2, the long version of tests/save_faults.rs's kill loop: `viaroad build` is
# killed with SIGKILL at random moments, uniformly over its whole run time (learning, writing
# the temporary file, fsync, rename), ROUNDS times. After every kill the target must be the
# previous roadmap or the new one byte for byte (never torn, never missing) and must load
# (`viaroad info`); at the end a complete build must succeed and leave no temporary file.
#
#   benches/kill_saves.sh [ROUNDS=200] [NODES=60000]
#
# Needs a release build (cargo build --release). Prints how many kills landed before the
# save, during it (a temporary file left behind) and after it (the new roadmap in place).
set -euo pipefail
ROUNDS=${1:-200}
NODES=${2:-60000}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN=$ROOT/target/release/viaroad
SCENE=$ROOT/scenes/discs-cluttered.toml
DIR=$(mktemp -d /tmp/viaroad-kill-saves.XXXXXX)
trap 'rm -rf "$DIR"' EXIT
OUT=$DIR/r.bin

"$BIN" build "$SCENE" -o "$DIR/old.bin" --nodes 300 --seed 1 >/dev/null
"$BIN" build "$SCENE" -o "$DIR/new.bin" --nodes "$NODES" --seed 2 >/dev/null
# how long a full build takes, to spread the kills over all of it (+20 %)
t0=$(date +%s%N)
"$BIN" build "$SCENE" -o "$DIR/timing.bin" --nodes "$NODES" --seed 2 >/dev/null
t1=$(date +%s%N)
span_us=$(( (t1 - t0) / 1000 * 12 / 10 ))
echo "full build: $(( (t1 - t0) / 1000000 )) ms; killing at uniform moments in [0, $(( span_us / 1000 )) ms]; $ROUNDS rounds"

before=0 during=0 after=0
for ((i = 1; i <= ROUNDS; i++)); do
    cp "$DIR/old.bin" "$OUT"
    "$BIN" build "$SCENE" -o "$OUT" --nodes "$NODES" --seed 2 >/dev/null 2>&1 &
    pid=$!
    delay_us=$(( (RANDOM * 32768 + RANDOM) % span_us ))
    sleep "$(printf '%d.%06d' $((delay_us / 1000000)) $((delay_us % 1000000)))"
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    if cmp -s "$OUT" "$DIR/old.bin"; then
        if compgen -G "$DIR/.r.bin.$pid-*.tmp" >/dev/null; then
            during=$((during + 1))
        else
            before=$((before + 1))
        fi
    elif cmp -s "$OUT" "$DIR/new.bin"; then
        after=$((after + 1))
    else
        echo "round $i: the target is neither the old nor the new roadmap (killed after $delay_us us)" >&2
        exit 1
    fi
    "$BIN" info "$OUT" >/dev/null || { echo "round $i: the target does not load" >&2; exit 1; }
done
# targeted rounds: kill as soon as the temporary file appears, i.e. during the write itself
# (uniform moments rarely land in the few milliseconds the write takes)
targeted=0
for ((i = 1; i <= ROUNDS / 4; i++)); do
    cp "$DIR/old.bin" "$OUT"
    "$BIN" build "$SCENE" -o "$OUT" --nodes "$NODES" --seed 2 >/dev/null 2>&1 &
    pid=$!
    while kill -0 "$pid" 2>/dev/null && ! compgen -G "$DIR/.r.bin.$pid-*.tmp" >/dev/null; do :; done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    if compgen -G "$DIR/.r.bin.$pid-*.tmp" >/dev/null; then
        targeted=$((targeted + 1))
    fi
    if ! cmp -s "$OUT" "$DIR/old.bin" && ! cmp -s "$OUT" "$DIR/new.bin"; then
        echo "targeted round $i: the target is neither the old nor the new roadmap" >&2
        exit 1
    fi
    "$BIN" info "$OUT" >/dev/null || { echo "targeted round $i: the target does not load" >&2; exit 1; }
done
echo "targeted: $((ROUNDS / 4)) kills as the temporary appeared, $targeted of them left it half-written; 0 lost roadmaps"
# a stray temporary must not trip the next build up: it is cleaned
"$BIN" build "$SCENE" -o "$OUT" --nodes 300 --seed 1 >/dev/null
cmp -s "$OUT" "$DIR/old.bin" || { echo "the final build differs" >&2; exit 1; }
if compgen -G "$DIR/.r.bin.*.tmp" >/dev/null; then
    echo "temporaries left after a complete build:" >&2
    ls -A "$DIR" >&2
    exit 1
fi
echo "ok: $ROUNDS kills, 0 lost roadmaps; killed before the save $before, during it $during (temporary left, cleaned by the next build), after it $after"
