#!/usr/bin/env bash
# A pour with an outlet (tests/cli/pour.toml) on 1 and 2 ranks:
#  1. the same grains come in and leave: inflow.csv and outflow.csv are the same bytes on 1 and
#     2 ranks, and the energies agree to 1e-6 (relative);
#  2. the books close: |balance| < 1 % of the inserted energy;
#  3. resumed half way on 2 ranks, the run ends in the same bytes as the straight one;
#  4. branched from the poured run's end (its grains are its sources', not the scene's), with
#     the silo then lifted along its axis: the branch runs, the lifting silo does work on the
#     grains through friction, and the books still close.
# usage: pour.sh YUXI MPIEXEC WORK_DIR
set -euo pipefail
yuxi=$1
mpiexec=$2
work=$3
scene=$(cd "$(dirname "$0")" && pwd)/pour.toml
rm -rf "$work"
mkdir -p "$work"
cd "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
on() { # NP ARGS...
  local np=$1
  shift
  "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$yuxi" "$@" --no-progress --no-plots
}
on 1 run "$scene" -o np1 > np1.log 2>&1 || fail "the 1-rank run failed: $(tail -3 np1.log)"
on 2 run "$scene" -o np2 > np2.log 2>&1 || fail "the 2-rank run failed: $(tail -3 np2.log)"

# 1. the same grains on 1 and 2 ranks
for f in inflow.csv outflow.csv; do
  cmp -s "np1/$f" "np2/$f" || fail "$f differs between 1 and 2 ranks"
done
grains_in=$(tail -1 np1/inflow.csv | cut -d, -f4)
[[ $grains_in == 400 ]] || fail "inflow.csv ends at $grains_in grains, expected 400"
grains_out=$(tail -1 np1/outflow.csv | cut -d, -f4)
((grains_out > 0)) || fail "no grain left through the cup"
paste -d, <(tail -n +2 np1/energies.csv) <(tail -n +2 np2/energies.csv) | awk -F, '
  { n = NF / 2; for (i = 3; i <= n; i++) { a = $i; b = $(i + n); d = a - b; if (d < 0) d = -d;
    s = (a < 0 ? -a : a) + (b < 0 ? -b : b); if (d > 1e-6 * s + 1e-9) bad++ } }
  END { exit bad > 0 }' || fail "the 2-rank energies differ from 1 rank's beyond 1e-6"

# 2. the books
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "balance") b = i; if ($i == "inserted") s = i } }
         END { d = $b; if (d < 0) d = -d; exit !(s > 0 && d < 0.01 * $s) }' np1/energies.csv ||
  fail "the books do not close: $(tail -1 np1/energies.csv)"

# 3. resumed on 2 ranks
on 2 run "$scene" -o halves --t-end 1.5 > first.log 2>&1 || fail "the first half failed"
on 2 run --resume halves --t-end 3.0 > second.log 2>&1 || fail "the resume failed"
last=$(ls np2/checkpoints | tail -1)
for f in "checkpoints/$last" energies.csv inflow.csv outflow.csv; do
  cmp -s "np2/$f" "halves/$f" || fail "resumed on 2 ranks, $f differs from the straight run's"
done

# 4. a branch of the poured run, the silo lifted at 0.5 from t = 3.1 to 3.5
sed -e 's/^t_end = 3.0/t_end = 4.0/' \
  -e '/^name = "silo"/a velocity = [0.0, 0.0, 0.5]\nt0 = 3.1\nt1 = 3.5' "$scene" > lifted.toml
on 1 run lifted.toml --from np1 -o lifted > lifted.log 2>&1 ||
  fail "the branch of the poured run failed: $(tail -3 lifted.log)"
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "work") w = i }
         $3 == "silo" && $2 > 3.5 { work = $w } END { exit !(work > 0) }' lifted/walls.csv ||
  fail "the lifted silo did no work on the grains: $(grep silo lifted/walls.csv | tail -1)"
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "balance") b = i; if ($i == "inserted") s = i } }
         END { d = $b; if (d < 0) d = -d; exit !(s > 0 && d < 0.01 * $s) }' lifted/energies.csv ||
  fail "the lifted branch's books do not close: $(tail -1 lifted/energies.csv)"

if ((failures > 0)); then
  echo "$failures check(s) failed"
  exit 1
fi
echo "pour: $grains_in grains in, $grains_out out; all checks passed"
