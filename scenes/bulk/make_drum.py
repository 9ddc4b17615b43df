#!/usr/bin/env python3
"""Writes the rotating-drum scenes: a drum of radius R = 10 d and length 10 d about the y axis (an
analytic [[cylinder]] with flat caps, turning at omega), 40 % filled by a [[fill]] lattice; the
dynamic angle of repose is the slope of a line fitted to the free surface across the middle of
the drum ([[measure]] quantity = "angle" along x), averaged over the run's second half.

    drum-fr<Fr>.toml   Froude numbers Fr = omega^2 R / g = 0.001, 0.003, 0.01, 0.03, 0.1
                       (the long suite: angle against Fr)
    drum-small.toml    Fr = 0.01 for 60 tau (the default tests)

Each run turns the drum through at least three quarters of a turn after a 20 tau spin-up.
Units: d = 1 (radii uniform in 0.45-0.55), grain density 6/pi (m = 1 for d = 1), g = 1.

usage: make_drum.py  (writes every file beside this script)
"""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
R, L = 10.0, 10.0
GRAIN_VOLUME = 4 / 3 * math.pi * (0.55**4 - 0.45**4) / (4 * 0.1)


def scene(name, froude, t_end=None):
    omega = math.sqrt(froude * 1.0 / R)
    if t_end is None:
        t_end = round(20 + 1.5 * math.pi / omega)
    count = round(0.6 * 0.4 * math.pi * R**2 * L / GRAIN_VOLUME)  # 40 % full
    out = [f"# Rotating drum, R = {R:g} d, L = {L:g} d, 40 % full ({count} grains), "
           f"Froude number {froude:g} (omega = {omega:.5g} / tau).",
           "# Written by make_drum.py.", "",
           'materials = ["grain", "drum"]', "", "[material.grain]",
           "density = 1.909859317 # m = 1 for d = 1", "",
           "[run]", f'name = "{name}"', "dt = 8.0e-4", f"t_end = {t_end}", "",
           "[output]", "energy_interval = 1.0", f"snapshot_interval = {t_end / 4:g}", "",
           "[checkpoint]", "every_minutes = 20", "",
           "[domain]", f"lo = [{-R - 1}, -1.0, {-R - 1}]", f"hi = [{R + 1}, {L + 1}, {R + 1}]",
           "gravity = [0.0, 0.0, -1.0]", "skin = 0.2", "",
           "[contact]", 'model = "linear"']
    for partner in ("grain", "drum"):
        out += ["[[contact.pair]]", f'materials = ["grain", "{partner}"]', "k_n = 2.0e4",
                "k_t = 5714.2857", "gamma_n = 50.0", "gamma_t = 25.0", "mu_s = 0.5", "mu_d = 0.5"]
    out += ["",
            "[[cylinder]]", 'name = "drum"', "center = [0.0, 0.0, 0.0]", "axis = [0.0, 1.0, 0.0]",
            f"radius = {R}", "lo = 0.0", f"hi = {L}", 'ends = "capped"', f"omega = {omega:.8g}",
            'material = "drum"', "",
            "[[fill]]", 'material = "grain"', f"count = {count}", 'placement = "lattice"',
            "jitter = 0.02", "seed = 3",
            'size = { distribution = "uniform", min = 0.45, max = 0.55 }',
            f'region = {{ shape = "cylinder", center = [0.0, 0.0, 0.0], axis = [0.0, 1.0, 0.0], '
            f"radius = {R}, lo = 0.0, hi = {L} }}", "",
            "[[measure]]", 'name = "angle"', 'quantity = "angle"', "direction = [1.0, 0.0, 0.0]",
            "bin = 1.0", "from = -5.0", "to = 5.0",
            f'region = {{ shape = "box", lo = [{-R}, 1.0, {-R}], hi = [{R}, {L - 1}, {R}] }}',
            "[[measure]]", 'name = "ke"', 'quantity = "kinetic_per_grain"',
            "[[measure]]", 'name = "drum"', 'quantity = "wall_force"', 'wall = "drum"', ""]
    (HERE / f"{name}.toml").write_text("\n".join(out))


for fr in (0.001, 0.003, 0.01, 0.03, 0.1):
    scene(f"drum-fr{fr:g}", fr)
scene("drum-small", 0.01, 60)
