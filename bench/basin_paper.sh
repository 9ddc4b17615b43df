#!/usr/bin/env bash
# yuxi against LAMMPS on the fish basin at the paper's size (scenes/basin-paper.toml: about
# 296,000 particles) in LAMMPS conventions (bench/peers/lammps_basin_scene.py: one friction
# coefficient, the grain-grain law for every pair). yuxi settles the scene to t = 10 tau on
# SETTLE_RANKS ranks (about 10 minutes on 2 cores; the settled folder is kept and reused by later
# invocations), bench/peers/lammps_data_from_dump.py hands that state to LAMMPS (bench/peers/in.basin), and
# both codes run STEPS steps of the m = 2 excitation from there, on 1 and 2 ranks, alternating
# (LAMMPS, yuxi, ...) REPEATS times. Prints the medians, the yuxi/LAMMPS ratios, each code's
# time breakdown and peak memory per particle, and yuxi's parallel efficiency on this scene.
# usage: bench/basin_paper.sh [STEPS] [REPEATS] [SETTLED_DIR] [SETTLE_RANKS]
#        (build first: cmake --build --preset release)
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-1000}
repeats=${2:-2}
settled=${3:-runs/bench-basin-paper-settled}
settle_ranks=${4:-2}
yuxi=$PWD/build/release/apps/yuxi/yuxi
source bench/side_by_side.sh

python3 bench/peers/lammps_basin_scene.py scenes/basin-paper.toml "$work"
if [[ ! -s $settled/particles.lammpstrj ]] || ! ls "$settled"/checkpoints/* > /dev/null 2>&1; then
  echo "settling basin-paper to t = 10 tau on $settle_ranks ranks into $settled"
  "${mpi[@]}" -np "$settle_ranks" "$yuxi" run "$work/basin-vibrating.toml" --t-end 10 \
    -o "$settled" --overwrite --no-progress --no-plots > "$work/settle.log" 2>&1 ||
    { cat "$work/settle.log"; exit 1; }
fi
python3 bench/peers/lammps_data_from_dump.py "$settled/particles.lammpstrj" "$work/basin.data" --heavy 2
particles=$(grep -oP '^\d+(?= atoms)' "$work/basin.data")
skin=$(run_skin "$settled")
t_end=$(awk -v s="$steps" 'BEGIN {printf "%.6f", 10 + s * 1e-4}')
# The basin's axis: the middle of the domain in x and y.
centre=$(grep -oP '^hi *= *\[\K[0-9.]+' scenes/basin-paper.toml | awk '{print $1 / 2}')

for r in $(seq 1 "$repeats"); do
  for np in 1 2; do
    run_lammps paper "$np" "$particles" "$steps" -var datafile "$work/basin.data" \
      -var steps "$steps" -var excite 1 -var xc "$centre" -var yc "$centre" \
      -var skin "$skin" -in "$PWD/bench/peers/in.basin"
    rm -rf "$work/resumed" && cp -r "$settled" "$work/resumed"
    run_yuxi paper "$np" --resume "$work/resumed" --t-end "$t_end"
  done
done
report paper "basin-paper from t = 10 tau, side wall vibrating (m = 2, omega = 400, dr = 0.9), $particles particles, $steps steps" "$particles"
one=$(echo "${rates[yuxi,paper,1]}" | median)
two=$(echo "${rates[yuxi,paper,2]}" | median)
awk -v a="$one" -v b="$two" 'BEGIN {printf "\nyuxi parallel efficiency at 2 ranks: %.1f %%\n", 100 * b / (2 * a)}'
