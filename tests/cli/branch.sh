#!/usr/bin/env bash
# `yuxi run SCENE --from CHECKPOINT`: a run that continues another's saved state under a scene.
#  1. The checkpoint's own scene continues as --resume does: the same bytes in the final
#     checkpoint and in energies.csv from the branch point on.
#  2. Another excitation mode (m = 3) and another contact model (hooke, whose history is
#     dropped, with a warning) run on; the books carry on closed: the balance of the branch's
#     first row equals the saved run's at that time (the change of stored energy is booked as
#     `inserted`), and the run ends without a failure.
#  3. The same branch on 2 ranks gives the energies of 1 rank to 1e-9 (relative).
#  4. Refusals, exit code 2 and a message naming the problem: other materials, other wall
#     particles than the checkpoint holds, an end time before the checkpoint's, and a domain
#     that does not hold the saved grains.
#  5. The grains are the checkpoint's: a scene that builds fewer takes them all, and so does a
#     scene that builds none (its cells and skin sized for the saved grains).
# usage: branch.sh YUXI MPIEXEC WORK_DIR
set -euo pipefail
yuxi=$1
mpiexec=$2
work=$3
here=$(cd "$(dirname "$0")" && pwd)
basin=$here/../reliability/basin.toml
rm -rf "$work"
mkdir -p "$work"
cd "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
run() { "$yuxi" run "$@" --no-progress --no-plots; }

# The saved run: the reliability basin to t = 1.0 (its wall starts shaking at t = 1).
run "$basin" -o saved --t-end 1.0 > saved.log 2>&1 || fail "the saved run did not finish"
checkpoint=saved/checkpoints/$(ls saved/checkpoints | tail -1)

# 1. The checkpoint's own scene (another name and end time do not count).
cp "$basin" same.toml
run same.toml --from "$checkpoint" -o branched --t-end 1.2 > branched.log 2>&1 ||
  fail "the identical branch did not run"
cp -r saved resumed
run --resume resumed --t-end 1.2 > resumed.log 2>&1 || fail "the resume did not run"
grep -q "continues as --resume would" branched.log || fail "the identical scene was not seen"
last=$(ls resumed/checkpoints | tail -1)
cmp -s "branched/checkpoints/$last" "resumed/checkpoints/$last" ||
  fail "the identical branch's final checkpoint differs from the resumed run's"
rows=$(($(wc -l < branched/energies.csv) - 1))
diff -q <(tail -n "$rows" branched/energies.csv) <(tail -n "$rows" resumed/energies.csv) > /dev/null ||
  fail "the identical branch's energies.csv differs from the resumed run's"

# The balance column of a CSV row at a given step.
balance_at() {
  awk -F, -v step="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "balance") c = i }
                        NR > 1 && $1 == step { print $c }' "$1"
}
step=$(tail -1 saved/energies.csv | cut -d, -f1)
same_balance() { # FILE: the branch's first balance against the saved run's at the same step
  local a b
  a=$(balance_at saved/energies.csv "$step")
  b=$(balance_at "$1" "$step")
  awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-9 * (a < 0 ? -a : a)) }' ||
    fail "$1: balance $b at the branch point, the saved run had $a"
}

# 2. Another mode, and another contact model.
sed 's/^mode = 2 .*/mode = 3/' "$basin" > m3.toml
run m3.toml --from saved -o m3 --t-end 1.2 > m3.log 2>&1 || fail "the m = 3 branch failed"
same_balance m3/energies.csv
sed -e 's/^model = "linear"/model = "hooke"/' -e '/^k_t\|^gamma_t\|^mu_s\|^mu_d/d' "$basin" > hooke.toml
run hooke.toml --from saved -o hooke --t-end 1.2 > hooke.log 2>&1 ||
  fail "the hooke branch failed: $(tail -3 hooke.log)"
grep -q "history .* is dropped" hooke.log || fail "no warning that the history is dropped"
same_balance hooke/energies.csv

# 3. On 2 ranks.
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$yuxi" run m3.toml --from saved -o m3np2 \
  --t-end 1.2 --no-progress --no-plots > m3np2.log 2>&1 || fail "the 2-rank branch failed"
paste -d, <(tail -n +2 m3/energies.csv) <(tail -n +2 m3np2/energies.csv) | awk -F, '
  { n = NF / 2; for (i = 3; i <= n; i++) { a = $i; b = $(i + n); d = a - b; if (d < 0) d = -d;
    s = (a < 0 ? -a : a) + 1e-300; if (d > 1e-9 * s + 1e-12) bad++ } }
  END { exit bad > 0 }' || fail "the 2-rank branch's energies differ from 1 rank's beyond 1e-9"

# 4. Refusals.
refused() { # NAME PATTERN SCENE [ARGS...]: exit code 2 and a message matching PATTERN
  local name=$1 pattern=$2
  shift 2
  set +e
  run "$@" -o "refused_$name" > "refused_$name.log" 2>&1
  local code=$?
  set -e
  [[ $code == 2 ]] || fail "$name: exit code $code, expected 2"
  grep -q "$pattern" "refused_$name.log" || fail "$name: no message matching '$pattern'"
}
sed 's/^materials = \["grain", "wall"\]/materials = ["sand", "wall"]/; s/"grain"/"sand"/g' "$basin" > other_materials.toml
refused materials "materials: \[sand, wall\] are not the checkpoint's" other_materials.toml --from saved
sed 's/^wall_height = .*/wall_height = 9/' "$basin" > lower.toml
refused lower "the checkpoint holds .* wall particles, this scene builds" lower.toml --from saved
refused early "is not after the checkpoint's time" same.toml --from saved --t-end 0.5

# A grain thrown up to z ~ 8 by t = 1, and a branch whose domain ends at z = 5.
cat > thrown.toml <<'EOF'
materials = ["grain"]
[run]
dt = 1e-3
t_end = 1.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 20.0]
gravity = [0.0, 0.0, -1.0]
[contact]
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 1e4
[[particle]]
position = [5.0, 5.0, 2.0]
velocity = [0.0, 0.0, 6.5]
radius = 0.5
mass = 1.0
material = "grain"
EOF
sed 's/^hi = \[10.0, 10.0, 20.0\]/hi = [10.0, 10.0, 5.0]/; s/^t_end = 1.0/t_end = 2.0/' thrown.toml > low.toml
run thrown.toml -o thrown > thrown.log 2>&1 || fail "the thrown grain's run failed"
refused outside "outside this scene's domain" low.toml --from thrown

# 5. The grains are the checkpoint's.
column_at() { # FILE COLUMN: the column of the last row
  awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) c = i } END { print $c }' "$1"
}
sed 's/^fill_layers = 5/fill_layers = 4/' "$basin" > fewer.toml
run fewer.toml --from saved -o fewer --t-end 1.05 > fewer.log 2>&1 ||
  fail "a scene that builds fewer grains was refused: $(tail -2 fewer.log)"
[[ $(column_at fewer/energies.csv grains) == $(column_at saved/energies.csv grains) ]] ||
  fail "fewer: $(column_at fewer/energies.csv grains) grains, the checkpoint held $(column_at saved/energies.csv grains)"
sed '/^\[\[particle\]\]/,$d; s/^t_end = 1.0/t_end = 1.5/' thrown.toml > empty.toml
run empty.toml --from thrown -o empty > empty.log 2>&1 ||
  fail "a scene with no grains of its own was refused: $(tail -2 empty.log)"
[[ $(column_at empty/energies.csv grains) == 1 ]] || fail "empty: the thrown grain did not come along"
grep -q "skin 0.2" empty.log || fail "empty: the skin was not sized for the saved grain"

if ((failures > 0)); then
  echo "$failures check(s) failed"
  exit 1
fi
echo "branch: all checks passed"
