// The fish basin's radial cosine wave at one wall point (docs/models/fish-basin.md section 6):
// a point at rest at azimuth alpha about the vertical axis through `center` moves radially by
// dr cos(m alpha) sin(omega (t - t0)), at the speed omega dr cos(m alpha) cos(omega (t - t0)).
// The two phase terms come in computed once per step for every point (`radial`, `speed`), so
// the sine and cosine are taken once, on the host; cos(m alpha) comes from cos(alpha) by the
// Chebyshev recurrence T_{k+1}(c) = 2 c T_k(c) - T_{k-1}(c), with no trigonometric call per
// point. Written once for the CPU engine (scene/wall_motion.hpp) and the device engine.
#pragma once

#include "core/host_device.hpp"
#include "core/vec3.hpp"

#include <cmath>

namespace yuxi {

struct PlacedPoint {
  Vec3 position;
  Vec3 velocity;
};

YUXI_HD inline PlacedPoint radial_cosine_place(const Vec3& center, int mode, double radial,
                                               double speed, const Vec3& rest) {
  const double dx = rest.x - center.x, dy = rest.y - center.y;
  const double r0 = std::sqrt(dx * dx + dy * dy);
  if (r0 == 0.0) return {rest, {}};
  const double c = dx / r0, s = dy / r0; // cos(alpha), sin(alpha)
  double before = 1.0, shape = c;        // T_0, T_1
  for (int k = 1; k < mode; ++k) {
    const double next = 2.0 * c * shape - before;
    before = shape;
    shape = next;
  }
  if (mode == 0) shape = 1.0;
  const double r = r0 + shape * radial;
  const double rdot = shape * speed;
  return {{center.x + r * c, center.y + r * s, rest.z}, {rdot * c, rdot * s, 0.0}};
}

} // namespace yuxi
