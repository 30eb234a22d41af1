#!/bin/bash
# house2, second part: the wheel candidate (opt-level 2, no debug info) against release, then cold cargo test
cd /work/house2-measure
unset CARGO_PROFILE_RELEASE_DEBUG
ld() { cut -d' ' -f1-3 /proc/loadavg; }
export CARGO_TARGET_DIR=/work/house2-measure/t-release
s=$(date +%s); cargo build -q --bin viaroad --profile release 2>&1 | tail -3; e=$(date +%s)
echo "== cli release incremental build (finished) $((e-s)) s more, $(date -u +%T) load $(ld)"
for p in m-o2; do
  export CARGO_TARGET_DIR=/work/house2-measure/t-$p
  echo "== py $p start $(date -u +%T) load $(ld)"
  s=$(date +%s)
  cargo build -q -p viaroad-python --profile $p 2>&1 | tail -3
  e=$(date +%s)
  echo "== py $p cold build $((e-s)) s, end $(date -u +%T) load $(ld); .so $(stat -c %s t-$p/$p/lib_viaroad.so) bytes"
  s=$(date +%s)
  cargo build -q --bin viaroad --profile $p 2>&1 | tail -3
  e=$(date +%s)
  echo "== cli $p incremental build $((e-s)) s, end $(date -u +%T) load $(ld)"
done
unset CARGO_TARGET_DIR
for r in 1 2 3; do
  for p in release m-o2; do
    for s in scenes/ompl/3D/Abstract.cfg scenes/ompl/3D/Home.cfg scenes/arms/panda-cage-1.toml; do
      a=$(date +%s.%N)
      out=$(RAYON_NUM_THREADS=1 t-$p/$p/viaroad solve $s --seed 1 --nodes 3000 2>&1 | tail -1)
      b=$(date +%s.%N)
      echo "run $r $p $(basename $s) $(echo "$b - $a" | bc) s load $(ld) | $out"
    done
  done
done
echo "== cold test build start $(date -u +%T) load $(ld)"
export CARGO_PROFILE_RELEASE_DEBUG=false
export CARGO_TARGET_DIR=/work/house2-measure/t-test
s=$(date +%s)
cargo test --release --no-run 2>&1 | tail -4
e=$(date +%s)
echo "== cold test build $((e-s)) s, end $(date -u +%T) load $(ld)"
s=$(date +%s)
cargo test --release 2>&1 | grep -E "^test result|Running|Doc-tests|FAILED|panicked|running for over"
e=$(date +%s)
echo "== test run $((e-s)) s, end $(date -u +%T) load $(ld)"
echo "== suite report-time start $(date -u +%T) load $(ld)"
RUSTC_BOOTSTRAP=1 $(ls t-test/release/deps/suite-* | grep -v '\.d$' | head -1) -Z unstable-options --report-time > suite-report-time.txt 2>&1
echo "== suite report-time end $(date -u +%T) load $(ld)"
echo DONE
