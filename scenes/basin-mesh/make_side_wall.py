#!/usr/bin/env python3
"""Writes side_wall.stl: an open vertical tube (no caps) of `segments` facets, the smooth side
wall of scenes/basin-mesh.toml. Its vertices follow the basin's radial mode in the scene.

usage: make_side_wall.py [--radius R] [--center X Y] [--z0 Z] [--height H] [--segments N] OUT
"""
import argparse
import math
import struct


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
    with open(a.out, "wb") as f:
        f.write(b"yuxi basin side wall".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for v in t:
                f.write(struct.pack("<3f", *v))
            f.write(struct.pack("<H", 0))
    print(f"{a.out}: {len(tris)} triangles")


if __name__ == "__main__":
    main()
