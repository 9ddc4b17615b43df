# Shared by the side-by-side benchmarks (versus_lammps.sh, basin_paper.sh), which source it:
# installs LAMMPS from Debian if missing, makes the work folder ($work), and defines
#   run_lammps CASE NP PARTICLES STEPS LMP-ARGS...   and   run_yuxi CASE NP YUXI-RUN-ARGS...
# which record each run's rate, peak memory and time breakdown, and
#   report CASE TITLE PARTICLES                      (uses $repeats)
# which prints medians and yuxi/LAMMPS ratios per rank count, and
#   run_skin RUN_DIR
# the Verlet skin of the yuxi run that both codes continue, for LAMMPS's `neighbor`.
# Expects $yuxi (the binary) to be set. Where $YUXI_BASELINE names another yuxi binary (an
# earlier build), run_yuxi runs it too, right after, as code "base", and report adds its row and
# the yuxi/base ratio run by run: a change's cost measured in the same invocation.
if ! command -v lmp > /dev/null; then
  if [[ $(id -u) -eq 0 ]]; then apt-get install -y -q lammps > /dev/null; else sudo apt-get install -y -q lammps > /dev/null; fi
fi
# shellcheck source=bench/stats.sh
source "$(dirname "${BASH_SOURCE[0]}")/stats.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
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
  # A case of several runs (settling, then shaking) prints a loop time and a breakdown for each:
  # their times are added up.
  local loop
  loop=$(grep -oP 'Loop time of \K[0-9.e+-]+' "$work/lammps.log" | awk '{t += $1} END {print t}')
  rates[lammps,$case,$np]+="$(awk -v t="$loop" -v n="$particles" -v s="$steps" 'BEGIN {print n * s / t}') "
  memory[lammps,$case,$np]=$(peak_kb)
  breakdown[lammps,$case,$np]=$(awk -F'|' -v loop="$loop" '
    $1 ~ /^(Pair|Neigh|Comm|Output|Modify|Other) *$/ {name = $1; gsub(/ /, "", name); t[name] += $3}
    END {printf "pair %.2f%% neigh %.2f%% comm %.2f%% output %.2f%% modify %.2f%% other %.2f%%",
      100 * t["Pair"] / loop, 100 * t["Neigh"] / loop, 100 * t["Comm"] / loop,
      100 * t["Output"] / loop, 100 * t["Modify"] / loop, 100 * t["Other"] / loop}' \
    "$work/lammps.log")
}
# The same with yuxi: run_yuxi CASE NP YUXI-RUN-ARGS..., and run_baseline CASE NP ARGS... with
# $YUXI_BASELINE where set (a run it resumes must be one it wrote: an older build may not read a
# newer build's checkpoints).
run_yuxi_as() {
  local code=$1 binary=$2 case=$3 np=$4
  shift 4
  rm -f "$work"/mem.*
  "${mpi[@]}" -np "$np" -x MEMDIR "$work/timed" "$binary" run "$@" --no-progress --no-plots \
    > "$work/yuxi.log" 2>&1
  rates[$code,$case,$np]+="$(grep -oP '[0-9.e+]+(?= particle-steps/s)' "$work/yuxi.log") "
  memory[$code,$case,$np]=$(peak_kb)
  breakdown[$code,$case,$np]=$(grep -oP 'time: \K.*' "$work/yuxi.log")
}
run_yuxi() {
  local case=$1 np=$2
  shift 2
  run_yuxi_as yuxi "$yuxi" "$case" "$np" "$@"
}
run_baseline() {
  [[ -n ${YUXI_BASELINE:-} ]] || return 0
  run_yuxi_as base "$YUXI_BASELINE" "$@"
}

# The skin a yuxi run used: its resolved scene holds every setting, defaults included, so a
# settled folder kept from an earlier invocation gives LAMMPS the skin that yuxi resumes with.
run_skin() { grep -oP '^skin *= *\K[0-9.e+-]+' "$1/scene.resolved.toml"; }

report() {
  local case=$1 title=$2 n=$3
  printf "\n%s (medians of %d)\n" "$title" "$repeats"
  printf "%-7s %5s %16s %8s %12s  %s\n" code ranks particle-steps/s ratio "B/particle" breakdown
  for np in 1 2; do
    local l
    l=$(echo "${rates[lammps,$case,$np]}" | median)
    local codes=(lammps yuxi)
    [[ -n ${YUXI_BASELINE:-} ]] && codes+=(base)
    for code in "${codes[@]}"; do
      local rate ratio bytes
      rate=$(echo "${rates[$code,$case,$np]}" | median)
      ratio=$(awk -v a="$rate" -v b="$l" 'BEGIN {printf "%.2f", a / b}')
      bytes=$(awk -v kb="${memory[$code,$case,$np]}" -v n="$n" -v np="$np" \
        'BEGIN {printf "%.0f", kb * 1024 / (n / np)}')
      printf "%-7s %5s %16.4g %8s %12s  %s\n" "$code" "$np" "$rate" "$ratio" "$bytes" \
        "${breakdown[$code,$case,$np]}"
    done
  done
  # Each yuxi run against the LAMMPS run just before it: a burst of load from other jobs on the
  # machine slows a run or two, and moves this median less than the ratio of the medians.
  for np in 1 2; do
    local ratios
    ratios=$(run_by_run "${rates[lammps,$case,$np]}" "${rates[yuxi,$case,$np]}" 1 %.2f)
    printf "yuxi/LAMMPS run by run on %d rank(s): %s(median %s)\n" "$np" "$ratios" \
      "$(echo "$ratios" | median)"
    if [[ -n ${YUXI_BASELINE:-} ]]; then
      ratios=$(run_by_run "${rates[base,$case,$np]}" "${rates[yuxi,$case,$np]}" 1 %.3f)
      printf "yuxi/base run by run on %d rank(s): %s(median %s)\n" "$np" "$ratios" \
        "$(echo "$ratios" | median)"
    fi
  done
}
