#!/usr/bin/env bash
# The cost of coarse-graining during a run: LAMMPS's chute (scenes/chute-lammps.toml, 32,000
# grains) run plain, with a [[coarse_grain]] profile along z (Gaussian, contacts included, every
# field) written every 100 steps, with the same profile averaged over every step
# (average_every = 1), with both of a flow's fields alone (density, velocity, stress,
# temperature: no contact points, no fabric), and with a profile of plain bins averaged over
# every step. The runs alternate, REPEATS times
# each; the script prints the median step rates and the overheads against the plain run, and,
# from each run's own log, the share of its wall time that coarse-graining took ("coarse-graining
# X%" in the log's time line) as an overhead X / (100 - X): a figure of one run, which a machine
# whose speed drifts between runs does not move.
# usage: bench/coarse_grain_cost.sh [YUXI] [STEPS] [REPEATS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
yuxi=${1:-$here/../build/release/apps/yuxi/yuxi}
steps=${2:-2000}
repeats=${3:-5}
# shellcheck source=bench/stats.sh
source "$here/stats.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
t_end=$(awk -v s="$steps" 'BEGIN { print s * 1.0e-4 }')
profile='[[coarse_grain]]
name = "profile"
width = 1.0
average = "xy"
n = [1, 1, 80]'
# (the copies name the LAMMPS data file by its absolute path)
sed "s|\"\.\./data/|\"$(cd "$here/.." && pwd)/data/|" "$here/../scenes/chute-lammps.toml" > "$work/plain.toml"
{ cat "$work/plain.toml"; printf '\n%s\ninterval = 0.01\n' "$profile"; } > "$work/every100.toml"
{ cat "$work/plain.toml"; printf '\n%s\ninterval = 0.01\naverage_every = 1\n' "$profile"; } \
  > "$work/every_step.toml"
flow='fields = ["density", "velocity", "stress", "temperature"]'
{ cat "$work/plain.toml"; printf '\n%s\n%s\ninterval = 0.01\n' "$profile" "$flow"; } \
  > "$work/flow_every100.toml"
{ cat "$work/plain.toml"; printf '\n%s\n%s\ninterval = 0.01\naverage_every = 1\n' "$profile" "$flow"; } \
  > "$work/flow_every_step.toml"
{
  cat "$work/plain.toml"
  printf '\n[[coarse_grain]]\nname = "bins"\nfunction = "bins"\naverage = "xy"\n'
  printf 'n = [1, 1, 80]\ninterval = 0.01\naverage_every = 1\n'
} > "$work/bins_every_step.toml"
run() { # SCENE: the run's steps per second of wall time (the log's "N steps in T s") and the
  # overhead of its coarse-graining in percent (0 where it has none)
  "$yuxi" run "$1" -o "$work/out" --t-end "$t_end" --overwrite --no-progress --no-plots \
    > "$work/log" 2>&1
  sed -n 's/.* \([0-9]*\) steps in \([0-9.]*\) s:.*/\1 \2/p' "$work/log" |
    awk '{ printf "%.6g", $1 / $2 }'
  share=$(sed -n 's/.*coarse-graining \([0-9.]*\)%.*/\1/p' "$work/log")
  awk -v x="${share:-0}" 'BEGIN { printf " %.3f", 100 * x / (100 - x) }'
}
declare -A rates shares
configs=(plain every100 every_step flow_every100 flow_every_step bins_every_step)
for ((k = 0; k < repeats; ++k)); do
  for c in "${configs[@]}"; do
    read -r r o <<< "$(run "$work/$c.toml")"
    rates[$c]+=" $r"
    shares[$c]+=" $o"
  done
done
p=$(median <<< "${rates[plain]}")
echo "chute, $steps steps, $repeats repeats, median steps/s: plain $p"
for c in "${configs[@]:1}"; do
  r=$(median <<< "${rates[$c]}")
  awk -v c="$c" -v p="$p" -v r="$r" 'BEGIN { printf "  %-16s %8.4g steps/s, overhead %.1f %%\n", c, r, 100 * (p / r - 1) }'
  echo "    run by run against plain: $(run_by_run "${rates[plain]}" "${rates[$c]}" 1 %.3f)"
  echo "    within each run (its log's share): median $(median <<< "${shares[$c]}") %," \
    "runs$(printf ' %s' ${shares[$c]})"
done
