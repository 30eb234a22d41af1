#!/bin/sh
# Longer runs on the four-square swap (and six): a roadmap learnt for 60 s with the bodies
# sampler (deep via-point method; and mixed with uniform), the grown roadmap of `solve` with the
# deep via-point method under a node budget (the same answer anywhere) and under time budgets,
# and the six-square swap for 60 s. Run from the repository root.
set -u
V=target/release/viaroad
T=${TMPDIR:-/tmp}/several-bodies-2
mkdir -p "$T"
S=scenes/bodies/swap-corridor-4.toml
echo "## k=4 build --time 60 --sampler bodies --local viapoint + query --check --time 30"
$V build $S -o "$T/s4v.bin" --time 60 --seed 1 --sampler bodies --local viapoint
$V query "$T/s4v.bin" --scene $S --check --time 30
echo "## k=4 build --time 60 --sampler mix:uniform=1,bodies=1 + query --check --time 30"
$V build $S -o "$T/s4m.bin" --time 60 --seed 1 --sampler mix:uniform=1,bodies=1
$V query "$T/s4m.bin" --scene $S --check --time 30
echo "## k=4 solve --roadmap --local viapoint --time 60 --check"
$V solve $S --roadmap --local viapoint --time 60 --check
for i in 1 2; do
  echo "## k=4 solve --roadmap --local viapoint --time 10 --check (run $i)"
  $V solve $S --roadmap --local viapoint --time 10 --check
done
echo "## k=4 solve --roadmap --local viapoint --nodes 18000 --check"
$V solve $S --roadmap --local viapoint --nodes 18000 --check --path-out "$T/swap4.path"
$V render $S --path "$T/swap4.path" -o "$T/swap-corridor-4.svg"
echo "## k=6 solve --roadmap --local viapoint --time 60 --check"
$V solve scenes/bodies/swap-corridor-6.toml --roadmap --local viapoint --time 60 --check
