#!/usr/bin/env python3
"""Writes a LAMMPS data file (atom_style sphere, with a Velocities section) from one frame of a
yuxi LAMMPS dump (columns id type radius mass x y z vx vy vz omegax omegay omegaz ...), so that
LAMMPS starts from the same state as yuxi.

LAMMPS ids start at 1: yuxi's global ids (from 0) are shifted by one. Particles of the types
given with --heavy get a density a million times their own: yuxi takes m_eff = m_grain
against a wall particle, LAMMPS m_i m_j / (m_i + m_j), which this makes equal.

usage: lammps_data_from_dump.py DUMP DATA [--frame first|last] [--heavy TYPE ...]
"""
import argparse
import math
import sys


def read_frame(path, which):
    frame = None
    with open(path) as f:
        lines = iter(f)
        for line in lines:
            if line.strip() != "ITEM: TIMESTEP":
                continue
            step = int(next(lines))
            next(lines)  # ITEM: NUMBER OF ATOMS
            n = int(next(lines))
            next(lines)  # ITEM: BOX BOUNDS ...
            box = [tuple(float(v) for v in next(lines).split()[:2]) for _ in range(3)]
            columns = next(lines).split()[2:]
            rows = [next(lines).split() for _ in range(n)]
            frame = (step, box, columns, rows)
            if which == "first":
                break
    if frame is None:
        sys.exit(f"{path}: no frame found (not a LAMMPS dump?)")
    return frame


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dump")
    ap.add_argument("data")
    ap.add_argument("--frame", choices=["first", "last"], default="last")
    ap.add_argument("--heavy", type=int, nargs="*", default=[])
    a = ap.parse_args()
    step, box, columns, rows = read_frame(a.dump, a.frame)
    need = ["id", "type", "radius", "mass", "x", "y", "z", "vx", "vy", "vz", "omegax", "omegay",
            "omegaz"]
    missing = [c for c in need if c not in columns]
    if missing:
        sys.exit(f"{a.dump}: the dump lacks the columns {' '.join(missing)}")
    col = {c: columns.index(c) for c in need}
    types = max(int(r[col["type"]]) for r in rows)
    with open(a.data, "w") as out:
        out.write(f"LAMMPS data file from the yuxi dump {a.dump}, step {step}\n\n")
        out.write(f"{len(rows)} atoms\n{types} atom types\n\n")
        for (lo, hi), axis in zip(box, "xyz"):
            out.write(f"{lo:.10g} {hi:.10g} {axis}lo {axis}hi\n")
        out.write("\nAtoms # sphere\n\n")
        for r in rows:
            radius, mass = float(r[col["radius"]]), float(r[col["mass"]])
            density = mass / (4.0 / 3.0 * math.pi * radius**3)
            if int(r[col["type"]]) in a.heavy:
                density *= 1e6
            out.write(f"{int(r[col['id']]) + 1} {r[col['type']]} {2 * radius:.10g} "
                      f"{density:.10g} {r[col['x']]} {r[col['y']]} {r[col['z']]}\n")
        out.write("\nVelocities\n\n")
        for r in rows:
            out.write(f"{int(r[col['id']]) + 1} {r[col['vx']]} {r[col['vy']]} {r[col['vz']]} "
                      f"{r[col['omegax']]} {r[col['omegay']]} {r[col['omegaz']]}\n")


if __name__ == "__main__":
    main()
