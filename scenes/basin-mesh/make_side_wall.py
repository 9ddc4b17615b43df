#!/usr/bin/env python3
"""Writes side_wall.stl: an open vertical tube (no caps) of `segments` facets, the smooth side
wall of scenes/basin-mesh.toml. Its vertices follow the basin's radial mode in the scene.

usage: make_side_wall.py [--radius R] [--center X Y] [--z0 Z] [--height H] [--segments N] OUT
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from binary_stl import write_binary_stl  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--radius", type=float, default=30.0)
    p.add_argument("--center", type=float, nargs=2, default=[36.0, 36.0])
    p.add_argument("--z0", type=float, default=0.0)
    p.add_argument("--height", type=float, default=48.0)
    p.add_argument("--segments", type=int, default=192)
    p.add_argument("out")
    a = p.parse_args()
    cx, cy = a.center
    ring = [(cx + a.radius * math.cos(2 * math.pi * k / a.segments),
             cy + a.radius * math.sin(2 * math.pi * k / a.segments)) for k in range(a.segments)]
    tris = []
    for k in range(a.segments):
        (x0, y0), (x1, y1) = ring[k], ring[(k + 1) % a.segments]
        lo0, lo1 = (x0, y0, a.z0), (x1, y1, a.z0)
        hi0, hi1 = (x0, y0, a.z0 + a.height), (x1, y1, a.z0 + a.height)
        tris += [(lo0, lo1, hi1), (lo0, hi1, hi0)]
    write_binary_stl(a.out, tris, "yuxi basin side wall")
    print(f"{a.out}: {len(tris)} triangles")


if __name__ == "__main__":
    main()
