#include "io/shape_scene_reader.hpp"

#include "io/sphere_list_reader.hpp"
#include "io/wall_scene_reader.hpp"

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <span>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace yuxi {

namespace {

std::vector<SphereMember> read_members(const Scene& scene, TomlReader& t) {
  if (t.has("spheres") == t.has("file"))
    t.fail("spheres", "give exactly one of 'spheres' (the members, [[x, y, z, r], ...]) and "
                      "'file' (a CSV or sphere-list file of them)");
  std::vector<SphereMember> members;
  if (t.has("spheres")) {
    for (const std::vector<double>& row : t.number_rows("spheres", 4)) {
      if (!(row[3] > 0.0))
        t.fail("spheres", fmt::format("member {} has radius {}: every radius must be positive",
                                      members.size() + 1, row[3]));
      members.push_back({{row[0], row[1], row[2]}, row[3]});
    }
  } else {
    const std::string given = t.string("file");
    const auto base = std::filesystem::path(scene.source).parent_path();
    const std::filesystem::path path =
        std::filesystem::path(given).is_absolute() ? std::filesystem::path(given) : base / given;
    try {
      members = read_sphere_list(std::filesystem::absolute(path).lexically_normal().string());
    } catch (const ShapeFileError& e) {
      t.fail("file", e.what());
    }
  }
  if (members.size() > max_clump_members)
    t.fail(t.has("file") ? "file" : "spheres",
           fmt::format("{} members; a clump holds at most {}", members.size(), max_clump_members));
  return members;
}

// The number of connected pieces of the members, two members joined where their balls touch.
std::size_t separate_pieces(std::span<const SphereMember> members) {
  std::vector<std::size_t> piece(members.size());
  for (std::size_t k = 0; k < piece.size(); ++k) piece[k] = k;
  const auto root = [&](std::size_t k) {
    while (piece[k] != k) k = piece[k] = piece[piece[k]];
    return k;
  };
  std::size_t pieces = members.size();
  for (std::size_t i = 0; i < members.size(); ++i)
    for (std::size_t j = i + 1; j < members.size(); ++j)
      if (norm(members[i].centre - members[j].centre) <= members[i].radius + members[j].radius &&
          root(i) != root(j)) {
        piece[root(i)] = root(j);
        --pieces;
      }
  return pieces;
}

void read_shape(Scene& scene, TomlReader& t) {
  const std::string name = t.plain_name("name", "_-", "a shape's name");
  for (const ClumpShape& s : scene.shapes)
    if (s.name == name) t.fail("name", fmt::format("a second shape named '{}'", name));
  std::vector<SphereMember> members = read_members(scene, t);
  // A fill or insert scales each clump to the bounding radius it draws: a shape's own size, and
  // so a scale or a file's unit, changes nothing. Said, rather than ignored.
  if (t.has("scale"))
    t.fail("scale", "a shape is scaled where it is used: each [[fill]] and [[insert]] scales its "
                    "clumps to the bounding radii it draws (its radius or size distribution), "
                    "and a [[clump]] by its own 'scale'; remove the key");
  t.finish();
  try {
    scene.shapes.push_back(make_clump_shape(name, members));
    scene.shape_spheres.push_back(std::move(members));
  } catch (const std::invalid_argument& e) {
    t.fail(t.has("file") ? "file" : "spheres", e.what());
  }
  // Members that touch no other: a rigid body still (as if joined by massless rods), but more
  // often a typo in a coordinate. Allowed, and said once.
  if (const std::size_t pieces = separate_pieces(scene.shapes.back().members); pieces > 1)
    scene.warnings.push_back(fmt::format(
        "shape '{}': its members make {} separate pieces that touch nothing of one another; "
        "the clump moves them as one rigid body",
        name, pieces));
}

// A [[clump]]: one clump of a shape where the table puts it.
void read_clump(Scene& scene, TomlReader& t) {
  ClumpSpec c;
  c.shape = shape_named(scene, t);
  c.position = t.vec3("position");
  if (!scene.sim.box.contains(c.position))
    t.fail("position", fmt::format("({}, {}, {}) is outside the domain", c.position.x, c.position.y,
                                   c.position.z));
  if (t.has("orientation")) {
    const std::vector<double> q = t.numbers("orientation");
    if (q.size() != 4)
      t.fail("orientation", fmt::format("{} numbers: give a unit quaternion [w, x, y, z] (the "
                                        "turn of the shape as its table writes it)",
                                        q.size()));
    c.orientation = {q[0], q[1], q[2], q[3]};
    const double length = std::sqrt(dot(c.orientation, c.orientation));
    if (!(std::abs(length - 1.0) <= 1e-6))
      t.fail("orientation", fmt::format("[{}, {}, {}, {}] has length {:.9g}: give a unit "
                                        "quaternion [w, x, y, z], such as [1, 0, 0, 0]",
                                        q[0], q[1], q[2], q[3], length));
    c.orientation = (1.0 / length) * c.orientation;
  }
  c.velocity = t.vec3("velocity", {});
  c.angular_velocity = t.vec3("angular_velocity", {});
  c.scale = t.positive("scale", 1.0);
  // Every member inside the domain, where the table puts it.
  const ClumpShape& shape = scene.shapes[static_cast<std::size_t>(c.shape)];
  const Quaternion turn = c.orientation * shape.frame;
  const Box& box = scene.sim.box;
  for (std::size_t k = 0; k < shape.members.size(); ++k) {
    const Vec3 member = c.position + to_lab(turn, c.scale * shape.members[k].centre);
    if (!box.contains(box.wrap(member)))
      t.fail("position", fmt::format("member {} of the clump would stand at ({:.6g}, {:.6g}, "
                                     "{:.6g}), outside the domain",
                                     k, member.x, member.y, member.z));
  }
  c.material = material_of(scene, t, "material");
  const double material_density = scene.material_properties[c.material].density;
  if (t.has("density"))
    c.density = t.positive("density");
  else if (std::isfinite(material_density) && material_density > 0)
    c.density = material_density;
  else
    t.fail("density", fmt::format("give the clump's density here or in [material.{}]",
                                  scene.materials[c.material]));
  t.finish();
  scene.clumps.push_back(c);
}

} // namespace

int shape_named(const Scene& scene, TomlReader& t) {
  const std::string name = t.string("shape");
  std::vector<std::string_view> names;
  int index = -1;
  for (std::size_t k = 0; k < scene.shapes.size(); ++k) {
    names.push_back(scene.shapes[k].name);
    if (scene.shapes[k].name == name) index = static_cast<int>(k);
  }
  if (index < 0)
    t.fail("shape", scene.shapes.empty()
                        ? fmt::format("no [[shape]] named '{}': the scene has no [[shape]]", name)
                        : fmt::format("no [[shape]] named '{}' (the scene's: {})", name,
                                      fmt::join(names, ", ")));
  return index;
}

void read_shapes(Scene& scene, TomlReader& root) {
  for (auto& t : root.tables("shape")) read_shape(scene, t);
  for (auto& t : root.tables("clump")) read_clump(scene, t);
}

} // namespace yuxi
