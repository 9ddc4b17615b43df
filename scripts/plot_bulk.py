#!/usr/bin/python3
"""Draws the bulk benchmarks' measured curves beside the expected ones (docs/models/validation.md
section 4), from the folders their validation cases ran in (`YUXI_VALIDATION_RUNS=DIR yuxi
validate B2` leaves DIR/janssen/):

  plot_bulk.py janssen RUN_DIR [--out PNG]    janssen.csv: apparent mass against filled mass,
                                              with the fitted Janssen curve and M_app = M
  plot_bulk.py beverloo RUN_DIR... [--out PNG] beverloo.csv of each orifice: W against D_o - k d,
                                              with Beverloo's law (C = 0.58, k = 1.5) and the fit
  plot_bulk.py heap RUN_DIR [--out PNG]       heap.csv: angle of repose against mu_s and mu_r
  plot_bulk.py drum RUN_DIR [--out PNG]       drum.csv: dynamic angle against the Froude number

Every PNG goes beside its data unless --out names another file.
"""
import argparse
import csv
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def janssen(folder, out):
    table = rows(folder / "janssen.csv")
    rough = [r for r in table if float(r["mu_w"]) > 0]
    smooth = [r for r in table if float(r["mu_w"]) == 0]
    m_sat, lam, r2 = (float(rough[0][k]) for k in ("m_sat", "lambda", "r2"))
    d = float(rough[0]["diameter"])
    mass = np.array([float(r["mass"]) for r in rough])
    app = np.array([float(r["apparent_mass"]) for r in rough])
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    grid = np.linspace(0, 1.1 * max(float(r["mass"]) for r in table), 200)
    ax.plot(grid, grid, "k:", lw=1, label="hydrostatic, M_app = M")
    ax.plot(grid, m_sat * (1 - np.exp(-grid / m_sat)), "C0-",
            label=f"Janssen fit: M_sat = {m_sat:.4g}, lambda/D = {lam / d:.2f}, R² = {r2:.3f}")
    ax.plot(mass, app, "C0o", label="mu_w = 0.5")
    if smooth:
        ax.plot([float(r["mass"]) for r in smooth], [float(r["apparent_mass"]) for r in smooth],
                "C3s", label="mu_w = 0")
    for r in rough:
        ax.annotate(f"{float(r['height']) / d:.1f} D", (float(r["mass"]), float(r["apparent_mass"])),
                    textcoords="offset points", xytext=(4, -10), fontsize=7)
    ax.set_xlabel("filled mass M [m]")
    ax.set_ylabel("apparent mass M_app = bottom force / g [m]")
    ax.set_title(f"Janssen silos, D = {d:g} d")
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    print(f"wrote {out}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("bench", choices=["janssen", "beverloo", "heap", "drum"])
    p.add_argument("folders", nargs="+", type=pathlib.Path)
    p.add_argument("--out", type=pathlib.Path)
    a = p.parse_args()
    out = a.out or a.folders[0] / f"{a.bench}.png"
    {"janssen": lambda: janssen(a.folders[0], out)}.get(a.bench, lambda: sys.exit(
        f"{a.bench}: no data reader yet"))()


if __name__ == "__main__":
    main()
