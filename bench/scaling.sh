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
# Each repeat also runs two 1-rank runs at once, one on core 0 and one on core 1 (the cores the
# 2 ranks get): the sum of their rates is what the two cores deliver together at that moment.
# The 2-rank rate against that sum is the parallel efficiency with the machine's own limits
# taken out (a core slowed by other virtual machines, memory shared by the two): what the
# exchanges, the waits and the imbalance cost. On a shared virtual machine the two cores' speeds
# can differ by a third for seconds at a time, which the rate of 1 rank alone does not see.
# Last, a 2-rank step's time, its share in exchanges and waits ("comm" in the log), and what MPI
# alone takes to move the same bytes between the two ranks (bench/kernels/exchange_cost.cpp, with the
# ghost count of the run's "halo:" line): the part of the exchanges no engine can save.
# usage: bench/scaling.sh [REPEATS] [SCENE]   (build first: cmake --build --preset release)
#        SCENE: run only the scenes whose file name contains it (chute, basin-small,
#        basin-paper: 1,000 steps of the vibrating wall resumed from the state that
#        bench/basin_paper.sh settles, when runs/bench-basin-paper-settled holds it)
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
only=${2:-}
# shellcheck source=bench/stats.sh
source bench/stats.sh
yuxi=build/release/apps/yuxi/yuxi
exchange_cost=build/release/bench/exchange_cost # (bench/kernels/exchange_cost.cpp)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# scene | simulated time | label. The basin runs whole: settling, then the vibrating wall (its
# first tau is free fall, with hardly a contact). The paper-size basin: bench/basin_paper.sh.
cases=("scenes/chute-lammps.toml|1.0|chute, 32,000 spheres, 10,000 steps"
       "scenes/basin-small.toml|11.0|basin-small, 4,220 particles, 110,000 steps")
settled=runs/bench-basin-paper-settled
if [[ -d $settled ]]; then
  cases+=("$settled|10.1|basin-paper, 295,892 particles, 1,000 steps")
fi
# variant: ranks and balancing ("1+1": two 1-rank runs at once, on cores 0 and 1)
variants=("1 pairs" "2 pairs" "2 time" "1+1 pairs")
# One run of yuxi on NP ranks (or on one core, CORE >= 0) into folder OUT, logged to LOG: a
# scene file, or a copy of a settled run folder resumed.
run_case() {
  local np=$1 core=$2 out=$3 log=$4
  local launch=(mpirun --allow-run-as-root --oversubscribe -np "$np")
  if ((core >= 0)); then launch=(taskset -c "$core"); fi
  local input=(run "$scene" -o "$out" --overwrite)
  if [[ -d $scene ]]; then
    rm -rf "$out"
    cp -r "$scene" "$out"
    input=(run --resume "$out")
  fi
  "${launch[@]}" "$yuxi" "${input[@]}" --t-end "$t_end" --balance-by "$by" --no-progress \
    --no-plots > "$log" 2>&1
}
rate_of() { grep -oP '[0-9.e+]+(?= particle-steps/s)' "$1"; }
printf "%-44s %-14s %16s %11s %10s %10s %10s\n" "scene" "ranks" "particle-steps/s" "efficiency" \
  "particles" "pairs" "compute"
for c in "${cases[@]}"; do
  IFS='|' read -r scene t_end label <<< "$c"
  [[ $scene == *"$only"* ]] || continue
  declare -A rates=()
  declare -A imbalance=()
  declare -A busy=()
  declare -A pairs=()
  declare -A comm=()
  declare -A steps_per_s=()
  for _ in $(seq 1 "$repeats"); do
    for v in "${variants[@]}"; do
      read -r np by <<< "$v"
      log=$work/run.log
      if [[ $np == "1+1" ]]; then
        run_case 1 0 "$work/out0" "$work/run0.log" &
        first=$!
        run_case 1 1 "$work/out1" "$work/run1.log"
        wait "$first"
        rates[$v]+="$(awk -v a="$(rate_of "$work/run0.log")" -v b="$(rate_of "$work/run1.log")" \
          'BEGIN {print a + b}') "
        continue
      fi
      run_case "$np" -1 "$work/out" "$log"
      rates[$v]+="$(rate_of "$log") "
      imbalance[$v]=$(grep -oP 'load max/mean \K[0-9.]+(?= in particles)' "$log" || echo 1.000)
      busy[$v]=$(grep -oP '\K[0-9.]+(?= in compute time)' "$log" || echo 1.000)
      pairs[$v]=$(grep -oP '\K[0-9.]+(?= in listed pairs)' "$log" || echo 1.000)
      if [[ $np == 2 ]]; then
        comm[$v]+="$(grep -oP 'comm \K[0-9.]+(?=%)' "$log") "
        copies=$(grep -oP 'halo: .* particles \K[0-9]+(?= of them)' "$log" || echo 0)
        steps_per_s[$v]+="$(grep -oP '[0-9.]+(?= steps/s)' "$log") "
      fi
    done
  done
  p1=$(echo "${rates[1 pairs]}" | median)
  for v in "${variants[@]}"; do
    read -r np by <<< "$v"
    [[ $np == "1+1" ]] && continue
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
    each=$(run_by_run "${rates[1+1 pairs]}" "${rates[2 $by]}" 100 %.1f) # 100 % * ps(2) / sum
    printf "%-44s   against two 1-rank runs at once: %s(median %s %%)\n" "" "$each" \
      "$(echo "$each" | median)"
  done
  printf "%-44s two 1-rank runs at once, summed (particle-steps/s):" ""
  for r in ${rates[1+1 pairs]}; do printf " %.3g" "$r"; done
  echo
  # The exchanges of a 2-rank step against what MPI alone takes to move the same bytes.
  floor=$(mpirun --allow-run-as-root --oversubscribe -np 2 "$exchange_cost" "$copies" |
    grep -oP "a step's exchanges \K[0-9.]+")
  for by in pairs time; do
    step_us=$(awk -v s="$(echo "${steps_per_s[2 $by]}" | median)" 'BEGIN {printf "%.1f", 1e6 / s}')
    printf "%-44s 2 by %s: a step %s us, its exchanges and waits %s %% of it (median)\n" "" \
      "$by" "$step_us" "$(echo "${comm[2 $by]}" | median)"
  done
  printf "%-44s   MPI alone, the same bytes (%s ghosts' fields and forces, one collective): %s us\n" \
    "" "$copies" "$floor"
  unset rates imbalance busy pairs comm steps_per_s
done
