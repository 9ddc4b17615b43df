"""The stress in a silo at rest, coarse-grained about its axis.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/silo_stress.py [--short]

Grains settle in a cylinder of diameter 10 d on a flat floor. yuxi.coarse_grain then makes the
fields on a grid about the silo's axis, averaged around it (docs/coarse-graining.md,
"Cylindrical grids"): the maps of sigma_zz and sigma_rr over r and z, and the mean of sigma_zz
over the cross-section against depth beside the weight above. Their difference is what the side
wall carries by its friction; a bed that was poured and settled mobilises little of it (the
Janssen validation case lowers its silos' floors to mobilise it, docs/results/bulk/README.md).
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import yuxi  # noqa: E402

RADIUS = 5.0  # the silo, in grain diameters
AXIS = (6.0, 6.0)
PAIR = {"k_n": 2.0e4, "k_t": 5.7e3, "gamma_n": 60.0, "gamma_t": 20.0, "mu_s": 0.5, "mu_d": 0.5}


def scene(count, t_end):
    return {
        "materials": ["grain", "wall"],
        "material": {"grain": {"density": 1.909859317}},  # m = 1 for d = 1
        "run": {"name": "silo-stress", "dt": 2.0e-4, "t_end": t_end},
        "output": {"energy_interval": 0.1, "snapshot_interval": 0.0},
        "domain": {"lo": [0.0, 0.0, 0.0], "hi": [12.0, 12.0, 60.0],
                   "gravity": [0.0, 0.0, -10.0], "boundary": ["wall", "wall", "wall"],
                   "wall_material": "wall"},
        "contact": {"model": "linear", "pair": [dict(PAIR, materials=["grain", "grain"]),
                                                 dict(PAIR, materials=["grain", "wall"])]},
        "cylinder": [{"name": "side", "center": [AXIS[0], AXIS[1], 0.0], "radius": RADIUS,
                      "material": "wall"}],
        "fill": [{"material": "grain", "size": {"distribution": "uniform", "min": 0.45,
                                                "max": 0.55},
                  "count": count, "placement": "lattice", "jitter": 0.05,
                  "region": {"shape": "cylinder", "center": [AXIS[0], AXIS[1], 0.0],
                             "radius": RADIUS - 0.6, "lo": 0.5, "hi": 59.0}}],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true", help="a short run (the tests)")
    parser.add_argument("--runs", default="runs/silo-stress")
    parser.add_argument("--out", default="silo_stress.png")
    args = parser.parse_args()

    count, settle = (600, 5.0) if args.short else (1300, 10.0)
    sim = yuxi.Simulation(scene(count, settle), output=os.path.join(args.runs, "run"),
                          overwrite=True, progress=False)
    sim.run()
    sim.record_contacts(True)  # the contact stress needs the contacts of a step
    sim.step()
    f = yuxi.coarse_grain(sim, width=0.5, axis=AXIS, lo=(0.0, 0.0), hi=(RADIUS, 24.0),
                          n=(10, 1, 48), average="theta")
    sim.close()

    r, z = f["r"], f["z"]
    szz = f["stress"][..., 2, 2]  # [r, z], in the local basis (e_r, e_theta, e_z)
    srr = f["stress"][..., 0, 0]
    cells = f["cell_volume"][:, None]  # the annuli's volumes: the cross-section's mean
    mean_szz = (szz * cells).sum(axis=0) / cells.sum()
    rho = (f["density"] * cells).sum(axis=0) / cells.sum()
    weight = 10.0 * np.cumsum((rho * (z[1] - z[0]))[::-1])[::-1]  # g times the mass above

    fig, (a, b, c) = plt.subplots(1, 3, figsize=(12, 4.6))
    image = a.pcolormesh(r, z, szz.T, shading="nearest", cmap="viridis")
    fig.colorbar(image, ax=a, label=r"$\sigma_{zz}$ [m g / d$^2$]")
    a.set_xlabel("r [d]")
    a.set_ylabel("z [d]")
    a.set_title(r"$\sigma_{zz}(r, z)$, averaged around the axis", fontsize=9)
    image = b.pcolormesh(r, z, srr.T, shading="nearest", cmap="viridis")
    fig.colorbar(image, ax=b, label=r"$\sigma_{rr}$ [m g / d$^2$]")
    b.set_xlabel("r [d]")
    b.set_title(r"$\sigma_{rr}(r, z)$: the push on the wall", fontsize=9)
    c.plot(mean_szz, z, label=r"mean $\sigma_{zz}$ over the cross-section")
    c.plot(weight, z, "k--", label=r"weight above, $g \int_z \rho$")
    c.set_xlabel("stress [m g / d$^2$]")
    c.legend(fontsize=8)
    c.set_title("the side wall carries the difference", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    bottom = np.argmax(mean_szz)
    print(f"{args.out}: at z = {z[bottom]:.2f} the mean sigma_zz is {mean_szz[bottom]:.3g}, "
          f"the weight above {weight[bottom]:.3g}")


if __name__ == "__main__":
    main()
