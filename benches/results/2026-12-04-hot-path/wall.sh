#!/bin/sh
# Wall milliseconds of each request instructions.sh asked (its WORK directory, its roadmap), as
# `viaroad query --json` reports them (`query_ms`), OLD and NEW interleaved, R rounds; one line
# per ask: round, request, binary, ms. The README reports per-request medians.
OLD=${OLD:-/tmp/old-target/release/viaroad}
NEW=${NEW:-target/release/viaroad}
W=${WORK:-/tmp/thin-instructions}
R=${R:-5}
for r in $(seq $R); do
  for f in $W/answer.*.json; do
    i=$(basename $f .json | cut -d. -f2)
    for v in old new; do
      if [ $v = old ]; then V=$OLD; else V=$NEW; fi
      ms=$($V query --scene $W/q$i.toml $ROADMAP --json --time 50 2>/dev/null | head -1 |
        python3 -c "import json,sys; print(json.loads(sys.stdin.readline())['query_ms'])")
      echo "$r $i $v $ms"
    done
  done
done
