#!/usr/bin/env bash
# Stored references of whole runs: a refactor proves that behaviour is unchanged to the bit.
# Each case runs yuxi and compares its outputs with the copies kept in reference/<case>/:
#   basin-np1, basin-np2  scenes/basin-small.toml to t = 10.3 tau (0.3 tau of shaking) on 1 and
#                         2 MPI ranks: energies.csv, and a SHA-256 of every particle's x, v and w
#                         in id order at the end (state_digest.py on the last VTK frame)
#   c1                    validation case C1: the LAMMPS chute (scenes/chute-lammps.toml), 100
#                         steps: energies.csv and the digest at step 100
#   collide               `yuxi collide` (every model's built-in set): its CSV tables
#   drum-stl-np1, -np2    scenes/drum/drum-stl.toml (575 grains in a turning 96-facet STL drum)
#                         to t = 4 tau (2,000 steps) on 1 and 2 ranks: energies.csv, walls.csv
#                         and the digest of the last frame
#   drum-cylinder-np1,    scenes/drum/drum-cylinder.toml, the same drum as an analytic cylinder,
#   drum-cylinder-np2     on 1 and 2 ranks
#   basin-mesh-np1, -np2  scenes/basin-mesh.toml (the basin's side wall an STL mesh) to t = 10.3
#                         tau on 1 and 2 ranks: energies.csv, walls.csv and the digest
#   device-c1, device-basin  the chute to step 1,000 and scenes/basin-small.toml to t = 10.3
#                         tau, with its analysis, on the device engine (--device host, or the
#                         device YUXI_DEVICE names: the GPU must give the host build's bytes):
#                         energies.csv, the digest of the last frame, and the basin's analysis
#                         files of the shaking
#   bulk-np1, bulk-np2    the small bulk cases of scenes/bulk/ (*-small.toml: the drum to t = 12,
#                         Beverloo's silo to 12 with its refill and outlet, the heap to 20 with
#                         its pour, the Janssen column to 15 while it fills) on 1 and 2 ranks:
#                         energies.csv, measurements.csv, inflow/outflow.csv, walls.csv, digest
# usage: references.sh [--update] YUXI MPIEXEC CASE|all WORK_DIR
# With --update the references are rewritten from this build instead (regenerate them only in a
# commit that changes the trajectory on purpose, and say so in it):
#   tests/regression/references.sh --update build/release/apps/yuxi/yuxi mpiexec all /tmp/refs
set -euo pipefail
update=0
if [[ ${1:-} == --update ]]; then update=1; shift; fi
yuxi=$(realpath "$1")
mpiexec=$2
case_name=$3
work=$4
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
refs=$here/reference
mpirun() { "$mpiexec" --allow-run-as-root --oversubscribe -np "$@"; }
digest() { /usr/bin/python3 "$here/state_digest.py" "$1"; }

status=0
# compare CASE FILE...: each file of the run against its stored copy (or store it).
compare() {
  local name=$1 out=$work/$1
  shift
  mkdir -p "$refs/$name"
  for f in "$@"; do
    if ((update)); then
      mkdir -p "$(dirname "$refs/$name/$f")"
      cp "$out/$f" "$refs/$name/$f"
      echo "$name: stored $f"
    elif cmp -s "$out/$f" "$refs/$name/$f"; then
      echo "$name: identical $f"
    else
      echo "$name: DIFFERENT $f"
      diff <(head -c 2000 "$refs/$name/$f") <(head -c 2000 "$out/$f") | head -8 || true
      status=1
    fi
  done
}

run_basin() { # NP
  local name=basin-np$1 out=$work/basin-np$1
  rm -rf "$out"
  mpirun "$1" "$yuxi" run "$repo/scenes/basin-small.toml" --t-end 10.3 -o "$out" --no-progress \
    --no-plots > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
  digest "$out/particles_000103000.vtu" > "$out/state.sha256"
  compare "$name" energies.csv state.sha256
}

run_c1() {
  local out=$work/c1
  rm -rf "$out"
  mkdir -p "$work"
  # The shipped scene with a frame at step 100 and the data file found from anywhere.
  sed -e 's|^snapshot_interval = .*|snapshot_interval = 0.01|' \
    -e "s|^file = .*|file = \"$repo/data/lammps/data.chute\"|" \
    "$repo/scenes/chute-lammps.toml" > "$work/c1.toml"
  "$yuxi" run "$work/c1.toml" --t-end 0.01 -o "$out" --no-progress --no-plots \
    > "$work/c1.log" 2>&1 || { cat "$work/c1.log"; exit 1; }
  digest "$out/particles_000000100.vtu" > "$out/state.sha256"
  compare c1 energies.csv state.sha256
}

run_drum() { # NAME SCENE NP
  local name=$1 out=$work/$1
  rm -rf "$out"
  mpirun "$3" "$yuxi" run "$repo/scenes/drum/$2.toml" --t-end 4 -o "$out" --no-progress \
    --no-plots > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
  digest "$out/particles_000002000.vtu" > "$out/state.sha256"
  compare "$name" energies.csv walls.csv state.sha256
}

# run_scene NAME SCENE T_END NP FILE...: the scene on NP ranks to T_END; the FILEs and the
# digest of the last frame compared.
run_scene() {
  local name=$1 scene=$2 t_end=$3 np=$4 out=$work/$1
  shift 4
  rm -rf "$out"
  mkdir -p "$(dirname "$out")"
  mpirun "$np" "$yuxi" run "$repo/scenes/$scene" --t-end "$t_end" -o "$out" --no-progress \
    --no-plots > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
  local frames=("$out"/particles_*.vtu)
  digest "${frames[-1]}" > "$out/state.sha256"
  compare "$name" "$@" state.sha256
}

run_bulk() { # NP
  local kind
  for kind in drum:12 beverloo:12 heap:20 janssen:15; do
    local name=bulk-np$1/${kind%%:*} files=(energies.csv measurements.csv)
    case ${kind%%:*} in
      drum) files+=(walls.csv) ;;
      beverloo) files+=(inflow.csv outflow.csv walls.csv) ;;
      heap) files+=(inflow.csv outflow.csv) ;;
      janssen) files+=(inflow.csv walls.csv) ;;
    esac
    run_scene "$name" "bulk/${kind%%:*}-small.toml" "${kind##*:}" "$1" "${files[@]}"
  done
}

run_device() { # NAME SCENE T_END FILE...
  local name=$1 scene=$2 t_end=$3 out=$work/$1
  shift 3
  rm -rf "$out"
  mkdir -p "$work"
  # (a frame at the end, and the data file found from anywhere)
  sed -e 's|^snapshot_interval = .*|snapshot_interval = 0.1|' \
    -e "s|^file = .*|file = \"$repo/data/lammps/data.chute\"|" \
    "$repo/scenes/$scene" > "$work/$name.toml"
  "$yuxi" run "$work/$name.toml" --t-end "$t_end" --device "${YUXI_DEVICE:-host}" -o "$out" \
    --no-progress --no-plots > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
  local frames=("$out"/particles_*.vtu)
  digest "${frames[-1]}" > "$out/state.sha256"
  compare "$name" energies.csv state.sha256 "$@"
}

run_collide() {
  local out=$work/collide
  rm -rf "$out"
  "$yuxi" collide -o "$out" --no-plots > "$work/collide.log" 2>&1 ||
    { cat "$work/collide.log"; exit 1; }
  compare collide restitution.csv oblique.csv collision_series.csv
}

mkdir -p "$work"
case $case_name in
  basin-np1) run_basin 1 ;;
  basin-np2) run_basin 2 ;;
  c1) run_c1 ;;
  collide) run_collide ;;
  drum-stl-np1) run_drum drum-stl-np1 drum-stl 1 ;;
  drum-stl-np2) run_drum drum-stl-np2 drum-stl 2 ;;
  drum-cylinder-np1) run_drum drum-cylinder-np1 drum-cylinder 1 ;;
  drum-cylinder-np2) run_drum drum-cylinder-np2 drum-cylinder 2 ;;
  basin-mesh-np1) run_scene basin-mesh-np1 basin-mesh.toml 10.3 1 energies.csv walls.csv ;;
  basin-mesh-np2) run_scene basin-mesh-np2 basin-mesh.toml 10.3 2 energies.csv walls.csv ;;
  device-c1) run_device device-c1 chute-lammps.toml 0.1 ;;
  device-basin)
    run_device device-basin basin-small.toml 10.3 analysis/peaks.csv analysis/period_sections.csv \
      analysis/surface_t10.25.csv ;;
  bulk-np1) run_bulk 1 ;;
  bulk-np2) run_bulk 2 ;;
  all)
    run_basin 1; run_basin 2; run_c1; run_collide
    run_drum drum-stl-np1 drum-stl 1; run_drum drum-stl-np2 drum-stl 2
    run_drum drum-cylinder-np1 drum-cylinder 1; run_drum drum-cylinder-np2 drum-cylinder 2
    run_scene basin-mesh-np1 basin-mesh.toml 10.3 1 energies.csv walls.csv
    run_scene basin-mesh-np2 basin-mesh.toml 10.3 2 energies.csv walls.csv
    run_bulk 1; run_bulk 2
    run_device device-c1 chute-lammps.toml 0.1
    run_device device-basin basin-small.toml 10.3 analysis/peaks.csv analysis/period_sections.csv \
      analysis/surface_t10.25.csv
    ;;
  *) echo "unknown case $case_name" >&2; exit 2 ;;
esac
exit $status
