#!/usr/bin/python3
"""Draws the steady chute flows of the validation cases C2 and C3 from the files they write
(docs/models/validation.md section 3.4):

  plot_chute.py profile PROFILE.csv [--out PNG]   YUXI_C2_PROFILE's coarse-grained profile: the
                                                  stress ratio against tan(theta), sigma_zz
                                                  against the weight above, the packing fraction,
                                                  the velocity and the inertial number along z
  plot_chute.py rheology POINTS.csv [--out PNG]   YUXI_C3_POINTS: mu(I) and phi(I), one point per
                                                  angle, with the least-squares lines

Every PNG goes beside its data unless --out names another file.
"""
import argparse
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def profile(path, out, degrees=24.0):
    d = np.genfromtxt(path, delimiter=",", names=True)
    z, phi = d["z"], d["packing_fraction"]
    surface = z[phi > 0.3].max()
    bulk = (z >= 4.0) & (z <= surface - 3.0)
    flowing = (d["sigma_zz"] > 0) & (z <= surface)
    shear = np.gradient(d["vx"], z)
    inertial = np.where(flowing, shear / np.sqrt(np.abs(d["sigma_zz"]) / (6 / math.pi) + 1e-300),
                        np.nan)
    fig, ax = plt.subplots(1, 4, figsize=(14, 5), sharey=True)
    ratio = np.where(flowing, -d["sigma_xz"] / np.where(flowing, d["sigma_zz"], 1.0), np.nan)
    ax[0].plot(ratio, z, label=r"$-\sigma_{xz}/\sigma_{zz}$")
    ax[0].axvline(math.tan(math.radians(degrees)), color="k", ls="--",
                  label=rf"$\tan {degrees:g}°$")
    ax[0].set_xlim(0.3, 0.6)
    ax[0].set_xlabel("stress ratio")
    ax[0].set_ylabel("z [d]")
    ax[1].plot(d["sigma_zz"], z, label=r"$\sigma_{zz}$ (coarse-grained)")
    ax[1].plot(d["weight_above"], z, "k--", label=r"$g\cos\theta\int_z\rho$")
    ax[1].set_xlabel(r"stress [$m g / d^2$]")
    ax[2].plot(phi, z, label="packing fraction")
    ax[2].plot(d["vx"] / d["vx"].max(), z, label=r"$v_x / v_{x,\max}$")
    ax[2].set_xlabel("packing, velocity")
    ax[3].plot(inertial, z)
    ax[3].set_xlabel("inertial number I")
    for a in ax:
        a.axhspan(4.0, surface - 3.0, color="0.9", zorder=0)
        a.legend(fontsize=8) if a.get_legend_handles_labels()[0] else None
    fig.suptitle(f"Steady chute flow at {degrees:g}° (C2), coarse-grained along z; grey: the "
                 f"bulk, mean I = {np.nanmean(inertial[bulk]):.3f}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def rheology(path, out):
    d = np.genfromtxt(path, delimiter=",", names=True)
    inertial = d["inertial_number"]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4.5))
    for a, key, label in ((ax[0], "mu", r"$\mu = -\sigma_{xz}/\sigma_{zz}$"),
                          (ax[1], "packing_fraction", r"$\phi$")):
        a.plot(inertial, d[key], "o")
        for i, deg in zip(inertial, d["degrees"]):
            a.annotate(f"{deg:g}°", (i, d[key][list(d["degrees"]).index(deg)]), fontsize=8,
                       xytext=(4, 4), textcoords="offset points")
        slope, intercept = np.polyfit(inertial, d[key], 1)
        grid = np.linspace(0.0, inertial.max() * 1.1, 50)
        a.plot(grid, intercept + slope * grid, "k--",
               label=f"{intercept:.3f} {'+' if slope >= 0 else '-'} {abs(slope):.3f} I")
        a.set_xlabel("inertial number I")
        a.set_ylabel(label)
        a.legend()
    ax[0].axhspan(math.tan(math.radians(19.5)), math.tan(math.radians(20.5)), color="0.85",
                  label="thick layers stop (Silbert 2001)")
    ax[0].legend(fontsize=8)
    fig.suptitle("Chute rheology (C3): one point per angle, bulk means")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=("profile", "rheology"))
    parser.add_argument("data", type=pathlib.Path)
    parser.add_argument("--out", type=pathlib.Path)
    args = parser.parse_args()
    out = args.out or args.data.with_suffix(".png")
    (profile if args.what == "profile" else rheology)(args.data, out)
    print(out)


if __name__ == "__main__":
    main()
