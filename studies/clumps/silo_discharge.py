#!/usr/bin/python3
"""Discharge of rods and of spheres of the same volume from one silo (scenes/clumps/).

usage: silo_discharge.py RODS_RUN SPHERES_RUN [--open T] [--out DIR] [--tag NAME]
                         [--orifice D_O]

Each RUN is a run folder of scenes/clumps/silo-rods*.toml or silo-spheres*.toml. From each it
reads
  RUN/energies.csv           time, grains (those still in the domain), escaped,
                             balance, dissipated (the books)
  RUN/particles.lammpstrj    the members' positions (the LAMMPS dump, every snapshot)
  RUN/scene.resolved.toml    [run] dt (the dump's steps into times)
The shutter opens at T (default 10). The discharge rate W [grains per time] is the slope of a
straight line fitted to the escaped count between 5 % and 20 % of the grains gone (the flow
once started, well before the bed runs low); its uncertainty is the slope's standard error.
Also: the fraction discharged at the end, and the longest pause with no grain leaving while
grains were left (a clog, where an arch over the orifice holds). The books' error is
|balance(t_end) - balance(0)| over the energy dissipated.

Writes into DIR (default: the current folder), NAME (default "silo") naming the files:
  NAME_discharge.csv    run,grains,rate,rate_error,t_5,t_20,discharged,longest_pause,books_error
  NAME_discharge.png    grains left against time after opening, both runs, with the fits
  NAME_rods_side.png    a side view (a slab |y| < 1) of the rods' members at the start and at
                        the first snapshot 5 time units after opening
and prints the table as Markdown.
"""
import argparse
import os
import sys

import tomllib

import numpy as np
import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402


def fail(msg):
    sys.exit(f"silo_discharge: {msg}")


def read_energies(run):
    path = os.path.join(run, "energies.csv")
    try:
        data = np.genfromtxt(path, delimiter=",", names=True, dtype=float, encoding="utf-8")
    except (OSError, ValueError) as e:
        fail(f"cannot read {path}: {e}")
    cols = {n: np.atleast_1d(data[n]) for n in data.dtype.names}
    for need in ("time", "grains", "escaped", "balance", "dissipated"):
        if need not in cols:
            fail(f"{path}: no column {need}")
    return cols


def rate(e, t_open):
    """(slope, its standard error, t at 5 %, t at 20 %, intercept) of escaped(t)."""
    n0 = e["grains"][0] + e["escaped"][0]
    after = e["time"] >= t_open
    t, gone = e["time"][after], e["escaped"][after] / n0
    window = (gone >= 0.05) & (gone <= 0.2)
    if window.sum() < 3:
        fail("fewer than three rows between 5 % and 20 % discharged: run longer")
    tw, yw = t[window], e["escaped"][after][window]
    (slope, intercept), cov = np.polyfit(tw, yw, 1, cov=True)
    return float(slope), float(np.sqrt(cov[0, 0])), float(tw[0]), float(tw[-1]), intercept


def longest_pause(e, t_open):
    """The longest time with no grain leaving after the first left, while grains were left."""
    after = (e["time"] >= t_open) & (e["grains"] > 0)
    t, gone = e["time"][after], e["escaped"][after]
    moves = t[np.flatnonzero(np.diff(gone) > 0) + 1]
    if moves.size == 0:
        return float(t[-1] - t[0]) if t.size else 0.0
    ends = np.append(moves, t[-1])
    return float(np.max(np.diff(ends)))


def read_frames(path):
    """[(timestep, array of (x, z, radius))] of a LAMMPS dump."""
    frames = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: TIMESTEP"):
            step = int(lines[k + 1])
            n = int(lines[k + 3])
            header = lines[k + 8].split()[2:]
            ix, iy, iz, ir = (header.index(c) for c in ("x", "y", "z", "radius"))
            rows = np.array([lines[k + 9 + j].split() for j in range(n)], dtype=float)
            if n == 0:
                rows = np.zeros((0, len(header)))
            frames.append((step, rows[:, [ix, iy, iz, ir]]))
            k += 9 + n
        else:
            k += 1
    return frames


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rods")
    ap.add_argument("spheres")
    ap.add_argument("--open", dest="t_open", type=float, default=10.0)
    ap.add_argument("--out", default=".")
    ap.add_argument("--tag", default="silo")
    ap.add_argument("--orifice", type=float, default=5.0, help="D_o, for the side view")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for label, run, colour in (("rods (aspect 2.4)", args.rods, "C3"),
                               ("spheres, same volume", args.spheres, "C0")):
        e = read_energies(run)
        w, dw, t20, t70, b = rate(e, args.t_open)
        books = abs(e["balance"][-1] - e["balance"][0]) / e["dissipated"][-1]
        n0 = int(e["grains"][0] + e["escaped"][0])
        done = float(e["escaped"][-1]) / n0
        rows.append((os.path.basename(os.path.normpath(run)), n0, w, dw, t20, t70, done,
                     longest_pause(e, args.t_open), books))
        ax.plot(e["time"] - args.t_open, e["grains"], color=colour, label=f"{label}: "
                f"W = {w:.1f} ± {dw:.1f} grains/τ")
        tt = np.array([t20, t70])
        ax.plot(tt - args.t_open, n0 - (w * tt + b), "k--", lw=0.8)
    ax.axvline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("time since the shutter opened [τ]")
    ax.set_ylabel("grains in the silo")
    ax.set_title(f"Silo D = 16 d ({args.tag}): rods against spheres of their volume")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, f"{args.tag}_discharge.png"), dpi=130)
    plt.close(fig)

    with open(os.path.join(args.out, f"{args.tag}_discharge.csv"), "w", encoding="utf-8") as f:
        f.write("run,grains,rate,rate_error,t_5,t_20,discharged,longest_pause,books_error\n")
        for r in rows:
            f.write(f"{r[0]},{r[1]},{r[2]:.4g},{r[3]:.2g},{r[4]:.4g},{r[5]:.4g},{r[6]:.4f},"
                    f"{r[7]:.4g},{r[8]:.3g}\n")
    print("| run | grains | W [grains/τ] (5-20 %) | discharged at the end | longest pause [τ] "
          "| books |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]:.2f} ± {r[3]:.2f} | {100 * r[6]:.1f} % | {r[7]:.3g} | "
              f"{r[8]:.2g} |")

    frames = read_frames(os.path.join(args.rods, "particles.lammpstrj"))
    if frames:
        with open(os.path.join(args.rods, "scene.resolved.toml"), "rb") as f:
            dt = float(tomllib.load(f)["run"]["dt"])
        pick = [frames[0]]
        later = [fr for fr in frames if fr[0] * dt >= args.t_open + 5.0 - 1e-9]
        if later:
            pick.append(later[0])
        fig, axes = plt.subplots(1, len(pick), figsize=(4.0 * len(pick), 5.5), sharey=True)
        axes = np.atleast_1d(axes)
        for a, (step, m) in zip(axes, pick):
            slab = np.abs(m[:, 1]) < 1.0
            for x, z, r in m[slab][:, [0, 2, 3]]:
                a.add_patch(plt.Circle((x, z), r, color="C3", alpha=0.6, lw=0))
            a.plot([-8, -8], [0, 32], "k-", [8, 8], [0, 32], "k-", lw=1)
            h = args.orifice / 2
            a.plot([-8, -h], [0, 0], "k-", [h, 8], [0, 0], "k-", lw=1)
            a.set_xlim(-9, 9)
            a.set_ylim(-4, 32)
            a.set_aspect("equal")
            a.set_title(f"t = {step * dt:g} τ")
            a.set_xlabel("x [d]")
        axes[0].set_ylabel("z [d]")
        fig.suptitle("Rods' members, slab |y| < 1 d")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, f"{args.tag}_rods_side.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    main()
