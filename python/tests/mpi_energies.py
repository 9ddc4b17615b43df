"""Run by test_mpi.py on 1 and on 2 ranks: the box scene, with a velocity written from Python
and a callback, to the end; rank 0 prints the final energy books as JSON."""
import json
import sys

import numpy as np

import yuxi
from conftest import BOX

out = sys.argv[1]
sim = yuxi.Simulation(BOX, output=out, overwrite=True, progress=False)
ids = np.asarray(sim.particles.id).copy()
mine = ids[ids % 7 == 0]  # each rank writes the grains it owns
sim.set_velocities(mine, np.tile([0.0, 0.0, 1.0], (len(mine), 1)))
counts = []
sim.run(callback=lambda s: counts.append(len(s.particles)), every=200)
owned = sim.gather("id")
e = sim.energies()
if sim.rank == 0:
    assert np.array_equal(owned, np.arange(343)), "gather: every id once, in order"
    print(json.dumps({"ranks": sim.ranks, "energies": e, "callbacks": len(counts)}))
sim.close()
