// The walls beyond flat planes: triangle meshes and analytic cylinders, one type for the
// simulation's list of them.
#pragma once

#include "scene/cylinder_wall.hpp"
#include "scene/mesh_wall.hpp"

#include <string>
#include <variant>

namespace yuxi {

using ShapedWall = std::variant<MeshWall, CylinderWall>;

inline const std::string& wall_name(const ShapedWall& w) {
  return std::visit([](const auto& wall) -> const std::string& { return wall.name; }, w);
}
inline std::uint8_t wall_material(const ShapedWall& w) {
  return std::visit([](const auto& wall) { return wall.material; }, w);
}
// The point about which walls.csv gives a wall's torque: a mesh's stated point, a cylinder's
// axis point (where its carrying motion has taken it).
inline Vec3 torque_point(const ShapedWall& w) {
  if (const auto* m = std::get_if<MeshWall>(&w)) return m->torque_point;
  return std::get<CylinderWall>(w).placed_center();
}
inline bool wall_active(const ShapedWall& w, double t) {
  return std::visit([t](const auto& wall) { return wall.active.at(t); }, w);
}

} // namespace yuxi
