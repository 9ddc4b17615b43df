#!/usr/bin/python3
"""Fig. 10 of Li & Cai (2008) under every plausible reading of the paper's words and axis.

usage: basin_fig10_readings.py RUN [--interior-margin D] [--bins-per-decade N]

The paper puts "about 40 %" of the energy in range A (E from 0.2 to 2; slopes -2.691 for E_k
and -2.782 for E_k + E_s) and about 4 % in range B (10 to 1e4; slopes -0.771 and -0.776) of
the per-grain energy densities over the first period of the excitation. Its text leaves open
what the fraction counts, the unit of the energy axis, which grains and which times enter.
This script recomputes, from the run's per-grain samples, the fraction and the fitted
log-log slope of the density of E_k and of E_k + E_s in A and B under each combination of:
  fraction_of    energy: sum of E over the grains in the range / the sum over all grains;
                 grains: the number of grains in the range / all (the probability)
  normalisation  "m sigma^2/tau^2": E as it is (the same as m g sigma where g = 1
                 sigma/tau^2, as in the basin scenes; a scene with another |g| also gets the
                 reading "m g sigma", E / (m g sigma) with m = 1 and sigma = 1);
                 "E/<E>": E over the mean of E over the selected grains of its sample
  grains         all: every grain; interior: grains more than D from the side wall
                 (r < R - D), more than D above the bottom (z - z_bottom > D, z the centre)
                 and more than D below the local free surface (the highest grain top,
                 z + radius, of the sample's grains whose centres lie in the same column of
                 the run's analysis grid)
  window         period: the samples from period_start to period_start + period_length;
                 all: every sample; period-mean: each grain's energy averaged over the
                 period's samples (grains matched by id; "interior" then means interior in at
                 least half of them), one value per grain
Density: bins of log10(E) with bins_per_decade bins per decade, edges at 10^(k / N) (as the
run's analysis, pdf_range starting at a power of 10); density = count / (n (e_hi - e_lo)),
n = every value pooled (zeros included). Slope: least squares of log10(density) against
log10(geometric bin centre) over the non-empty bins whose centres lie in the range.

Reads:  RUN/analysis/grains/grains_t<time>.npy (structured arrays: id int64; x, y, z, radius,
        mass float32; kinetic, elastic float64 in m sigma^2/tau^2), RUN/scene.resolved.toml
        (basin geometry, [analysis] period_start, period_length, grid; domain lo, hi, gravity)
Writes: RUN/analysis/fig10_readings.csv with the columns
          quantity,fraction_of,normalisation,grains,window,range,e_lo,e_hi,fraction,slope,
          slope_error,bins,samples,grains_per_sample
        (one row per reading; slope and its standard error do not depend on fraction_of),
        RUN/fig10_readings.md (the same as a Markdown table with the verdict), and prints the
        Markdown to stdout.
Units: sigma (mean grain radius), m (mean grain mass), tau; energies in m sigma^2/tau^2.
"""
import argparse
import glob
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "plots"))
from plot_basin import basin_geometry, line_fit, read_resolved_scene  # noqa: E402

RANGES = {"A": (0.2, 2.0), "B": (10.0, 1e4)}
PAPER = {  # (quantity, range): slope; fractions of the paper's text
    ("E_k", "A"): -2.691, ("E_k + E_s", "A"): -2.782,
    ("E_k", "B"): -0.771, ("E_k + E_s", "B"): -0.776}
PAPER_FRACTION = {"A": 0.40, "B": 0.04}
# A reading "matches" when both fractions lie within these bounds and both slopes within these
# distances of the paper's.
MATCH_FRACTION = {"A": (0.30, 0.50), "B": (0.02, 0.06)}
MATCH_SLOPE = {"A": 0.5, "B": 0.3}


def note(msg):
    print(f"basin_fig10_readings: {msg}", file=sys.stderr)


def load_samples(run):
    """[(time, structured array)] of RUN/analysis/grains/grains_t<time>.npy, sorted by time."""
    out = []
    for p in glob.glob(os.path.join(run, "analysis", "grains", "grains_t*.npy")):
        m = re.search(r"grains_t([-+0-9.eE]+)\.npy$", os.path.basename(p))
        if not m:
            continue
        try:
            out.append((float(m.group(1)), np.load(p)))
        except (OSError, ValueError) as e:
            note(f"cannot read {p}: {e}")
    return sorted(out, key=lambda s: s[0])


def interior_mask(a, geo, grid, lo, hi, margin):
    """Grains of sample `a` more than `margin` from the side wall, the bottom and the local
    free surface (see the module's docstring)."""
    x, y, z = (a[k].astype(float) for k in ("x", "y", "z"))
    top = z + a["radius"].astype(float)
    r = np.hypot(x - geo["axis"][0], y - geo["axis"][1])
    nx, ny = int(grid[0]), int(grid[1])
    i = np.clip(((x - lo[0]) / (hi[0] - lo[0]) * nx).astype(int), 0, nx - 1)
    j = np.clip(((y - lo[1]) / (hi[1] - lo[1]) * ny).astype(int), 0, ny - 1)
    col = j * nx + i
    surface = np.full(nx * ny, -np.inf)
    np.maximum.at(surface, col, top)
    return ((r < geo["R"] - margin) & (z - geo["z_bottom"] > margin)
            & (surface[col] - z > margin))


def density_slope(values, lo, hi, per_decade):
    """(slope, standard error, bins used) of the log-binned density of `values` over the
    non-empty bins whose geometric centres lie in [lo, hi]."""
    v = values[np.isfinite(values)]
    n = v.size
    pos = v[v > 0]
    if n == 0 or pos.size == 0:
        return math.nan, math.nan, 0
    k0 = math.floor(math.log10(pos.min()) * per_decade)
    k1 = math.ceil(math.log10(pos.max()) * per_decade) + 1
    edges = 10.0 ** (np.arange(k0, k1 + 1) / per_decade)
    counts, _ = np.histogram(pos, bins=edges)
    centres = np.sqrt(edges[1:] * edges[:-1])
    dens = counts / (n * np.diff(edges))
    sel = (centres >= lo) & (centres <= hi) & (counts > 0)
    if sel.sum() < 2:
        return math.nan, math.nan, int(sel.sum())
    slope, _, err = line_fit(np.log10(centres[sel]), np.log10(dens[sel]))
    return slope, err, int(sel.sum())


def readings(samples, geo, grid, lo, hi, margin, per_decade):
    """One dict per reading (see the module's docstring)."""
    ps, pl = geo["period_start"], geo["period_length"]
    eps = 1e-9 * max(1.0, abs(ps))
    in_period = [(t, a) for t, a in samples if ps - eps <= t <= ps + pl + eps]
    masks = {id(a): interior_mask(a, geo, grid, lo, hi, margin) for _, a in samples}
    norms = [("m sigma^2/tau^2", 1.0)]
    if abs(geo["g"] - 1.0) > 1e-12 and geo["g"] > 0:
        norms.append(("m g sigma", geo["g"]))
    norms.append(("E/<E>", None))
    quantities = [("E_k", lambda a: a["kinetic"].astype(float)),
                  ("E_k + E_s", lambda a: a["kinetic"].astype(float)
                   + a["elastic"].astype(float))]
    rows = []
    for qname, qf in quantities:
        for nname, unit in norms:
            for gname in ("all", "interior"):
                for wname in ("period", "all", "period-mean"):
                    chosen = in_period if wname != "all" else samples
                    if not chosen:
                        continue
                    pooled, counts = [], []
                    if wname == "period-mean":
                        # Each grain's energy averaged over the period's samples (by id).
                        ids = np.unique(np.concatenate([a["id"] for _, a in chosen]))
                        tot = np.zeros(ids.size)
                        seen = np.zeros(ids.size)
                        inner = np.zeros(ids.size)
                        for _, a in chosen:
                            k = np.searchsorted(ids, a["id"])
                            np.add.at(tot, k, qf(a))
                            np.add.at(seen, k, 1)
                            np.add.at(inner, k, masks[id(a)].astype(float))
                        e = tot / np.maximum(seen, 1)
                        keep = seen > 0
                        if gname == "interior":
                            keep &= inner >= 0.5 * seen
                        e = e[keep]
                        pooled.append(e / (unit if unit else (e.mean() if e.size else 1.0)))
                        counts.append(e.size)
                    else:
                        for _, a in chosen:
                            e = qf(a)
                            if gname == "interior":
                                e = e[masks[id(a)]]
                            if e.size == 0:
                                counts.append(0)
                                continue
                            mean = e.mean()
                            pooled.append(e / unit if unit else
                                          (e / mean if mean > 0 else e * math.nan))
                            counts.append(e.size)
                    vals = np.concatenate(pooled) if pooled else np.zeros(0)
                    vals = vals[np.isfinite(vals)]
                    total_e = vals.sum()
                    for rname, (elo, ehi) in RANGES.items():
                        inr = (vals >= elo) & (vals <= ehi)
                        slope, err, nb = density_slope(vals, elo, ehi, per_decade)
                        base = {"quantity": qname, "normalisation": nname, "grains": gname,
                                "window": wname, "range": rname, "e_lo": elo, "e_hi": ehi,
                                "slope": slope, "slope_error": err, "bins": nb,
                                "samples": len(chosen),
                                "grains_per_sample": float(np.mean(counts)) if counts else 0.0}
                        rows.append(dict(base, fraction_of="energy",
                                         fraction=float(vals[inr].sum() / total_e)
                                         if total_e > 0 else math.nan))
                        rows.append(dict(base, fraction_of="grains",
                                         fraction=float(inr.sum() / vals.size)
                                         if vals.size else math.nan))
    return rows


def pct(v):
    return f"{100 * v:.3g} %" if math.isfinite(v) else "—"


def num(v, d=3):
    return f"{v:.{d}g}" if isinstance(v, float) and math.isfinite(v) else "—"


def verdict(rows):
    """Markdown lines: which readings give A about 40 %, B about 4 % and slopes near the
    paper's; the closest ones if none does."""
    by = {}
    for r in rows:
        by.setdefault((r["quantity"], r["fraction_of"], r["normalisation"], r["grains"],
                       r["window"]), {})[r["range"]] = r
    scored = []
    for key, rr in by.items():
        if "A" not in rr or "B" not in rr:
            continue
        fa, fb = rr["A"]["fraction"], rr["B"]["fraction"]
        sa, sb = rr["A"]["slope"], rr["B"]["slope"]
        pa, pb = PAPER[(key[0], "A")], PAPER[(key[0], "B")]
        frac_ok = all(math.isfinite(f) and MATCH_FRACTION[g][0] <= f <= MATCH_FRACTION[g][1]
                      for f, g in ((fa, "A"), (fb, "B")))
        slope_ok = all(math.isfinite(s) and abs(s - p) <= MATCH_SLOPE[g]
                       for s, p, g in ((sa, pa, "A"), (sb, pb, "B")))
        score = 0.0
        for f, g in ((fa, "A"), (fb, "B")):
            score += abs(math.log(f / PAPER_FRACTION[g])) if math.isfinite(f) and f > 0 else 10
        for s, p, g in ((sa, pa, "A"), (sb, pb, "B")):
            score += abs(s - p) / MATCH_SLOPE[g] if math.isfinite(s) else 10
        scored.append((score, key, frac_ok, slope_ok, fa, fb, sa, sb))
    scored.sort(key=lambda s: s[0])

    def describe(s):
        q, fo, nm, gr, wi = s[1]
        return (f"{q}, fraction of {fo}, {nm}, {gr} grains, window {wi}: A {pct(s[4])} "
                f"(slope {num(s[6])}), B {pct(s[5])} (slope {num(s[7])})")

    both = [s for s in scored if s[2] and s[3]]
    lines = ["Criteria: A between 30 and 50 %, B between 2 and 6 %, slope within 0.5 of the "
             "paper's in A (-2.691 E_k, -2.782 E_k + E_s) and within 0.3 in B (-0.771, "
             "-0.776).", ""]
    if both:
        lines.append("Readings that match the paper in fractions and slopes:")
        lines += [f"- {describe(s)}" for s in both]
    else:
        lines.append("**No reading matches the paper in both fractions and slopes.**")
    fr = [s for s in scored if s[2] and not s[3]]
    sl = [s for s in scored if s[3] and not s[2]]
    if fr:
        lines += ["", "Fractions match, slopes do not:"] + [f"- {describe(s)}" for s in fr]
    if sl:
        lines += ["", "Slopes match, fractions do not:"] + [f"- {describe(s)}" for s in sl]
    if not both and scored:
        lines += ["", "Closest (score: sum of |ln(fraction / paper's)| and |slope - paper's| / "
                  "tolerance over A and B):"]
        lines += [f"- {describe(s)} (score {s[0]:.2f})" for s in scored[:3]]
    return lines


def table(rows):
    """Markdown table: one line per (quantity, normalisation, grains, window)."""
    by = {}
    for r in rows:
        k = (r["quantity"], r["normalisation"], r["grains"], r["window"])
        by.setdefault(k, {})[(r["range"], r["fraction_of"])] = r
    out = ["| quantity | normalisation | grains | window | A: energy | A: grains | A: slope "
           "| B: energy | B: grains | B: slope | samples | grains/sample |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for k, d in by.items():
        ae, ag = d.get(("A", "energy")), d.get(("A", "grains"))
        be, bg = d.get(("B", "energy")), d.get(("B", "grains"))
        out.append(f"| {k[0]} | {k[1]} | {k[2]} | {k[3]} | {pct(ae['fraction'])} | "
                   f"{pct(ag['fraction'])} | {num(ae['slope'])} | {pct(be['fraction'])} | "
                   f"{pct(bg['fraction'])} | {num(be['slope'])} | {ae['samples']} | "
                   f"{ae['grains_per_sample']:.0f} |")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="run folder")
    ap.add_argument("--interior-margin", type=float, default=5.0, metavar="D",
                    help="interior grains: more than D [sigma] from the side wall, the bottom "
                         "and the free surface (default 5)")
    ap.add_argument("--bins-per-decade", type=int, default=10,
                    help="logarithmic bins per decade of the densities (default 10)")
    args = ap.parse_args()
    run = args.run
    if not os.path.isdir(run):
        sys.exit(f"basin_fig10_readings: {run} is not a folder")
    scene = read_resolved_scene(run)
    geo = basin_geometry(scene)
    if geo is None:
        sys.exit("basin_fig10_readings: no basin scene (scene.resolved.toml with [basin])")
    samples = load_samples(run)
    if not samples:
        sys.exit("basin_fig10_readings: no analysis/grains/grains_t*.npy "
                 "(set [analysis] grain_sample_interval)")
    dom = scene.get("domain", {})
    lo, hi = dom.get("lo", [0.0, 0.0, 0.0]), dom.get("hi", [1.0, 1.0, 1.0])
    grid = (scene.get("analysis", {}) or {}).get("grid", [48, 48])
    rows = readings(samples, geo, grid, lo, hi, args.interior_margin, args.bins_per_decade)

    cols = ["quantity", "fraction_of", "normalisation", "grains", "window", "range", "e_lo",
            "e_hi", "fraction", "slope", "slope_error", "bins", "samples",
            "grains_per_sample"]
    csv_path = os.path.join(run, "analysis", "fig10_readings.csv")
    with open(csv_path, "w", encoding="utf-8") as f:
        f.write(",".join(cols) + "\n")
        for r in rows:
            f.write(",".join(f"{r[c]:.10g}" if isinstance(r[c], float) else str(r[c])
                             for c in cols) + "\n")

    times = [t for t, _ in samples]
    ps, pl = geo["period_start"], geo["period_length"]
    g_note = ("g = 1 sigma/tau^2 here, so m sigma^2/tau^2 and m g sigma are the same unit "
              "(one reading)" if abs(geo["g"] - 1.0) <= 1e-12
              else f"|g| = {geo['g']:g}: 'm g sigma' is E / |g|")
    md = [f"# Fig. 10 under every reading: {os.path.abspath(run)}", "",
          f"{len(samples)} grain samples, t = {times[0]:g} to {times[-1]:g} tau; the period: "
          f"{ps:g} to {ps + pl:g} tau. Interior grains: more than D = {args.interior_margin:g} "
          f"sigma from the side wall (r < {geo['R'] - args.interior_margin:g}), above the "
          f"bottom (z > {geo['z_bottom'] + args.interior_margin:g}) and below the local free "
          f"surface. {g_note}. Energy fractions are sum E in [e_lo, e_hi] / sum E; grain "
          "fractions count grains. Densities: "
          f"{args.bins_per_decade} log bins per decade; slopes by least squares over the "
          "non-empty bins with centres in the range. Paper: A about 40 % (slopes -2.691 E_k, "
          "-2.782 E_k + E_s), B about 4 % (-0.771, -0.776).", ""]
    md += table(rows) + [""] + verdict(rows) + [""]
    text = "\n".join(md)
    with open(os.path.join(run, "fig10_readings.md"), "w", encoding="utf-8") as f:
        f.write(text)
    print(text)
    print(f"wrote {csv_path} and {os.path.join(run, 'fig10_readings.md')}", file=sys.stderr)


if __name__ == "__main__":
    main()
