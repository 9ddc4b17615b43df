#!/usr/bin/env python3
"""Writes the inputs of the rotating-drum scenes: the drum as a binary STL (a closed cylinder of
`segments` facets about the y axis, with flat end caps) and its fill of grains as a LAMMPS data
file (atom style sphere: id type diameter density x y z), on a lattice in the lower part of the
drum, jittered in all three directions (unjittered along the axis, the layers never touch: the
bed would move as independent flat layers). Reduced units: grain diameter d = 1, mass 1 (density 6/pi), g = 1.

usage: make_drum.py [--radius R] [--length L] [--segments N] [--fill F] [--seed S]
                    [--rings K] [--bands B] [--ascii] OUTDIR
"""
import argparse
import math
import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from binary_stl import write_ascii_stl, write_binary_stl  # noqa: E402


def drum_triangles(radius, length, segments):
    ring = [(radius * math.cos(2 * math.pi * k / segments), radius * math.sin(2 * math.pi * k / segments))
            for k in range(segments)]
    tris = []
    for k in range(segments):
        (x0, z0), (x1, z1) = ring[k], ring[(k + 1) % segments]
        a, b, c, d = (x0, 0.0, z0), (x1, 0.0, z1), (x1, length, z1), (x0, length, z0)
        tris += [(a, b, c), (a, c, d)]                       # the side
        tris.append(((0.0, 0.0, 0.0), b, a))                 # the cap at y = 0
        tris.append(((0.0, length, 0.0), d, c))              # the cap at y = length
    return tris


def fine_drum_triangles(radius, length, segments, rings, bands):
    """The same closed drum with its side cut into `rings` along the axis and each cap into
    `bands` concentric annuli (a fan at the centre): triangles of about equal size, as a
    meshing tool would write them, for large drums."""
    def ring(r, y):
        return [(r * math.cos(2 * math.pi * k / segments), y, r * math.sin(2 * math.pi * k / segments))
                for k in range(segments)]
    tris = []
    for j in range(rings):
        lo, hi = ring(radius, length * j / rings), ring(radius, length * (j + 1) / rings)
        for k in range(segments):
            k1 = (k + 1) % segments
            tris += [(lo[k], lo[k1], hi[k1]), (lo[k], hi[k1], hi[k])]
    for y, facing in ((0.0, 1), (length, -1)):
        centre = (0.0, y, 0.0)
        inner = ring(radius / bands, y)
        for k in range(segments):
            a, b = inner[k], inner[(k + 1) % segments]
            tris.append((centre, b, a) if facing > 0 else (centre, a, b))
        for band in range(1, bands):
            i0, i1 = ring(radius * band / bands, y), ring(radius * (band + 1) / bands, y)
            for k in range(segments):
                k1 = (k + 1) % segments
                quad = [(i0[k], i1[k], i1[k1]), (i0[k], i1[k1], i0[k1])]
                tris += quad if facing > 0 else [(t[0], t[2], t[1]) for t in quad]
    return tris


def grains(radius, length, fill, seed):
    rng = random.Random(seed)
    spacing = 1.15
    out = []
    top = -radius + fill * 2 * radius  # the fill reaches this height (z)
    n = int(radius / spacing) + 1
    for i in range(-n, n + 1):
        for j in range(int(length / spacing) + 1):
            for k in range(-n, n + 1):
                x, y, z = i * spacing, 0.6 + j * spacing, k * spacing
                if y > length - 0.6 or z > top or math.hypot(x, z) > radius - 0.7:
                    continue
                d = rng.uniform(0.9, 1.0)
                out.append((d, x + rng.uniform(-0.05, 0.05), y + rng.uniform(-0.05, 0.05),
                            z + rng.uniform(-0.05, 0.05)))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--radius", type=float, default=10.0)
    p.add_argument("--length", type=float, default=4.0)
    p.add_argument("--segments", type=int, default=96)
    p.add_argument("--fill", type=float, default=0.4)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--rings", type=int, default=1, help="side cut into this many rings")
    p.add_argument("--bands", type=int, default=1, help="each cap cut into this many annuli")
    p.add_argument("--ascii", action="store_true",
                   help="also write the drum as ASCII STL (drum_ascii.stl), as LIGGGHTS reads it")
    p.add_argument("outdir", type=Path)
    a = p.parse_args()
    a.outdir.mkdir(parents=True, exist_ok=True)
    if a.rings == 1 and a.bands == 1:
        tris = drum_triangles(a.radius, a.length, a.segments)
    else:
        tris = fine_drum_triangles(a.radius, a.length, a.segments, a.rings, a.bands)
    write_binary_stl(a.outdir / "drum.stl", tris, "yuxi rotating drum")
    if a.ascii:
        # Through float32, as the binary file holds them: both files give the same mesh.
        import struct
        same = [tuple(struct.unpack("<3f", struct.pack("<3f", *v)) for v in t) for t in tris]
        write_ascii_stl(a.outdir / "drum_ascii.stl", same, "drum")
    g = grains(a.radius, a.length, a.fill, a.seed)
    density = 6 / math.pi
    with open(a.outdir / "grains.data", "w") as f:
        f.write(f"rotating drum fill: {len(g)} grains (make_drum.py)\n\n{len(g)} atoms\n\n1 atom types\n\n")
        f.write(f"{-a.radius - 1} {a.radius + 1} xlo xhi\n-1 {a.length + 1} ylo yhi\n")
        f.write(f"{-a.radius - 1} {a.radius + 1} zlo zhi\n\nAtoms # sphere\n\n")
        for k, (d, x, y, z) in enumerate(g, 1):
            f.write(f"{k} 1 {d:.6f} {density:.12g} {x:.6f} {y:.6f} {z:.6f}\n")
    print(f"{a.outdir}/drum.stl: {len(tris)} triangles; "
          f"{a.outdir}/grains.data: {len(g)} grains")


if __name__ == "__main__":
    main()
