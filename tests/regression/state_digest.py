#!/usr/bin/env python3
"""Prints a SHA-256 of every particle's position, velocity and angular velocity, in id order,
from a VTK frame that yuxi wrote (particles_<step>.vtu: raw appended little-endian arrays).

Two runs whose digests agree hold the same bits in x, v and w for every particle, however
their ranks split the particles (a frame holds each rank's particles in turn).

usage: state_digest.py FRAME.vtu
"""
import hashlib
import re
import struct
import sys


def arrays(path):
    raw = open(path, "rb").read()
    head, _, data = raw.partition(b'<AppendedData encoding="raw">\n_')
    if not data:
        sys.exit(f"{path}: no raw appended data (not a yuxi VTK frame)")
    n = int(re.search(rb'NumberOfPoints="(\d+)"', head).group(1))
    out = {}
    for m in re.finditer(rb'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" '
                         rb'format="appended" offset="(\d+)"', head):
        kind, name, comps, offset = m.group(1).decode(), m.group(2).decode(), int(m.group(3)), \
            int(m.group(4))
        size = struct.unpack_from("<Q", data, offset)[0]
        out[name] = (kind, comps, data[offset + 8: offset + 8 + size])
    return n, out


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    n, a = arrays(sys.argv[1])
    ids = struct.unpack(f"<{n}q", a["id"][2])
    order = sorted(range(n), key=lambda k: ids[k])
    digest = hashlib.sha256()
    for name in ("Points", "velocity", "angular_velocity"):
        kind, comps, data = a[name]
        width = 8 * comps
        for k in order:
            digest.update(data[k * width:(k + 1) * width])
    print(f"{n} particles, x v w sha256 {digest.hexdigest()}")


main()
