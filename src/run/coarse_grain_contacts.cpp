#include "run/coarse_grain_contacts.hpp"

#include "core/ball_volume.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace yuxi {

namespace {

// The contacts into `out` (cleared first, its storage kept).
void gather_contacts(const Simulation& sim, std::span<const std::int64_t> grain_of,
                     std::vector<analysis::CgContact>& out) {
  const ContactRecord& rec = sim.contact_record();
  if (!rec.enabled)
    throw std::runtime_error("contacts are not recorded: call record_contacts(True), then step");
  const ParticleStore& p = sim.particles();
  const NeighborList& list = sim.neighbor_list();
  out.clear();
  out.reserve(rec.wall.size() + list.planes.size() / 2 + rec.pairs.size());
  const auto place = [&](std::size_t i) -> std::int64_t {
    return i < grain_of.size() ? grain_of[i] : -1;
  };
  // Grain i (radius r) touched with force f: by a grain j of radius r_b whose centre is x_i - b,
  // or by a wall at `at` (r_b < 0, j unused); e its elastic energy, q the energy it dissipated
  // in the step, e_r its relaxation energy, u the work of a moving wall on i in the step.
  const double per_second = 1.0 / sim.config().dt;
  const auto add = [&](std::size_t i, double r, const Vec3& f, const Vec3& b, const Vec3& at,
                       double r_b, std::size_t j, double e, double q, double e_r, double u) {
    // (filled field by field in place: a whole struct built on the stack and copied in costs
    // a stalled load for each of its wider parts)
    const bool wall = r_b < 0;
    analysis::CgContact& c = out.emplace_back();
    c.centre = p.x[i];
    c.volume = ball_volume(r);
    c.wall = wall;
    c.volume_b = wall ? 0.0 : ball_volume(r_b);
    c.force = f;
    c.branch = b;
    c.point = at;
    c.elastic = e;
    c.grain = place(i);
    c.grain_b = wall ? -1 : place(j);
    c.dissipation = q * per_second;
    c.relaxation = e_r;
    c.wall_power = u * per_second;
  };
  for (const PairContactRecord& r : rec.pairs) {
    std::uint32_t i = list.rows[r.pair], j = list.partners[r.pair];
    Vec3 f = r.force;
    if (!p.is_grain(i)) std::swap(i, j), f = -f;
    if (!p.is_grain(i)) continue; // two wall particles
    const Vec3 d = p.x[i] - p.x[j];
    const double dist = norm(d), overlap = p.radius[i] + p.radius[j] - dist;
    const Vec3 at = p.x[i] - d * ((p.radius[i] - 0.5 * overlap) / dist);
    if (p.is_grain(j))
      add(i, p.radius[i], f, d, at, p.radius[j], j, r.elastic, r.dissipated, r.relaxation, 0.0);
    else
      add(i, p.radius[i], f, p.x[i] - at, at, -1.0, j, r.elastic, r.dissipated, r.relaxation,
          r.wall_work);
  }
  for (std::size_t k = 0; k < list.planes.size() && k < rec.plane_force.size(); ++k) {
    if (!rec.holds_plane(k)) continue;
    const auto& pc = list.planes[k];
    const PlaneWall& w = sim.planes()[pc.plane];
    const Vec3 x = p.x[pc.particle];
    const Vec3 at = x - w.normal * w.distance(x, sim.time());
    add(pc.particle, p.radius[pc.particle], rec.plane_force[k], x - at, at, -1.0, 0,
        rec.plane_elastic[k], rec.plane_dissipated[k], rec.plane_relaxation[k],
        rec.plane_wall_work[k]);
  }
  for (const WallContactRecord& r : rec.wall) {
    const WallContactRef ref = list.walls[r.candidate];
    const Vec3 x = p.x[ref.particle];
    add(ref.particle, p.radius[ref.particle], r.force, x - r.point, r.point, -1.0, 0, r.elastic,
        r.dissipated, r.relaxation, r.wall_work);
  }
}

} // namespace

std::vector<analysis::CgContact> coarse_grain_contacts(const Simulation& sim,
                                                       std::span<const std::int64_t> grain_of) {
  std::vector<analysis::CgContact> out;
  gather_contacts(sim, grain_of, out);
  return out;
}

void CoarseGrainInput::gather(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  x.clear(), v.clear(), mass.clear(), volume.clear();
  grain_of.assign(p.n_owned(), -1);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (!p.is_grain(i)) continue;
    grain_of[i] = static_cast<std::int64_t>(x.size());
    x.push_back(p.x[i]), v.push_back(p.v[i]), mass.push_back(p.mass[i]);
    volume.push_back(ball_volume(p.radius[i]));
  }
  if (sim.contact_record().enabled)
    gather_contacts(sim, grain_of, contacts);
  else
    contacts.clear();
}

} // namespace yuxi
