#include "io/wall_scene_reader.hpp"

#include "io/stl_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <limits>

namespace yuxi {
namespace {

ActiveWindow read_window(TomlReader& t) {
  ActiveWindow w;
  w.from = t.number("active_from", w.from);
  w.until = t.number("active_until", w.until);
  if (!(w.from < w.until)) t.fail("active_until", "must come after active_from");
  return w;
}

// The part of a rigid motion that carries a wall without turning it: the drift and the
// oscillation, between t0 and t1.
void read_carrying(TomlReader& t, RigidMotion& m) {
  m.drift = t.vec3("velocity", Vec3{});
  m.amplitude = t.number("oscillate_amplitude", 0.0);
  if (m.amplitude != 0.0) {
    m.direction = unit_vector(t, "oscillate_direction", Vec3{0, 0, 1});
    m.frequency = t.positive("oscillate_omega");
  }
  m.t0 = t.number("t0", 0.0);
  m.t1 = t.number("t1", HUGE_VAL);
  if (!(m.t1 > m.t0)) t.fail("t1", "the motion must stop (t1) after it starts (t0)");
}

// The motion of a mesh's vertices: rigid (a turn, a drift, an oscillation, summed) or the
// basin's radial mode, from t0.
WallMotion read_motion(TomlReader& t) {
  const bool radial = t.has("radial_mode") || t.has("radial_amplitude");
  const bool rigid = t.has("omega") || t.has("velocity") || t.has("oscillate_amplitude");
  if (radial && rigid)
    t.fail("radial_mode", "a mesh moves rigidly (omega, velocity, oscillate_*) or by the radial "
                          "mode (radial_*), not both");
  if (radial) {
    RadialCosineMotion m;
    m.center = t.vec3("radial_center", Vec3{});
    m.mode = static_cast<int>(t.integer("radial_mode", 2, 0, 64));
    m.amplitude = t.number("radial_amplitude");
    m.omega = t.non_negative("radial_omega", 0.0);
    m.t0 = t.number("t0", 0.0);
    return m;
  }
  if (!rigid) return StaticMotion{};
  RigidMotion m;
  m.omega = t.number("omega", 0.0);
  m.axis = unit_vector(t, "axis", Vec3{0, 0, 1});
  m.center = t.vec3("axis_point", Vec3{});
  read_carrying(t, m);
  return m;
}

// Fails at the table if the mesh lies wholly outside the box at any of a few hundred times of
// the run, or reaches across a periodic face.
void check_mesh_in_box(const Scene& scene, TomlReader& t, const MeshWall& wall) {
  const Box& box = scene.sim.box;
  const double t_end = std::max(scene.run.t_end, 0.0);
  constexpr int samples = 256;
  for (int k = 0; k <= samples; ++k) {
    const double time = t_end * k / samples;
    const WallMotionAtTime now = at_time(wall.motion, time);
    Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = -lo;
    for (const Vec3& rest : wall.mesh.vertices) {
      const Vec3 p = place(now, rest).position;
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    }
    for (int a = 0; a < 3; ++a) {
      if (hi[a] < box.lo[a] || lo[a] > box.hi[a])
        t.fail("", fmt::format("mesh '{}' {} the box along {} at t = {:.6g} (it spans {:.6g} .. "
                               "{:.6g}, the box {:.6g} .. {:.6g})",
                               wall.name, k == 0 ? "lies outside" : "is carried out of", "xyz"[a],
                               time, lo[a], hi[a], box.lo[a], box.hi[a]));
      if (box.periodic(a) && (lo[a] < box.lo[a] || hi[a] > box.hi[a]))
        t.fail("", fmt::format("mesh '{}' reaches across the periodic faces along {} at t = "
                               "{:.6g} (it spans {:.6g} .. {:.6g}, the box {:.6g} .. {:.6g}); "
                               "meshes must stay within a periodic axis",
                               wall.name, "xyz"[a], time, lo[a], hi[a], box.lo[a], box.hi[a]));
    }
    if (std::holds_alternative<StaticMotion>(wall.motion)) break;
  }
}

void read_mesh(Scene& scene, TomlReader& t, std::size_t index) {
  MeshWall w;
  w.name = t.string("name", fmt::format("mesh {}", index + 1));
  PlacedMesh placed = read_placed_mesh(scene, t);
  w.file = std::move(placed.file);
  w.file_crc32 = placed.crc32;
  if (placed.dropped_degenerate > 0)
    scene.warnings.push_back(fmt::format("{}: mesh '{}': {} triangles of zero area left out of {}",
                                         t.where("file"), w.name, placed.dropped_degenerate,
                                         w.file));
  w.mesh = std::move(placed.mesh);
  w.scale = placed.scale;
  w.rotate_axis = placed.rotate_axis;
  w.rotate_degrees = placed.rotate_degrees;
  w.translate = placed.translate;
  w.material = material_of(scene, t, "material");
  w.motion = read_motion(t);
  w.surface_velocity = t.vec3("surface_velocity", Vec3{});
  w.active = read_window(t);
  w.merge_degrees = t.non_negative("merge_degrees", w.merge_degrees);
  if (w.merge_degrees >= 90.0)
    t.fail("merge_degrees", "must be below 90 (a groove's two faces would count as one)");
  w.torque_point = t.vec3("torque_point", std::holds_alternative<RigidMotion>(w.motion)
                                              ? std::get<RigidMotion>(w.motion).center
                                              : Vec3{});
  if (t.has("servo_force")) {
    // A piston: its speed along servo_axis is gain (servo_force - the grains' push), at most
    // servo_max_speed. Stable for gain k_n dt < 1 (k_n: the stiffest grain-wall spring).
    w.servo_axis = unit_vector(t, "servo_axis", Vec3{0, 0, -1});
    w.controller = std::make_shared<ForceServo>(t.number("servo_force"), t.positive("servo_gain"),
                                                t.positive("servo_max_speed"));
    if (t.boolean("controlled", false))
      t.fail("controlled", "a wall is either a servo (servo_force) or controlled from outside");
  } else if (t.boolean("controlled", false)) {
    // Its speed along servo_axis is set from outside while the run goes (the Python API).
    w.servo_axis = unit_vector(t, "servo_axis", Vec3{0, 0, -1});
    w.controller = std::make_shared<HeldSpeed>();
  }
  check_mesh_in_box(scene, t, w);
  t.finish();
  scene.walls.push_back(std::move(w));
}

void read_cylinder(Scene& scene, TomlReader& t, std::size_t index) {
  CylinderWall c;
  c.name = t.string("name", fmt::format("cylinder {}", index + 1));
  c.center = t.vec3("center");
  c.axis = unit_vector(t, "axis", Vec3{0, 0, 1});
  c.radius = t.positive("radius");
  c.inside = t.choice("grains", {"inside", "outside"}, "inside") == "inside";
  c.lo = t.number("lo", -std::numeric_limits<double>::infinity());
  c.hi = t.number("hi", std::numeric_limits<double>::infinity());
  if (!(c.lo < c.hi)) t.fail("hi", "must be above lo");
  c.capped = t.choice("ends", {"capped", "open"}, "capped") == "capped";
  c.omega = t.number("omega", 0.0);
  read_carrying(t, c.carried);
  c.material = material_of(scene, t, "material");
  c.active = read_window(t);
  t.finish();
  scene.walls.push_back(std::move(c));
}

} // namespace

Vec3 unit_vector(TomlReader& t, std::string_view key, Vec3 fallback) {
  const Vec3 v = t.vec3(key, fallback);
  if (!(norm(v) > 0.0)) t.fail(key, "must not be the zero vector");
  return v / norm(v);
}

PlacedMesh read_placed_mesh(const Scene& scene, TomlReader& t) {
  PlacedMesh m;
  const std::string given = t.string("file");
  const auto base = std::filesystem::path(scene.source).parent_path();
  const std::filesystem::path path =
      std::filesystem::path(given).is_absolute() ? std::filesystem::path(given) : base / given;
  m.file = std::filesystem::absolute(path).lexically_normal().string();
  TriangleSoup soup;
  try {
    soup = read_stl(m.file);
  } catch (const MeshFileError& e) {
    t.fail("file", e.what());
  }
  m.crc32 = soup.crc32;
  m.dropped_degenerate = soup.dropped_degenerate;
  m.mesh = TriangleMesh::weld(soup.triangles);
  m.scale = t.positive("scale", 1.0);
  m.rotate_axis = unit_vector(t, "rotate_axis", Vec3{0, 0, 1});
  m.rotate_degrees = t.number("rotate_degrees", 0.0);
  m.translate = t.vec3("translate", Vec3{});
  m.mesh.transform(m.scale, m.rotate_axis, m.rotate_degrees, m.translate);
  if (!m.mesh.finite()) t.fail("scale", "the transformed mesh has non-finite coordinates");
  return m;
}

void read_shaped_walls(Scene& scene, TomlReader& root) {
  for (auto& t : root.tables("mesh")) read_mesh(scene, t, scene.walls.size());
  for (auto& t : root.tables("cylinder")) read_cylinder(scene, t, scene.walls.size());
}

} // namespace yuxi
