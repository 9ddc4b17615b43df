"""Run by test_mpi.py on 2 ranks. `mismatch`: rank 0 asks for the energies while rank 1 gathers
a field; both raise CollectiveError naming each rank's call, and stay in step (the next
collective call works). `timeout`: rank 0 asks for the energies alone; it raises after its
timeout instead of waiting forever, prints what it saw, and ends the job."""
import json
import sys
import time

import yuxi
from conftest import BOX
from mpi4py import MPI

mode, out = sys.argv[1], sys.argv[2]
sim = yuxi.Simulation(BOX, output=out, overwrite=True, progress=False)
sim.run(steps=50)

if mode == "mismatch":
    try:
        if sim.rank == 0:
            sim.energies()
        else:
            sim.gather("id")
        raised = ""
    except yuxi.CollectiveError as e:
        raised = str(e)
    grains = sim.energies()["grains"]  # in step again
    sim.run(steps=50)
    report = {"rank": sim.rank, "raised": raised, "grains": grains, "step": sim.step_count}
    everyone = MPI.COMM_WORLD.gather(report, root=0)
    if sim.rank == 0:
        print(json.dumps(everyone))
    sim.close()
else:
    sim.collective_timeout = 1.0
    if sim.rank == 0:
        start = time.monotonic()
        try:
            sim.energies()
            raised = ""
        except yuxi.CollectiveError as e:
            raised = str(e)
        try:
            sim.run(steps=10)
            after = ""
        except yuxi.CollectiveError as e:
            after = str(e)
        print(json.dumps({"raised": raised, "after": after,
                          "waited": time.monotonic() - start}), flush=True)
        MPI.COMM_WORLD.Abort(3)  # the ranks are out of step: the job ends
    else:
        time.sleep(60)
