// Reads an STL file, the triangle mesh of a wall, as a soup of triangles in file order. Accepts
//   ASCII STL:  solid [name] / facet normal nx ny nz / outer loop / vertex x y z (three times) /
//               endloop / endfacet / ... / endsolid [name]   (keywords in any case; several
//               solids one after the other are read as one mesh)
//   binary STL: an 80-byte header, a uint32 triangle count, then 50 bytes per triangle: normal,
//               three vertices (float32 x y z each), uint16 attribute; all little-endian.
// A file is binary when 84 + 50 * count is exactly its size (even when its header starts with
// "solid", as many exporters write it), otherwise ASCII when it starts with "solid", otherwise
// binary. The stored facet normals are ignored: the vertex order defines the triangle.
// Triangles of zero area are left out and counted. Any malformed file is a MeshFileError whose
// message starts with "<file>: " and names the place: the line for ASCII, the triangle
// (numbered from 1) and its byte offset for binary.
#pragma once

#include "core/vec3.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi {

class MeshFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct TriangleSoup {
  std::vector<std::array<Vec3, 3>> triangles; // as read, in file order
  // Triangles left out for zero area: two equal vertices, or collinear to round-off
  // (|(b - a) x (c - a)| <= 1e-12 * (longest edge)^2).
  std::size_t dropped_degenerate = 0;
  std::uint32_t crc32 = 0; // zlib's CRC-32 of the file's bytes
  std::uint64_t bytes = 0; // the file's size
};

// Parses the bytes of an STL file; `source_name` names it in errors.
TriangleSoup parse_stl(std::string_view bytes, const std::string& source_name);

// Reads the file at `path` (an error naming it when it is missing or unreadable), then parses it.
TriangleSoup read_stl(const std::string& path);

} // namespace yuxi
