#!/bin/bash
# user+system CPU seconds of the same solves with each profile's CLI (one rayon thread)
cd /work/house2-measure
for r in 1 2 3; do
  for p in release m-o2; do
    for s in scenes/ompl/3D/Abstract.cfg scenes/ompl/3D/Home.cfg scenes/arms/panda-cage-1.toml scenes/arms/panda-table_pick-1.toml; do
      /usr/bin/time -o /tmp/h2cpu.txt -f "%U %S" env RAYON_NUM_THREADS=1 t-$p/$p/viaroad solve $s --seed 1 --nodes 3000 >/dev/null 2>&1; t=$(cat /tmp/h2cpu.txt)
      echo "cpu $r $p $(basename $s) $t load $(cut -d' ' -f1 /proc/loadavg)"
    done
  done
done
echo DONE
