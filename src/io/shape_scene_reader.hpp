// The [[shape]] tables of a scene file (docs/scene-format.md, "Clumps"): each names a clump of
// overlapping spheres, its members given inline (`spheres = [[x, y, z, r], ...]`) or read from
// a file (`file`: CSV or a sphere list, io/sphere_list_reader.hpp), scaled by `scale`; its mass
// properties and principal frame computed at once (scene/clump_shape.hpp).
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

namespace yuxi {

void read_shapes(Scene& scene, TomlReader& root);

} // namespace yuxi
