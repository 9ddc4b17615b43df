// The rotation of a rigid body by Miller, Eleftheriou, Pattnaik, Ndirango, Newns & Martyna's
// NO_SQUISH integrator (J. Chem. Phys. 116:8649, 2002; docs/clumps.md): the orientation is a
// unit quaternion q, its conjugate momentum the 4-vector p = 2 q (0, L_body), where L_body is
// the angular momentum in the body's principal frame (moments I1, I2, I3). The free rotor's
// Hamiltonian, sum_k (p . q e_k)^2 / (8 I_k), is split into its three terms, each a rotation
// about one body axis integrated exactly; the step is the symmetric sequence
// R3(h/2) R2(h/2) R1(h) R2(h/2) R3(h/2), between half kicks of the torque. It is symplectic and
// time-reversible, keeps |q| = 1 to round-off with no renormalising, and keeps the lab's angular
// momentum of a free body to round-off (each sub-rotation turns the body about its own axis and
// leaves L_lab unchanged); the energy error stays bounded and shrinks as h^2.
#pragma once

#include "core/host_device.hpp"
#include "core/particle_energy.hpp"
#include "core/portable_math.hpp"
#include "core/quaternion.hpp"
#include "core/vec3.hpp"

namespace yuxi {

// q e_k, the product with the unit quaternion of body axis k (1, 2, 3: i, j, k): Miller et al.'s
// permutation P_k q.
YUXI_HD constexpr Quaternion times_axis(const Quaternion& q, int k) {
  if (k == 1) return {-q.x, q.w, q.z, -q.y};
  if (k == 2) return {-q.y, -q.z, q.w, q.x};
  return {-q.z, q.y, -q.x, q.w};
}

// The conjugate momentum p = 2 q (0, L_body), and back.
YUXI_HD constexpr Quaternion rotor_momentum(const Quaternion& q, const Vec3& body_momentum) {
  return 2.0 * (q * pure(body_momentum));
}
YUXI_HD constexpr Vec3 body_angular_momentum(const Quaternion& q, const Quaternion& p) {
  return 0.5 * (conjugate(q) * p).vector();
}

// The angular velocity in the lab's frame, R(q) I^-1 L_body [rad/time].
YUXI_HD constexpr Vec3 lab_angular_velocity(const Quaternion& q, const Quaternion& p,
                                            const Vec3& inertia) {
  const Vec3 l = body_angular_momentum(q, p);
  return to_lab(q, {l.x / inertia.x, l.y / inertia.y, l.z / inertia.z});
}

// The rotational kinetic energy sum_k L_k^2 / (2 I_k).
YUXI_HD constexpr double rotor_energy(const Quaternion& q, const Quaternion& p,
                                      const Vec3& inertia) {
  const Vec3 l = body_angular_momentum(q, p);
  return 0.5 * (l.x * l.x / inertia.x + l.y * l.y / inertia.y + l.z * l.z / inertia.z);
}

// A rigid body's kinetic energy, of its centre's motion and of its rotation, plus its
// gravitational energy at x under gravity's potential part (as mechanical_energy() for a sphere)
// [energy]: the clumps' books on both engines.
YUXI_HD inline double rigid_mechanical_energy(double mass, const Vec3& x, const Vec3& v,
                                              const Quaternion& q, const Quaternion& p,
                                              const Vec3& inertia, const Vec3& g_potential) {
  return translational_energy(mass, v) + rotor_energy(q, p, inertia) - mass * dot(g_potential, x);
}

// A kick by the torque (lab frame) over dt: dp/dt = 2 q (0, tau_body).
YUXI_HD constexpr void kick_rotor(const Quaternion& q, Quaternion& p, const Vec3& torque,
                                  double dt) {
  p = p + (2.0 * dt) * (q * pure(to_body(q, torque)));
}

// The exact flow of the term (p . q e_k)^2 / (8 I_k) over dt: a turn by the angle
// 2 zeta = omega_k dt about body axis k. In two parts, which a loop over many bodies can run
// apart (sim/clump_bodies.cpp): zeta, then the turn by its sine and cosine.
YUXI_HD constexpr double turn_half_angle(const Quaternion& q, const Quaternion& p, int k,
                                         double moment, double dt) {
  return dt * dot(p, times_axis(q, k)) / (4.0 * moment);
}
YUXI_HD constexpr void turn_by(Quaternion& q, Quaternion& p, int k, double sin_zeta,
                               double cos_zeta) {
  const Quaternion qk = times_axis(q, k), pk = times_axis(p, k);
  q = cos_zeta * q + sin_zeta * qk;
  p = cos_zeta * p + sin_zeta * pk;
}
YUXI_HD inline void rotate_about_body_axis(Quaternion& q, Quaternion& p, int k, double moment,
                                           double dt) {
  const portable::SinCos t = portable::sin_cos(turn_half_angle(q, p, k, moment, dt));
  turn_by(q, p, k, t.sin, t.cos);
}

// The free rotation over dt (no torque), the symmetric sequence of the three axes.
YUXI_HD inline void free_rotation(Quaternion& q, Quaternion& p, const Vec3& inertia, double dt) {
  rotate_about_body_axis(q, p, 3, inertia.z, 0.5 * dt);
  rotate_about_body_axis(q, p, 2, inertia.y, 0.5 * dt);
  rotate_about_body_axis(q, p, 1, inertia.x, dt);
  rotate_about_body_axis(q, p, 2, inertia.y, 0.5 * dt);
  rotate_about_body_axis(q, p, 3, inertia.z, 0.5 * dt);
}

} // namespace yuxi
