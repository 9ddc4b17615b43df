// A basin scene of scenes/ (or scenes/basin-models/) shrunk to a test of seconds: the same law
// and coefficients on a smaller lattice under stronger gravity, its wall shaking early and
// gently. Shared by the backend and device-engine tests.
#pragma once

#include "scene_edits.hpp"

#include <string>
#include <utility>

namespace yuxi::test {

// The basin's law and coefficients on a 12 x 12 x 12 lattice (60 grains, 464 wall particles),
// under ten times the gravity so that the grains land and bounce within 1 tau and lose most of
// their energy by 3 (the basin's 10 at g = 1), the side wall shaking from t = 3.2 at a ninth of
// the basin's amplitude (40 sigma/tau at most).
inline std::string small_basin(std::string text) {
  const SceneEdit edits[] = {
      {R"(hi = \[72\.0, 72\.0, 150\.0\])", "hi = [36.0, 36.0, 150.0]"},
      {R"(gravity = \[0\.0, 0\.0, -1\.0\])", "gravity = [0.0, 0.0, -10.0]"},
      {R"(cells = \[24, 24, 16\])", "cells = [12, 12, 12]"},
      {R"(\nradius = 10\.0 )", "\nradius = 3.0 "},
      {R"(wall_height = 15 )", "wall_height = 11 "},
      {R"(fill_layers = 8)", "fill_layers = 5"},
      {R"(t0 = 10\.0 )", "t0 = 3.2 "},
      {R"(amplitude = 0\.9 )", "amplitude = 0.1 "},
  };
  return edited_scene(std::move(text), edits);
}

} // namespace yuxi::test
