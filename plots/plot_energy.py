#!/usr/bin/python3
"""Plots a run's energies.csv like Fig. 4 of Li & Cai (2008): translational, rotational,
elastic, gravitational and total mechanical energy against time on a log axis, with the
energy books (dissipated, wall work) in a second panel.

usage: plot_energy.py energies.csv energies.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{src}: no rows")
    col = {k: [float(r[k]) for r in rows] for k in rows[0]}
    t = col["time"]
    fig, (ax, books) = plt.subplots(2, 1, figsize=(8, 8), sharex=True,
                                    gridspec_kw={"height_ratios": [3, 2]})
    for key, label in [("translational", "translational kinetic"),
                       ("rotational", "rotational kinetic"),
                       ("elastic", "elastic"),
                       ("gravitational", "gravitational"),
                       ("mechanical", "total mechanical")]:
        values = [v if v > 0 else float("nan") for v in col[key]]
        ax.plot(t, values, label=label, lw=1.5 if key == "mechanical" else 1.0)
    ax.set_yscale("log")
    ax.set_ylabel("energy [m sigma^2 / tau^2]")
    ax.set_title("Energies of the grains (cf. Li & Cai 2008, Fig. 4)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)

    books.plot(t, col["dissipated"], label="dissipated (cumulative)")
    books.plot(t, col["wall_work"], label="work of moving walls (cumulative)")
    books.plot(t, col["removed"], label="carried off by removed grains")
    books.plot(t, col["gravity_work"], label="work of gravity along periodic axes")
    books.plot(t, [b - col["balance"][0] for b in col["balance"]],
               label="books: mechanical + dissipated + removed - wall work - gravity work (change)", color="k")
    books.set_xlabel("time [tau]")
    books.set_ylabel("energy")
    books.legend(loc="best", fontsize=8)
    books.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(dst, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
