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
import pathlib
import re

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


def beverloo(folders, out):
    table = []
    for folder in folders:
        table += rows(folder / "beverloo.csv")
    orifice = np.array([float(r["orifice"]) for r in table])
    w = np.array([float(r["w"]) for r in table])
    rho_b = np.mean([float(r["rho_b"]) for r in table])
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    x = np.linspace(max(orifice.min() - 1.5, 2.0), orifice.max() + 1, 100)
    ax.plot(x - 1.5, 0.58 * rho_b * (x - 1.5) ** 2.5, "k:",
            label=f"Beverloo, C = 0.58, k = 1.5, rho_b = {rho_b:.3f}")
    if "c_fit" in table[0]:
        c, k = float(table[0]["c_fit"]), float(table[0]["k_fit"])
        ax.plot(x - 1.5, c * rho_b * np.clip(x - k, 0, None) ** 2.5, "C0-",
                label=f"fit: C = {c:.3f}, k = {k:.2f}")
    ax.plot(orifice - 1.5, w, "C0o", label="yuxi")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("D_o - 1.5 d [d]")
    ax.set_ylabel("discharge rate W [m / tau]")
    ax.set_title("Beverloo discharge, flat-bottomed silo")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    print(f"wrote {out}")


def heap(folder, out):
    by = {r["scene"]: (float(r["angle"]), float(r["r2"])) for r in rows(folder / "heap.csv")}
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.8))
    # each heap of the mu_s series (three random floors and pours a mu_s), and their means
    singles = sorted((float(n[len("heap-mu"):].split("-")[0]), by[n][0]) for n in by
                     if re.fullmatch(r"heap-mu[0-9.]+(-seed[0-9]+)?", n))
    a.plot([m for m, _ in singles], [t for _, t in singles], "C0.", alpha=0.6,
           label="each heap, k_n = 2e4, e = 0.68")
    if (folder / "heap_mu.csv").exists():
        means = rows(folder / "heap_mu.csv")
        a.errorbar([float(r["mu"]) for r in means], [float(r["mean"]) for r in means],
                   yerr=[2 * float(r["standard_error"]) for r in means], fmt="C0o-", capsize=3,
                   label="mean, 2 standard errors")
    # the variants at mu_s = 0.5, drawn a little to the right of it: the mean of three heaps
    # with 2 standard errors where heap_variants.csv has it, else the one heap
    variants = {r["scene"]: r for r in rows(folder / "heap_variants.csv")} \
        if (folder / "heap_variants.csv").exists() else {}
    for k, (name, marker, label) in enumerate((("heap-mu0.5-stiff", "s", "k_n x 10"),
                                               ("heap-mu0.5-e0.5", "v", "e = 0.5"),
                                               ("heap-mu0.5-e0.9", "^", "e = 0.9"))):
        x = 0.53 + 0.03 * k
        if name in variants:
            r = variants[name]
            a.errorbar([x], [float(r["mean"])], yerr=[2 * float(r["standard_error"])],
                       fmt="C1" + marker, capsize=3, label=label + f" (mean of {r['heaps']})")
        elif name in by:
            a.plot([x], [by[name][0]], "C1" + marker, label=label)
    a.axhspan(18, 26, color="0.9", label="band (a), 18-26 degrees")
    a.set_xlabel("sliding friction mu_s = mu_d")
    a.set_ylabel("angle of repose [degrees]")
    a.legend(fontsize=7)
    rolls = [(0.0, by["heap-mu0.5"][0])] if "heap-mu0.5" in by else []
    rolls += sorted((float(n.split("mur")[1]), by[n][0]) for n in by if "mur" in n)
    b.plot([m for m, _ in rolls], [t for _, t in rolls], "C2o-")
    b.set_xlabel("rolling friction mu_r (mu_s = 0.5)")
    b.set_ylabel("angle of repose [degrees]")
    fig.suptitle("Heaps poured on a rough floor")
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    print(f"wrote {out}")


def drum(folder, out):
    table = rows(folder / "drum.csv")
    fr = [float(r["froude"]) for r in table]
    angle = [float(r["angle"]) for r in table]
    spread = [float(r["spread"]) for r in table]
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    ax.errorbar(fr, angle, yerr=spread, fmt="C0o-", capsize=3, label="yuxi (mean, sd over time)")
    ax.set_xscale("log")
    ax.set_xlabel("Froude number omega^2 R / g")
    ax.set_ylabel("dynamic angle of repose [degrees]")
    ax.set_title("Rotating drum, R = 10 d, L = 10 d, 40 % full, mu = 0.5")
    ax.legend(fontsize=7)
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
    {"janssen": lambda: janssen(a.folders[0], out),
     "beverloo": lambda: beverloo(a.folders, out),
     "heap": lambda: heap(a.folders[0], out),
     "drum": lambda: drum(a.folders[0], out)}[a.bench]()


if __name__ == "__main__":
    main()
