"""Writes a list of triangles as a binary STL file (for the scene generators beside it): an
80-byte header, the uint32 count, then per triangle a zero normal, three float32 vertices and
a uint16 attribute, little-endian."""
import struct


def write_binary_stl(path, tris, header):
    with open(path, "wb") as f:
        f.write(header.encode().ljust(80, b" ")[:80])
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for v in t:
                f.write(struct.pack("<3f", *v))
            f.write(struct.pack("<H", 0))
