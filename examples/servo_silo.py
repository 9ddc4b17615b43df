"""A piston on a bed of grains, driven to a target pressure by a controller written in Python.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/servo_silo.py [--short]

Grains settle in a square box; a square mesh piston (`controlled = true`: its speed is set from
outside) waits above them. Every 20 steps a callback reads the grains' push on the piston
(sim.wall_loads()) and sets the piston's speed with a proportional-integral law, so the pressure
on the bed rises to the target and holds. The figure shows the pressure and the piston's travel
against time.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import yuxi  # noqa: E402

SIDE = 10.0  # the box, in grain diameters
PAIR = {"k_n": 2.0e4, "k_t": 5.7e3, "gamma_n": 60.0, "gamma_t": 20.0, "mu_s": 0.5, "mu_d": 0.5}


def scene(piston_file, t_end):
    return {
        "materials": ["grain", "wall"],
        "material": {"grain": {"density": 1.909859317}},  # m = 1 for d = 1
        "run": {"name": "servo-silo", "dt": 2.0e-4, "t_end": t_end},
        "output": {"energy_interval": 0.05, "snapshot_interval": 0.5},
        "domain": {"lo": [0.0, 0.0, 0.0], "hi": [SIDE, SIDE, 16.0],
                   "gravity": [0.0, 0.0, -10.0], "boundary": ["wall", "wall", "wall"],
                   "wall_material": "wall"},
        "contact": {"model": "linear", "pair": [dict(PAIR, materials=["grain", "grain"]),
                                                 dict(PAIR, materials=["grain", "wall"])]},
        "fill": [{"material": "grain", "size": {"distribution": "uniform", "min": 0.45,
                                                "max": 0.55},
                  "count": 400, "placement": "lattice", "jitter": 0.05,
                  "region": {"shape": "box", "lo": [0.2, 0.2, 0.2],
                             "hi": [SIDE - 0.2, SIDE - 0.2, 12.0]}}],
        "mesh": [{"name": "piston", "file": piston_file, "material": "wall",
                  "translate": [SIDE / 2, SIDE / 2, 12.5], "controlled": True,
                  "servo_axis": [0.0, 0.0, -1.0]}],
    }


class PressureController:
    """Down at `approach` until the piston touches the bed; then
    speed = kp (target - F) + ki integral (target - F) dt, at most max_speed either way.
    (Stable for kp k_bed dt_control < 1, k_bed the bed's stiffness under the piston.)"""

    def __init__(self, target, kp, ki, max_speed, approach):
        self.target, self.kp, self.ki = target, kp, ki
        self.max_speed, self.approach = max_speed, approach
        self.integral, self.touched = 0.0, False

    def __call__(self, force, dt):
        self.touched = self.touched or force > 0
        if not self.touched:
            return self.approach
        error = self.target - force
        self.integral += error * dt
        speed = self.kp * error + self.ki * self.integral
        return float(np.clip(speed, -self.max_speed, self.max_speed))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true", help="a short run (the tests)")
    parser.add_argument("--pressure", type=float, default=20.0,
                        help="target pressure on the bed [m g / d^2]")
    parser.add_argument("--runs", default="runs/servo-silo")
    parser.add_argument("--out", default="servo_silo.png")
    args = parser.parse_args()

    os.makedirs(args.runs, exist_ok=True)
    piston = os.path.abspath(os.path.join(args.runs, "piston.stl"))
    yuxi.write_stl(piston, yuxi.square(SIDE / 2 - 0.05), header="piston")
    settle, press = (0.4, 0.4) if args.short else (2.0, 6.0)
    sim = yuxi.Simulation(scene(piston, settle + press), output=os.path.join(args.runs, "run"),
                          overwrite=True)
    sim.run(t_end=settle)  # the bed settles; the piston waits

    area = SIDE * SIDE
    every = 20
    control = PressureController(args.pressure * area, kp=1e-4, ki=2e-3, max_speed=2.0,
                                 approach=4.0)
    times, pressures, travel = [], [], []

    def steer(s):
        push = s.wall_loads()["piston"]["force"][2]  # the grains push the piston up (+z)
        s.set_wall_speed("piston", control(push, every * s.dt))
        times.append(s.time)
        pressures.append(push / area)
        travel.append(s.wall_motion("piston")["offset"])

    sim.run(callback=steer, every=every)
    sim.close()

    fig, (a, b) = plt.subplots(2, 1, figsize=(6, 5.4), sharex=True)
    a.plot(times, pressures, label="on the piston")
    a.axhline(args.pressure, color="k", ls=":", label="target")
    a.set_ylabel("pressure [m g / d^2]")
    a.legend(fontsize=8)
    b.plot(times, travel)
    b.set_ylabel("piston travel [d]")
    b.set_xlabel("t [sqrt(d / g)]")
    a.set_title("a piston driven to a target pressure from Python")
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)
    print(f"{args.out}: final pressure {np.mean(pressures[-10:]):.3g} (target {args.pressure})")


if __name__ == "__main__":
    main()
