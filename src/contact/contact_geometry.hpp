// What a contact model is told about one contact, and what it answers.
//
// Conventions (docs/models/validation.md section 0.1): n is the unit vector from j to i, overlap
// delta = a_i + a_j - |x_i - x_j| (> 0 when touching), the force returned acts on i and its
// opposite on j. For a flat wall j is the wall: a_j = 0 and its velocity is the wall's.
#pragma once

#include "core/vec3.hpp"

#include <cmath>

namespace yuxi {

struct ContactGeometry {
  Vec3 n;          // unit normal, from j to i
  double overlap;  // delta = a_i + a_j - distance [length]
  double distance; // |x_i - x_j| (for a wall: distance from the plane) [length]
  Vec3 v_rel;      // v_i - v_j of the centres (for a wall: v_i - v_wall) [length/time]
  Vec3 w_i, w_j;   // angular velocities [1/time]
  double a_i, a_j; // lever arms: the radii (0 for a flat wall) [length]
  double m_eff;    // m_i m_j / (m_i + m_j); m_i against a wall particle or flat wall [mass]
  double r_eff;    // a_i a_j / (a_i + a_j); a_i against a flat wall [length]
  double dt;       // time step [time]

  // Velocity of i's surface point relative to j's at the contact (docs/models/validation.md 0.3):
  // v_c = v_i - v_j - (a_i w_i + a_j w_j) x n.
  YUXI_HD Vec3 contact_velocity() const { return v_rel - cross(a_i * w_i + a_j * w_j, n); }
};

// The geometry of touching particles i and j, from d = x_i - x_j and r2 = |d|^2 (> 0), their
// radii, velocities, angular velocities and inverse masses (0 for a wall particle). The one
// function of the pair loop and of a device kernel; the linear law's SIMD lanes compute the
// same, operation for operation (tests/unit/test_linear_batch.cpp holds them to the bit).
YUXI_HD inline ContactGeometry pair_geometry(const Vec3& d, double r2, double a_i, double a_j,
                                             const Vec3& v_i, const Vec3& v_j, const Vec3& w_i,
                                             const Vec3& w_j, double inv_mass_i, double inv_mass_j,
                                             double dt) {
  ContactGeometry g;
  const double dist = std::sqrt(r2);
  const double touch = a_i + a_j;
  g.n = d * (1.0 / dist);
  g.overlap = touch - dist;
  g.distance = dist;
  g.v_rel = v_i - v_j;
  g.w_i = w_i;
  g.w_j = w_j;
  g.a_i = a_i;
  g.a_j = a_j;
  g.m_eff = 1.0 / (inv_mass_i + inv_mass_j);
  g.r_eff = a_i * a_j / touch;
  g.dt = dt;
  return g;
}

// The geometry of grain i (radius a_i) against a wall element (a plane, a triangle, a
// cylinder's patch) of zero radius, no spin and infinite mass: unit normal n from the wall's
// point to the centre, the centre at `distance` from it, the point moving with `v_wall`.
YUXI_HD inline ContactGeometry wall_geometry(const Vec3& n, double distance, double a_i,
                                             const Vec3& v_i, const Vec3& v_wall, const Vec3& w_i,
                                             double inv_mass_i, double dt) {
  ContactGeometry g;
  g.n = n;
  g.overlap = a_i - distance;
  g.distance = distance;
  g.v_rel = v_i - v_wall;
  g.w_i = w_i;
  g.w_j = Vec3{};
  g.a_i = a_i;
  g.a_j = 0.0;
  g.m_eff = 1.0 / inv_mass_i;
  g.r_eff = a_i;
  g.dt = dt;
  return g;
}

// The contact-point velocity split into its normal component and tangential vector.
struct SplitVelocity {
  double normal;   // v_c . n (< 0 approaching)
  Vec3 tangential; // v_c - (v_c . n) n
};

YUXI_HD inline SplitVelocity split_contact_velocity(const ContactGeometry& g) {
  const Vec3 vc = g.contact_velocity();
  const double vn = dot(vc, g.n);
  return {vn, vc - vn * g.n};
}

struct ContactResult {
  Vec3 force;            // on i; -force acts on j [force]
  Vec3 torque_i;         // on i about its centre [force length]
  Vec3 torque_j;         // on j about its centre [force length]
  double elastic = 0;    // energy stored in the contact's springs after this step [energy]
  double dissipated = 0; // energy turned to heat during this step [energy]
  double relaxation = 0; // energy held in the contact's relaxation buffer (thermodynamic model)
  bool touching = false; // the contact carries load (its history must be kept)

  // Adds a force normal_force n + f_t acting on i at the contact point (lever arm -a_i n on i,
  // +a_j n on j where -F acts): torques -a_i n x f_t on i and -a_j n x f_t on j.
  YUXI_HD void add_contact_force(const ContactGeometry& g, double normal_force, const Vec3& f_t) {
    force += normal_force * g.n + f_t;
    const Vec3 nxf = cross(g.n, f_t);
    torque_i -= g.a_i * nxf;
    torque_j -= g.a_j * nxf;
  }
};

} // namespace yuxi
