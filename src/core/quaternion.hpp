// Unit quaternions for the orientation of a rigid body: q = (w, x, y, z) turns a vector of the
// body's frame into the lab's, v_lab = q v_body q*. Hamilton's convention (i j = k), as in Miller
// et al., J. Chem. Phys. 116:8649 (2002), whose rotation integrator (core/free_rotation.hpp)
// works on them (docs/clumps.md).
#pragma once

#include "core/host_device.hpp"
#include "core/portable_math.hpp"
#include "core/vec3.hpp"

#include <cmath>

namespace yuxi {

struct Quaternion {
  double w = 1.0, x = 0.0, y = 0.0, z = 0.0;

  YUXI_HD constexpr Vec3 vector() const { return {x, y, z}; }
  constexpr bool operator==(const Quaternion&) const = default;
};

YUXI_HD constexpr Quaternion operator*(const Quaternion& a, const Quaternion& b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
YUXI_HD constexpr Quaternion operator*(double s, const Quaternion& a) {
  return {s * a.w, s * a.x, s * a.y, s * a.z};
}
YUXI_HD constexpr Quaternion operator+(const Quaternion& a, const Quaternion& b) {
  return {a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z};
}
YUXI_HD constexpr Quaternion conjugate(const Quaternion& a) {
  return {a.w, -a.x, -a.y, -a.z};
}
YUXI_HD constexpr double dot(const Quaternion& a, const Quaternion& b) {
  return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}
// Whether q has unit length to 1e-9 (false for NaN): an orientation.
YUXI_HD constexpr bool is_unit(const Quaternion& q) {
  const double d = dot(q, q) - 1.0;
  return d < 1e-9 && d > -1e-9;
}
YUXI_HD inline Quaternion normalized(const Quaternion& a) {
  return (1.0 / std::sqrt(dot(a, a))) * a;
}
// The pure quaternion (0, v).
YUXI_HD constexpr Quaternion pure(const Vec3& v) {
  return {0.0, v.x, v.y, v.z};
}

// v_body turned into the lab's frame, q v q* (for a unit q), as R(q) v with R's rows written out.
YUXI_HD constexpr Vec3 to_lab(const Quaternion& q, const Vec3& v) {
  const double ww = q.w * q.w, xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return {(ww + xx - yy - zz) * v.x + 2.0 * (xy - wz) * v.y + 2.0 * (xz + wy) * v.z,
          2.0 * (xy + wz) * v.x + (ww - xx + yy - zz) * v.y + 2.0 * (yz - wx) * v.z,
          2.0 * (xz - wy) * v.x + 2.0 * (yz + wx) * v.y + (ww - xx - yy + zz) * v.z};
}
// The rotation matrix of q, v_lab = R v_body, built once for many vectors: R * v gives to_lab's
// bits (the same products, added in the same order).
struct Rotation {
  Vec3 row[3];
  YUXI_HD constexpr Vec3 operator*(const Vec3& v) const {
    return {row[0].x * v.x + row[0].y * v.y + row[0].z * v.z,
            row[1].x * v.x + row[1].y * v.y + row[1].z * v.z,
            row[2].x * v.x + row[2].y * v.y + row[2].z * v.z};
  }
};
YUXI_HD constexpr Rotation rotation_of(const Quaternion& q) {
  const double ww = q.w * q.w, xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return {{{ww + xx - yy - zz, 2.0 * (xy - wz), 2.0 * (xz + wy)},
           {2.0 * (xy + wz), ww - xx + yy - zz, 2.0 * (yz - wx)},
           {2.0 * (xz - wy), 2.0 * (yz + wx), ww - xx - yy + zz}}};
}
// v_lab turned into the body's frame, q* v q.
YUXI_HD constexpr Vec3 to_body(const Quaternion& q, const Vec3& v) {
  return to_lab(conjugate(q), v);
}

// The rotation by `angle` (radians) about the unit vector `axis`.
YUXI_HD inline Quaternion about_axis(const Vec3& axis, double angle) {
  const portable::SinCos t = portable::sin_cos(0.5 * angle);
  return {t.cos, t.sin * axis.x, t.sin * axis.y, t.sin * axis.z};
}

// The unit quaternion of a proper rotation matrix m (rows m[r][c], det +1), by Shepperd's
// choice of the largest of w, x, y, z to divide by (J. Guidance 1:223, 1978), with w >= 0.
YUXI_HD inline Quaternion from_rotation_matrix(const double (&m)[3][3]) {
  const double trace = m[0][0] + m[1][1] + m[2][2];
  Quaternion q;
  if (trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + trace); // 4 w
    q = {0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
  } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]); // 4 x
    q = {(m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
  } else if (m[1][1] >= m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]); // 4 y
    q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]); // 4 z
    q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s};
  }
  if (q.w < 0) q = -1.0 * q;
  return normalized(q);
}

} // namespace yuxi
