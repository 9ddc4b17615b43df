// Prescribed motions of wall particles: pure functions of the rest position and the time that
// give the position and the velocity. A wall particle never integrates an equation of motion.
#pragma once

#include "core/vec3.hpp"

#include <cmath>
#include <variant>

namespace yuxi {

struct PlacedState {
  Vec3 position;
  Vec3 velocity;
};

// Does not move.
struct StaticMotion {
  PlacedState at(const Vec3& rest, double) const { return {rest, {}}; }
};

// The fish-basin excitation (fish_basin.md section 6): each wall point at azimuth alpha about
// the vertical axis through `center` moves radially,
//   r(alpha, t)    = R + dr cos(m alpha) sin(omega (t - t0))
//   rdot(alpha, t) = omega dr cos(m alpha) cos(omega (t - t0))
// for t >= t0, with R its own rest radius; at rest before t0. Height is unchanged.
struct RadialCosineMotion {
  Vec3 center;          // a point on the axis (its z is ignored)
  int mode = 2;         // m: 2 gives four antinodes, 3 gives six
  double amplitude = 0; // dr [length]
  double omega = 0;     // [1/time]
  double t0 = 0;        // start of the excitation [time]

  PlacedState at(const Vec3& rest, double t) const {
    if (t < t0) return {rest, {}};
    const double dx = rest.x - center.x, dy = rest.y - center.y;
    const double r0 = std::hypot(dx, dy);
    if (r0 == 0.0) return {rest, {}};
    const double c = dx / r0, s = dy / r0; // cos(alpha), sin(alpha)
    const double alpha = std::atan2(dy, dx);
    const double shape = amplitude * std::cos(mode * alpha);
    const double phase = omega * (t - t0);
    const double r = r0 + shape * std::sin(phase);
    const double rdot = omega * shape * std::cos(phase);
    return {{center.x + r * c, center.y + r * s, rest.z}, {rdot * c, rdot * s, 0.0}};
  }
  double max_excursion() const { return std::abs(amplitude); }
};

using WallMotion = std::variant<StaticMotion, RadialCosineMotion>;

inline PlacedState place(const WallMotion& m, const Vec3& rest, double t) {
  return std::visit([&](const auto& motion) { return motion.at(rest, t); }, m);
}

} // namespace yuxi
