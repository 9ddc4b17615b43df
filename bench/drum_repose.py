#!/usr/bin/env python3
"""The dynamic angle of repose of a rotating drum from a LAMMPS dump of its grains.

The drum turns about the y axis; in each frame the grains' (x, z) positions form the bed's
cross-section, a circular segment whose chord is the free surface. The chord is parallel to the
principal axis of the segment's second moments, so the surface's angle to the horizontal is the
angle of the covariance matrix's major eigenvector. The angle is averaged over the frames from
--from on; its standard error comes from --blocks consecutive blocks of frames (frames closer
than an avalanche are not independent).

usage: drum_repose.py DUMP [--from T_FRAME_STEP] [--blocks 5] [--dt DT]
prints: mean angle [degrees], standard error, frames used
"""
import argparse
import math
import statistics


def frames(path):
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                return
            if not line.startswith("ITEM: TIMESTEP"):
                continue
            step = int(f.readline())
            f.readline()
            n = int(f.readline())
            for _ in range(4):
                f.readline()
            cols = f.readline().split()[2:]
            ix, iz = cols.index("x"), cols.index("z")
            xs, zs = [], []
            for _ in range(n):
                v = f.readline().split()
                xs.append(float(v[ix]))
                zs.append(float(v[iz]))
            yield step, xs, zs


def surface_angle(xs, zs):
    mx, mz = statistics.fmean(xs), statistics.fmean(zs)
    sxx = statistics.fmean([(x - mx) ** 2 for x in xs])
    szz = statistics.fmean([(z - mz) ** 2 for z in zs])
    sxz = statistics.fmean([(x - mx) * (z - mz) for x, z in zip(xs, zs)])
    # the major axis of [[sxx, sxz], [sxz, szz]]
    return math.degrees(0.5 * math.atan2(2 * sxz, sxx - szz))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dump")
    p.add_argument("--from-step", type=int, default=0)
    p.add_argument("--blocks", type=int, default=5)
    a = p.parse_args()
    angles = [surface_angle(xs, zs) for step, xs, zs in frames(a.dump) if step >= a.from_step]
    if len(angles) < a.blocks:
        raise SystemExit(f"{a.dump}: {len(angles)} frames after step {a.from_step}, too few")
    size = len(angles) // a.blocks
    means = [statistics.fmean(angles[k * size:(k + 1) * size]) for k in range(a.blocks)]
    mean = statistics.fmean(angles[: size * a.blocks])
    err = statistics.stdev(means) / math.sqrt(a.blocks)
    print(f"{mean:.2f} {err:.2f} {size * a.blocks}")


if __name__ == "__main__":
    main()
