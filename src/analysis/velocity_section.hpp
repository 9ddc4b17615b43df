// The grains in a thin vertical slice through the basin axis and their in-plane velocities
// (Li & Cai 2008, Fig. 7: the plane through two opposite excitation points).
//
// The plane contains the vertical axis through `axis` (its x and y) and the horizontal
// direction e = (cos a, sin a, 0) of azimuth a (radians from +x toward +y); its normal is
// n = (-sin a, cos a, 0). The wall motion cos(m alpha) has antinodes at alpha = k pi / m, so
// azimuth 0 passes through two opposite antinodes for any mode m.
// A grain is in the slice when |(p - axis) . n| <= half_thickness. For it:
//   s  = (p - axis) . e   signed distance along the plane from the axis (sigma)
//   z  = p.z              height (sigma)
//   vs = v . e, vz = v.z  in-plane velocity (sigma / tau); vn = v . n, the out-of-plane part.
//
// CSV (write_velocity_section_csv), e.g. analysis/velocity_t10.50.csv:
//   s,z,vs,vz,vn        one row per grain in the slice, in input order.
#pragma once

#include "core/vec3.hpp"

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

namespace yuxi::analysis {

struct SectionPoint {
  std::size_t index; // position of the grain in the input spans
  double s, z;
  double vs, vz, vn;
};

struct VelocitySection {
  Vec3 axis;             // a point of the vertical axis (z unused)
  double azimuth;        // radians
  double half_thickness; // sigma
  std::vector<SectionPoint> points;
};

// Throws std::invalid_argument if the spans differ in size or half_thickness < 0.
VelocitySection velocity_section(std::span<const Vec3> positions, std::span<const Vec3> velocities,
                                 const Vec3& axis, double azimuth, double half_thickness);

void write_velocity_section_csv(const std::filesystem::path& path, const VelocitySection& section);

} // namespace yuxi::analysis
