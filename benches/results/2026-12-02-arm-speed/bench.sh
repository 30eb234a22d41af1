#!/bin/sh
B=/tmp/arms-before-wt/target/release/deps/arm-4b32d194ad414dc2
A=/work/wt-arms3/target/release/deps/arm-4b32d194ad414dc2
cd /work/wt-arms3
for side in before after; do
  if [ $side = before ]; then X=$B; else X=$A; fi
  echo "== $side criterion $(date -u +%H:%M:%S) $(uptime)"
  $X --bench 2>&1 | grep -E "^arm/|time:" 
done
for side in before after; do
  if [ $side = before ]; then X=$B; else X=$A; fi
  echo "== $side ARM_MOVES=table $(date -u +%H:%M:%S) $(uptime)"
  ARM_MOVES=table $X 2>&1
done
echo "== end $(date -u +%H:%M:%S) $(uptime)"
