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
  analysis/period_sections.csv   section,z0,z1,x,y,number_density,kinetic_energy_density,
                                 elastic_energy_density
                                                    horizontal sections, coarse-grained and
                                                    averaged over the first excitation period
  analysis/pdf_kinetic.csv, pdf_elastic.csv, pdf_total.csv
                                 e_lo,e_hi,e_center,count,density,energy   (log bins)
  analysis/fits.csv              quantity,range,e_lo,e_hi,slope,intercept,slope_error,bins,
                                 energy_fraction,e_lo_used,e_hi_used
  analysis/peaks.csv             step,time,sector,azimuth,r,height
                                 every track_interval, the highest free-surface column of each
                                 of the 2m antinode wedges: distance r from the axis, height
  analysis/surface_profile.csv, elastic_profile.csv
                                 step,time,direction,r_lo,r_hi,columns,mean,median,max
                                 radial profiles (bins of r) of the free-surface height and of
                                 the column-summed elastic energy over the antinode wedges
                                 (direction=antinode) or the node wedges (direction=node)
Grids are long CSV (one row per cell, x fastest); <T> is the time in tau, e.g. 10.25.
Geometry (the basin's axis and inner radius R = radius * spacing), the excitation and the
grain-grain contact pair are read from scene.resolved.toml (else scene.toml, with the
documented defaults).

Writes into DIR (default RUN_DIR): fig4_energies.png, fig5_surface.png, fig6_contours.png,
fig6b_peaks.png, fig7_velocity.png, fig8_elastic_maps.png, fig8b_waves.png, fig9_sections.png,
fig10_pdf.png, report.md; and into RUN_DIR/analysis/peaks_summary.csv
  time,peaks,mean_r,sd_r,mean_height,max_height,crest_r,crest_height
  (per tracking time: the mean and standard deviation of the 2m peaks' distances from the axis,
  their mean and largest height, and crest_r, the centre of the radial bin of largest median
  surface height along the antinodes, with that median height; lengths in sigma).
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


def read_profile(path):
    """A radial-profile CSV (step,time,direction,r_lo,r_hi,columns,mean,median,max) as
    {direction: {"time": (nt,), "r_lo": (nb,), "r_hi": (nb,), "columns", "mean", "median",
    "max": (nt, nb) arrays}}, times and bins sorted (nan where a row is missing); None if the
    file cannot be read or has no rows."""
    rows = {}
    try:
        with open(path, newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                try:
                    rows.setdefault(r["direction"], []).append(
                        [float(r[k]) for k in ("time", "r_lo", "r_hi", "columns", "mean",
                                               "median", "max")])
                except (KeyError, ValueError, TypeError):
                    continue
    except OSError as e:
        note(f"cannot read {path}: {e}")
        return None
    out = {}
    for direction, data in rows.items():
        a = np.array(data)
        times = np.unique(a[:, 0])
        bins = np.unique(a[:, 1:3], axis=0)  # sorted by r_lo
        it = np.searchsorted(times, a[:, 0])
        ib = np.searchsorted(bins[:, 0], a[:, 1])
        d = {"time": times, "r_lo": bins[:, 0], "r_hi": bins[:, 1]}
        for col, name in ((3, "columns"), (4, "mean"), (5, "median"), (6, "max")):
            g = np.full((len(times), len(bins)), np.nan)
            g[it, ib] = a[:, col]
            d[name] = g
        out[direction] = d
    return out or None


def read_resolved_scene(run):
    """The run's scene as a dict, preferring scene.resolved.toml (every default filled in)."""
    if tomllib is None:
        return None
    for name in ("scene.resolved.toml", "scene.toml"):
        p = os.path.join(run, name)
        if os.path.exists(p):
            try:
                with open(p, "rb") as f:
                    return tomllib.load(f)
            except (OSError, tomllib.TOMLDecodeError) as e:
                note(f"{p}: {e}")
    return None


def basin_geometry(scene):
    """What the sector figures need from a basin scene (docs/scene-format.md, [basin] and
    [analysis]), with the documented defaults where a key is absent; None without [basin].
    Lengths in the scene's units (sigma), times in tau:
      R          inner radius of the container, radius * spacing
      axis       (x, y) of the basin's axis: the centre of its lattice
      z_bottom   top of the bottom layer of wall particles
      t0, omega, amplitude, mode       the excitation
      period_start, period_length      the analysis window (default t0, 2 pi / omega)
      k_n, k_t   the grain-grain contact pair (None if there is none)
      radius_mean, radius_sd, g        grain radii and the magnitude of gravity"""
    if not isinstance(scene, dict) or not isinstance(scene.get("basin"), dict):
        return None
    b = scene["basin"]
    dom = scene.get("domain", {}) or {}
    ex = b.get("excitation", {}) or {}
    an = scene.get("analysis", {}) or {}
    spacing = float(b.get("spacing", 3.0))
    cells = b.get("cells", [24, 24, 16])
    lo = dom.get("lo", [0.0, 0.0, 0.0])
    t0 = float(ex.get("t0", 10.0))
    omega = float(ex.get("omega", 400.0))
    geo = {
        "R": float(b.get("radius", 10.0)) * spacing,
        "axis": (lo[0] + 0.5 * cells[0] * spacing, lo[1] + 0.5 * cells[1] * spacing),
        "z_bottom": lo[2] + (int(b.get("bottom_layers", 1)) - 0.5) * spacing
        + float(b.get("wall_radius", 1.5)),
        "t0": t0, "omega": omega, "amplitude": float(ex.get("amplitude", 0.9)),
        "mode": int(an.get("mode", ex.get("mode", 2))),
        "period_start": float(an.get("period_start", t0)),
        "period_length": float(an.get("period_length", 2 * math.pi / omega)),
        "radius_mean": float(b.get("radius_mean", 1.0)),
        "radius_sd": float(b.get("radius_sd", 0.1)),
        "g": float(np.linalg.norm(dom.get("gravity", [0.0, 0.0, -1.0]))),
        "k_n": None, "k_t": None,
    }
    grain = b.get("grain_material")
    for pair in lookup(scene, "contact", "pair") or []:
        mats = pair.get("materials", [])
        if len(mats) == 2 and mats[0] == mats[1] and (grain is None or mats[0] == grain):
            geo["k_n"] = float(pair["k_n"]) if "k_n" in pair else None
            geo["k_t"] = float(pair.get("k_t", 0.0))
            break
    return geo


def inside_container(xs, ys, geo):
    """Mask (ny, nx) of the grid columns whose centres lie within R of the basin's axis (all
    columns without a basin geometry)."""
    X, Y = np.meshgrid(xs, ys)
    if geo is None:
        return np.ones(X.shape, bool)
    return np.hypot(X - geo["axis"][0], Y - geo["axis"][1]) < geo["R"]


def bed_range(values, lo_pct=2.0, hi_pct=90.0, min_span=1.0):
    """(lo, hi) of a linear colour scale for heights: the lo_pct-th to the hi_pct-th percentile
    of the finite values, at least min_span wide; None without finite values."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return None
    lo, hi = (float(x) for x in np.percentile(v, [lo_pct, hi_pct]))
    if hi - lo < min_span:
        mid = 0.5 * (lo + hi)
        lo, hi = mid - 0.5 * min_span, mid + 0.5 * min_span
    return lo, hi


def floor_norm(values, floor_pct=5.0):
    """A LogNorm from the floor_pct-th percentile of the positive finite values to their
    maximum (None without positive values): the floor follows the quiet bed, not the peak."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return None
    vmin, vmax = float(np.percentile(v, floor_pct)), float(v.max())
    return LogNorm(vmin=vmin, vmax=vmax if vmax > vmin else vmin * 10)


def line_fit(x, y):
    """Least squares y = a + b x: (b, a, standard error of b); NaNs with fewer than 2 points."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    if x.size < 2 or np.ptp(x) == 0:
        return math.nan, math.nan, math.nan
    xm, ym = x.mean(), y.mean()
    sxx = ((x - xm) ** 2).sum()
    b = ((x - xm) * (y - ym)).sum() / sxx
    a = ym - b * xm
    err = math.nan
    if x.size >= 3:
        res = y - (a + b * x)
        err = math.sqrt((res ** 2).sum() / (x.size - 2) / sxx)
    return float(b), float(a), err


def edges_of(centres, fallback=1.0):
    """Cell edges for pcolormesh around sorted centres (midpoints; the outer cells mirrored)."""
    c = np.asarray(centres, float)
    if c.size == 1:
        return np.array([c[0] - fallback / 2, c[0] + fallback / 2])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


def draw_container(ax, geo):
    """The basin's inner wall (dashed circle of radius R) and its antinode azimuths k pi / m."""
    if geo is None:
        return
    cx, cy = geo["axis"]
    a = np.linspace(0, 2 * math.pi, 181)
    ax.plot(cx + geo["R"] * np.cos(a), cy + geo["R"] * np.sin(a), "--", color="0.4", lw=0.6)
    for k in range(2 * geo["mode"]):
        phi = k * math.pi / geo["mode"]
        ax.plot(cx + geo["R"] * np.array([1.0, 1.12]) * math.cos(phi),
                cy + geo["R"] * np.array([1.0, 1.12]) * math.sin(phi), "-", color="red", lw=1.2)


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


def fig6_contours(analysis, out, geo=None, max_panels=9, hi_pct=90.0):
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
    # The colour scale follows the bed, not the jets: grains thrown up make the highest columns
    # tens of sigma taller than the bed, and a scale up to them paints the bed one colour. The
    # levels span the 2nd to the hi_pct-th percentile of the heights inside the container
    # (r < R) over every panel; taller columns take the top colour.
    inside = np.concatenate([g[2]["height"][inside_container(g[0], g[1], geo)].ravel()
                             for _, g in grids])
    rng = bed_range(inside, 2.0, hi_pct)
    if rng is None:
        raise Skip("every surface is empty")
    lo, hi = rng
    top = float(np.nanmax(inside))
    levels = np.linspace(lo, hi, 16)
    rows, cols = panel_grid(len(grids))
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.4 * rows), squeeze=False)
    cs = None
    for ax, (t, (xs, ys, f)) in zip(axes.flat, grids):
        h = np.clip(f["height"], lo, None)  # below the bottom level: the bottom colour
        cs = ax.contourf(xs, ys, np.ma.masked_invalid(h), levels=levels, cmap="viridis",
                         extend="max")
        draw_container(ax, geo)
        ax.set_title(f"t = {t:g} tau", fontsize=9)
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(grids):]:
        ax.axis("off")
    cb = fig.colorbar(cs, ax=axes, shrink=0.8, extend="max", format="%.3g")
    cb.set_label("surface height [sigma]" + (f"\n(top colour: above {hi:.3g}, up to {top:.3g})"
                                             if top > hi else ""), fontsize=8)
    fig.suptitle("Free surface, contours (cf. Li & Cai 2008, Fig. 6)")
    fig.savefig(os.path.join(out, "fig6_contours.png"), dpi=120)
    plt.close(fig)
    where = ("inside the container (r < R = " + f"{geo['R']:g} sigma, dashed; red ticks: the "
             "antinodes)") if geo else "over the grid"
    return ("fig6_contours.png",
            "Contour maps of the free surface (height of the highest grain top over each "
            "column) at " + ", ".join(f"{t:g}" for t, _ in grids) + " tau (x, y in sigma). "
            f"The 16 levels run from {lo:.3g} to {hi:.3g} sigma, the 2nd to the "
            f"{hi_pct:g}th percentile of the heights {where} over all panels, so that the "
            "bed's relief shows; columns above the top level (grains thrown up, up to "
            f"{top:.3g} sigma) take the top colour. Empty columns are blank.")


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


def fig8_elastic_maps(analysis, out, geo=None, max_panels=12, floor_pct=5.0):
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
    # Log scale from a low percentile of the positive column energies inside the container to
    # the largest: the bed far from the wall holds 6 to 8 decades less than the columns the
    # wall strikes, and a floor a fixed 4 decades below the maximum would leave it blank.
    inside = np.concatenate([e[inside_container(xs, ys, geo)].ravel()
                             for _, xs, ys, e in maps])
    norm = floor_norm(inside, floor_pct)
    if norm is None:
        raise Skip("the elastic maps hold no positive energy")
    rows, cols = panel_grid(len(maps))
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.4 * rows), squeeze=False)
    cmap = plt.get_cmap("inferno").copy()
    cmap.set_bad("0.85")  # columns without a contact (zero energy) or without grains: grey
    im = None
    for ax, (t, xs, ys, e) in zip(axes.flat, maps):
        im = ax.imshow(np.ma.masked_where(~(e > 0), e), origin="lower",
                       extent=grid_extent(xs, ys), norm=norm, cmap=cmap,
                       interpolation="nearest")
        draw_container(ax, geo)
        ax.set_title(f"t = {t:g} tau", fontsize=9)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(maps):]:
        ax.axis("off")
    fig.colorbar(im, ax=axes, shrink=0.8, extend="min",
                 label=f"elastic energy per column [{UNIT_E}]")
    fig.suptitle("Elastic energy summed over z (cf. Li & Cai 2008, Fig. 8)")
    fig.savefig(os.path.join(out, "fig8_elastic_maps.png"), dpi=120)
    plt.close(fig)
    return ("fig8_elastic_maps.png",
            "Elastic energy summed over the height of each column at "
            + ", ".join(f"{m[0]:g}" for m in maps) + " tau. Log colour scale from "
            f"{norm.vmin:.3g} (the {floor_pct:g}th percentile of the positive column energies "
            f"{'inside the container' if geo else 'of the maps'}; lower values take the "
            f"bottom colour) to {norm.vmax:.3g} {UNIT_E} (the largest); grey: no energy. "
            + ("Dashed: the wall at rest (r = R); red ticks: the antinodes." if geo else ""))


def nearest_index(times, t, tol=1e-6):
    """Index of the entry of the sorted array `times` within tol of t, else None."""
    if len(times) == 0:
        return None
    j = int(np.argmin(np.abs(times - t)))
    return j if abs(times[j] - t) <= tol * max(1.0, abs(t)) else None


def inward_window(times, r, t0):
    """Indices of the window where r(t) moves inward after t0: from the largest r after t0 to
    the smallest r after that; None with fewer than 3 points in it."""
    idx = np.flatnonzero((times > t0 + 1e-9) & np.isfinite(r))
    if idx.size < 3:
        return None
    i_max = idx[np.argmax(r[idx])]
    rest = idx[idx >= i_max]
    i_min = rest[np.argmin(r[rest])]
    w = idx[(idx >= i_max) & (idx <= i_min)]
    return w if w.size >= 3 else None


def fig6b_peaks(analysis, out, geo, summary):
    path = os.path.join(analysis, "peaks.csv")
    if not os.path.exists(path):
        raise Skip("no analysis/peaks.csv")
    t = read_table(path)
    if t is None or not all(k in t for k in ("time", "sector", "r", "height")) \
            or len(t["time"]) == 0:
        raise Skip(f"{path}: missing columns or rows")
    times = np.unique(t["time"])
    it = np.searchsorted(times, t["time"])
    n = len(times)
    count = np.zeros(n, int)
    mean_r, sd_r, mean_h, max_h = (np.full(n, np.nan) for _ in range(4))
    for i in range(n):
        sel = (it == i) & np.isfinite(t["r"]) & np.isfinite(t["height"])
        count[i] = int(sel.sum())
        if count[i]:
            mean_r[i], sd_r[i] = t["r"][sel].mean(), t["r"][sel].std()
            mean_h[i], max_h[i] = t["height"][sel].mean(), t["height"][sel].max()
    ppath = os.path.join(analysis, "surface_profile.csv")
    prof = read_profile(ppath) if os.path.exists(ppath) else None
    anti = prof.get("antinode") if prof else None
    node = prof.get("node") if prof else None
    # crest_r: where the median surface along the antinodes is highest; bed: the median over
    # the bins of both directions, the height of the bed around the peaks.
    crest_r, crest_h, bed = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    for i, ti in enumerate(times):
        meds = []
        for d in (anti, node):
            j = nearest_index(d["time"], ti) if d is not None else None
            if j is None:
                continue
            row = d["median"][j]
            meds.append(row[np.isfinite(row)])
            if d is anti and np.isfinite(row).any():
                k = int(np.nanargmax(row))
                crest_r[i] = 0.5 * (d["r_lo"][k] + d["r_hi"][k])
                crest_h[i] = row[k]
        if meds and np.concatenate(meds).size:
            bed[i] = float(np.median(np.concatenate(meds)))
    with open(os.path.join(analysis, "peaks_summary.csv"), "w", encoding="utf-8") as f:
        f.write("time,peaks,mean_r,sd_r,mean_height,max_height,crest_r,crest_height\n")
        for i in range(n):
            f.write(f"{times[i]:.10g},{count[i]},{mean_r[i]:.10g},{sd_r[i]:.10g},"
                    f"{mean_h[i]:.10g},{max_h[i]:.10g},{crest_r[i]:.10g},"
                    f"{crest_h[i]:.10g}\n")

    R = geo["R"] if geo else None
    t0 = geo["t0"] if geo else float(times[0])
    res = {"times": n, "sectors": int(np.unique(t["sector"]).size), "t0": t0, "R": R,
           "track": {}}
    # Two trackers: the mean of the 2m highest columns (peaks.csv), and the crest of the
    # antinode profile (the bin of largest median height, which follows the bed rather than
    # single grains thrown up). Each gets its own window of inward motion and a line fit.
    for key, r, h in (("peaks", mean_r, mean_h), ("crest", crest_r, crest_h)):
        w = inward_window(times, r, t0)
        after = (times > t0 + 1e-9) & np.isfinite(r)
        tr = {"speed_all": line_fit(times[after], r[after])[0]}
        if w is not None:
            v, a, err = line_fit(times[w], r[w])
            tr.update(window=(float(times[w[0]]), float(times[w[-1]])), speed=v,
                      speed_err=err, r_from=float(r[w[0]]), r_to=float(r[w[-1]]),
                      h_from=float(h[w[0]]), h_to=float(h[w[-1]]),
                      height_rate=line_fit(times[w], h[w])[0], fit=(v, a))
        res["track"][key] = tr
    summary["peaks"] = res

    fig = plt.figure(figsize=(15, 8))
    gs = fig.add_gridspec(2, 3, width_ratios=[1.35, 1, 1], hspace=0.3, wspace=0.35)
    ax_r, ax_h = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[1, 0])
    for k in np.unique(t["sector"]).astype(int):
        sel = t["sector"].astype(int) == k
        o = np.argsort(t["time"][sel])
        az = t["azimuth"][sel][0] if "azimuth" in t else math.nan
        lab = f"antinode {k}" + (f" ({math.degrees(az):.0f} deg)" if math.isfinite(az) else "")
        ax_r.plot(t["time"][sel][o], t["r"][sel][o], "o-", ms=3, lw=0.8, alpha=0.7, label=lab)
        ax_h.plot(t["time"][sel][o], t["height"][sel][o], "o-", ms=3, lw=0.8, alpha=0.7,
                  label=lab)
    ax_r.plot(times, mean_r, "k-", lw=2, label="mean of the peaks")
    ax_r.plot(times, crest_r, "s-", color="tab:purple", ms=4, lw=1, mfc="none",
              label="crest of the antinode profile")
    ax_h.plot(times, mean_h, "k-", lw=2, label="mean of the peaks")
    ax_h.plot(times, crest_h, "s-", color="tab:purple", ms=4, lw=1, mfc="none",
              label="crest: its median height")
    ax_h.plot(times, bed, "-", color="0.5", lw=2, label="median surface (profile bins)")
    fit_style = {"peaks": ("red", "peaks"), "crest": ("magenta", "crest")}

    def draw_fits(ax, swap=False):
        for key, (colour, what) in fit_style.items():
            tr = res["track"][key]
            if "fit" in tr:
                tw = np.array(tr["window"])
                rw = tr["fit"][1] + tr["fit"][0] * tw
                ax.plot(*((rw, tw) if swap else (tw, rw)), "--", color=colour, lw=2,
                        label=f"fit, {what}: {tr['speed']:.3g} sigma/tau")

    draw_fits(ax_r)
    for ax in (ax_r, ax_h):
        if times[0] <= t0 < times[-1]:
            ax.axvline(t0, color="grey", ls=":", lw=0.8)
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("time [tau]")
    if R is not None:
        ax_r.axhline(R, color="grey", ls="--", lw=0.8)
        ax_r.set_ylim(0, R * 1.08)
        sec = ax_r.secondary_yaxis("right", functions=(lambda r: R - r, lambda d: R - d))
        sec.set_ylabel("from the wall, R - r [sigma]")
    ax_r.set_ylabel("distance from the axis r [sigma]")
    ax_r.set_title("Highest column of each antinode wedge (thin lines)", fontsize=10)
    handles, labels = ax_r.get_legend_handles_labels()
    keep = [i for i, lab in enumerate(labels) if not lab.startswith("antinode")]
    ax_r.legend([handles[i] for i in keep], [labels[i] for i in keep], fontsize=7,
                loc="lower left", framealpha=0.7)
    ax_h.set_ylabel("height [sigma]")
    ax_h.legend(fontsize=7, loc="upper left", ncol=2, framealpha=0.7)

    if anti is not None:
        dirs = [(anti, "antinodes")] + ([(node, "nodes")] if node is not None else [])
        allmed = np.concatenate([d["median"].ravel() for d, _ in dirs])
        rng = bed_range(allmed, 2.0, 90.0)
        if rng is not None:
            norm = plt.Normalize(*rng)
            im = None
            img_axes = []
            for col, (d, name) in enumerate(dirs):
                ax = fig.add_subplot(gs[:, 1 + col])
                img_axes.append(ax)
                r_edges = np.concatenate([d["r_lo"], d["r_hi"][-1:]])
                im = ax.pcolormesh(r_edges, edges_of(d["time"]), d["median"], norm=norm,
                                   cmap="viridis", shading="flat")
                if d is anti:
                    ax.plot(mean_r, times, "o", color="white", mec="k", ms=4,
                            label="mean peak r")
                    ax.plot(crest_r, times, "s", color="magenta", mfc="none", ms=5,
                            label="crest")
                    draw_fits(ax, swap=True)
                    ax.legend(fontsize=7, loc="upper right", framealpha=0.7)
                if R is not None:
                    ax.axvline(R, color="white", ls="--", lw=0.8)
                    ax.set_xlim(0, max(R, r_edges[-1]))
                ax.set_xlabel("distance from the axis r [sigma]")
                ax.set_ylabel("time [tau]")
                ax.set_title(f"median surface height along the {name}", fontsize=10)
            fig.colorbar(im, ax=img_axes, extend="max", shrink=0.9,
                         label=f"median surface height [sigma]; above {rng[1]:.3g}: top colour")
            res["image_range"] = rng
    fig.suptitle("Peaks of the free surface along the antinodes (cf. Li & Cai 2008, Fig. 6)")
    fig.savefig(os.path.join(out, "fig6b_peaks.png"), dpi=110)
    plt.close(fig)

    cap = (f"Left: the distance r from the axis (right axis: from the wall, R - r) and the "
           f"height of the highest free-surface column in each of the {res['sectors']} "
           f"antinode wedges (thin lines), every tracking time ({n} times, "
           f"{times[0]:g} to {times[-1]:g} tau); black: their mean; purple squares: the crest "
           "of the antinode profile (the radial bin of largest median surface height) and "
           "that median height; grey: the median over all profile bins (the bed). ")
    for key, what in (("peaks", "the peaks' mean r"), ("crest", "the crest's r")):
        tr = res["track"][key]
        if "fit" in tr:
            cap += (f"Dashed ({fit_style[key][0]}): a least-squares line through {what} from "
                    f"its largest value after t0 to its smallest after that "
                    f"({tr['window'][0]:g} to {tr['window'][1]:g} tau): "
                    f"{tr['speed']:.3g} ± {fmt(tr['speed_err'], 2)} sigma/tau (r from "
                    f"{tr['r_from']:.3g} to {tr['r_to']:.3g} sigma). ")
        else:
            cap += f"Too few tracking times after t0 for a fit of {what}. "
    if "image_range" in res:
        cap += ("Right: space-time images of the median surface height in each radial bin "
                "along the antinodes and the nodes; linear colour scale from "
                f"{res['image_range'][0]:.3g} to {res['image_range'][1]:.3g} sigma (the 2nd "
                "to the 90th percentile of the bins' medians), taller bins in the top colour; "
                "blank: bins without columns.")
    else:
        cap += "No surface_profile.csv: no space-time images."
    return "fig6b_peaks.png", cap


def measure_front(p, R, t0, factor=1e3, wall_fraction=1e-4):
    """The elastic front of one profile direction. Threshold: `factor` times the bed's
    background (the median of the positive bin means at times <= t0, before the wall moves);
    without such times, `wall_fraction` of each time's largest bin mean. For each time after
    t0, walking inward from the wall: the front is the innermost bin of the run of bins above
    the threshold that starts within the 3 outermost bins, a single quiet bin (or a bin
    without columns) not ending it. Returns (distance from the wall R - r of that bin's centre
    per time (nan: none), threshold description, threshold value or None)."""
    times, mean = p["time"], p["mean"]
    rc = 0.5 * (p["r_lo"] + p["r_hi"])
    order = np.argsort(-rc)
    before = mean[times <= t0 + 1e-9]
    bg = before[np.isfinite(before) & (before > 0)]
    if bg.size:
        background = float(np.median(bg))
        thr = factor * background
        how = (f"{factor:g} x the bed's background before t0 (median bin mean "
               f"{background:.3g} {UNIT_E}): {thr:.3g} {UNIT_E}")
    else:
        thr = None
        how = f"{wall_fraction:g} of each time's largest bin mean"
    front = np.full(len(times), np.nan)
    for i, ti in enumerate(times):
        if ti <= t0 + 1e-9:
            continue
        row = mean[i, order]
        if thr is not None:
            th = thr
        else:
            th = wall_fraction * np.nanmax(row) if np.isfinite(row).any() else math.inf
        started, gap, where = False, 0, None
        for k, v in enumerate(row):
            if np.isfinite(v) and v > th:
                if not started and k >= 3:
                    break
                started, gap, where = True, 0, rc[order][k]
            elif started and np.isfinite(v):
                gap += 1
                if gap >= 2:
                    break
        if where is not None:
            front[i] = R - where
    return front, how, thr


def front_speed(times, front, R, width, t0):
    """Linear fit of the front's distance from the wall against time while it is inside the
    bed: after t0, more than one bin from the wall, until it first comes within 1.5 bins of
    the axis. Returns (speed, intercept, standard error, mask of the times used)."""
    ok = (times > t0 + 1e-9) & np.isfinite(front)
    arrived = np.flatnonzero(ok & (front >= R - 1.5 * width))
    if arrived.size:
        ok &= np.arange(len(times)) < arrived[0]
    ok &= front >= width
    v, a, err = line_fit(times[ok], front[ok])
    return v, a, err, ok


def sound_speed(geo, energies, analysis):
    """Effective-medium sound speed of the bed before t0 for linear springs (Walton 1987;
    Digby 1981): K = phi Z k_n / (12 pi R_g), G = phi Z (2 k_n + 3 k_t) / (60 pi R_g),
    M = K + 4 G / 3, rho_b = phi m / (4/3 pi R_g^3), c_p = sqrt(M / rho_b); and the speed of a
    1-D chain of touching grains, c_1 = 2 R_g sqrt(k_n / m). R_g: the mean grain radius; m:
    the mean grain mass (1 in the basin scenes). Z = 2 contacts / grains from the last
    energies.csv row at or before t0 (grain-wall contacts included). phi: the grains' volume
    over the bed's, pi R^2 (h - z_bottom), h the median free-surface height inside the
    container at or before t0; 0.6 where that cannot be estimated or falls outside
    [0.3, 0.74]. Returns a dict of the inputs and results (None without k_n)."""
    if geo is None or geo.get("k_n") is None:
        return None
    kn, kt, rg, m = geo["k_n"], geo["k_t"] or 0.0, geo["radius_mean"], 1.0
    t0 = geo["t0"]
    res = {"k_n": kn, "k_t": kt, "R_g": rg, "m": m, "Z": math.nan, "Z_time": math.nan,
           "grains": math.nan}
    if energies is not None and all(k in energies for k in ("time", "contacts", "grains")):
        rows = np.flatnonzero(energies["time"] <= t0 + 1e-9)
        if rows.size:
            j = rows[-1]
            res["Z"] = 2.0 * energies["contacts"][j] / max(energies["grains"][j], 1.0)
            res["Z_time"], res["grains"] = float(energies["time"][j]), float(energies["grains"][j])
    # The bed's height: the median free surface inside the container at or before t0.
    h, h_from = math.nan, None
    surf = [(t, p) for t, p in timed_files(analysis, "surface") if t <= t0 + 1e-9]
    if surf:
        g = read_grid(surf[-1][1])
        if g is not None and "height" in g[2]:
            v = g[2]["height"][inside_container(g[0], g[1], geo)]
            v = v[np.isfinite(v)]
            if v.size:
                h, h_from = float(np.median(v)), f"surface_t{surf[-1][0]:g}"
    if not math.isfinite(h):
        path = os.path.join(analysis, "surface_profile.csv")
        prof = read_profile(path) if os.path.exists(path) else None
        vals = []
        for d in (prof or {}).values():
            for i in np.flatnonzero(d["time"] <= t0 + 1e-9)[-1:]:
                ok = np.isfinite(d["median"][i])
                vals += list(np.repeat(d["median"][i][ok], d["columns"][i][ok].astype(int)))
        if vals:
            h, h_from = float(np.median(vals)), "surface_profile.csv"
    r3 = rg ** 3 + 3 * rg * geo["radius_sd"] ** 2  # <r^3> of a normal distribution
    samples = sorted(glob.glob(os.path.join(analysis, "grains", "grains_t*.npy")))
    if samples:
        try:
            r3 = float(np.mean(np.load(samples[0])["radius"].astype(float) ** 3))
        except (OSError, ValueError, KeyError):
            pass
    phi, phi_from = math.nan, None
    if math.isfinite(h) and math.isfinite(res["grains"]) and h > geo["z_bottom"]:
        phi = res["grains"] * 4 / 3 * math.pi * r3 / (math.pi * geo["R"] ** 2
                                                      * (h - geo["z_bottom"]))
        phi_from = (f"{int(res['grains'])} grains of mean r^3 {r3:.3g} sigma^3 over pi R^2 "
                    f"(h - z_bottom), h = {h:.3g} sigma (median surface, {h_from}), "
                    f"z_bottom = {geo['z_bottom']:.3g} sigma")
    if not (0.3 <= phi <= 0.74):
        phi_from = ("assumed 0.6" + (f" (the estimate {phi:.3g} is implausible)"
                                     if math.isfinite(phi) else " (no estimate possible)"))
        phi = 0.6
    Z = res["Z"]
    K = phi * Z * kn / (12 * math.pi * rg)
    G = phi * Z * (2 * kn + 3 * kt) / (60 * math.pi * rg)
    M = K + 4 * G / 3
    rho = phi * m / (4 / 3 * math.pi * rg ** 3)
    res.update(phi=phi, phi_from=phi_from, K=K, G=G, M=M, rho=rho,
               c_p=math.sqrt(M / rho) if M > 0 else math.nan,
               c_1=2 * rg * math.sqrt(kn / m),
               wall_speed=geo["omega"] * geo["amplitude"])
    return res


def fig8b_waves(analysis, out, geo, energies, summary):
    path = os.path.join(analysis, "elastic_profile.csv")
    if not os.path.exists(path):
        raise Skip("no analysis/elastic_profile.csv")
    prof = read_profile(path)
    if not prof:
        raise Skip(f"{path}: no rows")
    dirs = [(d, prof[d]) for d in ("antinode", "node") if d in prof]
    if not dirs:
        raise Skip(f"{path}: neither antinode nor node rows")
    R = geo["R"] if geo else float(max(p["r_hi"].max() for _, p in dirs))
    ps = geo["period_start"] if geo else float(dirs[0][1]["time"][0])
    t0 = geo["t0"] if geo else ps
    norm = floor_norm(np.concatenate([p["mean"].ravel() for _, p in dirs]), 5.0)
    if norm is None:
        raise Skip(f"{path}: no positive elastic energy")
    fronts = {}
    for name, p in dirs:
        front, how, thr = measure_front(p, R, t0)
        width = float(np.median(p["r_hi"] - p["r_lo"]))
        v, a, err, used = front_speed(p["time"], front, R, width, t0)
        fronts[name] = {"front": front, "how": how, "speed": v, "intercept": a, "err": err,
                        "used": used, "n": int(used.sum()),
                        "span": ((float(p["time"][used][0]), float(p["time"][used][-1]))
                                 if used.any() else None),
                        "d_span": ((float(front[used][0]), float(front[used][-1]))
                                   if used.any() else None)}
    snd = sound_speed(geo, energies, analysis)
    summary["waves"] = {"fronts": fronts, "sound": snd, "R": R, "period_start": ps}

    fig = plt.figure(figsize=(15, 6.5))
    gs = fig.add_gridspec(1, 4, width_ratios=[1, 1, 0.05, 0.9], wspace=0.3, left=0.05,
                          right=0.99)
    cmap = plt.get_cmap("inferno").copy()
    cmap.set_bad("0.85")
    im = None
    img_axes = []
    for col, (name, p) in enumerate(dirs):
        ax = fig.add_subplot(gs[0, col])
        img_axes.append(ax)
        # Distance from the wall grows inward: reverse the bins so that x increases.
        d_edges = R - np.concatenate([p["r_hi"][::-1], p["r_lo"][:1]])
        field = p["mean"][:, ::-1]
        im = ax.pcolormesh(d_edges, edges_of(p["time"] - ps), np.ma.masked_where(~(field > 0),
                                                                                  field),
                           norm=norm, cmap=cmap, shading="flat")
        fr = fronts[name]
        ax.plot(fr["front"], p["time"] - ps, ".", color="cyan", ms=3, label="front")
        if math.isfinite(fr["speed"]):
            tt = p["time"][fr["used"]]
            ax.plot(fr["intercept"] + fr["speed"] * tt, tt - ps, "--", color="cyan", lw=1.5,
                    label=f"fit: {fr['speed']:.3g} sigma/tau")
        ax.legend(fontsize=7, loc="upper right")
        ax.set_xlabel("distance from the wall R - r [sigma]")
        ax.set_ylabel(f"time - {ps:g} [tau]")
        ax.set_title(f"mean column elastic energy along the {name}s", fontsize=10)
    fig.colorbar(im, cax=fig.add_subplot(gs[0, 2]), extend="min",
                 label=f"elastic energy per column [{UNIT_E}]")
    tax = fig.add_subplot(gs[0, 3])
    tax.axis("off")
    lines = ["Front (threshold: see caption)"]
    for name, fr in fronts.items():
        lines.append(f"  {name}: " + (f"{fr['speed']:.4g} sigma/tau ({fr['n']} times)"
                                      if math.isfinite(fr["speed"]) else "no fit"))
    if snd:
        lines += ["", "Sound speed of the bed before t0",
                  f"  k_n = {snd['k_n']:.4g}, k_t = {snd['k_t']:.4g} m/tau^2",
                  f"  R_g = {snd['R_g']:g} sigma, m = {snd['m']:g}",
                  f"  Z = {fmt(snd['Z'], 3)} (2 contacts/grains",
                  f"      at t = {snd['Z_time']:g})",
                  f"  phi = {snd['phi']:.3g}",
                  f"  K = {snd['K']:.4g}, G = {snd['G']:.4g}",
                  f"  M = K + 4G/3 = {snd['M']:.4g} m/(sigma tau^2)",
                  f"  rho_b = {snd['rho']:.3g} m/sigma^3",
                  f"  c_p = sqrt(M/rho_b) = {fmt(snd['c_p'], 4)} sigma/tau",
                  f"  c_1 = 2 R_g sqrt(k_n/m) = {snd['c_1']:.4g} sigma/tau",
                  f"  wall's peak speed omega dr = {snd['wall_speed']:.4g} sigma/tau"]
    tax.text(0.12, 1.0, "\n".join(lines), va="top", ha="left", family="monospace",
             fontsize=8.5, transform=tax.transAxes)
    fig.suptitle("Elastic waves from the wall (cf. Li & Cai 2008, Fig. 8)")
    fig.savefig(os.path.join(out, "fig8b_waves.png"), dpi=110)
    plt.close(fig)

    cap = ("Space-time images of the mean elastic energy per grid column (summed over z) in "
           "radial bins along the antinode and the node wedges: x = distance from the wall at "
           f"rest (R - r, R = {R:g} sigma), y = time from {ps:g} tau. Log colour scale from "
           f"{norm.vmin:.3g} (the 5th percentile of the positive bin means) to {norm.vmax:.3g} "
           f"{UNIT_E}; grey: no energy. Front (cyan dots): for each time after t0, the bin "
           "farthest from the wall in the run of bins, starting at the wall, above the "
           f"threshold, {fronts[dirs[0][0]]['how']}; dashed: a least-squares line through "
           "the front while it is inside the bed (more than one bin from the wall, until it "
           "first comes within 1.5 bins of the axis). ")
    for name, fr in fronts.items():
        if math.isfinite(fr["speed"]):
            cap += (f"Front speed along the {name}s: {fr['speed']:.4g} ± {fr['err']:.2g} "
                    f"sigma/tau ({fr['span'][0]:g} to {fr['span'][1]:g} tau). ")
        else:
            cap += f"Along the {name}s: too few front positions for a fit. "
    if snd:
        cap += (f"Sound speed of the bed (effective medium for linear springs, Walton 1987 / "
                f"Digby 1981): k_n = {snd['k_n']:.4g}, k_t = {snd['k_t']:.4g} m/tau^2, "
                f"R_g = {snd['R_g']:g} sigma, m = {snd['m']:g}, Z = {fmt(snd['Z'], 3)} "
                f"(2 contacts/grains at t = {snd['Z_time']:g} tau, grain-wall contacts "
                f"counted), phi = {snd['phi']:.3g} ({snd['phi_from']}): K = {snd['K']:.4g}, "
                f"G = {snd['G']:.4g}, M = {snd['M']:.4g} m/(sigma tau^2), rho_b = "
                f"{snd['rho']:.3g} m/sigma^3, c_p = {fmt(snd['c_p'], 4)} sigma/tau (phi cancels "
                f"in c_p); 1-D chain c_1 = {snd['c_1']:.4g} sigma/tau; the wall's peak speed "
                f"omega * amplitude = {snd['wall_speed']:.4g} sigma/tau.")
    return "fig8b_waves.png", cap


def fig9_sections(analysis, out):
    path = os.path.join(analysis, "period_sections.csv")
    if not os.path.exists(path):
        raise Skip("no analysis/period_sections.csv")
    t = read_table(path)
    names = {"elastic": "elastic_energy_density", "kinetic": "kinetic_energy_density"}
    need = ("section", "z0", "z1", "x", "y", *names.values())
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
            g[j, i] = t[names[q]][sel]
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
            ax.set_title(f"{q}, {z0:g} <= z <= {z1:g} sigma", fontsize=9)
            ax.tick_params(labelsize=7)
            fig.colorbar(im, ax=ax, shrink=0.8, label=f"[{UNIT_E} / sigma^3]")
    fig.suptitle("Energy densities averaged over the first excitation period, horizontal "
                 "sections\n(coarse-grained; cf. Li & Cai 2008, Fig. 9)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig9_sections.png"), dpi=120)
    plt.close(fig)
    return ("fig9_sections.png",
            "Elastic and kinetic energy densities of the grains, coarse-grained over x and y "
            "(the grid's cells, or a Gaussian: `section_width`) and averaged over z in "
            + ", ".join(f"[{p[1]:g}, {p[2]:g}]" for p in panels)
            + " and over the first excitation period (log colour scale; each grain's energy "
            "at its centre, half of each contact's elastic energy to each grain).")


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


def peaks_section(res):
    """Report lines on the travelling peaks (fig6b_peaks)."""
    lines = ["## Travelling peaks (Fig. 6b)", "",
             "The paper: \"The four peaks of the surface start near the wall, travel to the "
             "centre and decay because of dissipation.\" Two measures here: the peaks, the "
             "highest free-surface column in each antinode wedge (`analysis/peaks.csv`), "
             "averaged over the wedges; and the crest, the radial bin of largest median "
             "surface height along the antinodes (`analysis/surface_profile.csv`). Per-time "
             "values in `analysis/peaks_summary.csv`. Each speed is a least-squares line "
             "through r(t) from its largest value after t0 to its smallest after that.", "",
             "| measure | window [tau] | r [sigma] | from the wall [sigma] | speed "
             "[sigma/tau] | trend after t0 [sigma/tau] | height [sigma] | travels | height |",
             "|---|---|---|---|---|---|---|---|---|"]
    R = res["R"]
    for key, what in (("peaks", "peaks (highest columns)"), ("crest", "crest (median)")):
        tr = res["track"][key]
        if "fit" not in tr:
            lines.append(f"| {what} | — | — | — | — | {fmt(tr['speed_all'], 3)} | — | — | — |")
            continue
        wall = (f"{R - tr['r_from']:.3g} → {R - tr['r_to']:.3g}" if R is not None else "—")
        lines.append(
            f"| {what} | {tr['window'][0]:g} – {tr['window'][1]:g} | {tr['r_from']:.3g} → "
            f"{tr['r_to']:.3g} | {wall} | **{tr['speed']:.3g}** ± {fmt(tr['speed_err'], 2)} | "
            f"{fmt(tr['speed_all'], 3)} | {tr['h_from']:.3g} → {tr['h_to']:.3g} | "
            f"{'inward' if tr['speed'] < 0 else 'outward'} | "
            f"{'grows' if tr['height_rate'] > 0 else 'decays'} |")
    lines.append("")
    pk = res["track"]["peaks"]
    if "fit" in pk and pk["height_rate"] > 0:
        lines += ["Unlike the paper's, the highest columns grow: here they are grains thrown "
                  "up by the wall (jets), not the crest of a heap of the bed.", ""]
    return lines


def waves_section(res):
    """Report lines on the elastic fronts and the sound speed (fig8b_waves)."""
    lines = ["## Elastic waves (Fig. 8b)", "",
             "The paper: \"Elastic energy travels as waves from the wall to the centre; the wave "
             "fronts appear alternately at the four symmetric points of the wall.\" Front: the "
             "innermost radial bin of the column elastic energy (mean over the wedges) above "
             "the threshold, in the run of such bins that starts at the wall "
             f"({next(iter(res['fronts'].values()))['how']}).", "",
             "| direction | front speed [sigma/tau] | ± s.e. | times fitted | window [tau] "
             "| distance from the wall [sigma] |", "|---|---|---|---|---|---|"]
    for name, fr in res["fronts"].items():
        if fr["span"]:
            lines.append(f"| {name} | {fmt(fr['speed'], 4)} | {fmt(fr['err'], 2)} | {fr['n']} "
                         f"| {fr['span'][0]:g} – {fr['span'][1]:g} | {fr['d_span'][0]:.3g} → "
                         f"{fr['d_span'][1]:.3g} |")
        else:
            lines.append(f"| {name} | — | — | 0 | — | — |")
    lines.append("")
    snd = res["sound"]
    if snd:
        lines += ["Sound speed of the bed before the excitation (effective medium for linear "
                  "springs, Walton 1987 / Digby 1981):", "",
                  "| input or result | value |", "|---|---|",
                  f"| k_n, k_t (grain-grain) | {snd['k_n']:.4g}, {snd['k_t']:.4g} m/tau^2 |",
                  f"| grain radius R_g, mass m | {snd['R_g']:g} sigma, {snd['m']:g} m |",
                  f"| coordination number Z = 2 contacts / grains at t = {snd['Z_time']:g} "
                  f"(grain-wall contacts counted) | {fmt(snd['Z'], 3)} |",
                  f"| packing fraction phi | {snd['phi']:.3g} ({snd['phi_from']}) |",
                  f"| K = phi Z k_n / (12 pi R_g) | {snd['K']:.4g} m/(sigma tau^2) |",
                  f"| G = phi Z (2 k_n + 3 k_t) / (60 pi R_g) | {snd['G']:.4g} m/(sigma tau^2) |",
                  f"| M = K + 4 G / 3 | {snd['M']:.4g} m/(sigma tau^2) |",
                  f"| rho_b = phi m / (4/3 pi R_g^3) | {snd['rho']:.3g} m/sigma^3 |",
                  f"| c_p = sqrt(M / rho_b) (phi cancels) | **{fmt(snd['c_p'], 4)} sigma/tau** |",
                  f"| c_1 = 2 R_g sqrt(k_n / m), a 1-D chain | **{snd['c_1']:.4g} sigma/tau** |",
                  f"| the wall's peak speed omega * amplitude | {snd['wall_speed']:.4g} "
                  "sigma/tau |", ""]
        for name, fr in res["fronts"].items():
            if math.isfinite(fr["speed"]) and snd["c_p"] > 0:
                lines.append(f"- along the {name}s the front travels at "
                             f"{fr['speed'] / snd['c_p']:.2f} c_p = "
                             f"{fr['speed'] / snd['c_1']:.2f} c_1")
        if snd["c_p"] > 0:
            lines.append(f"- the wall's peak speed is {snd['wall_speed'] / snd['c_p']:.2f} c_p "
                         f"= {snd['wall_speed'] / snd['c_1']:.2f} c_1")
        lines.append("")
    else:
        lines += ["No sound-speed estimate (no basin scene or no grain-grain k_n).", ""]
    return lines


def write_report(run, out, scene, energies, made, skipped, fits, summary=None):
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

    summary = summary or {}
    if "peaks" in summary:
        lines += peaks_section(summary["peaks"])
    if "waves" in summary:
        lines += waves_section(summary["waves"])

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
    geo = basin_geometry(read_resolved_scene(run))
    summary = {}

    jobs = [("fig4_energies.png", lambda: fig4_energies(run, out, t0)),
            ("fig5_surface.png", lambda: fig5_surface(analysis, out, args.surface_time)),
            ("fig6_contours.png", lambda: fig6_contours(analysis, out, geo)),
            ("fig6b_peaks.png", lambda: fig6b_peaks(analysis, out, geo, summary)),
            ("fig7_velocity.png", lambda: fig7_velocity(analysis, out, args.velocity_time)),
            ("fig8_elastic_maps.png", lambda: fig8_elastic_maps(analysis, out, geo)),
            ("fig8b_waves.png", lambda: fig8b_waves(analysis, out, geo, energies, summary)),
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
    write_report(run, out, scene, energies, made, skipped, fits, summary)
    print(f"wrote {os.path.join(out, 'report.md')}")


if __name__ == "__main__":
    main()
