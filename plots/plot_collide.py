#!/usr/bin/python3
"""Plots the collision study of `yuxi collide` like Figs. 3 and 4 of Jiang & Liu (2018):

  fig3_collision.png   the head-on collision of the thermodynamic model (v0 = 1e-3): (a) the
                       position of grain 1, (b) the normal force, (c) elastic, kinetic and
                       mechanical energy / E0, (d) the relaxation energy w_R / E0 (and heat);
  fig4_restitution.png the normal restitution coefficient against impact speed for every
                       model on one plot, log speed axis (engine runs as markers, the exact
                       two-grain solution as a line);
  oblique.png          e_n against the impact parameter.

usage: plot_collide.py RUN_FOLDER
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def column(rows, key):
    return [float(r[key]) for r in rows]


def fig3(folder):
    path = os.path.join(folder, "collision_series.csv")
    if not os.path.exists(path):
        print(f"{path} missing: no Fig. 3 (the study has no thermodynamic model)")
        return
    rows = read(path)
    t = column(rows, "t")
    fig, ax = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    ax[0, 0].plot(t, column(rows, "x1"))
    ax[0, 0].set_ylabel("position of grain 1, x1")
    ax[0, 0].set_title("(a)")
    ax[0, 1].plot(t, column(rows, "fn"))
    ax[0, 1].axhline(0, color="grey", lw=0.5)
    ax[0, 1].set_ylabel("normal force f_n")
    ax[0, 1].set_title("(b)")
    for key, label in [("w_el", "elastic w_e"), ("kinetic", "kinetic w_k"),
                       ("mechanical", "mechanical w = w_e + w_k")]:
        ax[1, 0].plot(t, column(rows, key), label=label)
    ax[1, 0].set_ylabel("energy / E0")
    ax[1, 0].legend()
    ax[1, 0].set_title("(c)")
    ax[1, 1].plot(t, column(rows, "w_relax"), label="relaxation w_R")
    ax[1, 1].plot(t, column(rows, "heat"), label="heat Q", ls="--")
    ax[1, 1].set_ylabel("energy / E0")
    ax[1, 1].legend()
    ax[1, 1].set_title("(d)")
    for a in ax[1]:
        a.set_xlabel("time (model units)")
    fig.suptitle("thermodynamic contact model, head-on, v0 = 1e-3 (exact two-grain solution)")
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "fig3_collision.png"), dpi=120)


def fig4(folder):
    rows = read(os.path.join(folder, "restitution.csv"))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    models = []
    for r in rows:
        if r["model"] not in models:
            models.append(r["model"])
    for k, model in enumerate(models):
        color = f"C{k}"
        for source, style in [("engine", dict(ls="none", marker="o")),
                              ("exact", dict(ls="-", marker=None))]:
            sel = [r for r in rows if r["model"] == model and r["source"] == source]
            if not sel:
                continue
            label = model + (" (DEM engine)" if source == "engine" else " (exact two-grain)")
            ax.plot(column(sel, "impact_speed"), column(sel, "e_n"), color=color, label=label,
                    **style)
    ax.set_xscale("log")
    ax.set_xlabel("impact speed 2 v0 (model units: m = 1, d = 1, k = 1)")
    ax.set_ylabel("normal restitution coefficient e")
    ax.set_title("restitution against impact speed")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "fig4_restitution.png"), dpi=120)


def oblique(folder):
    path = os.path.join(folder, "oblique.csv")
    if not os.path.exists(path):
        return
    rows = read(path)
    fig, ax = plt.subplots(figsize=(7, 5))
    keys = []
    for r in rows:
        if (r["model"], r["source"]) not in keys:
            keys.append((r["model"], r["source"]))
    for model, source in keys:
        sel = [r for r in rows if r["model"] == model and r["source"] == source]
        ax.plot(column(sel, "impact_parameter"), column(sel, "e_n"), marker="o",
                label=f"{model} ({source})")
    ax.set_xlabel("impact parameter b / d")
    ax.set_ylabel("normal restitution e_n (v0 = 1e-3)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "oblique.png"), dpi=120)


def main(folder):
    fig3(folder)
    fig4(folder)
    oblique(folder)
    print(f"plots in {folder}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
