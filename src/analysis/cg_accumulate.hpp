// How coarse-graining adds grains and contacts into its sums, whatever the grid: a geometry's
// weights (phi or psi at its points, by a visitor) and the sums' layout. Internal to
// src/analysis (coarse_grain.cpp, cg_cylinder.cpp); the definitions are in
// docs/coarse-graining.md.
#pragma once

#include "analysis/coarse_grain.hpp"

#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace yuxi::analysis::detail {

// Where each sum sits among a point's cg_sums_per_point.
struct Sum {
  enum : std::size_t {
    mass = 0,            // sum m phi
    number = 1,          // sum phi
    volume = 2,          // sum V phi
    momentum = 3,        // sum m v phi (3)
    momentum_flux = 6,   // sum m v v phi (9)
    kinetic = 15,        // sum m v^2 / 2 phi
    contact_stress = 16, // sum f b psi (9)
    wall_force = 25,     // sum over wall contacts f phi (3)
    contacts = 28,       // sum over contacts (phi_a + phi_b): sum z phi
    fabric = 29,         // sum over contacts (V_a phi_a + V_b phi_b) n n (9)
    elastic = 38,        // sum over contacts E phi(r - c)
    dissipation = 39,    // sum over contacts P phi(r - c)
    relaxation = 40,     // sum over contacts E_R phi(r - c)
    wall_power = 41,     // sum over wall contacts f . u_w phi(r - c)
  };
};
static_assert(cg_sums_per_point == Sum::wall_power + 1);

// t += a b^T w (row-major 3 x 3).
inline void add_outer(double* t, const Vec3& a, const Vec3& b, double w) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) t[3 * r + c] += a[r] * b[c] * w;
}

// sums[k] += q[k] w for k < n: a point's sums, weighed. (restrict: the compiler then knows the
// point's sums and the quantities apart, and vectorises.)
inline void add_weighted(double* __restrict sums, const double* __restrict q, std::size_t n,
                         double w) {
  for (std::size_t k = 0; k < n; ++k) sums[k] += q[k] * w;
}

// Adds the grains' and contacts' sums into `sums` (cg_sums_per_point a point) with the weights
// of `weights`: at_point(x, f) calls f(point, phi) for the points a position weighs on,
// along(from, b, f) f(point, psi) for the segment from `from` to from + b. The contacts' parts
// left out of `parts` are not added.
template <class Weights>
void add_sums(const CgGrains& grains, std::span<const CgContact> contacts, const Weights& weights,
              std::vector<double>& sums, const CgParts& parts = {}) {
  const std::size_t n_grains = grains.x.size();
  if (grains.v.size() != n_grains || grains.mass.size() != n_grains ||
      grains.volume.size() != n_grains)
    throw std::invalid_argument("coarse-graining: the grains' positions, velocities, masses and "
                                "volumes differ in number");
  const auto at = [&](std::size_t p, std::size_t s) { return &sums[cg_sums_per_point * p + s]; };
  // The contacts of grains known by their place: counted with the grain's own weights.
  std::vector<double> grain_contacts, grain_fabric;
  const auto known = [n_grains](std::int64_t g) {
    if (g >= static_cast<std::int64_t>(n_grains))
      throw std::invalid_argument("coarse-graining: a contact names grain " + std::to_string(g) +
                                  " of " + std::to_string(n_grains));
    return g >= 0;
  };
  const auto unit_branch = [](const CgContact& c) {
    const double length = norm(c.branch);
    return length > 0.0 ? c.branch / length : Vec3{};
  };
  if (!parts.any()) contacts = {};
  // The grains' own contacts, for coordination and fabric.
  if (parts.fabric)
    for (const CgContact& c : contacts) {
      const bool a = known(c.grain), b = !c.wall && known(c.grain_b);
      if (!a && !b) continue;
      if (grain_contacts.empty()) {
        grain_contacts.assign(n_grains, 0.0);
        grain_fabric.assign(9 * n_grains, 0.0);
      }
      const Vec3 unit = unit_branch(c);
      const auto count = [&](std::int64_t g, double volume) {
        const auto u = static_cast<std::size_t>(g);
        grain_contacts[u] += 1.0;
        add_outer(&grain_fabric[9 * u], unit, unit, volume);
      };
      if (a) count(c.grain, c.volume);
      if (b) count(c.grain_b, c.volume_b);
    }

  // A grain's own quantities in the order of its sums mass .. kinetic, made once and weighed
  // at each point in one loop the compiler vectorises (16 doubles: whole vectors).
  static_assert(Sum::number == 1 && Sum::volume == 2 && Sum::momentum == 3 &&
                Sum::momentum_flux == 6 && Sum::kinetic == 15);
  constexpr std::size_t own = Sum::kinetic + 1;
  for (std::size_t i = 0; i < n_grains; ++i) {
    const double m = grains.mass[i];
    const Vec3 v = grains.v[i];
    // (m (v_a v_b): the flux's tensor exactly symmetric)
    const double xy = m * (v.x * v.y), xz = m * (v.x * v.z), yz = m * (v.y * v.z);
    const double q[own] = {
        m,  1.0, grains.volume[i], m * v.x, m * v.y, m * v.z, m * (v.x * v.x), xy,
        xz, xy,  m * (v.y * v.y),  yz,      xz,      yz,      m * (v.z * v.z), 0.5 * m * norm2(v)};
    const bool touched = !grain_contacts.empty() && grain_contacts[i] > 0.0;
    weights.at_point(grains.x[i], [&](std::size_t p, double w) {
      add_weighted(at(p, 0), q, own, w);
      if (touched) {
        *at(p, Sum::contacts) += grain_contacts[i] * w;
        add_weighted(at(p, Sum::fabric), &grain_fabric[9 * i], 9, w);
      }
    });
  }
  for (const CgContact& c : contacts) {
    const Vec3 x_a = c.centre, from = x_a - c.branch;
    // The branch, from b's centre or the wall's contact point to a's centre.
    if (parts.branches) {
      // f b^T, made once: (f_r b_c) w is what add_outer would add, bit for bit.
      double fb[9];
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) fb[3 * r + k] = c.force[r] * c.branch[k];
      weights.along(from, c.branch, [&](std::size_t p, double w) {
        add_weighted(at(p, Sum::contact_stress), fb, 9, w);
      });
    }
    if (parts.contact_points)
      weights.at_point(c.point, [&](std::size_t p, double w) {
        *at(p, Sum::elastic) += c.elastic * w;
        *at(p, Sum::dissipation) += c.dissipation * w;
        *at(p, Sum::relaxation) += c.relaxation * w;
        if (c.wall) {
          for (int a = 0; a < 3; ++a) at(p, Sum::wall_force)[a] += c.force[a] * w;
          *at(p, Sum::wall_power) += c.wall_power * w;
        }
      });
    // The contact counts for each grain it joins, where that grain stands (counted above for
    // the grains known by their place).
    if (!parts.fabric) continue;
    const Vec3 unit = unit_branch(c);
    if (c.grain < 0)
      weights.at_point(x_a, [&](std::size_t p, double w) {
        *at(p, Sum::contacts) += w;
        add_outer(at(p, Sum::fabric), unit, unit, c.volume * w);
      });
    if (!c.wall && c.grain_b < 0)
      weights.at_point(from, [&](std::size_t p, double w) {
        *at(p, Sum::contacts) += w;
        add_outer(at(p, Sum::fabric), unit, unit, c.volume_b * w);
      });
  }
}

} // namespace yuxi::analysis::detail
