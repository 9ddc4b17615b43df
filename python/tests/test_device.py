"""A run on the device engine from Python (``device=``), in its host build: the same books as
the CPU engine, edits between steps reaching the engine, and misuse refused by name."""
import copy
import os

import numpy as np
import pytest

import yuxi


@pytest.fixture
def gas_scene(box_scene):
    """The box's 343 grains in a box periodic along every axis, without gravity: a granular gas
    once the test gives it velocities, colliding and cooling."""
    s = copy.deepcopy(box_scene)
    s["domain"]["boundary"] = ["periodic", "periodic", "periodic"]
    s["domain"]["gravity"] = [0.0, 0.0, 0.0]
    del s["domain"]["wall_material"]
    s["run"]["t_end"] = 0.06
    return s


def _stir(sim, seed):
    # (by id: the engines keep their particles in different orders)
    ids = np.sort(np.asarray(sim.particles.id)[np.asarray(sim.particles.grains)])
    v = np.random.default_rng(seed).normal(0.0, 3.0, (len(ids), 3))
    sim.set_velocities(ids, v)


def _books(scene, folder, device, stir_again):
    sim = yuxi.Simulation(scene, output=folder, progress=False, device=device)
    _stir(sim, 1)
    sim.run(steps=150)
    if stir_again:
        _stir(sim, 2)  # between steps: the device engine must start again from it
    sim.run()
    e = sim.energies()
    return e, sim.close()


@pytest.mark.parametrize("stir_again", [False, True])
def test_host_build_keeps_the_cpu_engines_books(gas_scene, tmp_path, stir_again):
    cpu, _ = _books(gas_scene, tmp_path / "cpu", None, stir_again)
    dev, summary = _books(gas_scene, tmp_path / "host", "host", stir_again)
    assert summary["device"] == "host (Thrust CPP)"
    assert 0 < summary["device_bytes_per_particle"] <= summary["device_peak_bytes_per_particle"]
    assert cpu["contacts"] > 50 and cpu["dissipated"] > 0
    assert dev["step"] == cpu["step"] == 300
    for book in ("translational", "rotational", "elastic", "dissipated", "inserted", "balance"):
        assert dev[book] == pytest.approx(cpu[book], rel=1e-9, abs=1e-12), book
    assert dev["contacts"] == cpu["contacts"]
    rows = np.genfromtxt(tmp_path / "host" / "energies.csv", delimiter=",", names=True)
    assert len(rows) == 7 and rows["step"][-1] == 300


def test_device_names_are_checked(gas_scene, tmp_path):
    with pytest.raises(ValueError, match="'tpu' is none of"):
        yuxi.Simulation(gas_scene, output=tmp_path / "a", progress=False, device="tpu")
    with pytest.raises(TypeError, match="device"):
        yuxi.Simulation(gas_scene, output=tmp_path / "b", progress=False, device=1)
    gas_scene["run"]["device"] = "tpu"
    with pytest.raises(ValueError, match="device"):
        yuxi.Simulation(gas_scene, output=tmp_path / "c", progress=False)


@pytest.mark.skipif(yuxi.has_cuda, reason="this build has CUDA")
def test_gpu_in_a_build_without_cuda_says_how_to_get_it(gas_scene, tmp_path):
    with pytest.raises(RuntimeError, match="YUXI_CUDA=ON"):
        yuxi.Simulation(gas_scene, output=tmp_path / "gpu", progress=False, device="gpu")
    assert not os.path.exists(tmp_path / "gpu"), "a refused run made its folder"


def test_box_walls_run_as_on_the_cpu_engine(box_scene, tmp_path):
    """343 grains falling into a box with walls on its faces (still planes), past the list build
    at step 1,226 that carries the contacts' springs: books and the floor's load agree."""
    box_scene["run"]["t_end"] = 0.3
    runs = []
    for device in (None, "host"):
        sim = yuxi.Simulation(box_scene, output=tmp_path / str(device), progress=False,
                              device=device)
        sim.run()
        runs.append((sim.energies(), sim.wall_loads()["box z lo"]))
        sim.close()
    (cpu, cpu_floor), (dev, dev_floor) = runs
    assert cpu["contacts"] > 200 and cpu_floor["contacts"] > 10
    for book in ("translational", "rotational", "elastic", "dissipated", "balance"):
        assert dev[book] == pytest.approx(cpu[book], rel=1e-9), book
    assert dev["contacts"] == cpu["contacts"]
    assert dev_floor["contacts"] == cpu_floor["contacts"]
    assert np.allclose(dev_floor["force"], cpu_floor["force"], rtol=1e-9, atol=1e-9)
    walls = np.genfromtxt(tmp_path / "host" / "walls.csv", delimiter=",", names=True, dtype=None,
                          encoding="utf-8")
    assert len(walls) > 6 * 10


def test_an_oscillating_plane_works_on_the_grains_as_on_the_cpu_engine(box_scene, tmp_path):
    """The box's grains landed on a plane that starts to shake at t = 0.25 and throws them up:
    its work, in the books and in its own load, and the books agree with the CPU engine."""
    box_scene["run"]["t_end"] = 0.4
    box_scene["plane"] = [{"name": "shaker", "point": [0.0, 0.0, 0.3], "normal": [0.0, 0.0, 1.0],
                           "material": "wall", "amplitude": 0.05, "omega": 60.0, "t0": 0.25}]
    runs = []
    for device in (None, "host"):
        sim = yuxi.Simulation(box_scene, output=tmp_path / str(device), progress=False,
                              device=device)
        sim.run()
        runs.append((sim.energies(), sim.wall_loads()["shaker"]["work"]))
        sim.close()
    (cpu, cpu_work), (dev, dev_work) = runs
    assert cpu["wall_work"] > 100.0 and cpu_work == pytest.approx(cpu["wall_work"])
    for book in ("translational", "elastic", "dissipated", "wall_work", "balance"):
        assert dev[book] == pytest.approx(cpu[book], rel=1e-9), book
    assert dev_work == pytest.approx(cpu_work, rel=1e-9)


def test_contacts_are_not_recorded_on_the_device(gas_scene, tmp_path):
    sim = yuxi.Simulation(gas_scene, output=tmp_path / "rec", progress=False, device="host")
    with pytest.raises(RuntimeError, match="CPU engine only"):
        sim.record_contacts(True)
    sim.close()


def _rods(scene):
    scene["shape"] = [{"name": "rod", "spheres": [[-0.3, 0.0, 0.0, 0.2],
                                                  [0.3, 0.0, 0.0, 0.2]]}]


def test_clumps_added_on_the_device_run_there_as_on_the_cpu(gas_scene, tmp_path):
    """Clumps added between steps: the device engine starts again from the simulation with
    them, and keeps the CPU engine's books and the clumps' motion."""
    _rods(gas_scene)
    out = []
    for device in (None, "host"):
        sim = yuxi.Simulation(gas_scene, output=tmp_path / str(device), progress=False,
                              device=device)
        _stir(sim, 1)
        sim.run(steps=50)
        ids = sim.add_clumps("rod", [[4.0, 4.0, 11.5], [7.95, 2.0, 11.5]],
                             velocities=[[0.0, 0.0, 4.0], [3.0, 0.0, -2.0]])
        sim.run(steps=200)
        out.append((sim.energies(), sim.clumps(), ids))
        sim.close()
    (cpu, cpu_clumps, cpu_ids), (dev, dev_clumps, dev_ids) = out
    assert list(dev_ids) == list(cpu_ids)
    assert dev["grains"] == cpu["grains"] == 345
    for book in ("translational", "rotational", "elastic", "dissipated", "balance"):
        assert dev[book] == pytest.approx(cpu[book], rel=1e-9, abs=1e-12), book
    np.testing.assert_allclose(dev_clumps["position"], cpu_clumps["position"], rtol=1e-9)
    np.testing.assert_allclose(dev_clumps["velocity"], cpu_clumps["velocity"], rtol=1e-8)


def test_a_scene_of_clumps_runs_on_the_device_as_on_the_cpu(box_scene, tmp_path):
    """A [[fill]] of clumps placed at the start settles onto the box's walls (planes) on both
    engines alike."""
    _rods(box_scene)
    box_scene["fill"][0]["shape"] = "rod"
    out = []
    for device in (None, "host"):
        with yuxi.Simulation(box_scene, output=tmp_path / str(device), progress=False,
                             device=device) as sim:
            sim.run(steps=5000)
            out.append((sim.energies(), sim.clumps()))
    (cpu, cpu_clumps), (dev, dev_clumps) = out
    assert dev["grains"] == cpu["grains"] == 343
    assert cpu["contacts"] > 50
    for book in ("translational", "rotational", "elastic", "dissipated", "balance"):
        assert dev[book] == pytest.approx(cpu[book], rel=1e-9, abs=1e-12), book
    np.testing.assert_allclose(dev_clumps["orientation"], cpu_clumps["orientation"], atol=1e-9)


def test_a_device_run_of_clumps_resumes_on_the_device_bit_for_bit(tmp_path):
    """scenes/clumps/rod-bed.toml: rods across periodic faces, checkpointed mid-way on the
    device and resumed there, end where the run straight through ends, to the bit."""
    import tomllib
    from conftest import REPO
    with open(os.path.join(REPO, "scenes", "clumps", "rod-bed.toml"), "rb") as f:
        scene = tomllib.load(f)
    scene["run"]["t_end"] = 1.2  # 6,000 steps: the rods settle on the plane and each other

    def state(sim):
        p, c = sim.particles, sim.clumps()
        order = np.argsort(np.asarray(p.id))
        return (np.asarray(p.position)[order], np.asarray(p.velocity)[order],
                np.asarray(c["position"]), np.asarray(c["orientation"]), sim.energies())

    with yuxi.Simulation(scene, output=tmp_path / "straight", progress=False,
                         device="host") as sim:
        sim.run()
        straight = state(sim)
    with yuxi.Simulation(scene, output=tmp_path / "stopped", progress=False,
                         device="host") as sim:
        sim.run(steps=4500)
        assert sim.energies()["contacts"] > 100
        sim.checkpoint()
    resumed = yuxi.Simulation.resume(tmp_path / "stopped", progress=False, device="host")
    resumed.run()
    again = state(resumed)
    resumed.close()
    for a, b in zip(straight[:4], again[:4]):
        assert np.array_equal(a, b)
    assert again[4]["contacts"] == straight[4]["contacts"]


def test_a_device_run_resumes_on_the_cpu(gas_scene, tmp_path):
    sim = yuxi.Simulation(gas_scene, output=tmp_path / "run", progress=False, device="host")
    _stir(sim, 1)
    sim.run(steps=150)
    sim.checkpoint()
    sim.close()
    again = yuxi.Simulation.resume(tmp_path / "run", progress=False, device="cpu")
    assert again.step_count == 150
    again.run()
    assert again.step_count == 300
    again.close()


def test_a_device_run_that_blows_up_stops_with_a_diagnosis(gas_scene, tmp_path):
    gas_scene["run"]["dt"] = 2.0e-2  # a hundred times the scene's: unstable
    gas_scene["run"]["t_end"] = 6.0
    sim = yuxi.Simulation(gas_scene, output=tmp_path / "blow", progress=False, force_dt=True,
                          device="host")
    _stir(sim, 1)
    with pytest.raises(RuntimeError, match="energy books gained .* time step is too large"):
        sim.run()
    assert (tmp_path / "blow" / "failure.txt").exists()
    assert (tmp_path / "blow" / "failure.vtu").exists()
    sim.close()
