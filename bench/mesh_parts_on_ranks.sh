#!/usr/bin/env bash
# How much of a mesh each rank holds: a flat STL plate of 2 x CELLS^2 triangles under a 40 x 40 d
# floor of 2,500 grains, run for 1,000 steps on each number of ranks given, and the log's line
# "mesh 'plate': each rank holds A to B of its N triangles" (docs/walls.md section 5). With
# --turning the plate turns about the vertical axis through its centre (a turntable, 0.2 rad/tau:
# its part is chosen again at every list build), in a domain wide enough for its corners.
# usage: bench/mesh_parts_on_ranks.sh [--turning] [YUXI] [MPIEXEC] [CELLS] [RANKS...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
turning=0
if [[ ${1:-} == --turning ]]; then turning=1; shift; fi
yuxi=${1:-$here/../build/release/apps/yuxi/yuxi}
mpiexec=${2:-mpirun}
cells=${3:-200}
shift $(($# < 3 ? $# : 3))
ranks=("$@")
((${#ranks[@]} > 0)) || ranks=(1 2 4)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The plate: binary STL (scenes/binary_stl.py), each cell of the 40 x 40 square at z = 0 cut
# into two triangles.
/usr/bin/python3 - "$work/plate.stl" "$cells" "$here/../scenes" <<'PY'
import sys
sys.path.insert(0, sys.argv[3])
from binary_stl import write_binary_stl
n = int(sys.argv[2])
h = 40.0 / n
tris = []
for j in range(n):
    for i in range(n):
        a, b = (i * h, j * h, 0.0), ((i + 1) * h, j * h, 0.0)
        c, d = ((i + 1) * h, (j + 1) * h, 0.0), (i * h, (j + 1) * h, 0.0)
        tris += [(a, b, c), (a, c, d)]
write_binary_stl(sys.argv[1], tris, "yuxi plate")
PY
lo="0.0, 0.0" hi="40.0, 40.0" motion=""
if ((turning)); then
  lo="-10.0, -10.0" hi="50.0, 50.0"
  motion=$'omega = 0.2\naxis_point = [20.0, 20.0, 0.0]'
fi
cat > "$work/plate.toml" <<TOML
materials = ["grain", "wall"]
[material.grain]
density = 1.909859317
[run]
name = "plate"
dt = 5.0e-4
t_end = 0.5
[domain]
lo = [$lo, -1.0]
hi = [$hi, 10.0]
boundary = ["wall", "wall", "wall"]
gravity = [0.0, 0.0, -1.0]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.0e4
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 2.0e4
[[mesh]]
name = "plate"
file = "plate.stl"
material = "wall"
$motion
[[fill]]
material = "grain"
count = 2500
size = { distribution = "uniform", min = 0.45, max = 0.55 }
region = { shape = "box", lo = [1.0, 1.0, 1.0], hi = [39.0, 39.0, 6.0] }
seed = 1
TOML
for np in "${ranks[@]}"; do
  line=$("$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$yuxi" run "$work/plate.toml" \
    -o "$work/np$np" --no-progress --no-plots 2>&1 | grep -o "mesh 'plate': .*" || true)
  echo "$np rank(s)$( ((turning)) && echo ", turning"): ${line:-every rank holds the whole mesh}"
done
