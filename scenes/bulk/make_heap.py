#!/usr/bin/env python3
"""Writes the heap scenes (docs/models/validation.md, B1): grains poured from a narrow region high
above the heap's apex onto a rough floor (a disc of fixed wall particles on a jittered lattice) pile into a cone; the angle
of repose is the slope of a line fitted to the free surface against the distance from the axis
([[measure]] quantity = "angle"). Grains that roll off the floor's edge fall into an outlet.

    heap-mu<mu>.toml          N = 4000 on a floor of radius 22 d, mu_s = mu_d = 0.1, 0.3, 0.5, 1.0  (the long suite)
    heap-mu<mu>-seed<k>.toml  the same with other random floors and pours, k = 2, 3: the angle
                              against mu_s is compared by the mean of three heaps
    heap-mu0.5-stiff.toml     k_n x 10 (dt / sqrt(10))
    heap-mu0.5-e0.5.toml, heap-mu0.5-e0.9.toml   restitution 0.5 and 0.9 (else about 0.68)
                              (each also -seed2 and -seed3, compared by the mean of three)
    heap-mu0.5-mur<mu_r>.toml rolling resistance mu_r = 0.05, 0.1, 0.2 (k_r = k_t / 2)
    heap-small.toml           N = 1200 on a floor of radius 14 d, mu = 0.5 (the default tests)

Units: d = 1 (radii uniform in 0.45-0.55), grain density 6/pi (m = 1 for d = 1), g = 1.
The linear law caps the whole tangential force at mu |F_n| (friction_cap = "total"), except in
heap-small, which keeps the paper's cap on the spring alone. The long heaps are poured gently,
from 2-6 d above the apex of a 30-degree cone at 0.5 sqrt(g d); heap-small from above a
40-degree cone at 2 sqrt(g d), as its checks were set.

usage: make_heap.py  (writes every file beside this script)
"""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent


def gamma_for(e, k, m):
    """The damping rate giving restitution e (docs/models/validation.md L1)."""
    le = math.log(e)
    return 2 * math.sqrt(k / m) * -le / math.sqrt(math.pi**2 + le**2)


def rod_volume(rod):
    """The volume of `rod` spheres of d = 1 in a row, 0.5 d apart: each after the first adds a
    sphere less its lens with the one before, pi (4 r + s) (2 r - s)^2 / 12 (r = 0.5, s = 0.5)."""
    sphere = math.pi / 6
    lens = math.pi * (4 * 0.5 + 0.5) * (2 * 0.5 - 0.5) ** 2 / 12
    return sphere + (rod - 1) * (sphere - lens)


def scene(name, grains, floor, mu=0.5, stiff=1.0, e=None, mu_r=0.0, seed=1, coulomb=True,
          gentle=True, rod=1, cone=None, folder=HERE):
    """rod > 1: the grains are clumps of `rod` spheres of d = 0.9-1.1 in a row, 0.5 d apart
    (aspect ratio 1 + 0.5 (rod - 1)), poured at the sphere heap's rate of volume; `grains`
    counts clumps. `cone`: the source above a cone of this angle [degrees] (else by `gentle`)."""
    k_n = 2.0e4 * stiff
    gamma_n = 50.0 * math.sqrt(stiff) if e is None else gamma_for(e, k_n, 0.5)
    dt = 8.0e-4 / math.sqrt(stiff)
    rate = 25.0 * rod_volume(1) / rod_volume(rod)
    pour = grains / rate
    t_end = round(pour + 25)
    # The source 2-6 d above the apex of a cone on the floor: the heap's apex must never reach it
    # (a capped apex would fix the angle at atan(apex / floor radius)). A gentle pour: a 30-degree
    # cone and a start at 0.5 sqrt(g d) down. The grains land about 6-10 d below the source. From
    # a 40-degree cone at 2 sqrt(g d) they landed from 13-17 d, and at e = 0.9 the heap came out
    # 2 degrees flatter (docs/results/bulk, B1).
    cone, speed = (30, 0.5) if gentle else (40, 2.0) if cone is None else (cone, 0.5)
    source_top = floor * math.tan(math.radians(cone)) + 6
    # (a rod's whole bounding ball must fit in the source, and rods still falling through it
    # leave room for the next: a source wider and taller by twice the rod's extra length)
    bounding = 0.5 + 0.25 * (rod - 1)  # (the size drawn for a clump: its bounding radius)
    extra = 2 * (bounding - 0.5)
    top = source_top + 2 * extra
    out = [f"# Heap: {grains} grains poured onto a rough floor of radius {floor} d; mu_s = mu_d = "
           f"{mu}, k_n = {k_n:g}, gamma_n = {gamma_n:.4g}, mu_r = {mu_r}"
           + (f"; random floor and pour {seed}." if seed != 1 else "."),
           "# Written by make_heap.py; docs/models/validation.md (B1).", "",
           'materials = ["grain", "floor"]', "", "[material.grain]",
           "density = 1.909859317 # m = 1 for d = 1", "",
           "[run]", f'name = "{name}"', f"dt = {dt:.6g}", f"t_end = {t_end}", "",
           "[output]", "energy_interval = 1.0", f"snapshot_interval = {t_end / 4}", "",
           "[checkpoint]", "every_minutes = 20", "",
           "[domain]", f"lo = [{-floor - 4}, {-floor - 4}, -8.0]",
           f"hi = [{floor + 4}, {floor + 4}, {top + 4}]", "gravity = [0.0, 0.0, -1.0]", "skin = 0.2",
           'on_escape = "remove" # grains that bounce off sideways', "",
           "[contact]", 'model = "linear"']
    if rod > 1:
        spheres = ", ".join(f"[{0.5 * k:g}, 0.0, 0.0, 0.5]" for k in range(rod))
        out[out.index("[contact]"):out.index("[contact]")] = [
            "[[shape]]", f'name = "rod{rod}"', f"spheres = [{spheres}]", ""]
    for partner in ("grain", "floor"):
        out += ["[[contact.pair]]", f'materials = ["grain", "{partner}"]', f"k_n = {k_n:g}",
                f"k_t = {k_n * 2 / 7:.8g}", f"gamma_n = {gamma_n:.8g}",
                f"gamma_t = {gamma_n / 2:.8g}", f"mu_s = {mu}", f"mu_d = {mu}"]
        # Coulomb's limit on the whole tangential force: a sliding contact carries mu |F_n|.
        # Under the paper's cap on the spring alone the dashpot adds m_eff gamma_t |u| on top,
        # often several times mu |F_n| in a heap's flowing layer, and the angle hardly follows
        # mu_s (docs/results/bulk, B1).
        if coulomb:
            out += ['friction_cap = "total"']
        if mu_r > 0:
            out += [f"k_r = {k_n / 7:.8g}", f"mu_r = {mu_r}"]
    # (fixed wall particles never push each other; the reader asks for every pair that can touch)
    out += ["[[contact.pair]]", 'materials = ["floor", "floor"]', f"k_n = {k_n:g}"]
    out += ["",
            "# the rough floor: fixed wall particles on a jittered lattice",
            "[[fill]]", 'kind = "wall"', 'material = "floor"', "radius = 0.5",
            'placement = "lattice"', "jitter = 0.1", "packing_fraction = 0.25"]
    # (seed 1: the sources' default streams; another seed, other streams for both)
    out += [f"seed = {2008 + 100 * seed}"] if seed != 1 else []
    out += [
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, 0.0], radius = {floor}, '
            "lo = -0.61, hi = 0.61 }", "",
            "[[insert]]", 'name = "pour"', 'material = "grain"', f"rate = {rate}",
            f"total = {grains}", "interval = 0.08", f"velocity = [0.0, 0.0, {-speed}]",
            "velocity_spread = 0.3"]
    out += [f'size = {{ distribution = "uniform", min = {0.9 * bounding:g}, '
            f"max = {1.1 * bounding:g} }}"]
    out += [f'shape = "rod{rod}"'] if rod > 1 else []
    out += [f"seed = {3008 + 100 * seed}"] if seed != 1 else []
    out += [
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, {source_top - 4}], '
            f"radius = {3.0 + extra}, lo = 0.0, hi = {4.0 + 2 * extra} }}", "",
            "[[outlet]]", 'name = "off_the_floor"',
            'region = { shape = "half_space", point = [0.0, 0.0, -4.0], normal = [0.0, 0.0, -1.0] }',
            "",
            "[[measure]]", 'name = "angle"', 'quantity = "angle"', "axis_point = [0.0, 0.0, 0.0]",
            "bin = 2.0", f"from = {0.2 * floor:.3g}", f"to = {0.7 * floor:.3g}",
            "[[measure]]", 'name = "height"', 'quantity = "surface_height"',
            'region = { shape = "cylinder", center = [0.0, 0.0, 0.0], radius = 3.0, lo = 0.0, '
            f"hi = {source_top - 4} }}",
            "[[measure]]", 'name = "heap_mass"', 'quantity = "mass"',
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, 0.0], radius = {floor + 2}, '
            f"lo = 0.0, hi = {top + 4} }}",
            "[[measure]]", 'name = "ke"', 'quantity = "kinetic_per_grain"', ""]
    (folder / f"{name}.toml").write_text("\n".join(out))


for mu in (0.1, 0.3, 0.5, 1.0):
    scene(f"heap-mu{mu}", 4000, 22.0, mu=mu)
    for seed in (2, 3):
        scene(f"heap-mu{mu}-seed{seed}", 4000, 22.0, mu=mu, seed=seed)
for seed in (1, 2, 3):
    tail = f"-seed{seed}" if seed != 1 else ""
    scene(f"heap-mu0.5-stiff{tail}", 4000, 22.0, stiff=10.0, seed=seed)
    for e in (0.5, 0.9):
        scene(f"heap-mu0.5-e{e}{tail}", 4000, 22.0, e=e, seed=seed)
for mu_r in (0.05, 0.1, 0.2):
    scene(f"heap-mu0.5-mur{mu_r}", 4000, 22.0, mu_r=mu_r)
# (the small heap checks the mechanics in the default tests: counts, books, a cone; it keeps the
# paper's cap, with which its checks were set)
scene("heap-small", 1200, 14.0, coulomb=False, gentle=False)
# Heaps of rods (docs/results/clumps): the same volume as 1200 spheres on the small floor, with
# Coulomb's cap, poured from above a 40-degree cone at 0.5 sqrt(g d); three pours each.
for rod in (1, 2, 3, 5):
    for seed in (1, 2, 3):
        tail = f"-seed{seed}" if seed != 1 else ""
        scene(f"heap-rod{rod}{tail}", round(1200 * rod_volume(1) / rod_volume(rod)), 14.0,
              rod=rod, cone=40, seed=seed, folder=HERE.parent / "clumps")
