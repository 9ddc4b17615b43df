// The [[measure]] tables of a scene file: what a run writes into measurements.csv on every
// energy interval (scene/measure_spec.hpp; docs/scene-format.md, "Measuring a bed").
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

namespace yuxi {

// Reads every [[measure]] table into the scene. Each bad value fails at its key: a name used
// twice or unfit for a CSV column, an unknown quantity, a wall that the scene does not have, a
// direction that is not horizontal. Needs the domain, the walls and the regions' readers.
void read_measures(Scene& scene, TomlReader& root);

} // namespace yuxi
