"""The intermediate-axis flip (Dzhanibekov, "tennis racket") of a clump, from Python.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/tumbling_clump.py \
        [--short] [--out F] [--runs DIR]

A T-shaped clump of four spheres floats without gravity, placed by a [[clump]] table. Python
spins it about its intermediate principal axis with a small push off it
(``set_clump_angular_velocities``), then follows its angular velocity in its own principal
frame (``clumps()``: orientation and angular velocity). The body flips over and back; the time
between flips is the period of the Euler equations' exact solution, 4 K(k) / nu in Jacobi's
elliptic functions (Landau & Lifshitz, Mechanics, section 37), which the script prints beside
the measured one and draws.
"""
import argparse
import math

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import yuxi  # noqa: E402

SCENE = {
    "materials": ["grain", "wall"],
    "material": {"grain": {"density": 1.0}},
    "run": {"name": "tumbling-clump", "dt": 1.0e-3, "t_end": 1000.0},
    "output": {"energy_interval": 1.0, "snapshot_interval": 0.0},
    "domain": {"lo": [0.0, 0.0, 0.0], "hi": [20.0, 20.0, 20.0], "gravity": [0.0, 0.0, 0.0],
               "boundary": ["wall", "wall", "wall"], "wall_material": "wall"},
    "contact": {"model": "linear", "pair": [
        {"materials": ["grain", "grain"], "k_n": 1.0e4, "gamma_n": 10.0},
        {"materials": ["grain", "wall"], "k_n": 1.0e4, "gamma_n": 10.0}]},
    # a T: a bar of three spheres along x and a fourth one off its middle along y
    "shape": [{"name": "tee", "spheres": [[-1.0, 0.0, 0.0, 0.5], [0.0, 0.0, 0.0, 0.5],
                                          [1.0, 0.0, 0.0, 0.5], [0.0, 1.3, 0.0, 0.5]]}],
    "clump": [{"shape": "tee", "position": [10.0, 10.0, 10.0], "material": "grain"}],
}


def rotate(q, v):
    """v turned by the unit quaternion q = (w, x, y, z)."""
    w, u = q[0], np.asarray(q[1:])
    return v + 2.0 * np.cross(u, np.cross(u, v) + w * v)


def complete_elliptic_k(k):
    """K(k) by the arithmetic-geometric mean: pi / (2 AGM(1, sqrt(1 - k^2)))."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-15 * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def euler_period(inertia, omega):
    """The period of a free body's angular velocity in its principal frame (Landau & Lifshitz
    section 37): 4 K(k) / nu, from the moments and the body-frame angular velocity."""
    i1, i2, i3 = inertia
    m2 = float(np.sum((inertia * omega) ** 2))  # L^2
    e2 = float(np.sum(inertia * omega ** 2))  # 2 E
    if m2 > e2 * i2:
        nu = math.sqrt((i3 - i2) * (m2 - e2 * i1) / (i1 * i2 * i3))
        k2 = (i2 - i1) * (e2 * i3 - m2) / ((i3 - i2) * (m2 - e2 * i1))
    else:
        nu = math.sqrt((i2 - i1) * (e2 * i3 - m2) / (i1 * i2 * i3))
        k2 = (i3 - i2) * (m2 - e2 * i1) / ((i2 - i1) * (e2 * i3 - m2))
    return 4.0 * complete_elliptic_k(math.sqrt(k2)) / nu


def tumble(runs, periods, every=5):
    """Spins the clump and follows it for `periods` of the Euler equations' period, recording
    (t, omega in the principal frame); returns them with the moments and that period."""
    sim = yuxi.Simulation(SCENE, output=f"{runs}/tumbling-clump", overwrite=True,
                          progress=False)
    c = sim.clumps()
    inertia = c["inertia"][0]
    omega_body = np.array([0.02, 1.0, 0.01])  # about the intermediate axis, pushed off it
    sim.set_clump_angular_velocities(c["id"], [rotate(c["orientation"][0], omega_body)])
    period = euler_period(inertia, omega_body)
    times, omegas = [], []

    def record(s):
        now = s.clumps()
        q = now["orientation"][0]
        q_inverse = np.array([q[0], -q[1], -q[2], -q[3]])
        times.append(s.time)
        omegas.append(rotate(q_inverse, now["angular_velocity"][0]))

    record(sim)
    sim.run(t_end=periods * period, callback=record, every=every)
    sim.close()
    return np.array(times), np.array(omegas), inertia, period


def upward_crossings(t, w):
    """The times w turns from negative to non-negative, by linear interpolation."""
    k = np.nonzero((w[:-1] < 0) & (w[1:] >= 0))[0]
    return t[k] + (t[k + 1] - t[k]) * w[k] / (w[k] - w[k + 1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true", help="two periods (the tests)")
    parser.add_argument("--out", default="tumbling_clump.png")
    parser.add_argument("--runs", default="runs")
    args = parser.parse_args()

    times, omegas, inertia, period = tumble(args.runs, 2.3 if args.short else 5.3)
    flips = upward_crossings(times, omegas[:, 1])
    measured = np.diff(flips)
    print(f"principal moments {inertia}; Euler equations' period {period:.6g}; "
          f"measured {', '.join(f'{m:.6g}' for m in measured)} "
          f"(relative differences {', '.join(f'{m / period - 1:.2g}' for m in measured)})")

    fig, ax = plt.subplots(figsize=(7, 4))
    for a, label in enumerate(["omega_1 (smallest moment)", "omega_2 (intermediate)",
                               "omega_3 (largest)"]):
        ax.plot(times, omegas[:, a], label=label)
    for f in flips:
        ax.axvline(f, color="0.7", lw=0.8)
    ax.set_xlabel("time")
    ax.set_ylabel("angular velocity in the principal frame")
    ax.set_title(f"flip period {np.mean(measured):.6g} (Euler equations: {period:.6g})")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)
    print(args.out)


if __name__ == "__main__":
    main()
