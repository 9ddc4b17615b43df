"""One script under mpirun -np 2 runs one decomposed simulation: the energies of 1 rank, to the
tolerance of the engine's MPI tests (tests/mpi/: 1e-9 relative over a run; the summation order
changes with the decomposition)."""
import json
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


def run(ranks, out):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [HERE] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    cmd = [sys.executable, os.path.join(HERE, "mpi_energies.py"), str(out)]
    if ranks > 1:
        launcher = ["mpirun", "-np", str(ranks), "--oversubscribe"]
        if os.geteuid() == 0:
            launcher.append("--allow-run-as-root")
        cmd = launcher + cmd
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    line = [s for s in done.stdout.splitlines() if s.startswith("{")][-1]
    return json.loads(line)


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_two_ranks_run_one_simulation_with_the_energies_of_one(tmp_path):
    one = run(1, tmp_path / "one")
    two = run(2, tmp_path / "two")
    assert one["ranks"] == 1 and two["ranks"] == 2
    assert one["callbacks"] == two["callbacks"] == 5
    for key in ("translational", "elastic", "gravitational", "dissipated", "inserted"):
        a, b = one["energies"][key], two["energies"][key]
        assert b == pytest.approx(a, rel=1e-9, abs=1e-12), key
    assert one["energies"]["grains"] == two["energies"]["grains"] == 343
