"""Run by test_mpi.py on 1 and on 2 ranks: the box of rods, with clumps added across the
sub-domains, set moving and removed from Python between steps; rank 0 prints the final energy
books and the clumps' ids and centres (gathered) as JSON."""
import json
import sys

import numpy as np

import yuxi
from conftest import BOX

scene = json.loads(json.dumps(BOX))
scene["run"]["dt"] = 1.0e-4
scene["run"]["t_end"] = 0.5
scene["shape"] = [{"name": "rod", "spheres": [[-0.3, 0.0, 0.0, 0.2], [0.0, 0.0, 0.0, 0.2],
                                              [0.3, 0.0, 0.0, 0.2]]}]
scene["fill"][0].update(shape="rod", count=64)
out = sys.argv[1]
sim = yuxi.Simulation(scene, output=out, overwrite=True, progress=False)
sim.step(200)
# across the cut of two ranks (x = 4) and on both sides, one turned a quarter about z
h = np.sqrt(0.5)
added = sim.add_clumps("rod", [[1.0, 2.0, 11.0], [4.0, 4.0, 11.0], [7.0, 6.0, 11.0]],
                       orientations=[[1, 0, 0, 0], [h, 0, 0, h], [1, 0, 0, 0]],
                       velocities=[[0.5, 0.0, -1.0]] * 3)
mine = sim.clumps()["id"]
sim.set_clump_velocities(mine[mine % 2 == 0], np.tile([0.0, 0.0, 1.0], (np.sum(mine % 2 == 0), 1)))
sim.set_clump_angular_velocities(mine[mine % 3 == 0],
                                 np.tile([0.0, 2.0, 0.0], (np.sum(mine % 3 == 0), 1)))
removed = sim.remove_clumps(np.concatenate([added[:1], np.arange(0, 192, 15)]))
sim.run()
e = sim.energies()
ids = sim.gather("id")
x = sim.gather("position")
if sim.rank == 0:
    print(json.dumps({"ranks": sim.ranks, "energies": e, "added": added.tolist(),
                      "removed": int(removed), "ids": ids.tolist(), "x": x.tolist()}))
sim.close()
