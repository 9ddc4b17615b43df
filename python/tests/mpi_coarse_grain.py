"""Run by test_mpi.py on 1, 2 and 4 ranks: the box scene's grains landing on the floor at t = 1,
coarse-grained (a 3-D Gaussian grid and a profile along z, with the contacts); rank 0 prints the
fields as JSON. Every rank must get the same fields, those of the whole."""
import json
import sys

import numpy as np

import yuxi
from conftest import BOX

out = sys.argv[1]
scene = dict(BOX, run=dict(BOX["run"], t_end=1.0),
             coarse_grain=[{"name": "pile", "width": 0.6, "n": [4, 4, 6], "interval": 0.5}])
sim = yuxi.Simulation(scene, output=out, overwrite=True, progress=False)
sim.run()
sim.record_contacts(True)
sim.step()
grid = yuxi.coarse_grain(sim, width=0.8, n=(8, 8, 12))
profile = yuxi.coarse_grain(sim, width=0.5, average="xy", n=(1, 1, 24), function="lucy")
fields = {}
for name, f in (("grid", grid), ("profile", profile)):
    for key in ("density", "stress", "coordination", "wall_force_density"):
        fields[f"{name}_{key}"] = f[key].tolist()
# Every rank holds the whole's fields: the largest difference from rank 0's, over the ranks.
mine = np.concatenate([np.ravel(grid["stress"]), np.ravel(profile["density"])])
from mpi4py import MPI  # noqa: E402

first = MPI.COMM_WORLD.bcast(mine, root=0)
worst = MPI.COMM_WORLD.reduce(float(np.abs(mine - first).max()), op=MPI.MAX, root=0)
if sim.rank == 0:
    # The run's own [[coarse_grain]] table, at t = 1 (summed over the ranks by the run).
    table = np.genfromtxt(f"{out}/coarse_grain/pile/pile_000005000.csv", delimiter=",",
                          names=True)
    for column in ("density", "stress_zz", "stress_xz", "coordination", "temperature"):
        fields[f"table_{column}"] = table[column].tolist()
    print(json.dumps({"ranks": sim.ranks, "fields": fields, "ranks_differ_by": worst}))
sim.close()
