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
