#!/bin/sh
# learning to 99 % on Twistycool and Home: 2837dac (the 2026-11-22 results' binary) and main, back to back
for b in 1122 main; do
  W=/work/main; [ $b = 1122 ] && W=/work/wt-old
  cd $W
  echo "$(date -u +%H:%M:%S) $b start, load $(cut -d' ' -f1-3 /proc/loadavg)"
  /tmp/learn/viaroad-$b bench local scenes/ompl/3D/Twistycool.cfg scenes/ompl/3D/Home.cfg --methods viapoint:max=3,calls=1000+both --runs 3 --time 20 --attach 10 --growth 2 --out /tmp/learn/out-$b > /tmp/learn/log-$b.txt 2>&1
  echo "$(date -u +%H:%M:%S) $b done, load $(cut -d' ' -f1-3 /proc/loadavg)"
done
# then, because the 2837dac binary reached 99 % on Home in none of its runs within 20 s on the loaded
# machine, Home again with 60 s (16:45–16:54 UTC), from /work/wt-old (a worktree at 2837dac):
#   /tmp/learn/viaroad-1122 bench local scenes/ompl/3D/Home.cfg --methods viapoint:max=3,calls=1000+both \
#       --runs 3 --time 60 --attach 10 --growth 2 --out /tmp/learn/out-1122-home60
