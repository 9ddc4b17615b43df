#!/usr/bin/env bash
# The rotating drum of the walls issue beside LIGGGHTS 3.8 (Debian's `liggghts`): about 5,000
# grains (d = 0.9-1) in a drum of R = 15 d and L = 30 d with flat caps, a 0.45 fill, turning at
# Froude number omega^2 R / g = 0.1 for 3.2 revolutions; linear springs with k_n = 2e3,
# k_t = 2/7 k_n, gamma_n = 30 / tau, no tangential damping, mu = 0.5. yuxi runs the drum as the
# STL mesh and as an analytic cylinder, LIGGGHTS as the same STL (fix mesh/surface +
# move/mesh); all three start from the same grains (scenes/drum/make_drum.py). Prints each run's
# time and dynamic angle of repose (bench/drum_repose.py: mean over the last 2.7 revolutions,
# standard error from 5 blocks).
# usage: bench/drum_vs_liggghts.sh [YUXI] [WORK] [NP]
set -euo pipefail
default_work=/tmp/yuxi-drum-liggghts default_np=1
source "$(dirname "$0")/liggghts_side.sh"
radius=15 length=30
/usr/bin/python3 "$repo/scenes/drum/make_drum.py" --radius $radius --length $length --fill 0.45 \
  --segments 96 --ascii . > make.log
omega=$(/usr/bin/python3 -c "import math; print(math.sqrt(0.1 / $radius))")
period=$(/usr/bin/python3 -c "import math; print(2 * math.pi / $omega)")
t_end=$(/usr/bin/python3 -c "print(round(3.2 * $period, 1))")
steps=$(/usr/bin/python3 -c "print(round($t_end / 0.002))")
from_step=$(/usr/bin/python3 -c "print(round(0.5 * $period / 0.002))")
for kind in stl cylinder; do
  drum_scene "$kind" "drum-$kind" grains.data "$omega" "$t_end"
done
angle() { # DUMP
  /usr/bin/python3 "$repo/bench/drum_repose.py" "$1" --from-step "$from_step" --blocks 5
}
echo "grains: $(sed -n 's/^\([0-9]*\) atoms$/\1/p' grains.data); omega = $omega / tau; $steps steps"
for kind in stl cylinder; do
  start=$(date +%s.%N)
  mpi "$np" "$yuxi" run "drum-$kind.toml" \
    -o "yuxi-$kind" --overwrite --no-progress --no-plots > "yuxi-$kind.log" 2>&1
  end=$(date +%s.%N)
  read -r a err frames < <(angle "yuxi-$kind/particles.lammpstrj")
  echo "yuxi $kind: $(echo "$end - $start" | bc) s; angle ${a#-} +- $err degrees ($frames frames)"
done
start=$(date +%s.%N)
mpi "$np" liggghts -in "$repo/bench/peers/in.drum.liggghts" \
  -var data grains.data -var stl drum_ascii.stl -var omega_period "$period" -var steps "$steps" \
  -var every 500 -var dump liggghts.dump -log liggghts.log -echo none > liggghts.out 2>&1
end=$(date +%s.%N)
read -r a err frames < <(angle liggghts.dump)
echo "liggghts stl: $(echo "$end - $start" | bc) s; angle ${a#-} +- $err degrees ($frames frames)"
