#include "analysis/velocity_section.hpp"

#include "analysis/analysis_csv.hpp"

#include <cmath>
#include <stdexcept>

namespace yuxi::analysis {

VelocitySection velocity_section(std::span<const Vec3> positions, std::span<const Vec3> velocities,
                                 const Vec3& axis, double azimuth, double half_thickness) {
  if (positions.size() != velocities.size())
    throw std::invalid_argument("velocity_section: positions and velocities differ in size");
  if (!(half_thickness >= 0.0))
    throw std::invalid_argument("velocity_section: half_thickness must be >= 0");
  const Vec3 e{std::cos(azimuth), std::sin(azimuth), 0.0};
  const Vec3 n{-std::sin(azimuth), std::cos(azimuth), 0.0};
  VelocitySection section{axis, azimuth, half_thickness, {}};
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const Vec3 d{positions[k].x - axis.x, positions[k].y - axis.y, 0.0};
    if (!(std::abs(dot(d, n)) <= half_thickness)) continue;
    const Vec3& v = velocities[k];
    section.points.push_back({k, dot(d, e), positions[k].z, dot(v, e), v.z, dot(v, n)});
  }
  return section;
}

void write_velocity_section_csv(const std::filesystem::path& path, const VelocitySection& section) {
  CsvWriter csv(path, {"s", "z", "vs", "vz", "vn"});
  for (const auto& p : section.points) csv.row({p.s, p.z, p.vs, p.vz, p.vn});
  csv.close();
}

} // namespace yuxi::analysis
