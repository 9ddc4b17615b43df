#!/usr/bin/env bash
# The rotating drum as an STL mesh and as an analytic cylinder (scenes/drum/), run for 3.2
# revolutions (t = 200 tau at omega = 0.1 / tau); prints each one's dynamic angle of repose
# (bench/drum_repose.py: mean over the last 2.7 revolutions, standard error from 5 blocks).
# usage: bench/drum_repose.sh [YUXI] [WORK]
set -euo pipefail
cd "$(dirname "$0")/.."
yuxi=${1:-build/release/apps/yuxi/yuxi}
work=${2:-/tmp/yuxi-drum-repose}
mkdir -p "$work"
for kind in stl cylinder; do
  "$yuxi" run "scenes/drum/drum-$kind.toml" -o "$work/$kind" --overwrite --no-progress --no-plots \
    --t-end 200 > "$work/$kind.log"
  read -r angle err frames < <(/usr/bin/python3 bench/drum_repose.py \
    "$work/$kind/particles.lammpstrj" --from-step 31400 --blocks 5)
  echo "drum-$kind: dynamic angle of repose ${angle#-} +- $err degrees ($frames frames)"
done
