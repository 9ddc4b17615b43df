"""Drives the Python module with random sequences of calls: runs and steps, views kept across
calls, writes to grains, grains added and removed, inserts steered and added, checkpoints,
resumes, branches, closes and calls after close, with random arguments, good and bad. Every call
must end in a result or a Python exception; the interpreter must never die (under the
sanitizers, CTest runs this with the module built with AddressSanitizer). A C++ exception that
reaches Python as pybind11's "unknown exception" counts as a failure too: its message says
nothing.

usage: fuzz_calls.py [--sequences N] [--calls N] [--seed S] WORK_DIR
"""
import argparse
import os
import random
import sys
import traceback

import numpy as np

import yuxi

PAIR = dict(k_n=2.0e4, k_t=5.7e3, gamma_n=60.0, gamma_t=20.0, mu_s=0.5, mu_d=0.5)
FIELDS = list(yuxi.Particles.FIELDS) + ["nothing"]


def scene(work, rng):
    """A small box: 8 grains, a floor, a held insert, a controlled lid (a mesh)."""
    lid = os.path.join(work, "lid.stl")
    if not os.path.exists(lid):
        yuxi.write_stl(lid, yuxi.square(1.5, 5.0))
    tables = {
        "materials": ["grain", "wall"], "material": {"grain": {"density": 1.909859317}},
        "run": {"name": "fuzz", "dt": 2e-4, "t_end": rng.choice([0.02, 0.05, 1.0])},
        "output": {"energy_interval": 0.01, "snapshot_interval": rng.choice([0, 0.02])},
        "checkpoint": {"every_minutes": 0},
        "domain": {"lo": [-2.0, -2.0, 0.0], "hi": [2.0, 2.0, 6.0], "gravity": [0, 0, -10.0],
                   "boundary": ["wall", rng.choice(["wall", "periodic"]), "wall"],
                   "wall_material": "wall"},
        "contact": {"pair": [dict(PAIR, materials=["grain", "grain"]),
                             dict(PAIR, materials=["grain", "wall"])]},
        "fill": [{"material": "grain", "radius": 0.4, "count": 8, "placement": "lattice",
                  "region": {"shape": "box", "lo": [-1.8, -1.8, 0.1], "hi": [1.8, 1.8, 3.0]}}],
        "insert": [{"name": "feed", "material": "grain", "radius": 0.4, "rate": 200, "total": 6,
                    "held": rng.random() < 0.5,
                    "region": {"shape": "box", "lo": [-1.5, -1.5, 3.5], "hi": [1.5, 1.5, 4.5]}}],
        "mesh": [{"name": "lid", "file": lid, "material": "wall", "controlled": True,
                  "servo_axis": [0, 0, -1]}],
        "shape": [{"name": "rod", "spheres": [[-0.2, 0, 0, 0.2], [0.2, 0, 0, 0.2]]},
                  {"name": "ball", "spheres": [[0, 0, 0, 0.3]]}],
    }
    if rng.random() < 0.5:
        tables["clump"] = [{"shape": "rod", "position": [0.0, 0.0, 5.0], "material": "grain",
                            "orientation": rng.choice([[1, 0, 0, 0], [0.5, 0.5, 0.5, 0.5]])}]
    if rng.random() < 0.15:  # a broken table: the reader must refuse it with SceneError
        victim = rng.choice(["run", "domain", "fill", "insert", "shape"])
        if isinstance(tables[victim], list):
            tables[victim][0][rng.choice(["radious", "count", "region"])] = rng.choice(
                [None, -1, "x", [1, 2], {"a": 1}])
        else:
            tables[victim][rng.choice(["dt", "lo", "gravity", "t_end"])] = rng.choice(
                [None, -1.0, "x", [1, 2], float("nan")])
    return tables


def anything(rng):
    return rng.choice([None, 0, -7, 2.5, float("nan"), float("inf"), "x", "", [], [1, 2, 3],
                       [[1.0, 2.0]], {"a": 1}, np.zeros((2, 3)), np.array([True, False]),
                       np.array([1.5]), np.array([0, 1, 2], dtype=np.int32), 10**30])


def ids(sim, rng):
    try:
        have = np.asarray(sim.particles.id).copy()
    except Exception:
        have = np.array([], dtype=np.int64)
    choice = rng.choice([0, 0, 0, 1, 2, 3, 4, 5])
    if choice == 0 and len(have):
        return have[: rng.randrange(1, len(have) + 1)]
    if choice == 1:
        return np.array([10**9, -1], dtype=np.int64)
    if choice == 2:
        return have.astype(float)
    if choice == 3:
        return have > 3
    if choice == 4:
        return np.array([], dtype=np.int64)
    return anything(rng)


def vectors(n, rng):
    choice = rng.choice([0, 0, 0, 1, 2, 3])
    if choice == 0:
        return np.zeros((n, 3))
    if choice == 1:
        return np.full((n, 3), rng.choice([0.5, -3.0, 100.0, float("nan")]))
    if choice == 2:
        return np.zeros((max(n - 1, 0), 3))
    return anything(rng)


class Driver:
    def __init__(self, work, rng):
        self.work, self.rng = work, rng
        self.sims, self.views, self.kept, self.checkpoints, self.folders = [], [], [], [], []

    def folder(self):
        name = os.path.join(self.work, f"run{len(self.folders)}")
        self.folders.append(name)
        return name

    def sim(self):
        return self.rng.choice(self.sims) if self.sims else None

    # -- the calls ------------------------------------------------------------------------
    def open(self):
        rng = self.rng
        kind = rng.randrange(4)
        if kind == 0 or not self.checkpoints:
            out = rng.choice([self.folder(), self.folders[0]]) if self.folders else self.folder()
            s = yuxi.Simulation(scene(self.work, rng), output=out, overwrite=rng.random() < 0.7,
                                progress=False, force_dt=rng.random() < 0.2)
        elif kind == 1:
            s = yuxi.Simulation.resume(rng.choice(self.folders), progress=False,
                                       t_end=rng.choice([None, 0.5, -1.0]))
        else:
            s = yuxi.Simulation.branch(rng.choice(self.checkpoints + self.folders),
                                       scene(self.work, rng), output=self.folder(),
                                       overwrite=True, progress=False)
        self.sims.append(s)

    def run(self):
        s, rng = self.sim(), self.rng
        which = rng.randrange(4)
        if which == 0:
            s.run(steps=rng.choice([0, 1, 7, 40, 40, 100, -3, 2.5, None]))
        elif which == 1:
            s.run(t_end=rng.choice([0.0, 0.01, 0.03, -1.0, float("nan")]))
        elif which == 2:
            s.step(rng.choice([1, 3, 0, -1]))
        else:
            s.run(steps=20, every=rng.choice([1, 5, 0]),
                  callback=lambda sim: rng.random() < 0.9 and None)

    def view(self):
        s = self.sim()
        self.views.append(getattr(s.particles, self.rng.choice(FIELDS)))

    def keep_particles(self):
        self.kept.append(self.sim().particles)

    def read_view(self):
        rng = self.rng
        if self.views and rng.random() < 0.6:
            v = rng.choice(self.views)
            op = rng.randrange(5)
            if op == 0:
                v[0]
            elif op == 1:
                len(v)
            elif op == 2:
                np.asarray(v).sum()
            elif op == 3:
                v + 1
            else:
                v.copy()
        elif self.kept:
            getattr(rng.choice(self.kept), rng.choice(FIELDS))[:]

    def write(self):
        s, rng = self.sim(), self.rng
        chosen = ids(s, rng)
        n = len(chosen) if hasattr(chosen, "__len__") else 1
        call = rng.choice([s.set_velocities, s.set_angular_velocities, s.set_positions])
        call(chosen, vectors(n, rng))

    def add_remove(self):
        s, rng = self.sim(), self.rng
        if rng.random() < 0.5:
            n = rng.randrange(0, 3)
            where = np.array([[rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(0, 7)]
                              for _ in range(n)])
            s.add_grains(where if rng.random() < 0.8 else anything(rng),
                         rng.choice([0.3, [0.3] * n, [0.3], -1.0, "x"]),
                         velocities=rng.choice([None, np.zeros((n, 3)), anything(rng)]),
                         material=rng.choice([None, "grain", "wall", "sand"]))
        else:
            s.remove_grains(ids(s, rng))

    def clumps(self):
        s, rng = self.sim(), self.rng
        try:
            have = np.asarray(s.clumps()["id"]).copy()
        except Exception:
            have = np.array([], dtype=np.int64)
        chosen = rng.choice([have, have + 1, have[:1], np.array([10**9]), ids(s, rng)])
        n = len(chosen) if hasattr(chosen, "__len__") else 1
        op = rng.randrange(6)
        if op == 0:
            k = rng.randrange(0, 3)
            where = np.array([[rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(0, 7)]
                              for _ in range(k)])
            s.add_clumps(rng.choice(["rod", "ball", "cube", anything(rng)]),
                         where if rng.random() < 0.8 else anything(rng),
                         orientations=rng.choice([None, [[1, 0, 0, 0]] * k, [[2, 0, 0, 0]] * k,
                                                  anything(rng)]),
                         velocities=rng.choice([None, np.zeros((k, 3)), anything(rng)]),
                         angular_velocities=rng.choice([None, np.ones((k, 3)), anything(rng)]),
                         scale=rng.choice([1.0, 0.5, [1.0] * k, 0.0, -1.0, 0.001, "x"]),
                         material=rng.choice([None, "grain", "wall", "sand"]),
                         frame=rng.choice(["shape", "principal", "x"]))
        elif op == 1:
            s.remove_clumps(chosen)
        elif op == 2:
            rng.choice([s.set_clump_velocities, s.set_clump_angular_velocities])(
                chosen, vectors(n, rng))
        elif op == 3:
            s.shape(rng.choice(["rod", "ball", "cube", anything(rng)]))
        elif op == 4:
            s.set_clump_poses(chosen, vectors(n, rng),
                              orientations=rng.choice([None, [[1, 0, 0, 0]] * n,
                                                       [[0, 0, 0, 0]] * n, anything(rng)]))
        else:
            s.clumps()

    def sources_and_walls(self):
        s, rng = self.sim(), self.rng
        name = rng.choice(["feed", "lid", "late", "nothing", ""])
        op = rng.randrange(6)
        if op == 0:
            s.start_insert(name)
        elif op == 1:
            s.pause_insert(name)
        elif op == 2:
            s.stop_insert(name)
        elif op == 3:
            s.add_insert(rng.choice([
                {"name": "late", "material": "grain", "radius": 0.4, "rate": 100, "total": 3,
                 "region": {"shape": "box", "lo": [-1, -1, 4], "hi": [1, 1, 5]}},
                {"name": "bad", "radius": 0.4}, anything(rng)]))
        elif op == 4:
            s.set_wall_speed(name, rng.choice([0.0, 0.5, -1.0, float("nan"), "x"]))
        else:
            s.wall_motion(name)

    def read(self):
        s, rng = self.sim(), self.rng
        op = rng.randrange(8)
        if op == 0:
            s.energies()
        elif op == 1:
            s.wall_loads()
        elif op == 2:
            s.inflow()
        elif op == 3:
            s.gather(rng.choice(FIELDS))
        elif op == 4:
            s.record_contacts(rng.random() < 0.5)
        elif op == 5:
            s.contacts()
        elif op == 6:
            (s.time, s.step_count, s.dt, s.folder, repr(s))
        else:
            s.energy_history()

    def checkpoint(self):
        s, rng = self.sim(), self.rng
        path = None if rng.random() < 0.6 else os.path.join(self.work, f"c{rng.randrange(3)}.yxc")
        written = s.checkpoint(path)
        self.checkpoints.append(written)

    def close(self):
        s = self.sim()
        s.close()
        if self.rng.random() < 0.5:
            self.sims.remove(s)  # (or kept, to be called after close)

    CALLS = ["run", "view", "keep_particles", "read_view", "write", "add_remove", "clumps",
             "sources_and_walls", "read", "checkpoint", "close", "open"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("work")
    parser.add_argument("--sequences", type=int, default=30)
    parser.add_argument("--calls", type=int, default=40)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    calls = raised = 0
    tally = {}  # per call: [answered, raised]
    for sequence in range(args.sequences):
        rng = random.Random(args.seed * 1000003 + sequence)
        work = os.path.join(args.work, f"seq{sequence}")
        os.makedirs(work, exist_ok=True)
        d = Driver(work, rng)
        for k in range(args.calls):
            name = "open" if not d.sims or rng.random() < 0.08 else rng.choice(Driver.CALLS)
            calls += 1
            counts = tally.setdefault(name, [0, 0])
            try:
                getattr(d, name)()
                counts[0] += 1
            except Exception as e:  # every Python exception is an answer ...
                raised += 1
                counts[1] += 1
                if "unknown exception" in str(e).lower():  # ... but this one says nothing
                    print(f"sequence {sequence}, call {k} ({name}): {e!r}")
                    traceback.print_exc()
                    return 1
        for s in d.sims:
            try:
                s.close()
            except Exception:
                pass
    print(f"{args.sequences} sequences, {calls} calls, {raised} raised; no crash")
    for name, (answered, failed) in sorted(tally.items()):
        print(f"  {name}: {answered} answered, {failed} raised")
    return 0


if __name__ == "__main__":
    sys.exit(main())
