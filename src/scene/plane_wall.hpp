// A flat, infinitely heavy wall: the plane through `point` with unit `normal` pointing into
// the region where grains are. It may oscillate along its normal:
//   offset(t) = A sin(omega (t - t0)) for t >= t0, 0 before   [length]
#pragma once

#include "core/vec3.hpp"

#include <cmath>
#include <cstdint>
#include <string>

namespace yuxi {

struct PlaneWall {
  std::string name; // for walls.csv ("plane 1", "box z lo", ...)
  Vec3 point;
  Vec3 normal{0, 0, 1};
  std::uint8_t material = 0;
  double amplitude = 0.0; // A [length]
  double omega = 0.0;     // [1/time]
  double t0 = 0.0;        // start of the oscillation [time]

  double offset(double t) const {
    return (amplitude == 0.0 || t < t0) ? 0.0 : amplitude * std::sin(omega * (t - t0));
  }
  Vec3 velocity(double t) const {
    if (amplitude == 0.0 || t < t0) return {};
    return (amplitude * omega * std::cos(omega * (t - t0))) * normal;
  }
  // Signed distance of p from the wall at time t (positive on the grains' side).
  double distance(const Vec3& p, double t) const { return dot(p - point, normal) - offset(t); }
  double distance_at_rest(const Vec3& p) const { return dot(p - point, normal); }
  double max_excursion() const { return std::abs(amplitude); }
};

} // namespace yuxi
