#!/usr/bin/env bash
# Runs the reliability basin (or SCENE) on NP MPI ranks to T_END; runs it again to T_HALF, then
# resumes it from its checkpoint to T_END: the final checkpoint, energies.csv and LAMMPS dump
# must be the same bytes (a checkpoint resumes bit for bit on the number of ranks that wrote it).
# usage: resume_on_ranks.sh YUXI MPIEXEC NP WORK_DIR [SCENE T_HALF T_END]
set -euo pipefail
yuxi=$1
mpiexec=$2
np=$3
work=$4
scene=${5:-$(cd "$(dirname "$0")" && pwd)/basin.toml}
t_half=${6:-2.5}
t_end=${7:-5.0}
run() { "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$yuxi" "$@" --no-progress; }
rm -rf "$work"
mkdir -p "$work"
run run "$scene" -o "$work/straight" --t-end "$t_end" > "$work/straight.log" 2>&1
run run "$scene" -o "$work/halves" --t-end "$t_half" > "$work/first_half.log" 2>&1
run run --resume "$work/halves" --t-end "$t_end" > "$work/second_half.log" 2>&1
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
