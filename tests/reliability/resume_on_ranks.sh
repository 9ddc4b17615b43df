#!/usr/bin/env bash
# Runs the reliability basin on NP MPI ranks to its end; runs it again to half way, then resumes
# it from its checkpoint to the end: the final checkpoint, energies.csv and LAMMPS dump must be
# the same bytes (a checkpoint resumes bit for bit on the number of ranks that wrote it).
# usage: resume_on_ranks.sh YUXI MPIEXEC NP WORK_DIR
set -euo pipefail
yuxi=$1
mpiexec=$2
np=$3
work=$4
scene=$(cd "$(dirname "$0")" && pwd)/basin.toml
run() { "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$yuxi" "$@" --no-progress; }
rm -rf "$work"
mkdir -p "$work"
run run "$scene" -o "$work/straight" > "$work/straight.log" 2>&1
run run "$scene" -o "$work/halves" --t-end 2.5 > "$work/first_half.log" 2>&1
run run --resume "$work/halves" --t-end 5.0 > "$work/second_half.log" 2>&1
last=$(ls "$work/straight/checkpoints" | tail -1)
status=0
for f in "checkpoints/$last" energies.csv particles.lammpstrj; do
  if cmp -s "$work/straight/$f" "$work/halves/$f"; then
    echo "identical on $np ranks: $f"
  else
    echo "DIFFERENT on $np ranks: $f"
    status=1
  fi
done
exit $status
