#!/usr/bin/env python3
"""Writes a basin scene in LAMMPS conventions, for the speed comparison with LAMMPS
(bench/peers/in.basin): one friction coefficient (mu_s = mu_d = 0.5, gran/hooke/history has one), the
grain-grain law of the scene for every pair, the LAMMPS preset of the linear model, no analysis,
and snapshots only every 10 tau (so that the settled state at t = 10 tau is written as a dump).

Writes OUT/basin-vibrating.toml (excited from the scene's t0) and OUT/basin-still.toml (never).

usage: lammps_basin_scene.py SCENE OUT
"""
import re
import sys


def grain_grain_law(scene):
    """The k_n, k_t, gamma_n, gamma_t lines of the scene's grain-grain [[contact.pair]]."""
    for block in scene.split("[[contact.pair]]")[1:]:
        if re.search(r'materials\s*=\s*\["grain",\s*"grain"\]', block):
            keys = ("k_n", "k_t", "gamma_n", "gamma_t")
            lines = [l.split("#")[0].strip() for l in block.splitlines()]
            law = [l for l in lines if l.split("=")[0].strip() in keys]
            if len(law) == len(keys):
                return "\n".join(law) + "\nmu_s = 0.5\n"
    sys.exit("lammps_basin_scene.py: the scene has no complete grain-grain [[contact.pair]]")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source, out = sys.argv[1], sys.argv[2]
    s = open(source).read()
    s = s[: s.index("[analysis]")] if "[analysis]" in s else s
    law = grain_grain_law(s)
    pairs = "".join(f'[[contact.pair]]\nmaterials = ["grain", "{m}"]\n{law}\n'
                    for m in ("grain", "wall"))
    s = s[: s.index("[[contact.pair]]")] + pairs + s[s.index("[basin]"):]
    s = s.replace('model = "linear"', 'model = "linear"\npreset = "lammps"')
    s = re.sub(r"snapshot_interval = [0-9.e+-]+", "snapshot_interval = 10.0", s)
    open(f"{out}/basin-vibrating.toml", "w").write(s)
    open(f"{out}/basin-still.toml", "w").write(s.replace("t0 = 10.0", "t0 = 1.0e9"))


if __name__ == "__main__":
    main()
