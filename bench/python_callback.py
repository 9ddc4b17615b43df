"""What a Python callback costs a run: the same bed stepped with no callback and with one every
100 steps that reads every grain's position (a numpy view, no copy) and sets a controlled wall's
speed (docs/performance.md, "Python callbacks").

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_callback.py \
        [--grains 100000] [--steps 300] [--repeats 2]

The bed is a jittered lattice that falls under gravity for `settle` steps first, so that its
lower layers pack and touch. The two runs then alternate (A-B-B-A, `repeats` times each) on
this machine: the ratio of their mean times is the overhead, with the machine's noise in it;
the time spent inside the callback itself, against the 100 steps between calls, is the part
the callback adds.
"""
import argparse
import os
import sys
import tempfile
import time

import numpy as np

import yuxi

PAIR = {"k_n": 2.0e4, "k_t": 5.7e3, "gamma_n": 60.0, "gamma_t": 20.0, "mu_s": 0.5, "mu_d": 0.5}


def scene(grains, lid, steps):
    per_row = int(np.ceil((grains / 40) ** 0.5))  # ~40 layers of lattice spacing 1.1
    side = per_row * 1.1 + 0.4
    height = (int(np.ceil(grains / per_row**2)) + 1) * 1.1 + 0.3
    return {
        "materials": ["grain", "wall"],
        "material": {"grain": {"density": 1.909859317}},
        "run": {"name": "callback-bench", "dt": 2.0e-4, "t_end": 1e6},
        "output": {"energy_interval": 1e5, "snapshot_interval": 0.0, "lammps_dump": False,
                   "vtk": False},
        "checkpoint": {"every_minutes": 0.0},
        "domain": {"lo": [0.0, 0.0, 0.0], "hi": [side, side, height + 2],
                   "gravity": [0.0, 0.0, -10.0], "boundary": ["wall", "wall", "wall"],
                   "wall_material": "wall"},
        "contact": {"model": "linear", "pair": [dict(PAIR, materials=["grain", "grain"]),
                                                 dict(PAIR, materials=["grain", "wall"])]},
        "fill": [{"material": "grain", "radius": 0.5, "count": grains, "placement": "lattice",
                  "jitter": 0.05,
                  "region": {"shape": "box", "lo": [0.1, 0.1, 0.1],
                             "hi": [side - 0.1, side - 0.1, height]}}],
        "mesh": [{"name": "lid", "file": lid, "material": "wall",
                  "translate": [side / 2, side / 2, height + 1.5], "controlled": True}],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grains", type=int, default=100000)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--repeats", type=int, default=4)
    parser.add_argument("--settle", type=int, default=3000)
    args = parser.parse_args()

    folder = tempfile.mkdtemp(prefix="yuxi-callback-bench-")
    lid = os.path.join(folder, "lid.stl")
    base = scene(args.grains, lid, args.steps)
    yuxi.write_stl(lid, yuxi.square(base["domain"]["hi"][0] / 2 - 0.1), header="lid")
    sim = yuxi.Simulation(base, output=os.path.join(folder, "run"), progress=False)
    n = int(sim.energies()["grains"])
    sim.step(args.settle)
    contacts = int(sim.energies()["contacts"])

    reads = []
    inside = [0.0]  # seconds spent in the callback itself

    def callback(s):
        t0 = time.perf_counter()
        x = s.particles.position  # every grain's position, as a view
        reads.append(float(np.asarray(x)[:, 2].max()))
        s.set_wall_speed("lid", 0.0)
        inside[0] += time.perf_counter() - t0

    times = {"none": [], "callback": []}
    # A-B-B-A: the bed goes on settling (its steps grow dearer), and the drift cancels.
    for r in range(args.repeats):
        for kind in ("none", "callback") if r % 2 == 0 else ("callback", "none"):
            t0 = time.perf_counter()
            if kind == "none":
                sim.run(steps=args.steps)
            else:
                sim.run(steps=args.steps, callback=callback, every=100)
            times[kind].append(time.perf_counter() - t0)
    sim.close()
    plain, steered = np.mean(times["none"]), np.mean(times["callback"])
    print(f"{n} grains ({contacts} contacts), {args.steps} steps per run, "
          f"{args.repeats} runs of each, alternating")
    print(f"no callback:                 {plain:.3f} s ({plain / args.steps * 1e3:.2f} ms/step)")
    print(f"callback every 100 steps:    {steered:.3f} s ({len(reads)} calls)")
    print(f"overhead: {100 * (steered / plain - 1):+.2f} % (the two runs' times; the machine's "
          "noise is in it)")
    per_call = inside[0] / max(len(reads), 1)
    print(f"in the callback: {per_call * 1e3:.3f} ms a call, "
          f"{100 * per_call / (plain / args.steps * 100):.3f} % of the 100 steps between calls")
    return 0


if __name__ == "__main__":
    sys.exit(main())
