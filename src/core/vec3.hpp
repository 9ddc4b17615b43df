// A 3-vector of doubles with the arithmetic the contact laws need.
#pragma once

#include "core/host_device.hpp"

#include <cmath>

namespace yuxi {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  YUXI_HD constexpr double& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }
  YUXI_HD constexpr double operator[](int axis) const {
    return axis == 0 ? x : (axis == 1 ? y : z);
  }

  YUXI_HD constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x, y += o.y, z += o.z;
    return *this;
  }
  YUXI_HD constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x, y -= o.y, z -= o.z;
    return *this;
  }
  YUXI_HD constexpr Vec3& operator*=(double s) {
    x *= s, y *= s, z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3&) const = default; // (on both sides: defaulted)
};

YUXI_HD constexpr Vec3 operator+(Vec3 a, const Vec3& b) {
  return a += b;
}
YUXI_HD constexpr Vec3 operator-(Vec3 a, const Vec3& b) {
  return a -= b;
}
YUXI_HD constexpr Vec3 operator-(const Vec3& a) {
  return {-a.x, -a.y, -a.z};
}
YUXI_HD constexpr Vec3 operator*(Vec3 a, double s) {
  return a *= s;
}
YUXI_HD constexpr Vec3 operator*(double s, Vec3 a) {
  return a *= s;
}
YUXI_HD constexpr Vec3 operator/(const Vec3& a, double s) {
  return {a.x / s, a.y / s, a.z / s};
}

YUXI_HD constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
YUXI_HD constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
YUXI_HD constexpr double norm2(const Vec3& a) {
  return dot(a, a);
}
YUXI_HD inline double norm(const Vec3& a) {
  return std::sqrt(norm2(a));
}
YUXI_HD inline Vec3 normalized(const Vec3& a) {
  return a / norm(a);
}
// A unit vector perpendicular to the unit vector a (crossed with whichever of x and y lies
// farther from it).
YUXI_HD inline Vec3 perpendicular(const Vec3& a) {
  return normalized(cross(a, std::abs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
}
YUXI_HD inline bool is_finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

} // namespace yuxi
