// An analytic cylinder wall: grains inside it (a drum, a silo) or outside it (a post), about
// any axis, infinite or between two heights along the axis, where a finite one has flat end
// caps or open rims. It may turn about its own axis (a rotating drum): its surface then moves
// with omega k x (p - c) and its shape stays. It may also be carried without turning, by the
// drift and oscillation of a rigid motion (rigid_motion.hpp, between t0 and t1: a floor lowered
// under a silo's bed, a shaken tube); c is then the centre carried to the time of the last
// place(), and the surface moves with omega k x (p - c) + the carrying velocity.
//
// For a grain at centre x, with h = (x - c).k its height along the axis and rho its distance
// from the axis (docs/walls.md section 3):
//   side  (h within the ends):  inside  distance R - rho, normal towards the axis;
//                               outside distance rho - R, normal away from it
//   caps  (rho <= R, capped):   inside  distance h - lo (normal +k) and hi - h (normal -k);
//                               outside lo - h (normal -k) and h - hi (normal +k)
//   rims  (otherwise: beyond an end and off the cap): the distance to the rim circle, normal
//                               from its nearest point to the centre.
// Inside a capped cylinder, side and cap meet at a concave corner and both touch; elsewhere a
// grain touches one patch at a time, and a rim hands over to a side or cap continuously.
// A patch touches a grain whose distance is below its radius r and above -r: a grain whose
// centre lies more than r behind a patch (an "inside" cylinder's grain outside it, far from its
// wall) is on the other side and untouched, so that several cylinders may share a box.
#pragma once

#include "core/vec3.hpp"
#include "scene/active_window.hpp"
#include "scene/rigid_motion.hpp"
#include "scene/wall_touch.hpp"

#include <cstdint>
#include <limits>
#include <string>

namespace yuxi {

struct CylinderWall {
  std::string name;
  Vec3 center;                                          // c: a point on the axis [length]
  Vec3 axis{0, 0, 1};                                   // k: unit
  double radius = 1;                                    // R [length]
  bool inside = true;                                   // grains inside the cylinder (else outside)
  double lo = -std::numeric_limits<double>::infinity(); // ends, as heights h along k [length]
  double hi = std::numeric_limits<double>::infinity();
  bool capped = false; // a finite cylinder's ends: flat caps, or open rims
  double omega = 0.0;  // turning rate about k [rad/time]
  std::uint8_t material = 0;
  ActiveWindow active;
  RigidMotion carried; // drift and oscillation only (omega 0), of the whole cylinder
  // Where the carrying motion has taken the centre, and its velocity, at the last place().
  Vec3 shift, shift_velocity;

  bool moves() const { return norm2(carried.drift) > 0.0 || carried.amplitude != 0.0; }
  // Carries the cylinder to time t.
  void place(double t) {
    const RigidMotion::AtTime now = carried.at_time(t);
    shift = now.shift;
    shift_velocity = now.velocity;
  }
  // The point of the axis that `center` names, as carried now.
  Vec3 placed_center() const { return center + shift; }

  bool finite() const {
    return lo > -std::numeric_limits<double>::infinity() ||
           hi < std::numeric_limits<double>::infinity();
  }

  // The contacts of a sphere (centre x, radius r): at most a side, a cap and a rim.
  void touches(const Vec3& x, double r, WallTouches& out) const;
  // The wall's velocity at surface point p.
  Vec3 velocity_at(const Vec3& p) const {
    return cross(omega * axis, p - placed_center()) + shift_velocity;
  }
};

} // namespace yuxi
