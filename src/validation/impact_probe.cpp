#include "validation/impact_probe.hpp"

#include <algorithm>
#include <stdexcept>

namespace yuxi::validation {

PlaneWall flat_wall(Vec3 point, Vec3 normal, std::uint8_t material) {
  PlaneWall w;
  w.point = point;
  w.normal = normal / norm(normal);
  w.material = material;
  return w;
}

AnyContactLaw linear_law(const LinearSpringDashpot::Coeffs& c, std::size_t n_materials) {
  ContactLaw<LinearSpringDashpot> law{PairTable<LinearSpringDashpot::Coeffs>(n_materials)};
  for (std::size_t a = 0; a < n_materials; ++a)
    for (std::size_t b = a; b < n_materials; ++b) law.coeffs.set(a, b, c);
  return law;
}

Simulation make_simulation(const Impact& setup) {
  double extent = 0, r_max = 0;
  for (const auto& b : setup.bodies) {
    r_max = std::max(r_max, b.radius);
    extent = std::max({extent, std::abs(b.x.x), std::abs(b.x.y), std::abs(b.x.z)});
  }
  SimulationConfig cfg;
  const double half = 4 * (extent + 2 * r_max);
  cfg.box = {{-half, -half, -half}, {half, half, half}};
  cfg.gravity = setup.gravity;
  cfg.dt = setup.dt;
  cfg.skin = 0.1 * r_max;
  cfg.max_overlap_ratio = 1.5; // soft springs (MFiX DEM01) reach half the radius
  ParticleStore store;
  GlobalId id = 0;
  for (const auto& b : setup.bodies) {
    ParticleSpec s;
    s.position = b.x;
    s.velocity = b.v;
    s.angular_velocity = b.w;
    s.radius = b.radius;
    s.mass = b.mass;
    s.material = b.material;
    s.kind = b.kind;
    s.spins = b.spins;
    store.add(s, id++);
  }
  return Simulation(cfg, std::move(store), setup.planes, {}, setup.law, Comm::world(), setup.walls);
}

std::size_t owned_index(const Simulation& sim, GlobalId id) {
  const auto& s = sim.particles();
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.gid[i] == id) return i;
  throw std::logic_error("a body of the impact left the simulation");
}

ImpactOutcome run_impact(const Impact& setup) {
  Simulation sim = make_simulation(setup);
  ImpactOutcome out;
  bool started = false;
  const auto index_of = [&](GlobalId g) { return owned_index(sim, g); };
  for (int k = 0; k < setup.max_steps; ++k) {
    sim.step();
    const bool touching = sim.last_tally().touching > 0;
    if (touching) {
      started = true;
      out.contact_time += setup.dt;
      const auto& s = sim.particles();
      const std::size_t i = index_of(0);
      out.peak_force = std::max(out.peak_force, norm(s.f[i] - s.mass[i] * setup.gravity));
      for (std::size_t j = 0; j < s.n_owned(); ++j)
        if (j != i)
          out.max_overlap =
              std::max(out.max_overlap, s.radius[i] + s.radius[j] - norm(s.x[i] - s.x[j]));
      for (const auto& p : setup.planes)
        out.max_overlap = std::max(out.max_overlap, s.radius[i] - p.distance(s.x[i], sim.time()));
    } else if (started) {
      out.separated = true;
      break;
    }
  }
  for (std::size_t b = 0; b < setup.bodies.size(); ++b) {
    const std::size_t i = index_of(static_cast<GlobalId>(b));
    out.v.push_back(sim.particles().v[i]);
    out.w.push_back(sim.particles().w[i]);
  }
  return out;
}

} // namespace yuxi::validation
