"""Misuse of the Python API ends in a Python exception that says what to do, never in a crash
or a silent wrong result."""
import os

import numpy as np
import pytest

import yuxi
from conftest import add_square_mesh


@pytest.fixture
def sim(box_scene, tmp_path):
    s = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    yield s
    s.close()


@pytest.mark.parametrize("call", [
    lambda s, kept: s.particles.position,
    lambda s, kept: kept.velocity,
    lambda s, kept: len(kept),
    lambda s, kept: s.checkpoint(),
    lambda s, kept: s.checkpoint("elsewhere.yxc"),
    lambda s, kept: s.run(steps=1),
    lambda s, kept: s.step(),
    lambda s, kept: s.energies(),
    lambda s, kept: s.time,
    lambda s, kept: s.gather("id"),
    lambda s, kept: s.add_grains([[4.0, 4.0, 11.0]], 0.5),
    lambda s, kept: s.set_velocities([0], [[0.0, 0.0, 0.0]]),
    lambda s, kept: s.wall_loads(),
])
def test_every_call_after_close_raises(box_scene, tmp_path, call):
    s = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    kept = s.particles
    view = s.particles.position
    s.run(steps=10)
    s.close()
    with pytest.raises(RuntimeError, match="closed|stepped"):
        call(s, kept)
    with pytest.raises(RuntimeError):
        view[0]
    s.close()  # (closing twice is harmless)


def test_ids_are_integer_ids_not_masks_or_floats(sim):
    grains = sim.particles.grains
    with pytest.raises(TypeError, match="boolean mask.*sim.particles.id\\[mask\\]"):
        sim.set_velocities(grains, np.zeros((int(grains.sum()), 3)))
    with pytest.raises(TypeError, match="integers.*float64"):
        sim.set_velocities([1.5], [[0.0, 0.0, 1.0]])
    with pytest.raises(TypeError, match="boolean mask"):
        sim.remove_grains(grains)
    with pytest.raises(ValueError, match="one-dimensional"):
        sim.set_positions([[0, 1]], [[1.0, 1.0, 1.0]])
    ids = np.asarray(sim.particles.id)[np.asarray(sim.particles.grains)][:3].copy()
    sim.set_velocities(ids.astype(np.int32), np.tile([0.0, 0.0, 1.0], (3, 1)))
    sim.set_velocities([], np.zeros((0, 3)))  # nothing to write is fine
    moved = np.asarray(sim.particles.velocity)[np.isin(np.asarray(sim.particles.id), ids)]
    assert np.all(moved[:, 2] == 1.0) and len(moved) == 3


def test_runs_go_forwards_only(sim):
    sim.run(steps=20)
    with pytest.raises(ValueError, match="forwards"):
        sim.run(steps=-5)
    with pytest.raises(ValueError, match="before the simulation's time"):
        sim.run(t_end=0.5 * sim.time)
    with pytest.raises(TypeError, match="whole number"):
        sim.run(steps=2.5)
    with pytest.raises(TypeError, match="whole number"):
        sim.step("3")
    with pytest.raises(ValueError, match="not finite"):
        sim.run(t_end=float("nan"))
    assert sim.step_count == 20
    sim.run(steps=0)
    sim.run(t_end=sim.time)
    assert sim.step_count == 20


def test_checkpoint_returns_the_file_it_wrote(sim, tmp_path):
    sim.run(steps=10)
    path = sim.checkpoint()
    assert os.path.isfile(path) and path.endswith(".yxc")
    assert os.path.dirname(path) == os.path.join(sim.folder, "checkpoints")
    other = sim.checkpoint(tmp_path / "mine.yxc")
    assert other == os.fspath(tmp_path / "mine.yxc") and os.path.isfile(other)


def test_wall_loads_are_numpy_arrays(sim):
    sim.run(steps=2000)  # (the bottom layer on the floor)
    loads = sim.wall_loads()
    floor = loads["box z lo"]
    assert isinstance(floor["force"], np.ndarray) and floor["force"].shape == (3,)
    assert isinstance(floor["torque"], np.ndarray) and floor["torque"].shape == (3,)
    assert floor["force"][2] != 0 and floor["contacts"] > 0


def test_a_grain_added_on_another_is_refused_by_name(sim):
    sim.run(steps=400)  # (the grains fall clear of the top of the box)
    x = np.asarray(sim.particles.position)[0].copy()
    gid = int(np.asarray(sim.particles.id)[0])
    n = sim.energies()["grains"]
    with pytest.raises(ValueError, match=f"new grain 0 .* overlaps grain {gid} by"):
        sim.add_grains([x + [0.3, 0.0, 0.0]], 0.5)
    with pytest.raises(ValueError, match="new grain 1 .* overlaps new grain 0 of the same call"):
        sim.add_grains([[4.0, 4.0, 11.0], [4.5, 4.0, 11.0]], 0.5)
    with pytest.raises(ValueError, match="overlaps the flat wall 'box z hi'"):
        sim.add_grains([[4.0, 4.0, 11.8]], 0.5)
    assert sim.energies()["grains"] == n  # nothing was added
    (new,) = sim.add_grains([[4.0, 4.0, 11.0]], 0.5)
    sim.run(steps=50)
    assert sim.energies()["grains"] == n + 1 and new >= 343


def test_grains_and_clumps_added_into_a_mesh_or_a_cylinder_are_refused_by_name(box_scene,
                                                                                  tmp_path):
    """The shaped walls are checked as the flat ones are: a new grain or clump member that would
    overlap a cylinder or a mesh is refused, naming the wall and the overlap, and nothing is
    added."""
    box_scene["cylinder"] = [{"name": "silo", "center": [4.0, 4.0, 0.0], "radius": 3.5,
                              "lo": 0.1, "hi": 11.9, "material": "wall"}]
    add_square_mesh(box_scene, tmp_path, "lid", 10.0)
    box_scene["shape"] = [{"name": "rod", "spheres": [[0.0, 0.0, -0.3, 0.2], [0.0, 0.0, 0.0, 0.2],
                                                      [0.0, 0.0, 0.3, 0.2]]}]
    del box_scene["fill"]
    box_scene["particle"] = [{"position": [4.0, 4.0, 1.0], "radius": 0.5, "density": 1.0,
                              "material": "grain"}]
    sim = yuxi.Simulation(box_scene, output=tmp_path / "walls", progress=False)
    sim.run(steps=10)
    n = sim.energies()["grains"]
    with pytest.raises(ValueError, match="new grain 0 at \\(7.3, 4, 5\\), radius 0.5, overlaps the "
                                         "cylinder 'silo' by 0.3 "):
        sim.add_grains([[7.3, 4.0, 5.0]], 0.5)
    with pytest.raises(ValueError, match="new grain 1 .* overlaps the mesh 'lid' by 0.2 "):
        sim.add_grains([[4.0, 4.0, 5.0], [3.0, 2.5, 9.7]], 0.5)
    with pytest.raises(ValueError, match="member 2 of new clump 0 .* overlaps the mesh 'lid' by "
                                         "0.1 "):
        sim.add_clumps("rod", [[4.0, 4.0, 9.6]])
    with pytest.raises(ValueError, match="member 0 of new clump 0 .* overlaps the cylinder "
                                         "'silo' by 0.1 "):
        sim.add_clumps("rod", [[2.0, 4.0, 0.5]])
    assert sim.energies()["grains"] == n  # nothing was added
    sim.add_grains([[4.0, 4.0, 5.0]], 0.5)
    sim.add_clumps("rod", [[5.0, 5.0, 5.0]])
    sim.run(steps=50)
    assert sim.energies()["grains"] == n + 2
    sim.close()


def test_a_clump_wider_than_a_periodic_box_is_refused(box_scene, tmp_path):
    """A clump whose bounding sphere is wider than the box along a periodic axis would meet its
    own periodic images, which the members of one clump never touch: refused, from Python and
    from the scene, naming the axis; one that fits is taken."""
    box_scene["domain"]["boundary"] = ["periodic", "wall", "wall"]
    del box_scene["fill"]
    box_scene["particle"] = [{"position": [4.0, 4.0, 1.0], "radius": 0.5, "density": 1.0,
                              "material": "grain"}]
    box_scene["shape"] = [
        {"name": "long", "spheres": [[0.4 * k - 4.2, 0.0, 0.0, 0.2] for k in range(22)]},
        {"name": "rod", "spheres": [[0.4 * k - 1.8, 0.0, 0.0, 0.2] for k in range(10)]}]
    sim = yuxi.Simulation(box_scene, output=tmp_path / "python", progress=False)
    with pytest.raises(ValueError, match="new clump 0 spans 8.8 .* more than the periodic box's "
                                         "length along x, 8: its members would meet their own "
                                         "periodic images"):
        sim.add_clumps("long", [[4.0, 4.0, 6.0]])
    assert sim.energies()["grains"] == 1
    sim.add_clumps("rod", [[4.0, 4.0, 6.0]])
    sim.run(steps=10)
    assert sim.energies()["grains"] == 2
    sim.close()
    box_scene["clump"] = [{"shape": "long", "position": [4.0, 4.0, 6.0], "material": "grain"}]
    with pytest.raises(ValueError, match="spans 8.8 .* along x, 8"):
        yuxi.Simulation(box_scene, output=tmp_path / "scene", progress=False)


def test_a_grain_too_large_for_the_cells_names_the_key_that_makes_room(box_scene, tmp_path):
    """The linked cells are sized for the scene's grains: a larger one added from Python is
    refused, naming the scene key that makes room for it and the value it needs; with that key
    set, the same grain is taken."""
    with yuxi.Simulation(box_scene, output=tmp_path / "small", progress=False) as sim:
        with pytest.raises(ValueError, match=r"new grain 0: radius 1.5 is larger than the linked "
                                             r"cells allow .*\[domain\] cell_size = 3.2 or more"):
            sim.add_grains([[4.0, 4.0, 8.0]], 1.5)
    box_scene["shape"] = [{"name": "big", "spheres": [[-0.5, 0.0, 0.0, 1.0], [0.5, 0.0, 0.0, 1.5]]}]
    with yuxi.Simulation(box_scene, output=tmp_path / "clumps", progress=False) as sim:
        with pytest.raises(ValueError, match=r"new clump 0: member 1: radius 1.5 is larger .*"
                                             r"cell_size = 3.2 or more"):
            sim.add_clumps("big", [[4.0, 4.0, 8.0]])
    box_scene["domain"]["cell_size"] = 3.2
    box_scene["fill"][0]["count"] = 27  # (the lowest layers: room above them)
    with yuxi.Simulation(box_scene, output=tmp_path / "room", progress=False) as sim:
        (big,) = sim.add_grains([[4.0, 4.0, 9.0]], 1.5)
        sim.run(steps=10)
        assert big in sim.gather("id")


def test_add_grains_checks_its_lengths(sim):
    with pytest.raises(ValueError, match="2 positions but radii of shape \\(3,\\)"):
        sim.add_grains([[4.0, 4.0, 11.0], [6.0, 4.0, 11.0]], [0.5, 0.5, 0.5])
    with pytest.raises(ValueError, match="velocities of shape"):
        sim.add_grains([[4.0, 4.0, 11.0]], 0.5, velocities=[[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]])
    with pytest.raises(ValueError, match="shape \\(n, 3\\)"):
        sim.add_grains([[4.0, 4.0]], 0.5)


def test_errors_speak_python(box_scene, tmp_path):
    out = tmp_path / "taken"
    yuxi.Simulation(box_scene, output=out, progress=False).close()
    with pytest.raises(FileExistsError, match="output= or pass overwrite=True"):
        yuxi.Simulation(box_scene, output=out, progress=False)
