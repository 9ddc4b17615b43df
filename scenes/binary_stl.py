"""Writes a list of triangles as a binary STL file (for the scene generators beside it): an
80-byte header, the uint32 count, then per triangle a zero normal, three float32 vertices and
a uint16 attribute, little-endian; or as an ASCII STL, for programs that read only that
(LIGGGHTS: bench/)."""
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


def write_ascii_stl(path, tris, name):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for t in tris:
            f.write("facet normal 0 0 0\nouter loop\n")
            for v in t:
                f.write("vertex %.7g %.7g %.7g\n" % tuple(v))
            f.write("endloop\nendfacet\n")
        f.write(f"endsolid {name}\n")
