#include "scene/cylinder_wall.hpp"

#include <cmath>

namespace yuxi {

void CylinderWall::touches(const Vec3& x, double r, WallTouches& out) const {
  out.n = 0;
  out.dropped = 0;
  const Vec3 c = placed_center();
  const Vec3 d = x - c;
  const double h = dot(d, axis);
  const Vec3 radial = d - h * axis;
  const double rho = norm(radial);
  // The unit radial direction (any, on the axis itself: no side or rim contact is possible
  // there unless the radius is below the grain's).
  const Vec3 e = rho > 0.0 ? radial * (1.0 / rho) : perpendicular(axis);
  const auto add = [&](double distance, const Vec3& normal, const Vec3& point,
                       std::uint32_t element) {
    // A grain more than its radius behind a patch is on the patch's other side: it touches
    // nothing there (several silos can then stand in one box).
    if (!(distance < r) || distance < -r) return;
    WallTouch t;
    t.distance = distance;
    t.normal = normal;
    t.point = point;
    t.velocity = velocity_at(point);
    t.element = element;
    // the deepest first
    std::size_t k = out.n;
    while (k > 0 && out.at[k - 1].distance > distance) {
      out.at[k] = out.at[k - 1];
      --k;
    }
    out.at[k] = t;
    ++out.n;
  };
  const bool within = h >= lo && h <= hi;
  const bool over_cap = rho <= radius;
  if (within) {
    const Vec3 point = c + h * axis + radius * e;
    if (inside)
      add(radius - rho, -e, point, 0);
    else
      add(rho - radius, e, point, 0);
  }
  if (capped && over_cap) {
    const Vec3 foot_lo = c + lo * axis + radial, foot_hi = c + hi * axis + radial;
    if (inside) {
      if (std::isfinite(lo)) add(h - lo, axis, foot_lo, 1);
      if (std::isfinite(hi)) add(hi - h, -axis, foot_hi, 2);
    } else {
      if (std::isfinite(lo) && h < lo) add(lo - h, -axis, foot_lo, 1);
      if (std::isfinite(hi) && h > hi) add(h - hi, axis, foot_hi, 2);
    }
  }
  // Rims: beyond an end, and not over a cap that already gave the contact.
  if (!within && !(capped && over_cap)) {
    const double end = h < lo ? lo : hi;
    if (std::isfinite(end)) {
      const Vec3 point = c + end * axis + radius * e;
      const Vec3 gap = x - point;
      const double dist = norm(gap);
      if (dist > 0.0) add(dist, gap * (1.0 / dist), point, h < lo ? 3 : 4);
    }
  }
}

} // namespace yuxi
