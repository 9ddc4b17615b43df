// The [[shape]] tables of a scene file (docs/scene-format.md, "Clumps"): each names a clump of
// overlapping spheres, its members given inline (`spheres = [[x, y, z, r], ...]`) or read from
// a file (`file`: CSV or a sphere list, io/sphere_list_reader.hpp), scaled by `scale`; its mass
// properties and principal frame computed at once (scene/clump_shape.hpp); and the [[clump]]
// tables, each one clump of a shape placed where it says.
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

namespace yuxi {

void read_shapes(Scene& scene, TomlReader& root);
// The index of the [[shape]] that key `shape` of `t` names (fails naming the scene's shapes).
int shape_named(const Scene& scene, TomlReader& t);

} // namespace yuxi
