#!/bin/sh
# solve --tree on OMPL.app rigid-body problems with the stairs given as $1 (prefix or whole), 30 s
V=${V:-target/release/viaroad}
M=$1
for p in alpha-1.5:1 alpha-1.5:2 alpha-1.5:3 alpha-1.5:4 Easy:1 Easy:2 cubicles:1 cubicles:2 Twistycool:1 Twistycool:2 Abstract:1 Home:1; do
  sc=${p%:*}; s=${p#*:}
  echo "$sc seed $s $M: $(timeout 60 $V solve scenes/ompl/3D/$sc.cfg --tree --tree-stairs $M --time 30 --seed $s 2>&1 | tail -1)"
done
