# Sourced by the scripts that run yuxi beside LIGGGHTS 3.8 (bench/*_liggghts.sh): stops unless
# Debian's `liggghts` is installed, reads the arguments [YUXI] [WORK] [NP] (defaults: the
# Release build, $default_work, $default_np), enters WORK and defines mpi, mpirun as root, and
# drum_scene for the drum benchmarks.
command -v liggghts > /dev/null ||
  { echo "LIGGGHTS is missing: apt-get install liggghts (Debian)" >&2; exit 1; }
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
yuxi=$(realpath "${1:-$repo/build/release/apps/yuxi/yuxi}")
work=${2:-$default_work}
np=${3:-$default_np}
mkdir -p "$work"
cd "$work"
mpi() { mpirun --allow-run-as-root --oversubscribe -np "$@"; }

# drum_scene KIND NAME DATA OMEGA T_END [SED_ARGS ...]: scenes/drum/drum-KIND.toml (stl or
# cylinder) as NAME.toml, resized to a drum of $radius and $length with the grains of DATA and
# the STL in WORK, turning at OMEGA, to T_END; SED_ARGS edit it further.
drum_scene() {
  local kind=$1 name=$2 data=$3 omega=$4 t_end=$5
  shift 5
  sed -e "s|^name = .*|name = \"$name\"|" -e "s|^t_end = .*|t_end = $t_end|" \
    -e "s|^lo = \[-11.0, -1.0, -11.0\]|lo = [-$((radius + 1)).0, -1.0, -$((radius + 1)).0]|" \
    -e "s|^hi = \[11.0, 7.0, 11.0\]|hi = [$((radius + 1)).0, $((length + 1)).0, $((radius + 1)).0]|" \
    -e "s|^file = \"grains.data\"|file = \"$work/$data\"|" \
    -e "s|^file = \"drum.stl\"|file = \"$work/drum.stl\"|" -e "s|^omega = .*|omega = $omega|" \
    -e "s|^radius = 10.0|radius = $radius.0|" -e "s|^hi = 6.0|hi = $length.0|" "$@" \
    "$repo/scenes/drum/drum-$kind.toml" > "$name.toml"
}
