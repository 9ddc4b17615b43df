#include "io/coarse_grain_scene_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace yuxi {
namespace {

void read_coarse_grain(Scene& scene, TomlReader& t) {
  CoarseGrainSpec c;
  c.name = t.plain_name("name", "_-", "a folder's name");
  for (const CoarseGrainSpec& other : scene.coarse_grains)
    if (other.name == c.name)
      t.fail("name", fmt::format("'{}' names another [[coarse_grain]]", c.name));
  c.function = t.choice("function", {"gaussian", "lucy", "bins"}, "gaussian");
  if (c.function != "bins") {
    if (!t.has("width")) t.fail("width", "missing: the coarse-graining width w (a length)");
    c.width = t.positive("width");
    c.cutoff = t.positive("cutoff", 3.0 * c.width);
  }
  const Box& box = scene.sim.box;
  c.lo = t.vec3("lo", box.lo);
  c.hi = t.vec3("hi", box.hi);
  for (int a = 0; a < 3; ++a) {
    if (!(c.hi[a] > c.lo[a]))
      t.fail("hi", fmt::format("must exceed lo along {} ({} <= {})", "xyz"[a], c.hi[a], c.lo[a]));
    if (c.hi[a] <= box.lo[a] || c.lo[a] >= box.hi[a])
      t.fail("lo", fmt::format("the grid lies outside the box along {}: [{}, {}] against the "
                               "box's [{}, {}]",
                               "xyz"[a], c.lo[a], c.hi[a], box.lo[a], box.hi[a]));
  }
  const std::string average = t.string("average", "");
  for (const char ch : average) {
    if (ch < 'x' || ch > 'z')
      t.fail("average", fmt::format("names axes among x, y, z (got \"{}\")", average));
    c.averaged[static_cast<std::size_t>(ch - 'x')] = true;
  }
  if (c.averaged[0] && c.averaged[1] && c.averaged[2])
    t.fail("average", "every axis is averaged: resolve one at least");
  if (t.has("n")) {
    const auto n = t.int3("n", 1);
    for (std::size_t a = 0; a < 3; ++a) {
      if (c.averaged[a] && n[a] != 1)
        t.fail("n", fmt::format("{} is averaged: it has one point (got {})", "xyz"[a], n[a]));
      c.n[a] = static_cast<int>(n[a]);
    }
  } else if (c.function == "bins") {
    t.fail("n", "missing: plain bins need the number of cells along x, y, z");
  } else {
    for (std::size_t a = 0; a < 3; ++a)
      c.n[a] =
          c.averaged[a]
              ? 1
              : std::max(1,
                         static_cast<int>(std::ceil(
                             (c.hi[static_cast<int>(a)] - c.lo[static_cast<int>(a)]) / c.width)));
  }
  c.interval =
      t.positive("interval",
                 scene.output.energy_interval > 0 ? scene.output.energy_interval : scene.run.t_end);
  c.average_every = static_cast<int>(t.integer("average_every", 0, 0, 1000000000));
  c.contacts = t.boolean("contacts", true);
  const auto& names = CoarseGrainSpec::field_names();
  if (t.has("fields")) {
    c.fields = t.strings("fields");
    for (const std::string& f : c.fields)
      if (std::find(names.begin(), names.end(), f) == names.end())
        t.fail("fields",
               fmt::format("no field named '{}' (fields: {})", f, fmt::join(names, ", ")));
  } else {
    c.fields = names;
  }
  t.finish();
  scene.coarse_grains.push_back(std::move(c));
}

} // namespace

void read_coarse_grains(Scene& scene, TomlReader& root) {
  for (TomlReader& t : root.tables("coarse_grain")) read_coarse_grain(scene, t);
}

} // namespace yuxi
