"""Where the wall's work goes in the fish basin's first period: coarse-grained fields.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/basin_fields.py [--short]

The small basin (scenes/basin-small.toml) settles until its side wall starts to vibrate in the
m = 2 mode. Over the first period of the vibration, every `--every` steps, yuxi.coarse_grain
makes the fields on a cylindrical grid about the basin's axis (docs/coarse-graining.md,
"The basin"): the power the wall puts into the grains, the power their contacts dissipate, the
kinetic and elastic energy densities, the granular temperature and the pressure. Their means
over the period are folded onto one quarter turn (the m = 2 mode repeats every 90 degrees) and
drawn in the vertical planes through an antinode and a node. The energy books give the budget
of the period: the wall's work against the changes in kinetic, elastic and potential energy and
the energy dissipated; the fields show where each happens, as profiles against the distance
from the wall.
"""
import argparse
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import yuxi  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
FIELDS = ("wall_power_density", "dissipation_rate_density", "kinetic_energy_density",
          "elastic_energy_density", "temperature", "pressure", "density")


def fields_now(sim, axis, lo, hi, n, width):
    """The fields at this step (the contacts of the step just taken), pressure = tr(stress) / 3."""
    f = yuxi.coarse_grain(sim, width=width, axis=axis, lo=lo, hi=hi, n=n)
    f["pressure"] = np.trace(f["stress"], axis1=-2, axis2=-1) / 3.0
    return f


def fold_quarter(a, n_theta):
    """The mean over the four quarter turns of an array indexed [r, theta, z]."""
    q = n_theta // 4
    return np.mean([a[:, k * q:(k + 1) * q] for k in range(4)], axis=0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true",
                        help="a short settling and a coarse grid (the tests): the path, not the "
                             "physics")
    parser.add_argument("--scene", default=os.path.join(HERE, "..", "scenes", "basin-small.toml"))
    parser.add_argument("--runs", default="runs/basin-fields")
    parser.add_argument("--out", default="basin_fields.png")
    parser.add_argument("--every", type=int, default=1, help="steps between samples")
    args = parser.parse_args()

    scene = yuxi.Scene(args.scene)
    resolved = scene.resolved()
    basin, excitation = resolved["basin"], resolved["basin"]["excitation"]
    changes = {"analysis": None, "output": {"snapshot_interval": 0.0}}
    if args.short:
        changes["basin"] = {"excitation": dict(excitation, t0=0.3)}
        excitation = changes["basin"]["excitation"]
    t0, omega, mode = excitation["t0"], excitation["omega"], excitation["mode"]
    if mode % 4 != 0 and 4 % mode != 0:
        raise SystemExit(f"the fold onto a quarter turn needs m = 1, 2 or 4 (m = {mode})")
    lo = resolved["domain"]["lo"]
    spacing = basin["spacing"]
    axis = (lo[0] + 0.5 * basin["cells"][0] * spacing, lo[1] + 0.5 * basin["cells"][1] * spacing)
    wall_r = basin["radius"] * spacing  # the lattice's inner radius: wall particles' centres
    # Points 1.5 sigma apart (around the circle too, at the wall), a Gaussian as wide: the
    # sums over the grid hold the integrals (docs/coarse-graining.md, "Grids").
    width = 1.5  # sigma
    # The grid reaches 3 w past the contacts: grains touch the side wall's particles up to one
    # amplitude beyond the lattice's inner radius, and its bottom layer above z = 0.
    r_hi, z_lo, z_hi = wall_r + 6.0, -4.5, 24.0
    n = (8, 32, 8) if args.short else (24, 128, 19)

    sim = yuxi.Simulation(scene.changed(dict(changes, run={"name": "basin-fields"})),
                          output=args.runs, overwrite=True, progress=False)
    sim.run(t_end=t0)
    period = 2.0 * math.pi / omega
    steps = max(1, round(period / sim.dt))
    before = sim.energies()
    sim.record_contacts(True)
    sums, samples, wall_integral, dissipation_integral = {}, 0, 0.0, 0.0
    for step in range(steps):
        sim.step()
        if step % args.every and step != steps - 1:
            continue
        f = fields_now(sim, axis, (0.0, z_lo), (r_hi, z_hi), n, width)
        for key in FIELDS:
            sums[key] = sums.get(key, 0.0) + f[key]
        samples += 1
        cells = f["cell_volume"][:, None, None]
        # Integrals over the grid of the powers, times the time each sample stands for.
        wall_integral += (f["wall_power_density"] * cells).sum() * args.every * sim.dt
        dissipation_integral += (f["dissipation_rate_density"] * cells).sum() * args.every * sim.dt
    after = sim.energies()
    sim.close()
    mean = {k: fold_quarter(v / samples, n[1]) for k, v in sums.items()}
    r = f["r"]
    z = f["z"]
    theta = f["theta"][:n[1] // 4]

    change = {k: after[k] - before[k] for k in ("wall_work", "kinetic", "elastic",
                                                  "gravitational", "dissipated", "removed",
                                                  "balance")}
    print(f"the first period, {steps} steps ({samples} samples):")
    print(f"  the wall's work (books) {change['wall_work']:.6g}, its power density integrated "
          f"{wall_integral:.6g}")
    for k in ("kinetic", "elastic", "gravitational", "dissipated", "removed"):
        print(f"  change in {k} {change[k]:.6g}")
    print(f"  the books' residual {change['balance']:.6g}: "
          f"{change['balance'] / change['wall_work']:.2%} of the wall's work (the time step's "
          f"first-order error: docs/results/books-convergence)" if change["wall_work"] else "")
    print(f"  dissipation density integrated {dissipation_integral:.6g} (the releases of ending "
          f"contacts are not in it)")

    # The antinode plane: the sectors next to theta = 0 (and 90 degrees, folded); the node
    # plane: those next to 45 degrees.
    q = n[1] // 4
    antinode = [0, q - 1]
    node = [q // 2 - 1, q // 2]

    fig = plt.figure(figsize=(15, 10))
    grid = fig.add_gridspec(3, 4)
    maps = [("wall_power_density", "wall power density", "inferno"),
            ("dissipation_rate_density", "dissipation rate density", "inferno"),
            ("temperature", "granular temperature", "viridis"),
            ("pressure", "pressure tr(sigma) / 3", "viridis")]
    for row, (name, sectors) in enumerate((("antinode", antinode), ("node", node))):
        for col, (key, title, cmap) in enumerate(maps):
            ax = fig.add_subplot(grid[row, col])
            data = mean[key][:, sectors].mean(axis=1)
            image = ax.pcolormesh(r, z, data.T, shading="nearest", cmap=cmap)
            fig.colorbar(image, ax=ax, shrink=0.85)
            ax.axvline(wall_r, color="w", lw=0.8, ls="--")
            ax.set_xlim(wall_r - 18.0, r_hi)
            ax.set_ylim(z_lo, 16.0)
            ax.set_title(f"{title}, {name} plane", fontsize=9)
            ax.set_xlabel("r [sigma]", fontsize=8)
            if col == 0:
                ax.set_ylabel("z [sigma]", fontsize=8)
            ax.tick_params(labelsize=7)

    # The budget of the period, from the books.
    ax = fig.add_subplot(grid[2, 0])
    names = ["wall's\nwork", "kinetic", "elastic", "potential", "dissipated", "residual"]
    values = [change["wall_work"], change["kinetic"], change["elastic"], change["gravitational"],
              change["dissipated"], change["balance"]]
    ax.bar(names, values, color=["k", "C0", "C1", "C2", "C3", "C7"])
    ax.axhline(0, color="k", lw=0.5)
    ax.set_ylabel("energy over the period [m sigma^2 / tau^2]", fontsize=8)
    ax.set_title("the first period's budget (energy books)", fontsize=9)
    ax.tick_params(labelsize=7)

    # Where: the period's mean powers and energies against the distance from the wall, summed
    # over theta and z.
    cells = f["cell_volume"][:, None, None] * 4  # a folded cell stands for four
    distance = wall_r - r
    shells = {k: (mean[k] * cells).sum(axis=(1, 2)) for k in mean}
    for k, label in (("wall_power_density", "the wall's power"),
                     ("dissipation_rate_density", "the dissipation"),
                     ("kinetic_energy_density", "the kinetic energy")):
        total = shells[k].sum()
        if total > 0:
            near = [shells[k][distance < d].sum() / total for d in (3.0, 6.0, 10.0)]
            print(f"  {label}: {near[0]:.1%}, {near[1]:.1%}, {near[2]:.1%} within 3, 6, 10 "
                  "sigma of the wall's lattice")
    antinode_power = mean["wall_power_density"][:, antinode].sum()
    node_power = mean["wall_power_density"][:, node].sum()
    if node_power > 0:
        print("  the wall's power, antinode plane over node plane: "
              f"{antinode_power / node_power:.3g}")
    profiles = [(("wall_power_density", "wall power in"),
                 ("dissipation_rate_density", "dissipated"),
                 "power per shell [m sigma^2 / tau^3]", "where the power enters and leaves"),
                (("kinetic_energy_density", "kinetic"), ("elastic_energy_density", "elastic"),
                 "energy per shell [m sigma^2 / tau^2]", "where the energy sits (period mean)")]
    for col, (first, second, ylabel, title) in enumerate(profiles, start=1):
        ax = fig.add_subplot(grid[2, col])
        for key, label in (first, second):
            ax.plot(distance, shells[key], label=label)
        ax.set_xlabel("distance from the wall's lattice [sigma]", fontsize=8)
        ax.set_ylabel(ylabel, fontsize=8)
        ax.set_title(title, fontsize=9)
        ax.set_xlim(distance.min(), 18.0)
        ax.legend(fontsize=8)
        ax.tick_params(labelsize=7)
    ax = fig.add_subplot(grid[2, 3])
    shell = (mean["temperature"] * mean["density"] * cells).sum(axis=(1, 2))
    mass = (mean["density"] * cells).sum(axis=(1, 2))
    ax.plot(distance, np.where(mass > 0, shell / np.where(mass > 0, mass, 1), np.nan))
    ax.set_xlabel("distance from the wall's lattice [sigma]", fontsize=8)
    ax.set_ylabel("T [sigma^2 / tau^2]", fontsize=8)
    ax.set_title("granular temperature, mass-weighted", fontsize=9)
    ax.set_xlim(distance.min(), 18.0)
    ax.tick_params(labelsize=7)
    fig.suptitle(f"The fish basin's first period (m = {mode}): coarse-grained fields, w = "
                 f"{width:g} sigma, means over {samples} samples, folded onto a quarter turn",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"{args.out}: antinode plane the sectors at {np.degrees(theta[antinode]).round(1)} "
          f"degrees, node plane at {np.degrees(theta[node]).round(1)}")


if __name__ == "__main__":
    main()
