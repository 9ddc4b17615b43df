#!/usr/bin/env bash
# A trajectory does not depend on when checkpoints are written. The default basin
# (scenes/basin-small.toml), shaken from t = 10, runs to t = 10.6 on NP ranks with no checkpoint
# but the last ("plain"), and three more ways, each of which must give plain's bytes
# (energies.csv, the LAMMPS dump, the last VTK frame; and the final checkpoint where the scene is
# the same):
#   clock    checkpoints by the wall clock, at every poll of the clock (every 50 steps)
#   extend   run to t = 10.1, then extend the finished run with --resume --t-end 10.6
#   signal   (NP = 1) stopped by SIGTERM, which writes a checkpoint, then resumed
# A list build forced at a checkpoint reorders the particles of the shaken bed, and its forces
# then sum in another order: the run to 10.1 extended to 10.6 differed from the straight one
# from t = 10.52 on.
# usage: checkpoint_anywhere.sh YUXI MPIEXEC NP WORK_DIR
set -euo pipefail
yuxi=$1
mpiexec=$2
np=$3
work=$4
here=$(cd "$(dirname "$0")" && pwd)
scene=$here/../../scenes/basin-small.toml
run() { "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$yuxi" "$@" --no-progress --no-plots; }
rm -rf "$work"
mkdir -p "$work"
# scene_with EVERY_STEPS EVERY_MINUTES: the reliability basin with that checkpoint policy.
scene_with() {
  cat "$scene"
  printf '\n[checkpoint]\nevery_steps = %s\nevery_minutes = %s\nkeep = 2\n' "$1" "$2"
}
scene_with 0 0 > "$work/plain.toml"
scene_with 0 1e-9 > "$work/clock.toml"

run run "$work/plain.toml" -o "$work/plain" --t-end 10.6 > "$work/plain.log" 2>&1
run run "$work/clock.toml" -o "$work/clock" --t-end 10.6 > "$work/clock.log" 2>&1
run run "$work/plain.toml" -o "$work/extend" --t-end 10.1 > "$work/extend_first.log" 2>&1
run run --resume "$work/extend" --t-end 10.6 > "$work/extend_second.log" 2>&1
variants=(clock extend)
if [[ $np == 1 ]]; then
  "$yuxi" run "$work/plain.toml" -o "$work/signal" --t-end 10.6 --no-progress --no-plots \
    > "$work/signal_first.log" 2>&1 &
  pid=$!
  sleep 2 # a third of the run or less
  kill -TERM "$pid"
  status=0
  wait "$pid" || status=$?
  if [[ $status != 143 ]]; then
    echo "the run did not stop on SIGTERM (exit $status)"
    cat "$work/signal_first.log"
    exit 1
  fi
  "$yuxi" run --resume "$work/signal" --no-progress --no-plots > "$work/signal_second.log" 2>&1
  variants+=(signal)
fi

last_frame=$(ls "$work/plain" | grep -E '^particles_[0-9]+\.vtu$' | tail -1)
last_checkpoint=$(ls "$work/plain/checkpoints" | tail -1)
status=0
for v in "${variants[@]}"; do
  files=(energies.csv particles.lammpstrj "$last_frame")
  [[ $v != clock ]] && files+=("checkpoints/$last_checkpoint")
  for f in "${files[@]}"; do
    if cmp -s "$work/plain/$f" "$work/$v/$f"; then
      echo "$v on $np ranks: identical $f"
    else
      echo "$v on $np ranks: DIFFERENT $f"
      status=1
    fi
  done
done
exit $status
