// Prescribed motions of wall particles and of the vertices of mesh walls: pure functions of the
// rest position and the time that give the position and the velocity. A wall particle or a
// mesh vertex never integrates an equation of motion.
#pragma once

#include "core/radial_wave.hpp"
#include "core/vec3.hpp"
#include "scene/placed_state.hpp"
#include "scene/rigid_motion.hpp"

#include <cmath>
#include <variant>

namespace yuxi {

// Does not move.
struct StaticMotion {
  // The motion at one time, for all its wall particles.
  struct AtTime {
    PlacedState place(const Vec3& rest) const { return {rest, {}}; }
    bool at_rest() const { return true; } // every particle at its rest place, still
  };
  AtTime at_time(double) const { return {}; }
};

// The fish-basin excitation (docs/models/fish-basin.md section 6): each wall point at azimuth alpha
// about the vertical axis through `center` moves radially,
//   r(alpha, t)    = R + dr cos(m alpha) sin(omega (t - t0))
//   rdot(alpha, t) = omega dr cos(m alpha) cos(omega (t - t0))
// for t >= t0, with R its own rest radius; at rest before t0. Height is unchanged.
struct RadialCosineMotion {
  Vec3 center;          // a point on the axis (its z is ignored)
  int mode = 2;         // m: 2 gives four antinodes, 3 gives six
  double amplitude = 0; // dr [length]
  double omega = 0;     // [1/time]
  double t0 = 0;        // start of the excitation [time]

  // The motion at one time: the phase terms are computed once for all wall particles
  // (core/radial_wave.hpp places each).
  struct AtTime {
    Vec3 center;
    int mode = 0;
    double radial = 0;   // dr sin(omega (t - t0)) [length]
    double speed = 0;    // omega dr cos(omega (t - t0)) [length/time]
    bool moving = false; // t >= t0

    bool at_rest() const { return !moving; }
    PlacedState place(const Vec3& rest) const {
      if (!moving) return {rest, {}};
      const PlacedPoint p = radial_cosine_place(center, mode, radial, speed, rest);
      return {p.position, p.velocity};
    }
  };
  AtTime at_time(double t) const {
    if (t < t0) return {};
    const double phase = omega * (t - t0);
    return {center, std::abs(mode), amplitude * std::sin(phase),
            omega * amplitude * std::cos(phase), true};
  }
  double max_excursion() const { return std::abs(amplitude); }
};

using WallMotion = std::variant<StaticMotion, RadialCosineMotion, RigidMotion>;
using WallMotionAtTime =
    std::variant<StaticMotion::AtTime, RadialCosineMotion::AtTime, RigidMotion::AtTime>;

inline WallMotionAtTime at_time(const WallMotion& m, double t) {
  return std::visit([&](const auto& motion) -> WallMotionAtTime { return motion.at_time(t); }, m);
}
inline bool at_rest(const WallMotionAtTime& m) {
  return std::visit([](const auto& motion) { return motion.at_rest(); }, m);
}
inline PlacedState place(const WallMotionAtTime& m, const Vec3& rest) {
  return std::visit([&](const auto& motion) { return motion.place(rest); }, m);
}
inline PlacedState place(const WallMotion& m, const Vec3& rest, double t) {
  return place(at_time(m, t), rest);
}

} // namespace yuxi
