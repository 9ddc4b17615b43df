// Writes a Scene back as TOML with every default filled in: the "resolved" scene that is
// echoed into each output folder, so that a run's inputs are never ambiguous.
#pragma once

#include "io/scene.hpp"

#include <string>

namespace yuxi {

std::string resolved_scene_toml(const Scene& scene);

} // namespace yuxi
