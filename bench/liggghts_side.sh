# Sourced by the scripts that run yuxi beside LIGGGHTS 3.8 (bench/*_liggghts.sh): stops unless
# Debian's `liggghts` is installed, reads the arguments [YUXI] [WORK] [NP] (defaults: the
# Release build, $default_work, $default_np), enters WORK and defines mpi, mpirun as root.
command -v liggghts > /dev/null ||
  { echo "LIGGGHTS is missing: apt-get install liggghts (Debian)" >&2; exit 1; }
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
yuxi=$(realpath "${1:-$repo/build/release/apps/yuxi/yuxi}")
work=${2:-$default_work}
np=${3:-$default_np}
mkdir -p "$work"
cd "$work"
mpi() { mpirun --allow-run-as-root --oversubscribe -np "$@"; }
