#include "run/coarse_grain_contacts.hpp"

#include "core/ball_volume.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace yuxi {

std::vector<analysis::CgContact> coarse_grain_contacts(const Simulation& sim) {
  const ContactRecord& rec = sim.contact_record();
  if (!rec.enabled)
    throw std::runtime_error("contacts are not recorded: call record_contacts(True), then step");
  const ParticleStore& p = sim.particles();
  const NeighborList& list = sim.neighbor_list();
  std::vector<analysis::CgContact> out;
  // A grain (centre x, radius r) touched with force f: by a grain of radius r_b whose centre is
  // x - b, or by a wall at `at` (r_b < 0).
  const auto add = [&](const Vec3& x, double r, const Vec3& f, const Vec3& b, const Vec3& at,
                       double r_b, double e) {
    out.push_back({x, ball_volume(r), r_b < 0, r_b < 0 ? 0.0 : ball_volume(r_b), f, b, at, e});
  };
  for (std::size_t k = 0; k < list.partners.size() && k < rec.pair_force.size(); ++k) {
    if (!ContactRecord::touched(rec.pair_force[k], rec.pair_elastic[k])) continue;
    std::uint32_t i = list.rows[k], j = list.partners[k];
    Vec3 f = rec.pair_force[k];
    if (!p.is_grain(i)) std::swap(i, j), f = -f;
    if (!p.is_grain(i)) continue; // two wall particles
    const Vec3 d = p.x[i] - p.x[j];
    const double dist = norm(d), overlap = p.radius[i] + p.radius[j] - dist;
    const Vec3 at = p.x[i] - d * ((p.radius[i] - 0.5 * overlap) / dist);
    if (p.is_grain(j))
      add(p.x[i], p.radius[i], f, d, at, p.radius[j], rec.pair_elastic[k]);
    else
      add(p.x[i], p.radius[i], f, p.x[i] - at, at, -1.0, rec.pair_elastic[k]);
  }
  for (std::size_t k = 0; k < list.planes.size() && k < rec.plane_force.size(); ++k) {
    if (!ContactRecord::touched(rec.plane_force[k], rec.plane_elastic[k])) continue;
    const auto& pc = list.planes[k];
    const PlaneWall& w = sim.planes()[pc.plane];
    const Vec3 x = p.x[pc.particle];
    const Vec3 at = x - w.normal * w.distance(x, sim.time());
    add(x, p.radius[pc.particle], rec.plane_force[k], x - at, at, -1.0, rec.plane_elastic[k]);
  }
  for (const WallContactRecord& r : rec.wall) {
    const WallContactRef ref = list.walls[r.candidate];
    const Vec3 x = p.x[ref.particle];
    add(x, p.radius[ref.particle], r.force, x - r.point, r.point, -1.0, r.elastic);
  }
  return out;
}

} // namespace yuxi
