// The shaped walls of a scene file: [[mesh]] (a triangle mesh from an STL file) and
// [[cylinder]] (docs/scene-format.md, "Walls of any shape").
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

#include <cstdint>
#include <string_view>

namespace yuxi {

// Reads every [[mesh]] and [[cylinder]] table into scene.walls; a mesh file that cannot be read
// or holds bad triangles fails at its `file` key with the file's own message (and the place in
// it), a mesh that lies outside the box, or that its motion would carry out of it or across a
// periodic face, fails at the table. Needs [domain], [run] and the materials read first.
void read_shaped_walls(Scene& scene, TomlReader& root);

// The material named at `key`, which must be in the scene's materials list.
std::uint8_t material_of(const Scene& scene, TomlReader& t, std::string_view key);

} // namespace yuxi
