// Reads a scene file (TOML) into a validated Scene. The schema, with units, is documented in
// docs/scene-format.md; the scenes/ folder has complete examples.
#pragma once

#include "io/scene.hpp"
#include "io/scene_error.hpp"

#include <string>
#include <string_view>

namespace yuxi {

Scene read_scene_file(const std::string& path);
// `lines`: errors give the text's line and column (false for a text made from a Python dict,
// whose lines the user never saw: the key's path alone).
Scene read_scene_text(std::string_view text, const std::string& source, bool lines = true);

// Without a `skin` key, the skin is this fraction of the largest grain diameter.
inline constexpr double default_skin_fraction = 0.2;

// A scene that builds and pours no grain continues a saved state (a branch, or a resume of
// one) whose largest grain has this radius: its cells, and its skin where it has no skin key,
// are sized for them. A scene with grains of its own is left as it is.
void size_for_saved_grains(Scene& scene, double largest_grain_radius);

} // namespace yuxi
