"""Pouring in stages and branching poured beds: inserts are matched by name, a chain of branches
gives the bytes of one straight run, and an insert started, paused, stopped or added from
Python keeps its state through checkpoints and resumes."""
import numpy as np
import pytest

import yuxi

PAIR = dict(k_n=2.0e4, k_t=5.7e3, gamma_n=60.0, gamma_t=20.0, mu_s=0.5, mu_d=0.5)


def insert(name, start, z, total=40, **more):
    return dict({"name": name, "material": "grain", "radius": 0.5, "rate": 400, "total": total,
                 "start": start, "region": {"shape": "box", "lo": [-3, -3, z], "hi": [3, 3, z + 4]}},
                **more)


def scene_tables(name, t_end):
    return {
        "materials": ["grain", "wall"], "material": {"grain": {"density": 1.909859317}},
        "run": {"name": name, "dt": 5e-4, "t_end": t_end},
        "output": {"snapshot_interval": 0, "energy_interval": 0.05},
        "domain": {"lo": [-3.5, -3.5, -0.5], "hi": [3.5, 3.5, 20], "gravity": [0, 0, -10],
                   "boundary": ["wall", "wall", "open"], "wall_material": "wall"},
        "contact": {"pair": [dict(PAIR, materials=["grain", "grain"]),
                             dict(PAIR, materials=["grain", "wall"])]},
        "plane": [{"name": "floor", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "wall"}]}


def scene(name, t_end, inserts):
    return yuxi.Scene(dict(scene_tables(name, t_end), insert=inserts))


def state(sim):
    """Every grain's id, position, velocity and spin, by id (rank 0)."""
    ids = sim.gather("id")
    order = np.argsort(ids)
    return [ids[order]] + [sim.gather(f)[order] for f in ("position", "velocity",
                                                            "angular_velocity")]


def same_bits(a, b):
    return all(x.shape == y.shape and np.array_equal(x, y) for x, y in zip(a, b))


def A():
    return insert("A", 0.0, 5)


def B():
    return insert("B", 0.6, 8)


def C():
    return insert("C", 1.1, 11)


def test_a_chain_of_three_branches_gives_the_bytes_of_one_straight_run(tmp_path):
    straight = yuxi.Simulation(scene("straight", 1.5, [A(), B(), C()]), output=tmp_path / "s",
                               progress=False)
    straight.run()
    want, books, flows = state(straight), straight.energies(), straight.inflow()
    straight.close()
    a = yuxi.Simulation(scene("a", 0.5, [A()]), output=tmp_path / "a", progress=False)
    a.run()
    a.close()
    b = yuxi.Simulation.branch(tmp_path / "a", scene("b", 1.0, [A(), B()]), output=tmp_path / "b",
                               progress=False)
    b.run()
    b.close()
    c = yuxi.Simulation.branch(tmp_path / "b", scene("c", 1.5, [A(), B(), C()]),
                               output=tmp_path / "c", progress=False)
    c.run()
    got = state(c)
    assert c.inflow() == flows and sum(f["grains"] for f in flows) > 100
    assert same_bits(got, want)
    assert c.energies()["balance"] == books["balance"]
    c.close()


def test_branch_inserts_are_matched_by_name(tmp_path):
    a = yuxi.Simulation(scene("a", 0.5, [A()]), output=tmp_path / "a", progress=False)
    a.run()
    saved = a.energies()["grains"]
    assert saved == a.inflow()[0]["grains"] > 30
    a.close()
    # a new insert where the old one stood pours its own total; the old one is not poured again
    b = yuxi.Simulation.branch(tmp_path / "a", scene("b", 1.0, [insert("new", 0.6, 8)]),
                               output=tmp_path / "b", progress=False)
    b.run()
    poured = b.inflow()[0]["grains"]
    assert poured > 30 and b.energies()["grains"] == saved + poured
    b.close()
    # the old insert kept, and one added in front of it: each keeps its own count
    c = yuxi.Simulation.branch(tmp_path / "a", scene("c", 1.0, [insert("new", 0.6, 8), A()]),
                               output=tmp_path / "c", progress=False)
    c.run()
    flows = {f["name"]: f["grains"] for f in c.inflow()}
    assert flows["A"] >= saved and flows["new"] > 30
    assert c.energies()["grains"] == flows["A"] + flows["new"]
    c.close()
    # an unnamed insert in another place is not taken for the checkpoint's unnamed one
    unnamed = insert("x", 0.0, 5)
    del unnamed["name"]
    d = yuxi.Simulation(scene("d", 0.5, [unnamed]), output=tmp_path / "d", progress=False)
    d.run()
    d.close()
    moved = dict(unnamed, region={"shape": "box", "lo": [-3, -3, 8], "hi": [3, 3, 12]})
    with pytest.raises(yuxi.SceneError, match="insert\\[1\\] pours from another region.*names"):
        yuxi.Simulation.branch(tmp_path / "d", scene("e", 1.0, [moved]), output=tmp_path / "e")


def test_a_branch_with_no_grains_of_its_own_takes_the_checkpoint_s(tmp_path):
    a = yuxi.Simulation(scene("a", 0.5, [A()]), output=tmp_path / "a", progress=False)
    a.run()
    saved = a.energies()["grains"]
    a.close()
    bare = scene_tables("bare", 0.6)
    b = yuxi.Simulation.branch(tmp_path / "a", bare, output=tmp_path / "b", progress=False)
    b.run()
    assert b.energies()["grains"] == saved > 30
    b.close()
    with pytest.raises(yuxi.SceneError, match="no grains"):
        yuxi.Simulation(bare, output=tmp_path / "c")


def poured_in_stages(sim):
    """Holds, starts, pauses, adds and stops inserts between pieces of the run."""
    sim.run(t_end=0.2)
    assert sim.energies()["grains"] == 0  # "held" waits
    sim.start_insert("held")
    sim.run(t_end=0.3)
    n = sim.energies()["grains"]
    assert 0 < n < 40
    sim.pause_insert("held")
    sim.run(t_end=0.5)
    assert sim.energies()["grains"] == n
    sim.start_insert("held")
    sim.add_insert(insert("late", 0.0, 12, total=60, rate=100))
    sim.run(t_end=0.6)


def test_an_insert_steered_from_python_keeps_its_state_through_a_resume(tmp_path):
    held = [insert("held", 0.0, 5, held=True)]
    whole = yuxi.Simulation(scene("whole", 1.2, held), output=tmp_path / "whole", progress=False)
    poured_in_stages(whole)
    whole.stop_insert("late")
    whole.run(t_end=0.8)
    whole.run()
    want = state(whole)
    flows = {f["name"]: f["grains"] for f in whole.inflow()}
    assert flows["held"] == 40 and 0 < flows["late"] < 60
    whole.close()
    # the same, with a checkpoint after the added insert and a resume from it
    cut = yuxi.Simulation(scene("cut", 1.2, held), output=tmp_path / "cut", progress=False)
    poured_in_stages(cut)
    cut.checkpoint()
    cut.close()
    resumed = yuxi.Simulation.resume(tmp_path / "cut", progress=False)
    assert [f["name"] for f in resumed.inflow()] == ["held", "late"]
    resumed.stop_insert("late")
    with pytest.raises(ValueError, match="stopped for good"):
        resumed.start_insert("late")
    resumed.run(t_end=0.8)
    resumed.run()
    assert same_bits(state(resumed), want)
    resumed.close()
    with open(tmp_path / "cut" / "scene.resolved.toml") as f:
        assert "name = 'late'" in f.read()


def test_steering_an_insert_that_cannot_be_is_refused(tmp_path):
    sim = yuxi.Simulation(scene("x", 1.0, [insert("A", 0.0, 5, total=5)]), output=tmp_path / "x",
                          progress=False)
    with pytest.raises(KeyError, match="no insert named 'B' .*A"):
        sim.start_insert("B")
    with pytest.raises(ValueError, match="exists already"):
        sim.add_insert(insert("A", 0.0, 8))
    with pytest.raises(yuxi.SceneError, match="radious"):
        sim.add_insert(dict(insert("B", 0.0, 8), radious=0.5))
    with pytest.raises(TypeError, match="dict"):
        sim.add_insert("B")
    # grains so light that the time step is a third of their contact time
    with pytest.raises(yuxi.SceneError, match="contact time .*force_dt=True"):
        sim.add_insert(dict(insert("dust", 0.0, 8), radius=0.02))
    sim.run(t_end=0.2)
    with pytest.raises(ValueError, match="poured its total of 5"):
        sim.start_insert("A")
    assert [f["name"] for f in sim.inflow()] == ["A"]  # (the refused ones were not added)
    sim.close()
