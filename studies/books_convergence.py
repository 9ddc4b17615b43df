#!/usr/bin/python3
"""Convergence of the energy books with the time step, from runs of one scene at several dt.

usage: books_convergence.py RUN1 RUN2 [RUN3 ...] [--from T] [--out DIR]

Each RUN is a run folder of the same scene (and the same start, e.g. branched with
`yuxi run SCENE --from CHECKPOINT`) at another time step. From each it reads
  RUN/scene.resolved.toml   [run] dt [tau]; [basin.excitation] t0 [tau] (the default start)
  RUN/energies.csv          time, balance, wall_work (one row per energy interval;
                            energies in the scene's units, m sigma^2/tau^2 for the basin)
The books' residual over the window is
  res(t) = balance(t) - balance(t_start),   W(t) = wall_work(t) - wall_work(t_start)
with t_start the first row at or after t0 (or --from T). For each run: res at the last time
all runs share, over W there (the residual fraction at the end), and the largest |res(t)| over
the window over the same W. Where no wall does work (W = 0), the fractions are of the largest
|balance| instead. The observed order of convergence between successive time steps is
  p = ln(|f1| / |f2|) / ln(dt1 / dt2)       (log2 of the ratio when dt halves)
of both fractions; velocity Verlet's books should converge at p = 2 (or 1 where a
non-smooth event, a contact opening or closing within a step, dominates).

Writes into DIR (default: the current folder):
  books_convergence.csv   run,dt,t_start,t_end,wall_work,residual_end,fraction_end,
                          max_residual,fraction_max,order_end,order_max
                          (order_*: against the previous, larger dt; empty for the first)
  books_convergence.png   residual fraction res(t)/W(t) against time for each dt, and both
                          fractions against dt on log-log axes with slope-1 and slope-2 guides
and prints the table as Markdown.
"""
import argparse
import math
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

try:
    import tomllib  # Python >= 3.11
except ImportError:  # pragma: no cover
    tomllib = None


def fail(msg):
    sys.exit(f"books_convergence: {msg}")


def read_run(run):
    """(dt, t0 or None, {column: array}) of one run folder."""
    scene_path = os.path.join(run, "scene.resolved.toml")
    if tomllib is None or not os.path.exists(scene_path):
        fail(f"{run}: no scene.resolved.toml (or no tomllib)")
    with open(scene_path, "rb") as f:
        scene = tomllib.load(f)
    dt = scene.get("run", {}).get("dt")
    if dt is None:
        fail(f"{scene_path}: no [run] dt")
    t0 = scene.get("basin", {}).get("excitation", {}).get("t0")
    if t0 is None and "basin" in scene:
        t0 = 10.0  # the documented default of [basin.excitation] t0
    path = os.path.join(run, "energies.csv")
    try:
        data = np.genfromtxt(path, delimiter=",", names=True, dtype=float, encoding="utf-8")
    except (OSError, ValueError) as e:
        fail(f"cannot read {path}: {e}")
    cols = {n: np.atleast_1d(data[n]) for n in data.dtype.names}
    for need in ("time", "balance", "wall_work"):
        if need not in cols:
            fail(f"{path}: no column {need}")
    return float(dt), t0, cols


def order(f1, f2, dt1, dt2):
    """Observed order between two runs: ln(|f1|/|f2|) / ln(dt1/dt2); nan if undefined."""
    if not all(math.isfinite(v) and v != 0 for v in (f1, f2)) or dt1 == dt2:
        return math.nan
    return math.log(abs(f1) / abs(f2)) / math.log(dt1 / dt2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="run folders of one scene at different dt")
    ap.add_argument("--from", dest="t_from", type=float,
                    help="start of the window [tau] (default: the excitation's t0)")
    ap.add_argument("--out", default=".", help="folder for the CSV and the PNG (default .)")
    args = ap.parse_args()
    if len(args.runs) < 2:
        fail("give at least two runs")
    runs = []
    for r in args.runs:
        dt, t0, cols = read_run(r)
        start = args.t_from if args.t_from is not None else t0
        if start is None:
            fail(f"{r}: no [basin.excitation] t0; give --from T")
        runs.append({"run": r, "dt": dt, "start": float(start), "e": cols})
    runs.sort(key=lambda x: -x["dt"])
    t_end = min(float(x["e"]["time"][-1]) for x in runs)

    for x in runs:
        t = x["e"]["time"]
        tol = 1e-6 * max(1.0, abs(x["start"]))
        i0 = np.flatnonzero(t >= x["start"] - tol)
        i1 = np.flatnonzero(t <= t_end + tol)
        if i0.size == 0 or i1.size == 0 or i1[-1] < i0[0]:
            fail(f"{x['run']}: no rows between {x['start']:g} and {t_end:g}")
        w = np.arange(i0[0], i1[-1] + 1)
        b, ww = x["e"]["balance"], x["e"]["wall_work"]
        res = b[w] - b[w[0]]
        work = ww[w] - ww[w[0]]
        scale = work[-1]
        x["scale_what"] = "wall work since t_start"
        if not (abs(scale) > 0):
            scale = float(np.max(np.abs(b[w]))) or 1.0
            x["scale_what"] = "largest |balance|"
        x.update(t=t[w], res=res, work=work, scale=float(scale), t_start=float(t[w[0]]),
                 t_last=float(t[w[-1]]), res_end=float(res[-1]),
                 res_max=float(np.max(np.abs(res))))
        x["f_end"] = x["res_end"] / x["scale"]
        x["f_max"] = x["res_max"] / x["scale"]
    for k, x in enumerate(runs):
        if k == 0:
            x["p_end"] = x["p_max"] = math.nan
        else:
            y = runs[k - 1]
            x["p_end"] = order(y["f_end"], x["f_end"], y["dt"], x["dt"])
            x["p_max"] = order(y["f_max"], x["f_max"], y["dt"], x["dt"])

    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "books_convergence.csv")
    with open(csv_path, "w", encoding="utf-8") as f:
        f.write("run,dt,t_start,t_end,wall_work,residual_end,fraction_end,max_residual,"
                "fraction_max,order_end,order_max\n")
        for x in runs:
            vals = [x["dt"], x["t_start"], x["t_last"], x["scale"], x["res_end"], x["f_end"],
                    x["res_max"], x["f_max"], x["p_end"], x["p_max"]]
            f.write(x["run"].replace(",", "_") + "," + ",".join(
                "" if not math.isfinite(v) else f"{v:.10g}" for v in vals) + "\n")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5))
    for x in runs:
        ok = np.abs(x["work"]) > 1e-3 * abs(x["scale"])  # W(t) ~ 0 at the very start
        frac = np.where(ok, x["res"] / np.where(ok, x["work"], 1.0), np.nan)
        if x["scale_what"] != "wall work since t_start":
            frac = x["res"] / x["scale"]
        ax1.plot(x["t"], frac, lw=1.2, label=f"dt = {x['dt']:g}")
    ax1.axhline(0, color="grey", lw=0.6)
    ax1.set_xlabel("time [tau]")
    ax1.set_ylabel("(balance(t) - balance(t_start)) / W(t)")
    ax1.set_title(f"Residual of the energy books from t_start = {runs[0]['t_start']:g}",
                  fontsize=10)
    ax1.grid(True, alpha=0.3)
    ax1.legend(fontsize=8)
    dts = np.array([x["dt"] for x in runs])
    for key, lab, mk in (("f_end", f"|residual| at t = {t_end:g} / W", "o"),
                         ("f_max", "max |residual| / W(end)", "s")):
        v = np.abs([x[key] for x in runs])
        ax2.loglog(dts, np.where(v > 0, v, np.nan), mk + "-", label=lab)
    ref = np.abs([x["f_max"] for x in runs])
    if ref[0] > 0:
        for p, ls in ((1, ":"), (2, "--")):
            ax2.loglog(dts, ref[0] * (dts / dts[0]) ** p, ls, color="grey",
                       label=f"slope {p}")
    ax2.set_xlabel("time step dt [tau]")
    ax2.set_ylabel("residual / wall work")
    ax2.set_title("Convergence with the time step", fontsize=10)
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    png_path = os.path.join(args.out, "books_convergence.png")
    fig.savefig(png_path, dpi=120)
    plt.close(fig)

    def g(v, d=4):
        return f"{v:.{d}g}" if math.isfinite(v) else "—"

    print(f"Energy books from t_start = {runs[0]['t_start']:g} to t = {t_end:g} tau; fractions "
          f"of the {runs[0]['scale_what']} ({g(runs[0]['scale'])} for the first run).")
    print()
    print("| dt [tau] | residual at the end | fraction at the end | max |residual| | "
          "max fraction | order (end) | order (max) |")
    print("|---|---|---|---|---|---|---|")
    for x in runs:
        print(f"| {x['dt']:g} | {g(x['res_end'])} | {g(x['f_end'], 3)} | {g(x['res_max'])} | "
              f"{g(x['f_max'], 3)} | {g(x['p_end'], 3)} | {g(x['p_max'], 3)} |")
    print(f"\nwrote {csv_path} and {png_path}", file=sys.stderr)


if __name__ == "__main__":
    main()
