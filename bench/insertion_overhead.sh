#!/usr/bin/env bash
# The cost of pouring: a bed of N grains settling in a box, run with and without an [[insert]]
# that pours a few grains per batch into an empty region above it (the batch's candidate checks,
# the list build it forces every `interval`). The runs alternate, REPEATS times each, and the
# script prints the median step rate of each and their ratio: the insertion's overhead per step
# (the poured grains, under 1 % of the bed, fall freely above it and cost next to nothing).
# usage: bench/insertion_overhead.sh [YUXI] [GRAINS] [STEPS] [REPEATS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
yuxi=${1:-$here/../build/release/apps/yuxi/yuxi}
grains=${2:-20000}
steps=${3:-5000}
repeats=${4:-5}
# shellcheck source=bench/stats.sh
source "$here/stats.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
side=$(awk -v n="$grains" 'BEGIN { printf "%.0f", sqrt(n / 12) * 1.2 + 2 }') # ~12 layers
cat > "$work/bed.toml" <<EOF2
materials = ["grain", "wall"]
[material.grain]
density = 1.909859317
[run]
dt = 8.0e-4
t_end = $(awk -v s="$steps" 'BEGIN { print s * 8.0e-4 }')
[output]
energy_interval = 1.0
snapshot_interval = 0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [$side, $side, 40.0]
boundary = ["periodic", "periodic", "wall"]
gravity = [0.0, 0.0, -1.0]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.0e4
k_t = 5714.2857
gamma_n = 50.0
gamma_t = 25.0
mu_s = 0.5
mu_d = 0.5
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 2.0e4
gamma_n = 50.0
[[fill]]
material = "grain"
count = $grains
placement = "lattice"
jitter = 0.02
size = { distribution = "uniform", min = 0.45, max = 0.55 }
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [$side, $side, 30.0] }
EOF2
cp "$work/bed.toml" "$work/pour.toml"
cat >> "$work/pour.toml" <<EOF2
[[insert]]
material = "grain"
rate = 50
size = { distribution = "uniform", min = 0.45, max = 0.55 }
region = { shape = "box", lo = [1.0, 1.0, 33.0], hi = [$((side - 1)), $((side - 1)), 39.0] }
EOF2
rate() { # SCENE: the run's steps per second of wall time (the log's "N steps in T s")
  "$yuxi" run "$1" -o "$work/out" --overwrite --no-progress --no-plots 2>&1 |
    sed -n 's/.* \([0-9]*\) steps in \([0-9.]*\) s:.*/\1 \2/p' | awk '{ printf "%.6g", $1 / $2 }'
}
bed="" pour=""
for ((k = 0; k < repeats; ++k)); do
  bed+=" $(rate "$work/bed.toml")"
  pour+=" $(rate "$work/pour.toml")"
done
b=$(median <<< "$bed")
p=$(median <<< "$pour")
echo "grains $grains, steps $steps, repeats $repeats"
echo "steps/s  without insertion: $b   with: $p"
awk -v b="$b" -v p="$p" 'BEGIN { printf "a step with an insertion active costs %.1f %% more\n", 100 * (b / p - 1) }'
echo "run by run (with / without): $(run_by_run "$bed" "$pour" 1 %.3f)"
