cd /work/main
P=/tmp/vamp/mbm/problems
W="--workcell --nodes 200 --query-time 5 --limit 100 --keep-answers --race 2"
date -u +%T > /tmp/r/start
for s in 1 2 3; do
  for v in head new; do
    /tmp/vr-$v bench mbm $P --robot scenes/arms/panda $W --seed $s --out /tmp/r/wc-$v-s$s > /dev/null 2>&1
  done
done
for v in head new; do
  /tmp/vr-$v bench mbm /tmp/vamp/mbm-ur5/problems --robot /tmp/vamp/vamp_planner-0.6.4/resources/ur5 $W --out /tmp/r/ur5-$v > /dev/null 2>&1
done
for v in head new; do
  /tmp/vr-$v bench mbm $P --robot scenes/arms/panda --time 5 --out /tmp/r/p700-$v > /dev/null 2>&1
done
date -u +%T > /tmp/r/end
