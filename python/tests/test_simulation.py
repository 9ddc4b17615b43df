"""Runs, views, writes between steps, steering, checkpoints and branches from Python."""
import filecmp
import os
import signal

import numpy as np
import pytest

import yuxi
from conftest import BOX_TOML, add_square_mesh


def run_to_end(scene, out, **kw):
    sim = yuxi.Simulation(scene, output=out, progress=False, **kw)
    sim.run()
    sim.close()
    return out


def test_a_scene_from_a_dict_gives_the_bytes_of_its_toml(box_scene, tmp_path):
    a = run_to_end(box_scene, tmp_path / "dict")
    b = run_to_end(BOX_TOML, tmp_path / "toml")
    assert filecmp.cmp(a / "energies.csv", b / "energies.csv", shallow=False)
    (ca,) = sorted((a / "checkpoints").iterdir())
    (cb,) = sorted((b / "checkpoints").iterdir())
    assert ca.name == cb.name
    assert filecmp.cmp(ca, cb, shallow=False)


def test_views_show_the_engine_after_each_step_and_go_stale(box_scene, tmp_path):
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    sim.step(50)
    p = sim.particles
    x, v = p.position, p.velocity
    assert x.shape == (343, 3) and v.shape == (343, 3)
    # No copy: the view is the engine's memory, read-only.
    assert not np.asarray(x).flags.writeable and not np.asarray(x).flags.owndata
    with pytest.raises(TypeError):
        x[0] = 0.0
    before = np.asarray(x).copy()
    speed = np.asarray(v).copy()
    sim.step()
    with pytest.raises(yuxi.StaleViewError):
        x.mean()
    with pytest.raises(yuxi.StaleViewError):
        np.asarray(v)
    after = sim.particles.position.copy()
    ids_now = np.asarray(sim.particles.id)
    # One step of free fall (no contact yet): x(t + dt) = x + v(t) dt + g dt^2 / 2.
    dt = sim.dt
    expected = before + speed * dt + 0.5 * np.array([0.0, 0.0, -10.0]) * dt * dt
    assert np.allclose(after, expected, rtol=0, atol=1e-12)
    # gather: every particle by id, on rank 0.
    g = sim.gather("position")
    assert g.shape == (343, 3)
    assert np.array_equal(g, after[np.argsort(ids_now)])
    sim.close()


def test_velocities_written_at_the_start_are_the_scene_s_initial_velocities(box_scene, tmp_path):
    # The C++ path: the fill's own initial velocity. The Python path: the same velocity written
    # before the first step. Same state, so the same trajectory to the bit.
    v0 = [0.3, -0.2, 0.5]
    with_velocity = dict(box_scene)
    with_velocity["fill"] = [dict(box_scene["fill"][0], velocity=v0)]
    a = yuxi.Simulation(with_velocity, output=tmp_path / "a", progress=False)
    b = yuxi.Simulation(box_scene, output=tmp_path / "b", progress=False)
    ids = np.asarray(b.particles.id).copy()
    b.set_velocities(ids, np.tile(v0, (len(ids), 1)))
    assert np.array_equal(np.asarray(b.particles.velocity), np.asarray(a.particles.velocity))
    a.step(300)
    b.step(300)
    assert np.array_equal(a.gather("position"), b.gather("position"))
    assert np.array_equal(a.gather("velocity"), b.gather("velocity"))
    # b booked what it put in.
    inserted = b.energies()["inserted"]
    m = np.asarray(b.particles.mass)
    assert inserted == pytest.approx(0.5 * m.sum() * np.dot(v0, v0), rel=1e-12)
    a.close(), b.close()


def balance_drift(sim):
    e = sim.energies()
    return e["balance"], e["dissipated"] + abs(e["inserted"]) + 1e-300


def test_the_books_close_across_every_kind_of_edit(box_scene, tmp_path):
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    sim.step(400)  # grains on the floor, touching
    b0 = sim.energies()["balance"]
    ids = np.asarray(sim.particles.id).copy()
    x = sim.particles.position.copy()
    v = sim.particles.velocity.copy()
    sim.set_velocities(ids[:10], v[:10] + [0.0, 0.0, 1.0])
    sim.set_angular_velocities(ids[:10], np.ones((10, 3)))
    sim.set_positions(ids[10:20], x[10:20] + [0.0, 0.0, 0.05])
    new = sim.add_grains([[4.0, 4.0, 11.0], [5.5, 4.0, 11.0]], 0.5, velocities=[[0, 0, -1.0]] * 2)
    assert list(new) == [343, 344]
    assert sim.remove_grains(ids[100:110]) == 10
    assert sim.energies()["grains"] == 343 + 2 - 10
    e = sim.energies()
    assert e["balance"] == pytest.approx(b0, rel=1e-9, abs=1e-9 * abs(e["gravitational"]))
    sim.step(400)
    e = sim.energies()
    # Integration error only: a small fraction of what the contacts dissipated.
    assert abs(e["balance"] - b0) < 0.02 * e["dissipated"]
    sim.close()


def test_writes_to_other_ranks_or_wall_particles_are_refused(box_scene, tmp_path):
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    with pytest.raises(ValueError, match="id 99999"):
        sim.set_velocities([99999], [[0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="shape"):
        sim.set_velocities([0], [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="outside the domain"):
        sim.set_positions([0], [[100.0, 0.0, 0.0]])
    sim.close()


def test_a_callback_steers_and_stops_the_run(box_scene, tmp_path):
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    seen = []

    def look(s):
        seen.append((s.step_count, float(s.particles.position[:, 2].max())))
        if s.step_count >= 300:
            return False

    sim.run(t_end=1.0, callback=look, every=100)
    assert [k for k, _ in seen] == [100, 200, 300]
    assert sim.step_count == 300
    sim.close()


def test_a_controlled_wall_moves_at_the_speed_a_callback_sets(box_scene, tmp_path):
    add_square_mesh(box_scene, tmp_path, "piston", 11.8, controlled=True,
                    servo_axis=[0.0, 0.0, -1.0])
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)

    def push(s):
        s.set_wall_speed("piston", 2.0)

    sim.run(steps=500, callback=push, every=100)
    state = sim.wall_motion("piston")
    assert state["speed"] == 2.0
    # Set at step 100, the speed holds over the last 400 steps.
    assert state["offset"] == pytest.approx(2.0 * 400 * sim.dt, rel=1e-9)
    # A controller function: every step, told the grains' push.
    pushes = []

    def hold(resisting, t):
        pushes.append(resisting)
        return 0.0

    sim.set_wall_controller("piston", hold)
    sim.step(10)
    assert len(pushes) == 10 and sim.wall_motion("piston")["speed"] == 0.0
    with pytest.raises(KeyError, match="no mesh or cylinder named 'lid'"):
        sim.set_wall_speed("lid", 1.0)
    sim.close()


def test_only_a_controlled_wall_takes_a_speed(box_scene, tmp_path):
    add_square_mesh(box_scene, tmp_path, "lid", 11.8)
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    with pytest.raises(ValueError, match="not a controlled mesh"):
        sim.set_wall_speed("lid", 1.0)
    sim.close()


def test_checkpoint_and_resume_continue_bit_for_bit(box_scene, tmp_path):
    straight = yuxi.Simulation(box_scene, output=tmp_path / "straight", progress=False)
    straight.run(steps=600)
    x = straight.gather("position")
    straight.close()

    first = yuxi.Simulation(box_scene, output=tmp_path / "pieces", progress=False)
    first.run(steps=250)
    first.checkpoint()
    first.close()
    again = yuxi.Simulation.resume(tmp_path / "pieces", progress=False)
    assert again.step_count == 250
    again.run(steps=350)
    assert np.array_equal(again.gather("position"), x)
    again.close()


def test_ctrl_c_in_a_callback_writes_a_checkpoint_then_raises(box_scene, tmp_path):
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)

    def interrupt(s):
        if s.step_count == 100:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        sim.run(t_end=1.0, callback=interrupt, every=100)
    assert sim.step_count == 100
    sim.close()
    resumed = yuxi.Simulation.resume(tmp_path / "out", progress=False)
    assert resumed.step_count == 100
    resumed.close()


def test_ctrl_c_between_callbacks_writes_a_checkpoint_then_raises(box_scene, tmp_path):
    box_scene["run"]["t_end"] = 1000.0
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    # SIGALRM raising KeyboardInterrupt, as Ctrl-C does, while the engine steps.
    previous = signal.signal(signal.SIGALRM, signal.default_int_handler)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.2)
        with pytest.raises(KeyboardInterrupt):
            sim.run()
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    stopped = sim.step_count
    assert 0 < stopped < 1000.0 / sim.dt and stopped % 50 == 0  # (the signal is polled)
    sim.close()
    resumed = yuxi.Simulation.resume(tmp_path / "out", progress=False)
    assert resumed.step_count == stopped
    resumed.close()


def test_a_branch_with_the_same_scene_is_a_resume(box_scene, tmp_path):
    run_to_end(box_scene, tmp_path / "base")
    longer = dict(box_scene, run=dict(box_scene["run"], t_end=0.3))
    branch = yuxi.Simulation.branch(tmp_path / "base", longer, output=tmp_path / "branch",
                                    progress=False)
    resume = yuxi.Simulation.resume(tmp_path / "base", t_end=0.3, progress=False)
    branch.run()
    resume.run()
    assert np.array_equal(branch.gather("velocity"), resume.gather("velocity"))
    branch.close(), resume.close()


def test_energy_history_is_a_record_array(box_scene, tmp_path):
    sim = yuxi.Simulation(box_scene, output=tmp_path / "out", progress=False)
    sim.run()
    h = sim.energy_history()
    assert h.step[0] == 0 and h.step[-1] == sim.step_count
    assert len(h) == 21
    assert "dissipated" in h.dtype.names
    sim.close()


def test_a_run_in_pieces_writes_the_files_of_a_run_in_one_go(box_scene, tmp_path):
    whole = run_to_end(box_scene, tmp_path / "whole")
    sim = yuxi.Simulation(box_scene, output=tmp_path / "pieces", progress=False)
    sim.run(t_end=0.05)
    sim.step(7)
    sim.run(steps=193, callback=lambda s: None, every=10)
    sim.run()
    sim.close()
    for name in ("energies.csv", "particles.lammpstrj"):
        assert filecmp.cmp(whole / name, tmp_path / "pieces" / name, shallow=False), name
