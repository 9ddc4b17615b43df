#!/usr/bin/env bash
# Speed of a heap of rod-shaped clumps against YADE (Debian's `yade`, one thread): the scene
# scenes/clumps/heap-rod<K>.toml (rods of K spheres, the volume of 1,200 spheres poured onto a
# rough floor, to t = 73 tau), run whole by yuxi on one rank and by bench/peers/yade/clump_heap.py
# (the same floor, pour, contact law and measurements: bench/peers/yade/README.md), one after the
# other, REPEATS times. Prints each run's wall time of the time loop (yuxi: the log's "steps in";
# YADE: the script's wall time of O.run with its pour and measurements), the final angle of
# repose of each, and the YADE/yuxi ratio of the times run by run.
# usage: bench/heap_rods_vs_yade.sh [YUXI] [K] [REPEATS] [WORK]
#   (defaults build/release/apps/yuxi/yuxi, 3, 2, a temporary folder)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
yuxi=$(realpath "${1:-$repo/build/release/apps/yuxi/yuxi}")
rod=${2:-3}
repeats=${3:-2}
work=${4:-$(mktemp -d)}
mkdir -p "$work"
if ! command -v yade > /dev/null; then
  if [[ $(id -u) -eq 0 ]]; then apt-get install -y -q yade > /dev/null; else sudo apt-get install -y -q yade > /dev/null; fi
fi
export OMP_NUM_THREADS=1
scene=$repo/scenes/clumps/heap-rod$rod.toml
[[ -f $scene ]] || { echo "no scene $scene (K is 1, 2, 3 or 5)" >&2; exit 2; }
cd "$work"
printf '%-7s %-7s %12s %10s\n' repeat code "loop [s]" "angle"
for repeat in $(seq "$repeats"); do
  "$yuxi" run "$scene" -o yuxi --overwrite --no-progress --no-plots > yuxi.log 2>&1
  yuxi_s=$(grep -oP 'steps in \K[0-9.]+' yuxi.log)
  yuxi_angle=$(/usr/bin/python3 -c "import csv; print(list(csv.DictReader(open('yuxi/measurements.csv')))[-1]['angle'])")
  printf '%-7s %-7s %12.2f %10.2f\n' "$repeat" yuxi "$yuxi_s" "$yuxi_angle"
  yade -j1 -n -x "$repo/bench/peers/yade/clump_heap.py" "$rod" --out yade > yade.log 2>&1
  yade_s=$(grep -oP '^wall time \K[0-9.]+' yade/angle.txt)
  yade_angle=$(grep -oP '^angle \K[0-9.]+' yade/angle.txt)
  printf '%-7s %-7s %12.2f %10.2f\n' "$repeat" yade "$yade_s" "$yade_angle"
  echo "        YADE/yuxi time: $(awk -v a="$yade_s" -v b="$yuxi_s" 'BEGIN {printf "%.2f", a / b}')"
done
