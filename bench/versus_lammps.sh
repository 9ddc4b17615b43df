#!/usr/bin/env bash
# yuxi against LAMMPS on LAMMPS's own granular chute benchmark (bench/in.chute, the
# 32,000-sphere ../shared/data/data.chute, gran/hooke/history), the same number of steps, on 1
# and 2 ranks, side by side in one invocation: runs alternate (LAMMPS, yuxi, LAMMPS, yuxi, ...)
# so that machine drift affects both alike. Prints per code and rank count the median
# particle-steps/s, the yuxi/LAMMPS ratio, each code's time breakdown, and peak memory per
# particle (largest resident set of one rank / particles on that rank).
# Then the fish basin (scenes/basin-small.toml, 4,220 particles) in LAMMPS conventions, with one
# friction coefficient (mu_s = mu_d) and the grain-grain law for every pair, as bench/in.basin
# runs it in LAMMPS: yuxi settles it to t = 10 tau, both codes start from that state for
# BASIN_STEPS steps, once with every wall particle still and once with the side wall vibrating.
# Installs LAMMPS from Debian if it is missing. Build yuxi first (cmake --build --preset release).
# usage: bench/versus_lammps.sh [STEPS] [REPEATS] [BASIN_STEPS]
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-10000}
repeats=${2:-3}
basin_steps=${3:-5000}
yuxi=$PWD/build/release/apps/yuxi/yuxi
data=$(realpath ../shared/data/data.chute)
if ! command -v lmp > /dev/null; then
  if [[ $(id -u) -eq 0 ]]; then apt-get install -y -q lammps > /dev/null; else sudo apt-get install -y -q lammps > /dev/null; fi
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
particles=32000
mpi=(mpirun --allow-run-as-root --oversubscribe --bind-to none)
export OMP_NUM_THREADS=1
# yuxi moves its halos through Open MPI's shared-memory buffers rather than single kernel copies
# (apps/yuxi/main.cpp); LAMMPS gets the same transport, so the comparison is of the codes.
export OMPI_MCA_btl_vader_single_copy_mechanism=none

# Each rank runs under /usr/bin/time, which writes its peak resident memory (kB) to mem.<rank>.
cat > "$work/timed" <<'WRAP'
#!/usr/bin/env bash
exec /usr/bin/time -f %M -o "$MEMDIR/mem.${OMPI_COMM_WORLD_RANK:-0}" "$@"
WRAP
chmod +x "$work/timed"
export MEMDIR=$work
peak_kb() { cat "$work"/mem.* | sort -n | tail -1; }

declare -A rates=() memory=() breakdown=()
# Runs one case with LAMMPS: run_lammps CASE NP PARTICLES STEPS LMP-ARGS...; records its rate
# (from the loop time), peak memory and time breakdown.
run_lammps() {
  local case=$1 np=$2 particles=$3 steps=$4
  shift 4
  rm -f "$work"/mem.*
  (cd "$work" && "${mpi[@]}" -np "$np" -x MEMDIR "$work/timed" lmp "$@" -log "$work/lammps.log" \
     -screen none)
  local loop
  loop=$(grep -oP 'Loop time of \K[0-9.e+-]+' "$work/lammps.log")
  rates[lammps,$case,$np]+="$(awk -v t="$loop" -v n="$particles" -v s="$steps" 'BEGIN {print n * s / t}') "
  memory[lammps,$case,$np]=$(peak_kb)
  breakdown[lammps,$case,$np]=$(awk '/^Pair  *\|/ {p=$(NF)} /^Neigh *\|/ {n=$(NF)} /^Comm  *\|/ {c=$(NF)}
    /^Output *\|/ {o=$(NF)} /^Modify *\|/ {m=$(NF)} /^Other *\|/ {x=$(NF)}
    END {printf "pair %s%% neigh %s%% comm %s%% output %s%% modify %s%% other %s%%", p, n, c, o, m, x}' \
    "$work/lammps.log")
}
# The same with yuxi: run_yuxi CASE NP YUXI-RUN-ARGS...
run_yuxi() {
  local case=$1 np=$2
  shift 2
  rm -f "$work"/mem.*
  "${mpi[@]}" -np "$np" -x MEMDIR "$work/timed" "$yuxi" run "$@" --no-progress --no-plots \
    > "$work/yuxi.log" 2>&1
  rates[yuxi,$case,$np]+="$(grep -oP '[0-9.e+]+(?= particle-steps/s)' "$work/yuxi.log") "
  memory[yuxi,$case,$np]=$(peak_kb)
  breakdown[yuxi,$case,$np]=$(grep -oP 'time: \K.*' "$work/yuxi.log")
}

# The basin scenes in LAMMPS conventions (excited from t0 = 10 tau, and never), settled by yuxi.
python3 - "$work" <<'PY'
import sys
work = sys.argv[1]
s = open("scenes/basin-small.toml").read()
s = s[: s.index("[analysis]")]
law = """k_n = 2.5e5
k_t = 0.57e5
gamma_n = 100.0
gamma_t = 32.0
mu_s = 0.5
"""
s = (s[: s.index("[[contact.pair]]")]
     + "".join(f'[[contact.pair]]\nmaterials = ["grain", "{m}"]\n{law}\n' for m in ("grain", "wall"))
     + s[s.index("[basin]"):])
s = s.replace('model = "linear"', 'model = "linear"\npreset = "lammps"')
s = s.replace("snapshot_interval = 0.25", "snapshot_interval = 10.0")
open(f"{work}/basin-vibrating.toml", "w").write(s)
open(f"{work}/basin-still.toml", "w").write(s.replace("t0 = 10.0", "t0 = 1.0e9"))
PY
for motion in vibrating still; do
  "$yuxi" run "$work/basin-$motion.toml" --t-end 10 -o "$work/settled-$motion" --no-progress \
    --no-plots > /dev/null
  python3 bench/lammps_data_from_dump.py "$work/settled-$motion/particles.lammpstrj" \
    "$work/basin-$motion.data" --heavy 2
done
basin_particles=$(grep -oP '^\d+(?= atoms)' "$work/basin-still.data")
t_basin=$(awk -v s="$basin_steps" 'BEGIN {printf "%.6f", 10 + s * 1e-4}')

for r in $(seq 1 "$repeats"); do
  for np in 1 2; do
    run_lammps chute "$np" "$particles" "$steps" -var datafile "$data" -var steps "$steps" \
      -in "$PWD/bench/in.chute"
    t_end=$(awk -v s="$steps" 'BEGIN {printf "%.6f", s * 1e-4}')
    run_yuxi chute "$np" scenes/chute-lammps.toml --t-end "$t_end" -o "$work/yuxi" --overwrite
    for motion in still vibrating; do
      run_lammps "basin-$motion" "$np" "$basin_particles" "$basin_steps" \
        -var datafile "$work/basin-$motion.data" -var steps "$basin_steps" \
        -var excite "$([[ $motion == vibrating ]] && echo 1 || echo 0)" -in "$PWD/bench/in.basin"
      rm -rf "$work/resumed" && cp -r "$work/settled-$motion" "$work/resumed"
      run_yuxi "basin-$motion" "$np" --resume "$work/resumed" --t-end "$t_basin"
    done
  done
done
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
report() {
  local case=$1 title=$2 n=$3
  printf "\n%s (medians of %d)\n" "$title" "$repeats"
  printf "%-7s %5s %16s %8s %12s  %s\n" code ranks particle-steps/s ratio "B/particle" breakdown
  for np in 1 2; do
    local l y
    l=$(echo "${rates[lammps,$case,$np]}" | median)
    y=$(echo "${rates[yuxi,$case,$np]}" | median)
    for code in lammps yuxi; do
      local rate ratio bytes
      rate=$([[ $code == lammps ]] && echo "$l" || echo "$y")
      ratio=$(awk -v a="$rate" -v b="$l" 'BEGIN {printf "%.2f", a / b}')
      bytes=$(awk -v kb="${memory[$code,$case,$np]}" -v n="$n" -v np="$np" \
        'BEGIN {printf "%.0f", kb * 1024 / (n / np)}')
      printf "%-7s %5s %16.4g %8s %12s  %s\n" "$code" "$np" "$rate" "$ratio" "$bytes" \
        "${breakdown[$code,$case,$np]}"
    done
  done
}
report chute "chute, $particles spheres, $steps steps" "$particles"
report basin-still "basin-small settled at t = 10 tau, walls still, $basin_particles particles, $basin_steps steps" "$basin_particles"
report basin-vibrating "basin-small from t = 10 tau, side wall vibrating (omega = 400, dr = 0.9), $basin_steps steps" "$basin_particles"
