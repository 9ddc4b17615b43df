#include "core/box.hpp"

#include <cmath>

namespace yuxi {

std::string_view to_string(Boundary b) {
  switch (b) {
  case Boundary::periodic:
    return "periodic";
  case Boundary::wall:
    return "wall";
  case Boundary::open:
    return "open";
  }
  return "?";
}

bool Box::contains(const Vec3& p) const {
  for (int a = 0; a < 3; ++a)
    if (!periodic(a) && (p[a] < lo[a] || p[a] > hi[a])) return false;
  return true;
}

Vec3 Box::wrap(Vec3 p) const {
  for (int a = 0; a < 3; ++a) {
    if (!periodic(a)) continue;
    const double l = length(a);
    p[a] -= l * std::floor((p[a] - lo[a]) / l);
    if (p[a] >= hi[a]) p[a] -= l; // round-off can land exactly on hi
    if (p[a] < lo[a]) p[a] = lo[a];
  }
  return p;
}

Box::Images Box::images_within(const Vec3& p, double reach) const {
  Images out;
  out.at[0] = wrap(p);
  out.n = 1;
  for (int a = 0; a < 3; ++a) {
    if (!periodic(a)) continue;
    const double x = out.at[0][a];
    const double shift = x - lo[a] < reach ? length(a) : (hi[a] - x < reach ? -length(a) : 0.0);
    if (shift == 0.0) continue;
    for (int k = 0, n = out.n; k < n; ++k) {
      Vec3 image = out.at[k];
      image[a] += shift;
      out.at[out.n++] = image;
    }
  }
  return out;
}

Vec3 Box::minimum_image(const Vec3& a, const Vec3& b) const {
  Vec3 d = a - b;
  for (int ax = 0; ax < 3; ++ax) {
    if (!periodic(ax)) continue;
    const double l = length(ax);
    d[ax] -= l * std::round(d[ax] / l);
  }
  return d;
}

} // namespace yuxi
