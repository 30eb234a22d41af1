#!/bin/sh
# Issue 10, trees for arms: `bench mbm` before (main 1773ee4, the grown roadmap after the
# via-point planner) and after (branch arms4: the tree stage, default `--planner tree`; and the
# roadmap stage of the same binary as a control), back to back on problems 1-10 of each family.
# Binaries: /tmp/viaroad-before = /work/main/target/release/viaroad built at 1773ee4;
# /tmp/a4/viaroad-after = target/release/viaroad of arms4 (`cargo build --release --bins`).
P=/tmp/vamp/mbm/problems        # vamp-planner 0.6.4 sdist, resources/panda/problems.tar.bz2
R=benches/results/2026-12-02-arm-tree
cd "$(dirname "$0")/../../.."
for side in before after after-roadmap after-balance; do
  case $side in
    before) X=/tmp/viaroad-before; EXTRA= ;;
    after) X=/tmp/a4/viaroad-after; EXTRA= ;;
    after-roadmap) X=/tmp/a4/viaroad-after; EXTRA="--planner roadmap" ;;
    # run at 17:15 with a build whose default was `--tree-balance true` (the option came after
    # the three runs above; the committed default is false, so it is spelt out here)
    after-balance) X=target/release/viaroad; EXTRA="--tree-balance true" ;;
  esac
  echo "== $side start $(date -u +%H:%M:%S) $(uptime)"
  $X bench mbm $P --robot scenes/arms/panda --time 5 --direct-calls 300 --limit 10 $EXTRA \
    --out $R/mbm-$side > $R/mbm-$side.log 2>&1
  echo "== $side end $(date -u +%H:%M:%S) $(uptime)"
done
