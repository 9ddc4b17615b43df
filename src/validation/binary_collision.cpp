#include "validation/binary_collision.hpp"

#include "validation/impact_probe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace yuxi::validation {

double contact_time(const AnyContactLaw& law, double mass, double radius, double v) {
  return std::visit(
      [&](const auto& l) {
        using Model = typename std::decay_t<decltype(l)>::model_type;
        return Model::contact_time(l.coeffs(0, 0), 0.5 * mass, 0.5 * radius, v);
      },
      law);
}

BinaryOutcome collide_binary(const BinaryCollision& c) {
  if (!(c.impact_parameter >= 0 && c.impact_parameter < 1))
    throw std::invalid_argument("impact parameter must be in [0, 1)");
  if (!(c.v0 > 0)) throw std::invalid_argument("impact speed must be positive");
  BinaryOutcome out;
  const double d = 2 * c.radius, b = c.impact_parameter * d;
  out.dt = contact_time(c.law, c.mass, c.radius, 2 * c.v0) / c.steps_per_contact;
  const double gap = 3 * 2 * c.v0 * out.dt; // touching after three steps
  const double dx = std::sqrt(d * d - b * b) + gap;
  Impact setup;
  setup.dt = out.dt;
  setup.law = c.law;
  setup.bodies.push_back({{-0.5 * dx, 0.5 * b, 0}, {c.v0, 0, 0}, {}, c.radius, c.mass});
  setup.bodies.push_back({{0.5 * dx, -0.5 * b, 0}, {-c.v0, 0, 0}, {}, c.radius, c.mass});
  for (auto& body : setup.bodies) body.spins = c.spins;
  Simulation sim = make_simulation(setup);

  const auto index = [&](GlobalId id) { return owned_index(sim, id); };
  // Normal and tangential relative velocity of the centres, the tangent fixed by the approach.
  const auto relative = [&](Vec3& n) {
    const auto& p = sim.particles();
    const std::size_t i = index(0), j = index(1);
    n = normalized(p.x[i] - p.x[j]);
    return p.v[i] - p.v[j];
  };
  Vec3 n_before;
  const Vec3 v_before = relative(n_before);
  const Vec3 tangent_before = v_before - dot(v_before, n_before) * n_before;

  const auto start = sim.energies();
  out.initial_energy = start.balance();
  double mech = start.mechanical();
  bool started = false;
  const int max_steps = static_cast<int>(100 * c.steps_per_contact) + 100;
  for (int k = 0; k < max_steps; ++k) {
    sim.step();
    const auto e = sim.energies();
    out.max_drift =
        std::max(out.max_drift, std::abs(e.balance() - out.initial_energy) / out.initial_energy);
    out.max_mech_rise = std::max(out.max_mech_rise, (e.mechanical() - mech) / out.initial_energy);
    out.peak_relax = std::max(out.peak_relax, e.relaxation / out.initial_energy);
    mech = e.mechanical();
    if (e.contacts > 0) {
      started = true;
      out.contact_time += out.dt;
      const auto& p = sim.particles();
      const std::size_t i = index(0), j = index(1);
      out.peak_force = std::max(out.peak_force, norm(p.f[i]));
      out.max_overlap = std::max(out.max_overlap, d - norm(p.x[i] - p.x[j]));
    } else if (started) {
      out.separated = true;
      break;
    }
  }
  Vec3 n_after;
  const Vec3 v_after = relative(n_after);
  out.e_n = -dot(v_after, n_after) / dot(v_before, n_before);
  const double t_len = norm(tangent_before);
  if (t_len > 1e-12 * norm(v_before)) {
    const Vec3 t = tangent_before / t_len;
    const Vec3 tangent_after = v_after - dot(v_after, n_after) * n_after;
    out.e_t = dot(tangent_after, t) / t_len;
  } else {
    out.e_t = std::numeric_limits<double>::quiet_NaN();
  }
  out.heat = sim.energies().dissipated / out.initial_energy;
  out.final_drift = (sim.energies().balance() - out.initial_energy) / out.initial_energy;
  for (GlobalId g = 0; g < 2; ++g) {
    out.v_after[g] = sim.particles().v[index(g)];
    out.w_after[g] = sim.particles().w[index(g)];
  }
  return out;
}

} // namespace yuxi::validation
