#include "io/measure_scene_reader.hpp"

#include "io/source_scene_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace yuxi {
namespace {

using Quantity = MeasureSpec::Quantity;

// The walls a wall_force measure may name: flat planes, shaped walls, the box's wall faces.
std::vector<std::string> wall_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const PlaneWall& p : scene.planes) names.push_back(p.name);
  for (const ShapedWall& w : scene.walls) names.push_back(wall_name(w));
  for (int a = 0; a < 3; ++a)
    if (scene.sim.box.boundary[a] == Boundary::wall)
      for (const char* side : {"lo", "hi"})
        names.push_back(fmt::format("box {} {}", "xyz"[a], side));
  return names;
}

void read_measure(Scene& scene, TomlReader& t) {
  MeasureSpec m;
  m.name = t.plain_name("name", "_-.", "a CSV column name");
  for (const MeasureSpec& other : scene.measures)
    if (other.name == m.name) t.fail("name", fmt::format("'{}' names another measure", m.name));
  if (!t.has("quantity"))
    t.fail("quantity", "missing: mass, grains, kinetic_per_grain, surface_height, angle or "
                       "wall_force");
  const std::string q = t.choice(
      "quantity", {"mass", "grains", "kinetic_per_grain", "surface_height", "angle", "wall_force"},
      "mass");
  m.quantity = q == "mass"                ? Quantity::mass
               : q == "grains"            ? Quantity::grains
               : q == "kinetic_per_grain" ? Quantity::kinetic_per_grain
               : q == "surface_height"    ? Quantity::surface_height
               : q == "angle"             ? Quantity::angle
                                          : Quantity::wall_force;
  if (m.quantity == Quantity::wall_force) {
    m.wall = t.string("wall");
    const auto names = wall_names(scene);
    if (std::find(names.begin(), names.end(), m.wall) == names.end())
      t.fail("wall", fmt::format("the scene has no wall named '{}' (it has: {})", m.wall,
                                 fmt::join(names, ", ")));
  } else if (t.has("region")) {
    m.region = read_region(scene, t);
  }
  if (m.quantity == Quantity::surface_height || m.quantity == Quantity::angle)
    m.bin = t.positive("bin", 0.0);
  if (m.quantity == Quantity::angle) {
    if (t.has("direction") && t.has("axis_point"))
      t.fail("axis_point", "give 'direction' (a slope along it) or 'axis_point' (a heap about "
                           "the vertical axis through it), not both");
    m.about_axis = t.has("axis_point");
    if (m.about_axis) {
      m.point = t.vec3("axis_point");
    } else {
      m.point = t.vec3("point", Vec3{});
      const Vec3 d = t.vec3("direction", Vec3{1, 0, 0});
      if (!(std::hypot(d.x, d.y) > 0) || std::abs(d.z) > 1e-12 * norm(d))
        t.fail("direction", "must be horizontal (z = 0) and not zero: heights are along z");
      m.direction = d / norm(d);
    }
    m.from = t.number("from", m.from);
    m.to = t.number("to", m.to);
    if (!(m.to > m.from)) t.fail("to", fmt::format("must exceed from = {}", m.from));
  }
  t.finish();
  scene.measures.push_back(std::move(m));
}

} // namespace

void read_measures(Scene& scene, TomlReader& root) {
  for (auto& t : root.tables("measure")) read_measure(scene, t);
}

} // namespace yuxi
