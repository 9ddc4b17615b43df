#!/usr/bin/env python3
"""Writes the Janssen silo scenes (docs/models/validation.md, B2): silos side by side in one box,
each an analytic cylinder (the side wall) standing on its own floor (the top of a flat puck), so
that walls.csv and measurements.csv give every silo's bottom and side forces apart.

    janssen.toml        D = 20 d, fill heights 0.5, 1, 2, 3, 4 and 6 D with mu_w = 0.5, and 1 D
                        with mu_w = 0 (about 125,000 grains; the long suite)
    janssen-small.toml  D = 10 d, 1 and 2 D with mu_w = 0.5, 1 D with mu_w = 0 (3,600 grains;
                        the default tests)
    janssen-lowered.toml  janssen.toml's silos, their floors then lowered by 0.2 d at 0.02 d/tau
                        and the beds left to settle again; branched from janssen.toml's settled
                        state (yuxi run janssen-lowered.toml --from <janssen's run folder>)

Units: d = 1 (radii uniform in 0.45-0.55), grain density 6/pi (m = 1 for d = 1), g = 1.
The linear law caps the whole tangential force at mu |F_n| (friction_cap = "total"), except in
janssen-small, which keeps the paper's cap on the spring alone, as its checks were set.
Each silo is poured in stages of one diameter of height: stage j pours its grains from a region
2-12 d above the height the stage fills to, so that no grain falls more than D + 12 d. The grains
then settle; Janssen's wall friction is mobilised by the grains settling along the wall. Settling
leaves it little mobilised near the top of a bed, so the lowered variant then sinks every floor a
little, as silo experiments do (Vanel & Clement, Eur. Phys. J. B 11 (1999) 525): the whole bed
slides down along the wall and its friction is mobilised everywhere.

usage: make_janssen.py  (writes both files beside this script)
"""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
R_MEAN_CUBE = (0.55**4 - 0.45**4) / (4 * 0.1)  # <r^3> of r uniform in [0.45, 0.55]
GRAIN_VOLUME = 4 / 3 * math.pi * R_MEAN_CUBE
PHI = 0.6  # the settled packing fraction the counts aim at


def scene(name, diameter, silos, rate, settle, comment, lowered=None, coulomb=True):
    """lowered: (speed, travel, settle) of the floors, which start sinking at the end of the
    pour-and-settle run; None for that run itself. coulomb: the linear law caps the whole
    tangential force at mu |F_n| (friction_cap = "total"), else the spring alone (the paper's
    scheme, whose dashpot adds to a sliding contact's friction)."""
    radius = diameter / 2
    pitch = diameter + 2.0
    columns = min(4, len(silos))
    rows = math.ceil(len(silos) / columns)
    per_height = PHI * math.pi * radius**2 / GRAIN_VOLUME
    counts = [round(per_height * h * diameter) for h, _ in silos]
    per_stage = round(per_height * diameter)
    stages = max(math.ceil(c / per_stage) for c in counts)
    top = (stages + 1) * diameter + 14
    t_end = round(stages * per_stage / rate + settle)
    motion = []
    if lowered:
        speed, travel, again = lowered
        t0, t1 = t_end, t_end + travel / speed
        t_end = round(t1 + again)
        motion = [f"velocity = [0.0, 0.0, {-speed}]", f"t0 = {t0}", f"t1 = {t1:.6g}"]
    out = [f"# {comment}", "# Written by make_janssen.py; docs/models/validation.md (B2).", ""]
    out += ['materials = ["grain", "wall", "smooth"]', "", "[material.grain]",
            "density = 1.909859317 # m = 1 for d = 1", "",
            "[run]", f'name = "{name}"', "dt = 8.0e-4", f"t_end = {t_end}", "",
            "[output]", "energy_interval = 1.0", "snapshot_interval = 20.0", "",
            "[checkpoint]", "every_minutes = 20", "",
            "[domain]", "lo = [0.0, 0.0, -2.0]",
            f"hi = [{columns * pitch}, {rows * pitch}, {math.ceil(top) + 2.0}]",
            'boundary = ["wall", "wall", "wall"]', "gravity = [0.0, 0.0, -1.0]", "skin = 0.2",
            'wall_material = "wall"', "",
            "[contact]", 'model = "linear"']
    for partner, mu in (("grain", 0.5), ("wall", 0.5), ("smooth", 0.0)):
        out += ["[[contact.pair]]", f'materials = ["grain", "{partner}"]', "k_n = 2.0e4",
                "k_t = 5714.2857", "gamma_n = 50.0", "gamma_t = 25.0", f"mu_s = {mu}",
                f"mu_d = {mu}"]
        out += ['friction_cap = "total"'] if coulomb else []
    out.append("")
    for k, ((height, material), count) in enumerate(zip(silos, counts)):
        x = pitch / 2 + pitch * (k % columns)
        y = pitch / 2 + pitch * (k // columns)
        tag = f"s{k + 1}"
        out += [f"# silo {tag}: H = {height} D, wall {material}, {count} grains",
                "[[cylinder]]", f'name = "{tag}_side"', f"center = [{x}, {y}, 0.0]",
                f"radius = {radius}", f'material = "{material}"',
                "[[cylinder]]", f'name = "{tag}_floor"', f"center = [{x}, {y}, 0.0]",
                f"radius = {radius + 0.5}", 'grains = "outside"', "lo = -1.0", "hi = 0.0",
                'material = "wall"',
                ] + motion
        for j in range(math.ceil(count / per_stage)):
            n = min(per_stage, count - j * per_stage)
            level = (j + 1) * diameter
            out += ["[[insert]]", f'name = "{tag}_stage{j + 1}"', 'material = "grain"',
                    f"rate = {rate}", f"start = {j * per_stage / rate:.6g}", f"total = {n}",
                    "interval = 0.08", f"seed = {100 * (k + 1) + j}",
                    'size = { distribution = "uniform", min = 0.45, max = 0.55 }',
                    f'region = {{ shape = "cylinder", center = [{x}, {y}, {level}], '
                    f"radius = {radius - 0.5}, lo = 2.0, hi = 12.0 }}"]
        out += ["[[measure]]", f'name = "{tag}_mass"', 'quantity = "mass"',
                f'region = {{ shape = "cylinder", center = [{x}, {y}, -1.0], radius = {radius}, '
                f"lo = 0.0, hi = {math.ceil(top) + 2} }}",
                "[[measure]]", f'name = "{tag}_height"', 'quantity = "surface_height"',
                f'region = {{ shape = "cylinder", center = [{x}, {y}, -1.0], '
                f"radius = {radius - 1.0}, lo = 0.0, hi = {math.ceil(top) + 2} }}",
                "[[measure]]", f'name = "{tag}_floor"', 'quantity = "wall_force"',
                f'wall = "{tag}_floor"',
                "[[measure]]", f'name = "{tag}_side"', 'quantity = "wall_force"',
                f'wall = "{tag}_side"', "",
                # the column's profile at the end: density, stress and the walls' force
                # density along z, averaged over the square about the silo
                "[[coarse_grain]]", f'name = "{tag}_column"', "width = 1.0",
                f"lo = [{x - radius}, {y - radius}, 0.0]",
                f"hi = [{x + radius}, {y + radius}, {math.ceil(top)}]",
                'average = "xy"', f"n = [1, 1, {2 * math.ceil(top)}]", f"interval = {t_end}",
                'fields = ["density", "stress", "wall_force_density"]', ""]
    out += ["[[measure]]", 'name = "ke"', 'quantity = "kinetic_per_grain"', ""]
    return "\n".join(out)


(HERE / "janssen.toml").write_text(scene(
    "janssen", 20.0,
    [(0.5, "wall"), (1, "wall"), (2, "wall"), (3, "wall"), (4, "wall"), (6, "wall"),
     (1, "smooth")], 400.0, 55.0,
    "Janssen silos: D = 20 d, H = 0.5-6 D with mu_w = 0.5, and 1 D with mu_w = 0."))
(HERE / "janssen-lowered.toml").write_text(scene(
    "janssen-lowered", 20.0,
    [(0.5, "wall"), (1, "wall"), (2, "wall"), (3, "wall"), (4, "wall"), (6, "wall"),
     (1, "smooth")], 400.0, 55.0,
    "Janssen silos of janssen.toml, their floors then lowered by 0.2 d to mobilise the wall "
    "friction.", lowered=(0.02, 0.2, 150.0)))
(HERE / "janssen-small.toml").write_text(scene(
    "janssen-small", 10.0, [(1, "wall"), (2, "wall"), (1, "smooth")], 150.0, 30.0,
    "Janssen silos, small: D = 10 d, H = 1 and 2 D with mu_w = 0.5, and 1 D with mu_w = 0.",
    coulomb=False))
