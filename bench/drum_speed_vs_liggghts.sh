#!/usr/bin/env bash
# Speed of a mesh-walled drum against LIGGGHTS 3.8 (Debian's `liggghts`): about 53,000 grains
# (d = 0.9-1) in a drum of R = 30 d and L = 70 d, an STL of 19,200 triangles of about equal
# size (scenes/drum/make_drum.py --rings --bands), settled by yuxi for 20 tau, then STEPS steps
# (default 5,000) turning at Froude number 0.1 from the same settled state in both codes, on 1
# and on NP ranks, yuxi and LIGGGHTS one after the other (REPEATS times, alternating). The
# contact law is the drum benchmark's (bench/peers/in.drum.liggghts). Prints each run's loop time
# (yuxi: the log's "steps in"; LIGGGHTS: "Loop time of"), without the set-up, and the ratio.
# YUXI_BASELINE=/path/to/an/earlier/yuxi runs that build too, right after yuxi, and prints the
# ratio of the two: the cost of a change, side by side in one invocation.
# usage: [YUXI_BASELINE=BINARY] bench/drum_speed_vs_liggghts.sh [YUXI] [WORK] [NP] [STEPS] [REPEATS]
set -euo pipefail
default_work=/tmp/yuxi-drum-speed default_np=2
source "$(dirname "$0")/liggghts_side.sh"
steps=${4:-5000}
repeats=${5:-1}
radius=30 length=70
if [ ! -f settled.data ]; then
  /usr/bin/python3 "$repo/scenes/drum/make_drum.py" --radius $radius --length $length --fill 0.45 \
    --segments 160 --rings 45 --bands 8 --ascii . > make.log
fi
scene() { # NAME DATA OMEGA T_END SNAPSHOT
  drum_scene stl "$1" "$2" "$3" "$4" -e "s|^energy_interval = .*|energy_interval = 1.0|" \
    -e "s|^snapshot_interval = .*|snapshot_interval = $5|"
}
if [ ! -f settled.data ]; then
  scene settle grains.data 0.0 20.0 20.0
  mpi "$np" "$yuxi" run settle.toml -o settle --overwrite --no-progress --no-plots > settle.log 2>&1
  /usr/bin/python3 "$repo/bench/peers/lammps_data_from_dump.py" settle/particles.lammpstrj settled.data \
    --frame last > /dev/null
fi
omega=$(/usr/bin/python3 -c "import math; print(math.sqrt(0.1 / $radius))")
period=$(/usr/bin/python3 -c "import math; print(2 * math.pi / $omega)")
t_end=$(/usr/bin/python3 -c "print($steps * 0.002)")
scene turn settled.data "$omega" "$t_end" 1000000.0
echo "grains: $(sed -n 's/^\([0-9]*\) atoms$/\1/p' settled.data); triangles: 19200; $steps steps"
for repeat in $(seq "$repeats"); do
  for n in 1 "$np"; do
    mpi "$n" "$yuxi" run turn.toml -o "yuxi-np$n" --overwrite --no-progress --no-plots \
      > "yuxi-np$n.log" 2>&1
    y=$(sed -n 's/.* \([0-9]*\) steps in \([0-9.]*\) s.*/\2/p' "yuxi-np$n.log" | tail -1)
    if [ -n "${YUXI_BASELINE:-}" ]; then
      mpi "$n" "$YUXI_BASELINE" run turn.toml -o "base-np$n" --overwrite --no-progress --no-plots \
        > "base-np$n.log" 2>&1
      b=$(sed -n 's/.* \([0-9]*\) steps in \([0-9.]*\) s.*/\2/p' "base-np$n.log" | tail -1)
      echo "np $n: yuxi $y s, baseline $b s, yuxi / baseline $(echo "scale=3; $y / $b" | bc)"
    fi
    mpi "$n" liggghts -in "$repo/bench/peers/in.drum.liggghts" -var data settled.data \
      -var stl drum_ascii.stl -var omega_period "$period" -var steps "$steps" -var every "$steps" \
      -var dump /dev/null -log "liggghts-np$n.log" -echo none > "liggghts-np$n.out" 2>&1
    l=$(sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' "liggghts-np$n.log" | tail -1)
    echo "np $n: yuxi $y s, liggghts $l s, liggghts / yuxi $(echo "scale=3; $l / $y" | bc)"
  done
done
