// A shipped scene's text changed for a test: each (pattern, replacement) applied in turn, and a
// pattern that no longer matches the scene fails loudly (the scene changed under the test).
#pragma once

#include <regex>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace yuxi::test {

using SceneEdit = std::pair<const char*, const char*>; // (regex, replacement)

inline std::string edited_scene(std::string text, std::span<const SceneEdit> edits) {
  for (const auto& [pattern, replacement] : edits) {
    const std::regex re(pattern);
    if (!std::regex_search(text, re)) throw std::runtime_error(std::string("no ") + pattern);
    text = std::regex_replace(text, re, replacement);
  }
  return text;
}

} // namespace yuxi::test
