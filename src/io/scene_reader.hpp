// Reads a scene file (TOML) into a validated Scene. The schema, with units, is documented in
// docs/scene-format.md; the scenes/ folder has complete examples.
#pragma once

#include "io/scene.hpp"
#include "io/scene_error.hpp"

#include <string>
#include <string_view>

namespace yuxi {

Scene read_scene_file(const std::string& path);
Scene read_scene_text(std::string_view text, const std::string& source);

} // namespace yuxi
