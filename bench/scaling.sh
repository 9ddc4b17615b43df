#!/usr/bin/env bash
# Strong scaling of yuxi on 1 and 2 MPI ranks, side by side in one invocation: runs alternate
# (1 rank, 2 ranks, 2 ranks balanced by time, ...) so that machine drift affects all alike.
# Prints, per scene and variant, the median particle-steps/s, the parallel efficiency
# ps(2) / (2 ps(1)), and the load imbalance after balancing (max/mean over ranks, of the last
# run): in owned particles, in listed pairs and in compute time (pairs, the rank's own part of the
# list builds, integration: no exchanges or waits).
# The 2-rank runs balance the cut planes by listed pairs (domain.balance_by = "pairs", the
# default) and by each rank's measured compute time (--balance-by time). Under each scene, the
# efficiency of each repeat (its 2-rank run against the 1-rank run just before it) and their
# median, which a burst of load from other jobs on the machine moves less than the ratio of the
# medians.
# usage: bench/scaling.sh [REPEATS] [SCENE]   (build first: cmake --build --preset release)
#        SCENE: run only the scenes whose file name contains it (chute, basin-small)
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
only=${2:-}
# shellcheck source=bench/stats.sh
source bench/stats.sh
yuxi=build/release/apps/yuxi/yuxi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# scene | simulated time | label. The basin runs whole: settling, then the vibrating wall (its
# first tau is free fall, with hardly a contact). The paper-size basin: bench/basin_paper.sh.
cases=("scenes/chute-lammps.toml|1.0|chute, 32,000 spheres, 10,000 steps"
       "scenes/basin-small.toml|11.0|basin-small, 4,220 particles, 110,000 steps")
# variant: ranks and balancing
variants=("1 pairs" "2 pairs" "2 time")
printf "%-44s %-14s %16s %11s %10s %10s %10s\n" "scene" "ranks" "particle-steps/s" "efficiency" \
  "particles" "pairs" "compute"
for c in "${cases[@]}"; do
  IFS='|' read -r scene t_end label <<< "$c"
  [[ $scene == *"$only"* ]] || continue
  declare -A rates=()
  declare -A imbalance=()
  declare -A busy=()
  declare -A pairs=()
  for _ in $(seq 1 "$repeats"); do
    for v in "${variants[@]}"; do
      read -r np by <<< "$v"
      log=$work/run.log
      mpirun --allow-run-as-root --oversubscribe -np "$np" "$yuxi" run "$scene" --t-end "$t_end" \
        --balance-by "$by" -o "$work/out" --overwrite --no-progress --no-plots \
        > "$log" 2>&1
      rates[$v]+="$(grep -oP '[0-9.e+]+(?= particle-steps/s)' "$log") "
      imbalance[$v]=$(grep -oP 'load max/mean \K[0-9.]+(?= in particles)' "$log" || echo 1.000)
      busy[$v]=$(grep -oP '\K[0-9.]+(?= in compute time)' "$log" || echo 1.000)
      pairs[$v]=$(grep -oP '\K[0-9.]+(?= in listed pairs)' "$log" || echo 1.000)
    done
  done
  p1=$(echo "${rates[1 pairs]}" | median)
  for v in "${variants[@]}"; do
    read -r np by <<< "$v"
    p=$(echo "${rates[$v]}" | median)
    name="1"
    eff=""
    if [[ $np == 2 ]]; then
      name="2, by $by"
      eff=$(awk -v a="$p1" -v b="$p" 'BEGIN {printf "%.1f %%", 100 * b / (2 * a)}')
    fi
    printf "%-44s %-14s %16.4g %11s %10s %10s %10s\n" "$label" "$name" "$p" "$eff" \
      "${imbalance[$v]}" "${pairs[$v]}" "${busy[$v]}"
    label=""
  done
  for by in pairs time; do
    each=$(run_by_run "${rates[1 pairs]}" "${rates[2 $by]}" 50 %.1f) # 100 % * ps(2) / (2 ps(1))
    printf "%-44s 2 by %s, repeat by repeat: %s(median %s %%)\n" "" "$by" "$each" \
      "$(echo "$each" | median)"
  done
  unset rates imbalance busy pairs
done
