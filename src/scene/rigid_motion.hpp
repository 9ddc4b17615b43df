// A rigid motion prescribed as a pure function of time: a rotation about a fixed axis, a
// constant drift and an oscillation, summed. For t >= t0, with tau = t - t0, a point at rest
// position p goes to
//   x(p, t) = c + R(omega tau) (p - c) + u tau + A sin(Omega tau) e
//   v(p, t) = omega k x R(omega tau) (p - c) + u + A Omega cos(Omega tau) e
// where R(theta) turns by theta about the unit axis k through c (right-handed, Rodrigues'
// formula), u is the drift velocity and e the unit direction of the oscillation; at rest
// before t0. At t1 the motion stops: from then on the wall holds the place it had at t1
// (tau = t1 - t0) with zero velocity. The velocity field is affine in position, so the
// velocity anywhere on a triangle is the barycentric mean of its corners' velocities.
#pragma once

#include "core/vec3.hpp"
#include "scene/placed_state.hpp"

#include <cmath>

namespace yuxi {

struct RigidMotion {
  Vec3 center;          // c: a point on the rotation axis [length]
  Vec3 axis{0, 0, 1};   // k: unit rotation axis
  double omega = 0.0;   // angular velocity about k [rad/time]
  Vec3 drift;           // u [length/time]
  Vec3 direction;       // e: unit direction of the oscillation
  double amplitude = 0; // A [length]
  double frequency = 0; // Omega [rad/time]
  double t0 = 0.0;      // start [time]
  double t1 = HUGE_VAL; // stop [time]

  struct AtTime {
    bool moving = false;
    Vec3 center, axis_omega, shift,
        velocity; // c, omega k, u tau + A sin(.) e, u + A Omega cos(.) e
    double r[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

    bool at_rest() const { return !moving; }
    Vec3 turn(const Vec3& d) const {
      return {r[0][0] * d.x + r[0][1] * d.y + r[0][2] * d.z,
              r[1][0] * d.x + r[1][1] * d.y + r[1][2] * d.z,
              r[2][0] * d.x + r[2][1] * d.y + r[2][2] * d.z};
    }
    PlacedState place(const Vec3& rest) const {
      if (!moving) return {rest, {}};
      const Vec3 arm = turn(rest - center);
      return {center + arm + shift, cross(axis_omega, arm) + velocity};
    }
  };

  AtTime at_time(double t) const {
    AtTime m;
    if (t < t0 || (omega == 0.0 && norm2(drift) == 0.0 && amplitude == 0.0)) return m;
    const bool going = t < t1; // (after t1: held where it was at t1, still)
    const double tau = (going ? t : t1) - t0;
    const double rate = going ? 1.0 : 0.0;
    m.moving = true;
    m.center = center;
    m.axis_omega = (rate * omega) * axis;
    m.shift = tau * drift;
    m.velocity = rate * drift;
    if (amplitude != 0.0) {
      m.shift += (amplitude * std::sin(frequency * tau)) * direction;
      m.velocity += (rate * amplitude * frequency * std::cos(frequency * tau)) * direction;
    }
    if (omega != 0.0) {
      // Rodrigues: R = cos(theta) I + sin(theta) [k]x + (1 - cos(theta)) k k^T
      const double theta = omega * tau, cs = std::cos(theta), sn = std::sin(theta);
      const double k[3] = {axis.x, axis.y, axis.z};
      const double kx[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          m.r[i][j] = (i == j ? cs : 0.0) + sn * kx[i][j] + (1.0 - cs) * k[i] * k[j];
    }
    return m;
  }
};

} // namespace yuxi
