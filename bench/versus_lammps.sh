#!/usr/bin/env bash
# yuxi against LAMMPS on LAMMPS's own granular chute benchmark (bench/peers/in.chute, the
# 32,000-sphere data/lammps/data.chute, gran/hooke/history), the same number of steps, on 1
# and 2 ranks, side by side in one invocation: runs alternate (LAMMPS, yuxi, LAMMPS, yuxi, ...)
# so that machine drift affects both alike. Prints per code and rank count the median
# particle-steps/s, the yuxi/LAMMPS ratio, each code's time breakdown, and peak memory per
# particle (largest resident set of one rank / particles on that rank).
# Then the fish basin (scenes/basin-small.toml, 4,220 particles) in LAMMPS conventions, with one
# friction coefficient (mu_s = mu_d) and the grain-grain law for every pair, as bench/peers/in.basin
# runs it in LAMMPS: yuxi settles it to t = 10 tau, both codes start from that state for
# BASIN_STEPS steps, once with every wall particle still and once with the side wall vibrating.
# Last the whole scene as it is shipped: both codes start from yuxi's initial state (t = 0), let
# the grains fall and settle to t0 = 10 tau with the walls still and shake them to t_end = 11 tau.
# Installs LAMMPS from Debian if it is missing. Build yuxi first (cmake --build --preset release).
# YUXI_BASELINE=/path/to/an/earlier/yuxi adds that build beside them, run after each yuxi run
# (bench/side_by_side.sh): the cost of a change, side by side in one invocation.
# usage: [YUXI_BASELINE=BINARY] bench/versus_lammps.sh [STEPS] [REPEATS] [BASIN_STEPS]
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-10000}
repeats=${2:-3}
basin_steps=${3:-5000}
yuxi=$PWD/build/release/apps/yuxi/yuxi
data=$(realpath data/lammps/data.chute)
particles=32000
source bench/side_by_side.sh

# The basin scenes in LAMMPS conventions (excited from t0 = 10 tau, and never), settled by yuxi.
python3 bench/peers/lammps_basin_scene.py scenes/basin-small.toml "$work"
for motion in vibrating still; do
  "$yuxi" run "$work/basin-$motion.toml" --t-end 10 -o "$work/settled-$motion" --no-progress \
    --no-plots > /dev/null
  if [[ -n ${YUXI_BASELINE:-} ]]; then
    "$YUXI_BASELINE" run "$work/basin-$motion.toml" --t-end 10 -o "$work/settled-$motion.base" \
      --no-progress --no-plots > /dev/null
  fi
  python3 bench/peers/lammps_data_from_dump.py "$work/settled-$motion/particles.lammpstrj" \
    "$work/basin-$motion.data" --heavy 2
done
basin_particles=$(grep -oP '^\d+(?= atoms)' "$work/basin-still.data")
basin_skin=$(run_skin "$work/settled-still")
t_basin=$(awk -v s="$basin_steps" 'BEGIN {printf "%.6f", 10 + s * 1e-4}')
# The whole run: yuxi's first frame (t = 0) for LAMMPS; steps to t0 and from t0 to t_end.
python3 bench/peers/lammps_data_from_dump.py "$work/settled-vibrating/particles.lammpstrj" \
  "$work/basin-start.data" --frame first --heavy 2
scene_value() { grep -oP "^ *$1 *= *\K[0-9.e+-]+" "$work/basin-vibrating.toml" | head -1; }
settle_steps=$(awk -v t="$(scene_value t0)" -v dt="$(scene_value dt)" 'BEGIN {printf "%d", t / dt + 0.5}')
shake_steps=$(awk -v t="$(scene_value t_end)" -v t0="$(scene_value t0)" -v dt="$(scene_value dt)" \
  'BEGIN {printf "%d", (t - t0) / dt + 0.5}')

for r in $(seq 1 "$repeats"); do
  for np in 1 2; do
    run_lammps chute "$np" "$particles" "$steps" -var datafile "$data" -var steps "$steps" \
      -in "$PWD/bench/peers/in.chute"
    t_end=$(awk -v s="$steps" 'BEGIN {printf "%.6f", s * 1e-4}')
    run_yuxi chute "$np" scenes/chute-lammps.toml --t-end "$t_end" -o "$work/yuxi" --overwrite
    run_baseline chute "$np" scenes/chute-lammps.toml --t-end "$t_end" -o "$work/yuxi" --overwrite
    for motion in still vibrating; do
      run_lammps "basin-$motion" "$np" "$basin_particles" "$basin_steps" \
        -var datafile "$work/basin-$motion.data" -var steps "$basin_steps" \
        -var excite "$([[ $motion == vibrating ]] && echo 1 || echo 0)" \
        -var skin "$basin_skin" -in "$PWD/bench/peers/in.basin"
      rm -rf "$work/resumed" && cp -r "$work/settled-$motion" "$work/resumed"
      run_yuxi "basin-$motion" "$np" --resume "$work/resumed" --t-end "$t_basin"
      if [[ -n ${YUXI_BASELINE:-} ]]; then
        rm -rf "$work/resumed" && cp -r "$work/settled-$motion.base" "$work/resumed"
        run_baseline "basin-$motion" "$np" --resume "$work/resumed" --t-end "$t_basin"
      fi
    done
    run_lammps basin-whole "$np" "$basin_particles" $((settle_steps + shake_steps)) \
      -var datafile "$work/basin-start.data" -var settle "$settle_steps" \
      -var steps "$shake_steps" -var excite 1 -var skin "$basin_skin" -in "$PWD/bench/peers/in.basin"
    run_yuxi basin-whole "$np" "$work/basin-vibrating.toml" -o "$work/whole" --overwrite
    run_baseline basin-whole "$np" "$work/basin-vibrating.toml" -o "$work/whole" --overwrite
  done
done
report chute "chute, $particles spheres, $steps steps" "$particles"
report basin-still "basin-small settled at t = 10 tau, walls still, $basin_particles particles, $basin_steps steps" "$basin_particles"
report basin-vibrating "basin-small from t = 10 tau, side wall vibrating (omega = 400, dr = 0.9), $basin_steps steps" "$basin_particles"
report basin-whole "basin-small whole run from t = 0: $settle_steps steps of settling, $shake_steps of shaking" "$basin_particles"
