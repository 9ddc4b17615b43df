#!/usr/bin/env bash
# The Beverloo case at D_o = 8 d (scenes/bulk/beverloo-Do8.toml: about 38,500 grains in a flat
# silo of D = 30 d, the orifice opened at 25 tau, refilled from above, 65 tau in all) in yuxi
# and in LIGGGHTS 3.8 (Debian's `liggghts`, bench/peers/in.beverloo.liggghts: insert/rate/region, the
# same annulus STL), on NP ranks, one after the other, from the same filled silo (yuxi's state
# at t = 0). Prints each code's loop time and its discharge rate W [m/tau] over the middle 60 %
# of the open time (as the validation case B3 measures it: a line fitted to the cumulative mass
# that left).
# usage: bench/beverloo_vs_liggghts.sh [YUXI] [WORK] [NP]
set -euo pipefail
default_work=/tmp/yuxi-beverloo-liggghts default_np=2
source "$(dirname "$0")/liggghts_side.sh"
mpi "$np" "$yuxi" run "$repo/scenes/bulk/beverloo-Do8.toml" -o yuxi --overwrite --no-progress \
  --no-plots > yuxi.log 2>&1
/usr/bin/python3 "$repo/bench/peers/lammps_data_from_dump.py" yuxi/particles.lammpstrj start.data \
  --frame first > /dev/null
/usr/bin/python3 - "$repo/scenes" <<'PY'
import math
import sys
sys.path.insert(0, sys.argv[1])
from binary_stl import write_ascii_stl
n, radius = 64, 4.5  # the shutter's top: a disc over the orifice at z = 0
ring = [(radius * math.cos(2 * math.pi * k / n), radius * math.sin(2 * math.pi * k / n), 0.0)
        for k in range(n + 1)]
write_ascii_stl("plug.stl", [((0.0, 0.0, 0.0), ring[k], ring[k + 1]) for k in range(n)], "plug")
PY
mpi "$np" liggghts -in "$repo/bench/peers/in.beverloo.liggghts" -var data start.data \
  -var floor "$repo/scenes/bulk/annulus-Do8.stl" -var plug plug.stl -var thermo 625 \
  -log liggghts.log -echo none > liggghts.out 2>&1
/usr/bin/python3 - <<'PY'
import re
import numpy as np

def rate(t, m, t_open=25.0, t_end=65.0):
    lo, hi = t_open + 0.2 * (t_end - t_open), t_end - 0.2 * (t_end - t_open)
    k = (t >= lo - 1e-9) & (t <= hi + 1e-9)
    return np.polyfit(t[k], m[k], 1)[0]

# yuxi: outflow.csv, cumulative mass that left.
import csv
rows = list(csv.DictReader(open("yuxi/outflow.csv")))
t = np.array([float(r["time"]) for r in rows])
m = np.array([float(r["mass"]) for r in rows])
y_time = float(re.findall(r"steps in ([0-9.]+) s", open("yuxi.log").read())[-1])
# LIGGGHTS: the mass in the box (thermo) and the mass inserted so far (insertion reports).
text = open("liggghts.log").read()
thermo = [tuple(map(float, l.split()[:3])) for l in text.splitlines()
          if re.match(r"^\s*\d+\s+\d+\s+[0-9.eE+-]+\s+[0-9.eE+-]+\s*$", l)]
steps = np.array([s for s, _, _ in thermo])
mass = np.array([x for _, _, x in thermo])
reports = re.findall(r"inserted \S+ particle templates \(mass [0-9.eE+-]+\) at step (\d+)\s*\n"
                     r" - a total of \S+ particle templates \(mass ([0-9.eE+-]+)\)", text)
ins_steps = np.array([int(s) for s, _ in reports])
ins_mass = np.array([float(x) for _, x in reports])
inserted = np.array([ins_mass[ins_steps <= s][-1] if (ins_steps <= s).any() else 0.0
                     for s in steps])
left = mass[0] + inserted - mass
# (the first run's last row and the second run's first row repeat a step)
_, first = np.unique(steps, return_index=True)
l_t = steps[first] * 8e-4
l_left = left[first]
loops = [float(x) for x in re.findall(r"Loop time of ([0-9.eE+-]+) on", text)]
print(f"yuxi:     {y_time:.0f} s, W = {rate(t, m):.2f} m/tau")
print(f"liggghts: {sum(loops):.0f} s, W = {rate(l_t, l_left):.2f} m/tau "
      f"(liggghts / yuxi time: {sum(loops) / y_time:.2f})")
PY
