#!/usr/bin/env bash
# yuxi against LAMMPS on LAMMPS's own granular chute benchmark (bench/in.chute, the
# 32,000-sphere ../shared/data/data.chute, gran/hooke/history), the same number of steps, on 1
# and 2 ranks, side by side in one invocation: runs alternate (LAMMPS, yuxi, LAMMPS, yuxi, ...)
# so that machine drift affects both alike. Prints per code and rank count the median
# particle-steps/s, the yuxi/LAMMPS ratio, each code's time breakdown, and peak memory per
# particle (largest resident set of one rank / particles on that rank).
# Installs LAMMPS from Debian if it is missing. Build yuxi first (cmake --build --preset release).
# usage: bench/versus_lammps.sh [STEPS] [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-10000}
repeats=${2:-3}
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

# Each rank runs under /usr/bin/time, which writes its peak resident memory (kB) to mem.<rank>.
cat > "$work/timed" <<'WRAP'
#!/usr/bin/env bash
exec /usr/bin/time -f %M -o "$MEMDIR/mem.${OMPI_COMM_WORLD_RANK:-0}" "$@"
WRAP
chmod +x "$work/timed"
export MEMDIR=$work
peak_kb() { cat "$work"/mem.* | sort -n | tail -1; }

declare -A rates=() memory=() breakdown=()
for r in $(seq 1 "$repeats"); do
  for np in 1 2; do
    # LAMMPS: its loop time and breakdown from the log.
    rm -f "$work"/mem.*
    (cd "$work" && "${mpi[@]}" -np "$np" -x MEMDIR "$work/timed" lmp -var datafile "$data" \
       -var steps "$steps" -in "$OLDPWD/bench/in.chute" -log "$work/lammps.log" -screen none)
    loop=$(grep -oP 'Loop time of \K[0-9.e+-]+' "$work/lammps.log")
    rates[lammps,$np]+="$(awk -v t="$loop" -v n="$particles" -v s="$steps" 'BEGIN {print n * s / t}') "
    memory[lammps,$np]=$(peak_kb)
    breakdown[lammps,$np]=$(awk '/^Pair  *\|/ {p=$(NF)} /^Neigh *\|/ {n=$(NF)} /^Comm  *\|/ {c=$(NF)}
      /^Output *\|/ {o=$(NF)} /^Modify *\|/ {m=$(NF)} /^Other *\|/ {x=$(NF)}
      END {printf "pair %s%% neigh %s%% comm %s%% output %s%% modify %s%% other %s%%", p, n, c, o, m, x}' \
      "$work/lammps.log")
    # yuxi: the same steps (dt = 1e-4).
    rm -f "$work"/mem.*
    t_end=$(awk -v s="$steps" 'BEGIN {printf "%.6f", s * 1e-4}')
    "${mpi[@]}" -np "$np" -x MEMDIR "$work/timed" "$yuxi" run scenes/chute-lammps.toml --t-end "$t_end" -o "$work/yuxi" --overwrite \
      --no-progress --no-plots > "$work/yuxi.log" 2>&1
    rates[yuxi,$np]+="$(grep -oP '[0-9.e+]+(?= particle-steps/s)' "$work/yuxi.log") "
    memory[yuxi,$np]=$(peak_kb)
    breakdown[yuxi,$np]=$(grep -oP 'time: \K.*' "$work/yuxi.log")
  done
done
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
printf "chute, %d spheres, %d steps, %d repeats (medians)\n" "$particles" "$steps" "$repeats"
printf "%-7s %5s %16s %8s %12s  %s\n" code ranks particle-steps/s ratio "B/particle" breakdown
for np in 1 2; do
  l=$(echo "${rates[lammps,$np]}" | median)
  y=$(echo "${rates[yuxi,$np]}" | median)
  for code in lammps yuxi; do
    rate=$([[ $code == lammps ]] && echo "$l" || echo "$y")
    ratio=$(awk -v a="$rate" -v b="$l" 'BEGIN {printf "%.2f", a / b}')
    bytes=$(awk -v kb="${memory[$code,$np]}" -v n="$particles" -v np="$np" \
      'BEGIN {printf "%.0f", kb * 1024 / (n / np)}')
    printf "%-7s %5s %16.4g %8s %12s  %s\n" "$code" "$np" "$rate" "$ratio" "$bytes" \
      "${breakdown[$code,$np]}"
  done
done
