#!/usr/bin/env python3
"""Writes the Beverloo discharge scenes (docs/models/validation.md, B3) and their floor meshes.

A flat-bottomed cylindrical silo (an analytic [[cylinder]] of diameter D >= 2.5 D_o + 10 d)
stands on a floor with a circular orifice of diameter D_o (an annulus of triangles, written here
as ASCII STL). The grains start on a jittered lattice and settle on a shutter (a flat puck under
the orifice, active until t_open); then the orifice opens, grains that fall 3 d below the floor
leave through an [[outlet]], and an [[insert]] pours fresh grains from a region above the bed at
1.3 times Beverloo's rate, so that the fill height stays near its start. The orifice stays open
150 tau for D_o <= 6 d (slow, intermittent flow) and 40 tau for the larger ones.

    beverloo-Do<N>.toml, annulus-Do<N>.stl   D_o / d = 5, 6, 8, 10, 12 (the long suite)
    beverloo-small.toml, annulus-small.stl   D_o = 5 d in a silo of 16 d (the default tests:
                                             the mechanics, and a rate within a wide band)

Units: d = 1 (radii uniform in 0.45-0.55), grain density 6/pi (m = 1 for d = 1), g = 1.

usage: make_beverloo.py  (writes every file beside this script)
"""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
GRAIN_VOLUME = 4 / 3 * math.pi * (0.55**4 - 0.45**4) / (4 * 0.1)
PHI = 0.6
SEGMENTS = 96


def annulus(path, inner, outer):
    """The annulus inner <= r <= outer at z = 0 as ASCII STL, normals up."""
    lines = [f"solid annulus_{inner:g}_{outer:g}"]
    for k in range(SEGMENTS):
        a0, a1 = 2 * math.pi * k / SEGMENTS, 2 * math.pi * (k + 1) / SEGMENTS
        p = [(r * math.cos(a), r * math.sin(a), 0.0)
             for r, a in ((inner, a0), (outer, a0), (outer, a1), (inner, a1))]
        for tri in ((p[0], p[1], p[2]), (p[0], p[2], p[3])):
            lines += ["facet normal 0 0 1", "outer loop"]
            lines += [f"vertex {x:.9g} {y:.9g} {z:.9g}" for x, y, z in tri]
            lines += ["endloop", "endfacet"]
    lines.append(f"endsolid annulus_{inner:g}_{outer:g}")
    path.write_text("\n".join(lines) + "\n")


def scene(name, orifice, diameter, height, settle, discharge):
    radius = diameter / 2
    count = round(PHI * math.pi * radius**2 * height / GRAIN_VOLUME)
    lattice = 2 * (0.55 + 0.02)
    per_layer = math.pi * (radius - 0.57) ** 2 / lattice**2
    fill_top = math.ceil(count / per_layer * lattice + 2 * lattice)
    rho_b = PHI * 6 / math.pi
    beverloo = 0.58 * rho_b * (orifice - 1.5) ** 2.5  # grains (m = 1) per unit time
    stl = f"annulus-{name.split('-', 1)[1]}.stl"
    annulus(HERE / stl, orifice / 2, radius + 1.0)
    t_open = settle
    t_end = settle + discharge
    half = radius + 2.0
    top = max(fill_top, height + 14) + 2
    out = [f"# Beverloo discharge: D_o = {orifice} d from a silo of D = {diameter} d filled to "
           f"about {height} d ({count} grains).",
           "# Written by make_beverloo.py; docs/models/validation.md (B3).", "",
           'materials = ["grain", "wall"]', "", "[material.grain]",
           "density = 1.909859317 # m = 1 for d = 1", "",
           "[run]", f'name = "{name}"', "dt = 8.0e-4", f"t_end = {t_end}", "",
           "[output]", "energy_interval = 0.5", f"snapshot_interval = {discharge / 4}", "",
           "[checkpoint]", "every_minutes = 20", "",
           "[domain]", f"lo = [{-half}, {-half}, -6.0]", f"hi = [{half}, {half}, {top}]",
           "gravity = [0.0, 0.0, -1.0]", "skin = 0.2", "",
           "[contact]", 'model = "linear"']
    for partner in ("grain", "wall"):
        out += ["[[contact.pair]]", f'materials = ["grain", "{partner}"]', "k_n = 2.0e4",
                "k_t = 5714.2857", "gamma_n = 50.0", "gamma_t = 25.0", "mu_s = 0.5", "mu_d = 0.5"]
    out += ["",
            "[[cylinder]]", 'name = "side"', "center = [0.0, 0.0, 0.0]", f"radius = {radius}",
            'material = "wall"', "",
            "[[mesh]]", 'name = "floor"', f'file = "{stl}"', 'material = "wall"', "",
            "# the shutter under the orifice, removed at t_open",
            "[[cylinder]]", 'name = "shutter"', "center = [0.0, 0.0, 0.0]",
            f"radius = {orifice / 2 + 0.5}", 'grains = "outside"', "lo = -1.0", "hi = 0.0",
            'material = "wall"', f"active_until = {t_open}", "",
            "[[fill]]", 'material = "grain"', f"count = {count}", 'placement = "lattice"',
            "jitter = 0.02", "seed = 1", 'size = { distribution = "uniform", min = 0.45, max = 0.55 }',
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, 0.0], radius = {radius}, '
            f"lo = 0.0, hi = {fill_top} }}", "",
            "# refill: 1.3 x Beverloo's rate from above the bed, throttled where the region is full",
            "[[insert]]", 'name = "refill"', 'material = "grain"',
            f"rate = {1.3 * beverloo:.4g}", f"start = {t_open}", "interval = 0.08", "seed = 7",
            'size = { distribution = "uniform", min = 0.45, max = 0.55 }',
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, {height}], '
            f"radius = {radius - 0.5}, lo = 2.0, hi = 12.0 }}", "",
            "[[outlet]]", 'name = "orifice"',
            'region = { shape = "half_space", point = [0.0, 0.0, -3.0], normal = [0.0, 0.0, -1.0] }',
            "",
            "[[measure]]", 'name = "silo_mass"', 'quantity = "mass"',
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, 0.0], radius = {radius}, '
            f"lo = 0.0, hi = {top} }}",
            "[[measure]]", 'name = "height"', 'quantity = "surface_height"',
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, 0.0], radius = {radius - 1}, '
            f"lo = 0.0, hi = {top} }}",
            "[[measure]]", 'name = "ke"', 'quantity = "kinetic_per_grain"', ""]
    return "\n".join(out), f"{name}: {count} grains, W_beverloo = {beverloo:.4g} per unit time"


for orifice in (5, 6, 8, 10, 12):
    d = 2 * math.ceil((2.5 * orifice + 10) / 2)
    # the small orifices drain slowly and in bursts: a longer window for a steady rate
    discharge = 150.0 if orifice <= 6 else 40.0
    text, note = scene(f"beverloo-Do{orifice}", orifice, d, 1.6 * d, 25.0, discharge)
    (HERE / f"beverloo-Do{orifice}.toml").write_text(text)
    print(note)
text, note = scene("beverloo-small", 5, 16, 16.0, 15.0, 20.0)
(HERE / "beverloo-small.toml").write_text(text)
print(note)
