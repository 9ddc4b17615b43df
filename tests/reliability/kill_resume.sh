#!/usr/bin/env bash
# Kills a running basin with SIGKILL at random moments (a bounded, seeded number of times),
# resumes it each time from its newest checkpoint, and checks that the finished run equals an
# uninterrupted one byte for byte: final checkpoint, energies.csv and the LAMMPS dump.
# usage: kill_resume.sh YUXI WORK_DIR [KILLS]
set -euo pipefail
yuxi=$1
work=$2
kills=${3:-6}
scene=$(cd "$(dirname "$0")" && pwd)/basin.toml
rm -rf "$work"
mkdir -p "$work"
"$yuxi" run "$scene" -o "$work/reference" --no-progress > "$work/reference.log" 2>&1

RANDOM=2008 # reproducible kill moments
# A run can be killed before its first checkpoint is complete (only a .tmp exists): then there
# is nothing to resume from and it starts again.
has_checkpoint() { compgen -G "$work/killed/checkpoints/*.yxc" > /dev/null; }
for k in $(seq 1 "$kills"); do
  if has_checkpoint; then
    cmd=("$yuxi" run --resume "$work/killed" --no-progress)
  else # killed before its first checkpoint: nothing to resume, start again
    cmd=("$yuxi" run "$scene" -o "$work/killed" --overwrite --no-progress)
  fi
  "${cmd[@]}" > "$work/run_$k.log" 2>&1 &
  pid=$!
  sleep "0.$((RANDOM % 6 + 2))" # 0.2 to 0.7 s into a run of about 2 s
  kill -KILL "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  echo "kill $k: $(ls "$work/killed/checkpoints" 2> /dev/null | tail -1)"
done
if has_checkpoint; then
  "$yuxi" run --resume "$work/killed" --no-progress > "$work/final.log" 2>&1
else
  "$yuxi" run "$scene" -o "$work/killed" --overwrite --no-progress > "$work/final.log" 2>&1
fi

last=$(ls "$work/reference/checkpoints" | tail -1)
status=0
for f in "checkpoints/$last" energies.csv particles.lammpstrj particles.pvd; do
  if cmp -s "$work/reference/$f" "$work/killed/$f"; then
    echo "identical: $f"
  else
    echo "DIFFERENT: $f"
    status=1
  fi
done
exit $status
