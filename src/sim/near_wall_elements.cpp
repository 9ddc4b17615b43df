#include "sim/near_wall_elements.hpp"

namespace yuxi {

void pick_near_wall_elements(const ParticleStore& s, const NeighborList& list,
                             const std::vector<ShapedWall>& walls, double margin,
                             NearWallElements& near) {
  near.elements.clear(); // (the capacities stay: the next pick needs about as much)
  near.start.clear();
  near.start.push_back(0);
  for (const WallContactRef& ref : list.walls) {
    const auto* mesh = std::get_if<MeshWall>(&walls[ref.wall]);
    const std::uint32_t* listed = list.wall_elements.data() + ref.first;
    if (mesh && !mesh->moves()) {
      const double reach = s.radius[ref.particle] + margin;
      for (std::uint32_t m = 0; m < ref.count; ++m)
        if (mesh->within(s.x[ref.particle], reach, listed[m])) near.elements.push_back(listed[m]);
    } else {
      near.elements.insert(near.elements.end(), listed, listed + ref.count);
    }
    near.start.push_back(static_cast<std::uint32_t>(near.elements.size()));
  }
  near.picked = true;
}

} // namespace yuxi
