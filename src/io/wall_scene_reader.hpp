// The shaped walls of a scene file: [[mesh]] (a triangle mesh from an STL file) and
// [[cylinder]] (docs/scene-format.md, "Walls of any shape").
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace yuxi {

// Reads every [[mesh]] and [[cylinder]] table into scene.walls; a mesh file that cannot be read
// or holds bad triangles fails at its `file` key with the file's own message (and the place in
// it), a mesh that lies outside the box, or that its motion would carry out of it or across a
// periodic face, fails at the table. Needs [domain], [run] and the materials read first.
void read_shaped_walls(Scene& scene, TomlReader& root);

// The material named at `key`, which must be in the scene's materials list.
std::uint8_t material_of(const Scene& scene, TomlReader& t, std::string_view key);

// The vector at `key` (or `fallback`) made unit length; fails at the key if it is zero.
Vec3 unit_vector(TomlReader& t, std::string_view key, Vec3 fallback);

// A triangle mesh from the STL file named at `file` (relative to the scene's folder), welded and
// placed by `scale`, `rotate_axis`, `rotate_degrees` and `translate`, as [[mesh]] walls and mesh
// regions read it. A file that cannot be read fails at `file` with the file's own message; a
// placement that leaves non-finite coordinates fails at `scale`.
struct PlacedMesh {
  std::string file; // absolute
  std::uint32_t crc32 = 0;
  std::size_t dropped_degenerate = 0; // zero-area triangles left out
  TriangleMesh mesh;
  double scale = 1.0;
  Vec3 rotate_axis{0, 0, 1};
  double rotate_degrees = 0.0;
  Vec3 translate;
};
PlacedMesh read_placed_mesh(const Scene& scene, TomlReader& t);

} // namespace yuxi
