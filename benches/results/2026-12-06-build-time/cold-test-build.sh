#!/bin/bash
# a cold build of the test suite (cargo test --release --no-run) in an empty target dir, timed,
# with cargo's per-unit timings (target-cold/cargo-timings/cargo-timing.html)
cd "$(dirname "$0")/../../.."
export CARGO_PROFILE_RELEASE_DEBUG=false
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-target-cold}
echo "start $(date -u) load $(cat /proc/loadavg)"
s=$(date +%s)
cargo test --release --no-run --timings 2>&1 | tail -5
e=$(date +%s)
echo "build $((e-s)) s, end $(date -u) load $(cat /proc/loadavg)"
