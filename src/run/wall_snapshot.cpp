#include "run/wall_snapshot.hpp"

namespace yuxi {

WallSurface wall_surface(const Simulation& sim) {
  WallSurface s;
  const std::vector<ShapedWall>& walls = sim.shaped_walls();
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!wall_active(walls[w], sim.time())) continue; // (the same on every rank)
    const auto index = static_cast<std::int32_t>(w);
    if (const auto* mesh = std::get_if<MeshWall>(&walls[w]))
      s.add_mesh(*mesh, sim.triangle_forces(w), index); // collective
    else
      s.add_cylinder(std::get<CylinderWall>(walls[w]), sim.config().box, sim.time(), index);
  }
  return s;
}

} // namespace yuxi
