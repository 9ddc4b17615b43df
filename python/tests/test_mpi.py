"""One script under mpirun -np 2 runs one decomposed simulation: the energies of 1 rank, to the
tolerance of the engine's MPI tests (tests/mpi/: 1e-9 relative over a run; the summation order
changes with the decomposition)."""
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


def run(ranks, out, script="mpi_energies.py", args=(), expect_rc=0):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [HERE] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    cmd = [sys.executable, os.path.join(HERE, script), *args, str(out)]
    if ranks > 1:
        launcher = ["mpirun", "-np", str(ranks), "--oversubscribe"]
        if os.geteuid() == 0:
            launcher.append("--allow-run-as-root")
        cmd = launcher + cmd
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)
    assert (done.returncode == 0) == (expect_rc == 0), done.stderr
    line = [s for s in done.stdout.splitlines() if s.startswith(("{", "["))][-1]
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


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_a_callback_s_stop_is_agreed_over_the_ranks(tmp_path):
    """A stop (or an exception) decided on one rank's particles stops every rank at that step,
    and each goes on to the next collective call: no rank is left waiting (the test would time
    out)."""
    ranks = run(2, tmp_path / "stop", "mpi_callback_stop.py")
    assert [r["rank"] for r in ranks] == [0, 1]
    assert [r["stopped_at"] for r in ranks] == [200, 200]
    assert [r["raised_at"] for r in ranks] == [300, 300]
    assert ranks[1]["raised"] == "ArithmeticError: rank 1's callback failed"
    assert ranks[0]["raised"].startswith("RuntimeError: the run stopped: the callback raised")
    assert ranks[0]["grains"] == ranks[1]["grains"] == 343


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_ranks_in_different_collective_calls_raise_on_every_rank(tmp_path):
    """Rank 0 in energies(), rank 1 in gather(): both raise CollectiveError naming each rank's
    call (the test would time out on a deadlock), and both go on in step."""
    ranks = run(2, tmp_path / "mismatch", "mpi_collective_guard.py", ["mismatch"])
    for r in ranks:
        assert "the ranks met in different ones (rank 0: energies(), rank 1: gather())" in \
            r["raised"], r["raised"]
    assert [r["grains"] for r in ranks] == [343, 343]
    assert [r["step"] for r in ranks] == [100, 100]


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_a_collective_call_on_one_rank_raises_after_the_timeout(tmp_path):
    """energies() on rank 0 alone (under `if rank == 0:`): CollectiveError after the timeout
    (1 s here), and every later collective call raises at once."""
    report = run(2, tmp_path / "alone", "mpi_collective_guard.py", ["timeout"], expect_rc=3)
    assert "energies() is collective: every rank must call it" in report["raised"]
    assert "rank 0 waited 1 s" in report["raised"]
    assert "the ranks are out of step since energies() timed out" in report["after"]
    assert 1.0 <= report["waited"] < 30.0


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_coarse_grained_fields_do_not_depend_on_the_ranks(tmp_path):
    """Each rank adds the sums of its grains and of its contacts (each contact on one rank), the
    sums are added over the ranks, and every rank makes the fields of the whole (from Python),
    or rank 0 writes them (a [[coarse_grain]] table): 1, 2 and 4 ranks give the same fields, to
    the runs' own agreement (the trajectories differ in the last digits with the
    decomposition's summation order)."""
    runs = [run(k, tmp_path / f"cg{k}", "mpi_coarse_grain.py") for k in (1, 2, 4)]
    assert [r["ranks"] for r in runs] == [1, 2, 4]
    one = runs[0]["fields"]
    assert np.sum(one["grid_density"]) > 0 and np.abs(one["profile_stress"]).max() > 0
    for other in runs[1:]:
        assert other["ranks_differ_by"] == 0.0
        for key, value in one.items():
            a, b = np.asarray(value), np.asarray(other["fields"][key])
            assert np.allclose(b, a, rtol=1e-6, atol=1e-9 * np.abs(a).max()), key


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_clumps_changed_from_python_on_two_ranks_run_as_on_one(tmp_path):
    """Clumps added across the ranks' cut, given velocities by the ranks that own them and
    removed by ids that only some rank holds: the run of 2 ranks is the run of 1, to the
    tolerance of the engine's MPI tests."""
    one = run(1, tmp_path / "one", "mpi_clump_edits.py")
    two = run(2, tmp_path / "two", "mpi_clump_edits.py")
    assert two["ranks"] == 2
    assert one["added"] == two["added"] and one["removed"] == two["removed"] > 1
    assert one["ids"] == two["ids"]
    assert np.allclose(two["x"], one["x"], rtol=0, atol=1e-7)
    for key in ("translational", "rotational", "elastic", "gravitational", "dissipated",
                "inserted", "removed"):
        a, b = one["energies"][key], two["energies"][key]
        assert b == pytest.approx(a, rel=1e-9, abs=1e-12), key
    assert one["energies"]["grains"] == two["energies"]["grains"]
