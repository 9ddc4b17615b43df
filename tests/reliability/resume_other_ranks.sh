#!/usr/bin/env bash
# A checkpoint written on FROM ranks resumes correctly on TO ranks: the particles and contact
# states are redistributed. The continuation is not bitwise (the summation order changes with
# the decomposition), so the energies after it are compared to a straight run at 1e-6.
# usage: resume_other_ranks.sh YUXI MPIEXEC FROM TO WORK_DIR
set -euo pipefail
yuxi=$1
mpiexec=$2
from=$3
to=$4
work=$5
scene=$(cd "$(dirname "$0")" && pwd)/basin.toml
run() {
  local np=$1
  shift
  "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$yuxi" "$@" --no-progress
}
rm -rf "$work"
mkdir -p "$work"
run "$to" run "$scene" -o "$work/straight" --t-end 3.2 > "$work/straight.log" 2>&1
run "$from" run "$scene" -o "$work/moved" --t-end 3.0 > "$work/first.log" 2>&1
run "$to" run --resume "$work/moved" --t-end 3.2 > "$work/second.log" 2>&1
grep -q "resuming from" "$work/second.log"
# last rows: step,time,translational,rotational,elastic,gravitational,mechanical,dissipated,...
a=$(tail -1 "$work/straight/energies.csv")
b=$(tail -1 "$work/moved/energies.csv")
echo "straight: $a"
echo "resumed:  $b"
awk -F, -v a="$a" -v b="$b" 'BEGIN {
  n = split(a, x, ","); split(b, y, ",");
  if (x[1] != y[1]) { print "different steps"; exit 1 }
  for (k = 3; k <= n; ++k) {
    scale = (x[k] < 0 ? -x[k] : x[k]) + 1;
    d = x[k] - y[k]; if (d < 0) d = -d;
    if (d > 1e-6 * scale) { printf "column %d differs: %s vs %s\n", k, x[k], y[k]; exit 1 }
  }
  print "energies agree to 1e-6"
}'
