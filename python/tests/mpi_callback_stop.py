"""Run by test_mpi.py on 2 ranks: a callback whose answer differs between the ranks (rank 1
says stop at step 200, rank 0 never does), then one that raises on rank 1 only. Every rank must
stop at the same step and go on to the next call; rank 0 prints what each rank saw as JSON."""
import json
import sys

import yuxi
from conftest import BOX

out = sys.argv[1]
sim = yuxi.Simulation(BOX, output=out, overwrite=True, progress=False)
sim.run(t_end=1.0, callback=lambda s: not (s.rank == 1 and s.step_count >= 200), every=100)
stopped_at = sim.step_count


def raises_on_rank_1(s):
    if s.rank == 1 and s.step_count >= 300:
        raise ArithmeticError("rank 1's callback failed")


try:
    sim.run(t_end=1.0, callback=raises_on_rank_1, every=100)
    raised = ""
except ArithmeticError as e:
    raised = "ArithmeticError: " + str(e)
except RuntimeError as e:
    raised = "RuntimeError: " + str(e)
grains = sim.energies()["grains"]  # collective: every rank is still in step
report = {"rank": sim.rank, "stopped_at": stopped_at, "raised_at": sim.step_count,
          "raised": raised, "grains": grains}
from mpi4py import MPI  # noqa: E402

everyone = MPI.COMM_WORLD.gather(report, root=0)
if sim.rank == 0:
    print(json.dumps(everyone))
sim.close()
