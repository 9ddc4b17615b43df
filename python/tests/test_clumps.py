"""Clumps from Python: a scene with a [[shape]], the clumps' arrays, the members' clump ids, and
the writes a member cannot take alone (docs/clumps.md, docs/python.md)."""
import numpy as np
import pytest

import yuxi


def rods_scene(box_scene):
    """The box scene's 343 lattice sites holding rods of three spheres instead of balls."""
    box_scene["run"]["dt"] = 1.0e-4
    box_scene["shape"] = [{"name": "rod", "spheres": [[-0.3, 0.0, 0.0, 0.2], [0.0, 0.0, 0.0, 0.2],
                                                      [0.3, 0.0, 0.0, 0.2]]}]
    box_scene["fill"][0]["shape"] = "rod"
    box_scene["fill"][0]["count"] = 64
    return box_scene


def quaternion_rotate(q, v):
    w, x, y, z = q
    u = np.array([x, y, z])
    return v + 2.0 * np.cross(u, np.cross(u, v) + w * v)


def test_clumps_are_arrays_and_their_members_follow_them(box_scene, tmp_path):
    sim = yuxi.Simulation(rods_scene(box_scene), output=tmp_path / "rods", progress=False)
    assert sim.shapes == ["rod"]
    sim.step(200)
    c = sim.clumps()
    assert len(c["id"]) == 64
    assert c["position"].shape == (64, 3) and c["orientation"].shape == (64, 4)
    assert np.allclose(np.linalg.norm(c["orientation"], axis=1), 1.0, atol=1e-12)
    assert np.all(c["shape"] == 0) and np.all(c["members"] == 3)
    assert np.all(np.diff(c["inertia"], axis=1) >= 0)  # ascending principal moments
    p = sim.particles
    clump = np.asarray(p.clump)
    ids = np.asarray(p.id)
    assert len(ids) == 192
    assert np.all(clump >= 0) and np.all((ids - clump >= 0) & (ids - clump < 3))  # all members
    assert set(clump) == set(c["id"])
    # Each clump's members: their mass adds up to the clump's, and their mean position is the
    # centre of mass (three equal members along an axis through it).
    mass, x = np.asarray(p.mass), np.asarray(p.position)
    for k, body in enumerate(c["id"][:5]):
        mine = clump == body
        assert mass[mine].sum() == pytest.approx(c["mass"][k], rel=1e-12)
        assert x[mine].mean(axis=0) == pytest.approx(c["position"][k], abs=1e-9)
    # A member moves with its clump: no velocity of its own, no removal alone.
    with pytest.raises(ValueError, match="member of clump"):
        sim.set_velocities(ids[:1], np.zeros((1, 3)))
    with pytest.raises(ValueError, match="a clump leaves whole"):
        sim.remove_grains(ids[:1])
    books = sim.energies()
    assert books["grains"] == 64
    sim.close()


def test_a_fill_naming_no_shape_is_refused(box_scene, tmp_path):
    scene = rods_scene(box_scene)
    scene["fill"][0]["shape"] = "cube"
    with pytest.raises(yuxi.SceneError, match="no \\[\\[shape\\]\\] named 'cube'"):
        yuxi.Simulation(scene, output=tmp_path / "bad", progress=False)


def test_an_insert_added_from_python_pours_clumps(box_scene, tmp_path):
    sim = yuxi.Simulation(rods_scene(box_scene), output=tmp_path / "pour", progress=False)
    assert sim.add_insert({"name": "more", "shape": "rod", "material": "grain", "radius": 0.4,
                           "rate": 1000.0, "total": 10, "interval": 0.01,
                           "region": {"shape": "box", "lo": [0.0, 0.0, 9.0],
                                      "hi": [8.0, 8.0, 12.0]}}) == "more"
    sim.step(100)
    c = sim.clumps()
    assert len(c["id"]) == 74
    assert np.all(c["members"] == 3)
    assert np.all(c["position"][64:, 2] >= 8.5)
    assert sim.energies()["grains"] == 74
    sim.close()
