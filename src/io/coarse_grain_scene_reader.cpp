#include "io/coarse_grain_scene_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace yuxi {
namespace {

// lo, hi, average and n of a Cartesian grid.
void read_cartesian_grid(CoarseGrainSpec& c, TomlReader& t, const Box& box) {
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
}

// A two-number key (r, z), or its fallback.
std::array<double, 2> pair_of(TomlReader& t, std::string_view key, std::array<double, 2> fallback) {
  if (!t.has(key)) return fallback;
  const std::vector<double> v = t.numbers(key);
  if (v.size() != 2) t.fail(key, "takes two numbers on a cylindrical grid: r and z");
  return {v[0], v[1]};
}

// axis, lo, hi (r and z), average ("theta", "z") and n (r, theta, z) of a cylindrical grid.
void read_cylindrical_grid(CoarseGrainSpec& c, TomlReader& t, const Box& box) {
  c.cylindrical = true;
  const std::vector<double> axis = t.numbers("axis");
  if (axis.size() != 2) t.fail("axis", "takes two numbers: the x and y of the vertical axis");
  c.axis_x = axis[0], c.axis_y = axis[1];
  double farthest = 0.0;
  for (const double x : {box.lo.x, box.hi.x})
    for (const double y : {box.lo.y, box.hi.y})
      farthest = std::max(farthest, std::hypot(x - c.axis_x, y - c.axis_y));
  const auto lo = pair_of(t, "lo", {0.0, box.lo.z});
  const auto hi = pair_of(t, "hi", {farthest, box.hi.z});
  if (!(lo[0] >= 0.0)) t.fail("lo", fmt::format("r must be 0 or more (got {})", lo[0]));
  if (!(hi[0] > lo[0])) t.fail("hi", fmt::format("r must exceed lo's ({} <= {})", hi[0], lo[0]));
  if (!(hi[1] > lo[1])) t.fail("hi", fmt::format("z must exceed lo's ({} <= {})", hi[1], lo[1]));
  if (hi[1] <= box.lo.z || lo[1] >= box.hi.z)
    t.fail("lo", fmt::format("the grid lies outside the box along z: [{}, {}] against the box's "
                             "[{}, {}]",
                             lo[1], hi[1], box.lo.z, box.hi.z));
  c.lo = {lo[0], 0.0, lo[1]};
  c.hi = {hi[0], 0.0, hi[1]};
  std::string average = t.string("average", "");
  std::string rest = average;
  for (const auto& [word, axis_index] : {std::pair{"theta", 1}, std::pair{"z", 2}})
    if (const auto at = rest.find(word); at != std::string::npos) {
      rest.erase(at, std::string_view(word).size());
      c.averaged[static_cast<std::size_t>(axis_index)] = true;
    }
  if (rest.find_first_not_of(" ,") != std::string::npos)
    t.fail("average", fmt::format("names \"theta\", \"z\" or both on a cylindrical grid (got "
                                  "\"{}\")",
                                  average));
  if (t.has("n")) {
    const auto n = t.int3("n", 1);
    for (std::size_t a = 0; a < 3; ++a) {
      if (c.averaged[a] && n[a] != 1)
        t.fail("n", fmt::format("{} is averaged: it has one point (got {})", a == 1 ? "theta" : "z",
                                n[a]));
      c.n[a] = static_cast<int>(n[a]);
    }
  } else if (c.function == "bins") {
    t.fail("n", "missing: plain bins need the number of cells along r, theta, z");
  } else {
    const double spans[3] = {hi[0] - lo[0], 2.0 * std::numbers::pi * hi[0], hi[1] - lo[1]};
    for (std::size_t a = 0; a < 3; ++a)
      c.n[a] = c.averaged[a] ? 1 : std::max(1, static_cast<int>(std::ceil(spans[a] / c.width)));
  }
}

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
  if (t.has("axis"))
    read_cylindrical_grid(c, t, box);
  else
    read_cartesian_grid(c, t, box);
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
