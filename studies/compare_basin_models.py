#!/usr/bin/python3
"""The fish basin under several contact models, side by side (docs/results/basin-models).

usage: compare_basin_models.py RUN [RUN ...] [--t0 T] [--out DIR]

Each RUN is a run folder of one scene of scenes/basin-models/ (branched from the same settled
bed). From each it reads
  RUN/scene.resolved.toml       [contact] model
  RUN/energies.csv              time, translational, rotational, elastic, relaxation,
                                dissipated, wall_work, balance, escaped (m sigma^2/tau^2)
  RUN/analysis/peaks.csv        time, sector, height: each antinode's highest column [sigma]
  RUN/analysis/fits.csv         Fig. 10's power-law slopes and energy fractions in A and B
The highest jet is reported before the domain's top clips it: its height at t0 + 0.25 and the
time it first reaches 100 sigma.
Energies are counted from the excitation's start t0 (default 10 tau): the wall's work W, the
energy dissipated D, the kinetic energy, the books' residual (balance - balance(t0)) over W.
Writes DIR/basin_models.png (kinetic energy, the wall's work and the dissipated energy against
time; the highest jet against time; the heat against the relaxation energy where a model has
one) and DIR/basin_models.csv, and prints the table as Markdown.
"""
import argparse
import csv
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "plots"))
from plot_basin import read_fits, read_resolved_scene, read_table  # noqa: E402


def read_run(path, t0):
    scene = read_resolved_scene(path)
    e = read_table(os.path.join(path, "energies.csv"))
    start = int(np.searchsorted(e["time"], t0 - 1e-9))
    since = {k: e[k] - e[k][start] for k in ("dissipated", "wall_work", "balance", "relaxation")}
    peaks = read_table(os.path.join(path, "analysis", "peaks.csv"))
    times = np.unique(peaks["time"])
    highest = np.array([peaks["height"][peaks["time"] == t].max() for t in times])
    fits = read_fits(os.path.join(path, "analysis"), {})
    slope = {key: (f["slope"], f["energy_fraction"]) for key, f in fits.items()}
    return {"name": os.path.basename(os.path.normpath(path)), "model": scene["contact"]["model"],
            "dt": scene["run"]["dt"], "e": e, "start": start, "since": since,
            "peak_t": times, "peak_h": highest, "slope": slope}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--t0", type=float, default=10.0)
    ap.add_argument("--out", default=".")
    args = ap.parse_args()
    runs = [read_run(r, args.t0) for r in args.runs]

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.4))
    for r in runs:
        e, s, k = r["e"], r["start"], r["model"]
        t = e["time"][s:]
        line, = ax[0].semilogy(t, (e["translational"] + e["rotational"])[s:], label=f"{k} kinetic")
        ax[0].semilogy(t, r["since"]["wall_work"][s:], ls="--", color=line.get_color(),
                       label=f"{k} wall work")
        ax[0].semilogy(t, r["since"]["dissipated"][s:], ls=":", color=line.get_color())
        ax[1].plot(r["peak_t"], r["peak_h"], label=k)
        if np.nanmax(np.abs(e["relaxation"])) > 0:
            ax[2].plot(t, r["since"]["dissipated"][s:], label=f"{k}: heat")
            ax[2].plot(t, e["relaxation"][s:], label=f"{k}: relaxation energy w_R")
    ax[0].set(xlabel="t [tau]", ylabel="energy [m sigma^2/tau^2]",
              title="kinetic (solid), wall work (dashed), dissipated (dotted)")
    ax[0].legend(fontsize=7, ncol=2)
    ax[1].set(xlabel="t [tau]", ylabel="highest column [sigma]", title="the highest jet")
    ax[1].legend(fontsize=8)
    ax[2].set(xlabel="t [tau]", ylabel="energy [m sigma^2/tau^2]",
              title="thermodynamic model: heat and relaxation energy")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    fig.savefig(os.path.join(args.out, "basin_models.png"), dpi=110)

    header = ["model", "dt", "W", "D/W", "kinetic_end", "residual/W", "jet_at_10.25", "t_jet_100",
              "escaped", "A_kinetic_slope", "A_total_slope", "A_total_fraction",
              "B_kinetic_slope", "B_total_slope", "B_total_fraction"]
    rows = []
    for r in runs:
        e, since = r["e"], r["since"]
        w = since["wall_work"][-1]
        # The jet before the domain's top clips it: its height at t0 + 0.25, and when it first
        # reaches 100 sigma.
        jet_then = np.interp(args.t0 + 0.25, r["peak_t"], r["peak_h"])
        high = np.nonzero(r["peak_h"] >= 100.0)[0]
        t_100 = r["peak_t"][high[0]] if len(high) else np.nan
        sl = r["slope"]
        rows.append([r["model"], r["dt"], w, since["dissipated"][-1] / w,
                     (e["translational"] + e["rotational"])[-1], since["balance"][-1] / w,
                     jet_then, t_100, e["escaped"][-1],
                     sl[("kinetic", "A")][0], sl[("total", "A")][0], sl[("total", "A")][1],
                     sl[("kinetic", "B")][0], sl[("total", "B")][0], sl[("total", "B")][1]])
    with open(os.path.join(args.out, "basin_models.csv"), "w", newline="") as f:
        csv.writer(f).writerows([header] + rows)
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(c if isinstance(c, str) else f"{c:.4g}" for c in row) + " |")


if __name__ == "__main__":
    main()
