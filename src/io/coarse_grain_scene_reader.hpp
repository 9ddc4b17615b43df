// The [[coarse_grain]] tables of a scene file (scene/coarse_grain_spec.hpp; docs/scene-format.md,
// "Coarse-grained fields").
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

namespace yuxi {

// Reads every [[coarse_grain]] table into the scene. Each bad value fails at its key: a name
// used twice or unfit for a folder, an unknown function or field, a width or cutoff that is not
// positive, a grid with hi not above lo or lying wholly outside the box, an axis both resolved and
// averaged. Needs the domain and the output settings.
void read_coarse_grains(Scene& scene, TomlReader& root);

} // namespace yuxi
