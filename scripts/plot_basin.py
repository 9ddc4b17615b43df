#!/usr/bin/python3
"""Plots a fish-basin run like the figures of Li & Cai (2008) and writes report.md.

usage: plot_basin.py RUN_DIR [--out DIR] [--surface-time T] [--velocity-time T]

Reads from RUN_DIR (every file is optional; a figure whose data are missing is skipped with a
message, and the report says so):
  energies.csv                   step,time,translational,rotational,elastic,gravitational,
                                 mechanical,...  (one row per energy interval)
  scene.toml or scene.resolved.toml   the scene the run used, printed in the report
  analysis/surface_t<T>.csv      x,y,height         free surface per column (nan: empty)
  analysis/velocity_t<T>.csv     s,z,vs,vz,vn       grains in the vertical plane through two
                                                    opposite antinodes
  analysis/elastic_map_t<T>.csv  x,y,<name>         elastic energy summed over z per column
  analysis/period_sections.csv   section,z0,z1,x,y,grains,elastic,kinetic
                                                    horizontal sections, averaged over the
                                                    first excitation period
  analysis/pdf_kinetic.csv, pdf_elastic.csv, pdf_total.csv
                                 e_lo,e_hi,e_center,count,density,energy   (log bins)
  analysis/fits.csv              quantity,range,e_lo,e_hi,slope,intercept,slope_error,bins,
                                 energy_fraction,e_lo_used,e_hi_used
Grids are long CSV (one row per cell, x fastest); <T> is the time in tau, e.g. 10.25.

Writes into DIR (default RUN_DIR): fig4_energies.png, fig5_surface.png, fig6_contours.png,
fig7_velocity.png, fig8_elastic_maps.png, fig9_sections.png, fig10_pdf.png, report.md.
Units are the scene's: the basin scenes use sigma (mean grain radius), m (mean grain mass) and
tau (g = 1 sigma/tau^2), so energies are in m sigma^2/tau^2.
"""
import argparse
import csv
import glob
import math
import os
import re
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

try:
    import tomllib  # Python >= 3.11
except ImportError:  # pragma: no cover
    tomllib = None

# Slopes and energy fractions Li & Cai (2008) report for Fig. 10 (None: not given).
PAPER_RANGES = {"A": (0.2, 2.0), "B": (10.0, 1e4)}
PAPER_SLOPES = {("kinetic", "A"): -2.691, ("total", "A"): -2.782, ("elastic", "A"): None,
                ("kinetic", "B"): -0.771, ("elastic", "B"): -0.813, ("total", "B"): -0.776}
PAPER_FRACTION = {"A": "about 40 %", "B": "about 4 %"}
QUANTITIES = [("kinetic", "E_k"), ("elastic", "E_s"), ("total", "E_k + E_s")]

UNIT_E = "m sigma^2 / tau^2"


def note(msg):
    print(f"plot_basin: {msg}", file=sys.stderr)


# --------------------------------------------------------------------------------------------
# Reading

def read_table(path):
    """A numeric CSV with a header line as {column: 1-D float array}; None if unreadable."""
    try:
        data = np.genfromtxt(path, delimiter=",", names=True, dtype=float, encoding="utf-8")
    except (OSError, ValueError) as e:
        note(f"cannot read {path}: {e}")
        return None
    if data.dtype.names is None:
        return None
    return {name: np.atleast_1d(data[name]) for name in data.dtype.names}


def read_grid(path):
    """A long grid CSV (x, y, values...) as (x centres, y centres, {name: (ny, nx) array})."""
    t = read_table(path)
    if t is None or "x" not in t or "y" not in t or len(t["x"]) == 0:
        return None
    xs, ys = np.unique(t["x"]), np.unique(t["y"])
    i, j = np.searchsorted(xs, t["x"]), np.searchsorted(ys, t["y"])
    fields = {}
    for name, values in t.items():
        if name in ("x", "y"):
            continue
        g = np.full((len(ys), len(xs)), np.nan)
        g[j, i] = values
        fields[name] = g
    return xs, ys, fields


def timed_files(folder, stem):
    """[(time, path)] of folder/<stem>_t<time>.csv, sorted by time."""
    out = []
    for p in glob.glob(os.path.join(folder, f"{stem}_t*.csv")):
        m = re.search(r"_t([-+0-9.eE]+)\.csv$", os.path.basename(p))
        if m and os.path.basename(p).startswith(stem + "_t"):
            try:
                out.append((float(m.group(1)), p))
            except ValueError:
                pass
    return sorted(out)


def closest(files, t):
    return min(files, key=lambda f: abs(f[0] - t)) if files else None


def spread(items, n):
    """At most n items, evenly spaced, first and last kept."""
    if len(items) <= n:
        return items
    idx = np.unique(np.round(np.linspace(0, len(items) - 1, n)).astype(int))
    return [items[k] for k in idx]


def read_scene(run):
    """(path, parsed dict or None, raw text) of the run's scene file, or None."""
    for name in ("scene.toml", "scene.resolved.toml"):
        p = os.path.join(run, name)
        if os.path.exists(p):
            with open(p, encoding="utf-8") as f:
                text = f.read()
            parsed = None
            if tomllib is not None:
                try:
                    parsed = tomllib.loads(text)
                except tomllib.TOMLDecodeError as e:
                    note(f"{p}: {e}")
            return p, parsed, text
    return None


def flatten(d, prefix=""):
    """Leaf keys of a TOML document as [(dotted.key, value)]; arrays of tables indexed from 1,
    as the scene reader's messages number them (the first [[contact.pair]] is contact.pair[1])."""
    rows = []
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            rows += flatten(v, key + ".")
        elif isinstance(v, list) and v and all(isinstance(e, dict) for e in v):
            for n, e in enumerate(v, start=1):
                rows += flatten(e, f"{key}[{n}].")
        else:
            rows.append((key, v))
    return rows


def lookup(d, *keys):
    for k in keys:
        if not isinstance(d, dict) or k not in d:
            return None
        d = d[k]
    return d


def grid_extent(xs, ys):
    dx = xs[1] - xs[0] if len(xs) > 1 else 1.0
    dy = ys[1] - ys[0] if len(ys) > 1 else 1.0
    return [xs[0] - dx / 2, xs[-1] + dx / 2, ys[0] - dy / 2, ys[-1] + dy / 2]


def positive_norm(arrays, decades=4.0):
    """A LogNorm over the positive values of the arrays, spanning at most `decades`."""
    vals = np.concatenate([a[np.isfinite(a) & (a > 0)].ravel() for a in arrays])
    if vals.size == 0:
        return None
    vmax = vals.max()
    vmin = max(vals.min(), vmax * 10.0 ** (-decades))
    return LogNorm(vmin=vmin, vmax=vmax if vmax > vmin else vmin * 10)


def panel_grid(n):
    cols = min(n, 4 if n > 6 else 3 if n > 4 else n)
    rows = math.ceil(n / cols)
    return rows, cols


# --------------------------------------------------------------------------------------------
# Figures: each returns (file name, caption) or raises Skip with the reason.

class Skip(Exception):
    pass


def fig4_energies(run, out, t0):
    path = os.path.join(run, "energies.csv")
    if not os.path.exists(path):
        raise Skip("no energies.csv")
    t = read_table(path)
    if t is None or "time" not in t or len(t["time"]) == 0:
        raise Skip("energies.csv has no rows")
    time = t["time"]
    fig, ax = plt.subplots(figsize=(8, 5.5))

    def positive(v):
        return np.where(v > 0, v, np.nan)  # log axis: non-positive values left out

    for key, label in [("translational", "translational kinetic"),
                       ("rotational", "rotational kinetic"), ("elastic", "elastic")]:
        if key in t:
            ax.plot(time, positive(t[key]), label=label, lw=1.0)
    # Gravitational energy is sum m g z, zero at z = 0; it is plotted as it is when positive
    # throughout, otherwise shifted by a constant C so its minimum is 1 % of its range (and the
    # total mechanical energy by the same C).
    shift, how = 0.0, "zero at z = 0"
    if "gravitational" in t:
        g = t["gravitational"]
        if np.nanmin(g) <= 0:
            span = np.nanmax(g) - np.nanmin(g)
            shift = -np.nanmin(g) + 0.01 * (span if span > 0 else 1.0)
            how = f"+ C, C = {shift:.6g} so that it stays positive"
        ax.plot(time, positive(g + shift), label=f"gravitational ({how})", lw=1.0)
    if "mechanical" in t:
        label = "total mechanical" + (" + C" if shift else "")
        ax.plot(time, positive(t["mechanical"] + shift), label=label, lw=1.8, color="k")
    if t0 is not None and time.min() < t0 < time.max():
        ax.axvline(t0, color="grey", ls="--", lw=0.8, label=f"excitation starts (t0 = {t0:g})")
    ax.set_yscale("log")
    ax.set_xlabel("time [tau]")
    ax.set_ylabel(f"energy [{UNIT_E}]")
    ax.set_title("Energies of the grains (cf. Li & Cai 2008, Fig. 4)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig4_energies.png"), dpi=120)
    plt.close(fig)
    return ("fig4_energies.png",
            "Translational, rotational, elastic, gravitational and total mechanical energy "
            f"against time (log scale); gravitational energy {how}.")


def fig5_surface(analysis, out, t_want):
    files = timed_files(analysis, "surface")
    if not files:
        raise Skip("no analysis/surface_t*.csv")
    t, path = closest(files, t_want)
    g = read_grid(path)
    if g is None or "height" not in g[2]:
        raise Skip(f"{path}: no height column")
    xs, ys, f = g
    h = f["height"]
    X, Y = np.meshgrid(xs, ys)
    fig = plt.figure(figsize=(8, 6.5))
    ax = fig.add_subplot(projection="3d")
    finite = np.isfinite(h)
    if not finite.any():
        plt.close(fig)
        raise Skip(f"{path}: every column is empty")
    norm = plt.Normalize(np.nanmin(h), np.nanmax(h))
    # Empty columns (outside the basin) stay NaN and are not drawn.
    ax.plot_surface(X, Y, np.ma.masked_invalid(h), cmap="viridis", norm=norm,
                    rstride=1, cstride=1, linewidth=0, antialiased=False)
    ax.set_xlabel("x [sigma]")
    ax.set_ylabel("y [sigma]")
    ax.set_zlabel("height [sigma]")
    ax.set_title(f"Free surface at t = {t:g} tau (cf. Li & Cai 2008, Fig. 5)")
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=ax, shrink=0.6,
                 label="height of the highest grain top [sigma]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig5_surface.png"), dpi=120)
    plt.close(fig)
    extra = "" if abs(t - t_want) < 1e-9 else f" (closest to the paper's t = {t_want:g})"
    return ("fig5_surface.png",
            f"Free surface (height of the highest grain top over each column) at t = {t:g} tau"
            f"{extra}; empty columns are not drawn.")


def fig6_contours(analysis, out, max_panels=9):
    files = timed_files(analysis, "surface")
    if not files:
        raise Skip("no analysis/surface_t*.csv")
    grids = []
    for t, p in spread(files, max_panels):
        g = read_grid(p)
        if g is not None and "height" in g[2]:
            grids.append((t, g))
    if not grids:
        raise Skip("no readable surface files")
    heights = np.concatenate([g[2]["height"].ravel() for _, g in grids])
    heights = heights[np.isfinite(heights)]
    if heights.size == 0:
        raise Skip("every surface is empty")
    levels = np.linspace(heights.min(), heights.max(), 16)
    if levels[0] == levels[-1]:
        levels = np.linspace(levels[0] - 1, levels[0] + 1, 16)
    rows, cols = panel_grid(len(grids))
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.4 * rows), squeeze=False)
    cs = None
    for ax, (t, (xs, ys, f)) in zip(axes.flat, grids):
        cs = ax.contourf(xs, ys, np.ma.masked_invalid(f["height"]), levels=levels,
                         cmap="viridis")
        ax.set_title(f"t = {t:g} tau", fontsize=9)
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(grids):]:
        ax.axis("off")
    fig.colorbar(cs, ax=axes, shrink=0.8, label="surface height [sigma]")
    fig.suptitle("Free surface, contours (cf. Li & Cai 2008, Fig. 6)")
    fig.savefig(os.path.join(out, "fig6_contours.png"), dpi=120)
    plt.close(fig)
    return ("fig6_contours.png",
            "Contour maps of the free surface at " + ", ".join(f"{t:g}" for t, _ in grids)
            + " tau (x, y in sigma).")


def fig7_velocity(analysis, out, t_want):
    files = timed_files(analysis, "velocity")
    if not files:
        raise Skip("no analysis/velocity_t*.csv")
    t, path = closest(files, t_want)
    v = read_table(path)
    if v is None or not all(k in v for k in ("s", "z", "vs", "vz")) or len(v["s"]) == 0:
        raise Skip(f"{path}: no grains")
    speed = np.hypot(v["vs"], v["vz"])
    fig, ax = plt.subplots(figsize=(10, 4.5))
    q = ax.quiver(v["s"], v["z"], v["vs"], v["vz"], speed, cmap="plasma", angles="xy",
                  scale_units="xy", pivot="tail", width=0.0015)
    ref = float(np.nanpercentile(speed, 90)) if np.isfinite(speed).any() else 1.0
    ax.quiverkey(q, 0.82, -0.16, ref if ref > 0 else 1.0, f"{ref:.3g} sigma/tau",
                 labelpos="E", coordinates="axes")
    fig.colorbar(q, ax=ax, label="in-plane speed [sigma / tau]")
    ax.set_aspect("equal")
    ax.set_xlabel("s: position along the plane through two opposite antinodes [sigma]")
    ax.set_ylabel("z [sigma]")
    ax.set_title(f"Grain velocities in the vertical plane, t = {t:g} tau "
                 "(cf. Li & Cai 2008, Fig. 7)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig7_velocity.png"), dpi=120)
    plt.close(fig)
    return ("fig7_velocity.png",
            f"In-plane velocities of the {len(v['s'])} grains within the slice through two "
            f"opposite excitation points at t = {t:g} tau.")


def fig8_elastic_maps(analysis, out, max_panels=12):
    files = timed_files(analysis, "elastic_map")
    if not files:
        raise Skip("no analysis/elastic_map_t*.csv")
    maps = []
    for t, p in spread(files, max_panels):
        g = read_grid(p)
        if g is not None and g[2]:
            xs, ys, f = g
            maps.append((t, xs, ys, next(iter(f.values()))))
    if not maps:
        raise Skip("no readable elastic maps")
    norm = positive_norm([m[3] for m in maps])
    if norm is None:
        raise Skip("the elastic maps hold no positive energy")
    rows, cols = panel_grid(len(maps))
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.4 * rows), squeeze=False)
    im = None
    for ax, (t, xs, ys, e) in zip(axes.flat, maps):
        im = ax.imshow(np.ma.masked_where(~(e > 0), e), origin="lower",
                       extent=grid_extent(xs, ys), norm=norm, cmap="inferno",
                       interpolation="nearest")
        ax.set_title(f"t = {t:g} tau", fontsize=9)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(maps):]:
        ax.axis("off")
    fig.colorbar(im, ax=axes, shrink=0.8, label=f"elastic energy per column [{UNIT_E}]")
    fig.suptitle("Elastic energy summed over z (cf. Li & Cai 2008, Fig. 8)")
    fig.savefig(os.path.join(out, "fig8_elastic_maps.png"), dpi=120)
    plt.close(fig)
    return ("fig8_elastic_maps.png",
            "Elastic energy summed over the height of each column at "
            + ", ".join(f"{m[0]:g}" for m in maps) + " tau (log colour scale).")


def fig9_sections(analysis, out):
    path = os.path.join(analysis, "period_sections.csv")
    if not os.path.exists(path):
        raise Skip("no analysis/period_sections.csv")
    t = read_table(path)
    need = ("section", "z0", "z1", "x", "y", "elastic", "kinetic")
    if t is None or not all(k in t for k in need) or len(t["x"]) == 0:
        raise Skip(f"{path}: missing columns or rows")
    sections = sorted(set(t["section"].astype(int)))[:4]
    panels = []
    for s in sections:
        sel = t["section"].astype(int) == s
        xs, ys = np.unique(t["x"][sel]), np.unique(t["y"][sel])
        i, j = np.searchsorted(xs, t["x"][sel]), np.searchsorted(ys, t["y"][sel])
        grids = {}
        for q in ("elastic", "kinetic"):
            g = np.full((len(ys), len(xs)), np.nan)
            g[j, i] = t[q][sel]
            grids[q] = g
        panels.append((s, t["z0"][sel][0], t["z1"][sel][0], xs, ys, grids))
    fig, axes = plt.subplots(len(panels), 2, figsize=(9, 4 * len(panels)), squeeze=False)
    for col, q in enumerate(("elastic", "kinetic")):
        norm = positive_norm([p[5][q] for p in panels])
        for row, (s, z0, z1, xs, ys, grids) in enumerate(panels):
            ax = axes[row][col]
            if norm is None:
                ax.text(0.5, 0.5, "no positive values", ha="center", transform=ax.transAxes)
                continue
            im = ax.imshow(np.ma.masked_where(~(grids[q] > 0), grids[q]), origin="lower",
                           extent=grid_extent(xs, ys), norm=norm, cmap="inferno",
                           interpolation="nearest")
            ax.set_title(f"{q}, {z0:g} <= z < {z1:g} sigma", fontsize=9)
            ax.tick_params(labelsize=7)
            fig.colorbar(im, ax=ax, shrink=0.8, label=f"[{UNIT_E}] per cell")
    fig.suptitle("Energies averaged over the first excitation period, horizontal sections\n"
                 "(cf. Li & Cai 2008, Fig. 9)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig9_sections.png"), dpi=120)
    plt.close(fig)
    return ("fig9_sections.png",
            "Elastic and kinetic energy of the grains in each cell of "
            + ", ".join(f"z in [{p[1]:g}, {p[2]:g})" for p in panels)
            + ", averaged over the first excitation period (log colour scale).")


def fit_from_pdf(pdf, lo, hi):
    """The fit of power_law.hpp redone from a pdf CSV: least squares of log10(density) against
    log10(e_center) over bins with centres in [lo, hi]. The energy fraction is of the binned
    energy only (the CSV does not hold the energy outside the bins)."""
    sel = (pdf["e_center"] >= lo) & (pdf["e_center"] <= hi) & (pdf["density"] > 0)
    n = int(sel.sum())
    res = {"bins": n, "slope": math.nan, "intercept": math.nan, "slope_error": math.nan,
           "energy_fraction": math.nan, "e_lo_used": math.nan, "e_hi_used": math.nan,
           "source": "pdf (binned energy only)"}
    if n == 0:
        return res
    total = np.nansum(pdf["energy"]) if "energy" in pdf else math.nan
    if total and "energy" in pdf:
        res["energy_fraction"] = float(pdf["energy"][sel].sum() / total)
    res["e_lo_used"], res["e_hi_used"] = float(pdf["e_lo"][sel][0]), float(pdf["e_hi"][sel][-1])
    if n < 2:
        return res
    x, y = np.log10(pdf["e_center"][sel]), np.log10(pdf["density"][sel])
    sxx = ((x - x.mean()) ** 2).sum()
    slope = ((x - x.mean()) * (y - y.mean())).sum() / sxx
    res["slope"], res["intercept"] = float(slope), float(y.mean() - slope * x.mean())
    if n >= 3:
        r = y - (res["intercept"] + slope * x)
        res["slope_error"] = float(math.sqrt((r ** 2).sum() / (n - 2) / sxx))
    return res


def read_fits(analysis, pdfs):
    """{(quantity, range): fit dict} from fits.csv, else computed from the pdf files."""
    fits = {}
    path = os.path.join(analysis, "fits.csv")
    if os.path.exists(path):
        with open(path, newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                try:
                    fit = {k: float(r[k]) for k in ("e_lo", "e_hi", "slope", "intercept",
                                                    "slope_error", "energy_fraction",
                                                    "e_lo_used", "e_hi_used")}
                    fit["bins"] = int(float(r["bins"]))
                except (KeyError, ValueError) as e:
                    note(f"{path}: bad row {r}: {e}")
                    continue
                fit["source"] = "fits.csv"
                fits[(r["quantity"], r["range"])] = fit
    else:
        note("no analysis/fits.csv: fitting the densities here")
        for q, pdf in pdfs.items():
            for rng, (lo, hi) in PAPER_RANGES.items():
                fit = fit_from_pdf(pdf, lo, hi)
                fit["e_lo"], fit["e_hi"] = lo, hi
                fits[(q, rng)] = fit
    return fits


def read_pdfs(analysis):
    pdfs = {}
    for q, _ in QUANTITIES:
        p = os.path.join(analysis, f"pdf_{q}.csv")
        if os.path.exists(p):
            t = read_table(p)
            if t is not None and all(k in t for k in ("e_lo", "e_hi", "e_center", "density")):
                pdfs[q] = t
    return pdfs


def fig10_pdf(out, pdfs, fits):
    if not pdfs:
        raise Skip("no analysis/pdf_kinetic.csv, pdf_elastic.csv or pdf_total.csv")
    fig, ax = plt.subplots(figsize=(8, 6))
    colours = {"kinetic": "tab:blue", "elastic": "tab:orange", "total": "tab:green"}
    markers = {"kinetic": "o", "elastic": "s", "total": "^"}
    for rng, (lo, hi) in PAPER_RANGES.items():
        ax.axvspan(lo, hi, color="grey", alpha=0.08)
        ax.text(math.sqrt(lo * hi), 0.98, rng, transform=ax.get_xaxis_transform(),
                ha="center", va="top", fontsize=10, color="grey")
    lines = []
    for q, label in QUANTITIES:
        if q not in pdfs:
            continue
        pdf = pdfs[q]
        ax.loglog(pdf["e_center"], pdf["density"], markers[q], ms=3.5, color=colours[q],
                  label=label, alpha=0.8)
        for rng in PAPER_RANGES:
            fit = fits.get((q, rng))
            if fit is None or not math.isfinite(fit["slope"]):
                continue
            e = np.geomspace(fit["e_lo_used"], fit["e_hi_used"], 20)
            ax.loglog(e, 10 ** fit["intercept"] * e ** fit["slope"], "-", color=colours[q],
                      lw=1.5)
            err = f" ± {fit['slope_error']:.3f}" if math.isfinite(fit["slope_error"]) else ""
            lines.append(f"{label}, {rng}: slope {fit['slope']:.3f}{err}")
    if lines:
        ax.text(0.02, 0.02, "\n".join(lines), transform=ax.transAxes, fontsize=8,
                va="bottom", ha="left", family="monospace",
                bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))
    ax.set_xlabel(f"energy per grain [{UNIT_E}]")
    ax.set_ylabel("probability density")
    ax.set_title("Per-grain energies over the first excitation period (cf. Li & Cai 2008, "
                 "Fig. 10)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig10_pdf.png"), dpi=120)
    plt.close(fig)
    return ("fig10_pdf.png",
            "Probability densities of the per-grain kinetic energy E_k, elastic energy E_s and "
            "E_k + E_s (logarithmic bins), with least-squares power laws over the ranges "
            "A = [0.2, 2] and B = [10, 1e4] (shaded).")


# --------------------------------------------------------------------------------------------
# Report

def fmt(v, digits=4):
    if isinstance(v, float):
        return f"{v:.{digits}g}" if math.isfinite(v) else "—"
    return str(v)


def slope_table(fits):
    rows = ["| quantity | range | fitted slope | ± s.e. | bins | bins cover | energy fraction "
            "| paper slope | paper fraction |",
            "|---|---|---|---|---|---|---|---|---|"]
    for rng in PAPER_RANGES:
        for q, label in QUANTITIES:
            fit = fits.get((q, rng))
            paper = PAPER_SLOPES.get((q, rng))
            paper_s = f"{paper:.3f}" if paper is not None else "—"
            paper_f = PAPER_FRACTION[rng] if q == "kinetic" else "—"
            if fit is None:
                rows.append(f"| {label} | {rng} | — | — | — | — | — | {paper_s} | {paper_f} |")
                continue
            frac = fit["energy_fraction"]
            frac_s = f"{100 * frac:.1f} %" if math.isfinite(frac) else "—"
            cover = (f"[{fmt(fit['e_lo_used'], 3)}, {fmt(fit['e_hi_used'], 3)}]"
                     if math.isfinite(fit["e_lo_used"]) else "—")
            rows.append(f"| {label} | {rng} | {fmt(fit['slope'], 4)} | "
                        f"{fmt(fit['slope_error'], 2)} | {fit['bins']} | {cover} | {frac_s} | "
                        f"{paper_s} | {paper_f} |")
    return "\n".join(rows)


def write_report(run, out, scene, energies, made, skipped, fits):
    lines = [f"# Fish-basin run: {os.path.abspath(run)}", ""]
    lines += ["Figures after Li Heng & Cai Qingdong, *Numerical simulation of granular flow in "
              "the Chinese Fish Basin*, Chinese J. Theor. Appl. Mech. 40(1), 2008.", ""]
    gravity = lookup(scene[1], "domain", "gravity") if scene and scene[1] else None
    lines += ["Units: those of the scene. The basin scenes use reduced units: length sigma = "
              "mean grain radius, mass m = mean grain mass, time tau with g = 1 sigma/tau^2; "
              f"energies in {UNIT_E}."
              + (f" This run's gravity vector: {gravity}." if gravity is not None else ""), ""]

    lines += ["## The run", ""]
    if energies is not None and "time" in energies and len(energies["time"]):
        last = {k: v[-1] for k, v in energies.items()}
        lines.append(f"- simulated time: {fmt(float(energies['time'][0]))} to "
                     f"{fmt(float(last['time']))} tau ({len(energies['time'])} energy rows)")
        for k, what in [("grains", "grains at the end"), ("contacts", "contacts at the end"),
                        ("escaped", "grains removed after leaving the domain")]:
            if k in last:
                lines.append(f"- {what}: {int(last[k])}")
        if "balance" in energies:
            b = energies["balance"]
            lines.append(f"- energy books (mechanical + dissipated + removed - work in): "
                         f"{fmt(float(b[0]), 8)} at the start, {fmt(float(b[-1]), 8)} at the end")
        lines.append("")
    if scene:
        path, parsed, text = scene
        lines += [f"Scene: `{os.path.basename(path)}`", ""]
        if parsed:
            lines += ["| parameter | value |", "|---|---|"]
            for k, v in flatten(parsed):
                lines.append(f"| `{k}` | `{v}` |")
        else:
            lines += ["```toml", text.rstrip(), "```"]
        lines.append("")
    else:
        lines += ["No scene file (scene.toml or scene.resolved.toml) in the run folder.", ""]

    lines += ["## Figures", ""]
    for name, caption in made:
        lines += [f"### {name}", "", f"![{name}]({name})", "", caption, ""]
    if skipped:
        lines += ["Not made (data missing):", ""]
        lines += [f"- {name}: {why}" for name, why in skipped]
        lines.append("")

    lines += ["## Power laws of Fig. 10", ""]
    if fits:
        src = {f.get("source", "") for f in fits.values()}
        lines += ["Least-squares fits of log10(density) against log10(E) over the bins whose "
                  "centres lie in the range; 'energy fraction' is the energy of the samples in "
                  "those bins over the energy of all samples (from "
                  + ", ".join(sorted(src)) + ").", "", slope_table(fits), ""]
    else:
        lines += ["No fits (no fits.csv and no densities).", ""]
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="run folder")
    ap.add_argument("--out", help="where figures and report.md go (default: the run folder)")
    ap.add_argument("--surface-time", type=float, default=10.25,
                    help="time of the 3-D surface (Fig. 5), default 10.25")
    ap.add_argument("--velocity-time", type=float, default=10.50,
                    help="time of the velocity section (Fig. 7), default 10.50")
    args = ap.parse_args()
    run = args.run
    if not os.path.isdir(run):
        sys.exit(f"plot_basin: {run} is not a folder")
    out = args.out or run
    os.makedirs(out, exist_ok=True)
    analysis = os.path.join(run, "analysis")

    scene = read_scene(run)
    t0 = lookup(scene[1], "basin", "excitation", "t0") if scene and scene[1] else None
    epath = os.path.join(run, "energies.csv")
    energies = read_table(epath) if os.path.exists(epath) else None
    pdfs = read_pdfs(analysis)
    fits = read_fits(analysis, pdfs)

    jobs = [("fig4_energies.png", lambda: fig4_energies(run, out, t0)),
            ("fig5_surface.png", lambda: fig5_surface(analysis, out, args.surface_time)),
            ("fig6_contours.png", lambda: fig6_contours(analysis, out)),
            ("fig7_velocity.png", lambda: fig7_velocity(analysis, out, args.velocity_time)),
            ("fig8_elastic_maps.png", lambda: fig8_elastic_maps(analysis, out)),
            ("fig9_sections.png", lambda: fig9_sections(analysis, out)),
            ("fig10_pdf.png", lambda: fig10_pdf(out, pdfs, fits))]
    made, skipped = [], []
    for name, job in jobs:
        try:
            made.append(job())
            print(f"wrote {os.path.join(out, name)}")
        except Skip as why:
            note(f"skipping {name}: {why}")
            skipped.append((name, str(why)))
            plt.close("all")
    write_report(run, out, scene, energies, made, skipped, fits)
    print(f"wrote {os.path.join(out, 'report.md')}")


if __name__ == "__main__":
    main()
