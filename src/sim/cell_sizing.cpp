#include "sim/cell_sizing.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace yuxi {

Vec3 occupied_lengths(const Box& box, const ParticleStore& s, const Comm* comm) {
  // (-lo, hi) per axis, so that one element-wise maximum combines the ranks
  double bounds[6] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (int a = 0; a < 3; ++a) {
      bounds[a] = std::max(bounds[a], -(s.x[i][a] - s.radius[i]));
      bounds[3 + a] = std::max(bounds[3 + a], s.x[i][a] + s.radius[i]);
    }
  if (comm) comm->max(bounds, 6);
  Vec3 lengths;
  for (int a = 0; a < 3; ++a) {
    const double extent = bounds[3 + a] + bounds[a];
    lengths[a] =
        box.periodic(a) || !std::isfinite(extent) ? box.length(a) : std::min(box.length(a), extent);
  }
  return lengths;
}

double cell_edge_for(SimulationConfig& c, double reach) {
  reach = std::max(reach, c.min_contact_reach);
  if (c.cell_size > 0.0) {
    if (c.cell_size < reach)
      throw std::invalid_argument(fmt::format(
          "cell size {} is smaller than the largest contact distance {} (largest pair of radii)",
          c.cell_size, reach));
    c.skin = std::min(c.skin, c.cell_size - reach);
  }
  if (c.skin < 0.0) throw std::invalid_argument("skin must not be negative");
  const double edge = std::max(c.cell_size, reach + c.skin);
  return edge > 0.0 ? edge : 1.0;
}

std::string cells_too_small_for(double radius, double cell_edge, double skin) {
  if (2 * radius + skin <= cell_edge) return "";
  return fmt::format("radius {} is larger than the linked cells allow ({}); give the scene's "
                     "[domain] cell_size = {} or more (the grain's diameter and the skin)",
                     radius, 0.5 * (cell_edge - skin), 2 * radius + skin);
}

} // namespace yuxi
