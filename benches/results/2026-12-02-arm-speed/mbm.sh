#!/bin/sh
P=/tmp/vamp/mbm/problems
cd /work/wt-arms3
for side in before after; do
  if [ $side = before ]; then X=/tmp/arms-before/viaroad; else X=/tmp/meas/viaroad-after; fi
  echo "== $side start $(date -u +%H:%M:%S) $(uptime)"
  $X bench mbm $P --robot scenes/arms/panda --time 5 --direct-calls 300 --limit 10 --out /tmp/meas/mbm-$side > /tmp/meas/mbm-$side.log 2>&1
  echo "== $side end $(date -u +%H:%M:%S) $(uptime)"
done
