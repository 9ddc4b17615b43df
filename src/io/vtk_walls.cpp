#include "io/vtk_walls.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace yuxi {

void WallSurface::add_mesh(const MeshWall& mesh, std::span<const Vec3> forces,
                           std::int32_t wall_index) {
  const auto base = static_cast<std::uint32_t>(points.size());
  // The whole mesh, placed, where a rank holds a part of it.
  const TriangleMesh& whole = mesh.whole_mesh();
  const std::vector<Vec3> at =
      mesh.holds_whole() && mesh.x.size() == whole.vertices.size() ? mesh.x : mesh.placed_whole();
  points.insert(points.end(), at.begin(), at.end());
  const bool loaded = forces.size() == whole.n_triangles();
  for (std::size_t k = 0; k < whole.n_triangles(); ++k) {
    const auto& t = whole.triangles[k];
    triangles.push_back({base + t[0], base + t[1], base + t[2]});
    force.push_back(loaded ? forces[k] : Vec3{});
    wall.push_back(wall_index);
  }
}

void WallSurface::add_cylinder(const CylinderWall& c, const Box& box, double t,
                               std::int32_t wall_index, int segments) {
  // Heights along the axis: the ends, an infinite one where the axis leaves the box.
  const Vec3 center = c.placed_center();
  double h_min = std::numeric_limits<double>::infinity(), h_max = -h_min;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                 corner & 4 ? box.hi.z : box.lo.z};
    const double h = dot(p - center, c.axis);
    h_min = std::min(h_min, h);
    h_max = std::max(h_max, h);
  }
  const double lo = std::isfinite(c.lo) ? c.lo : h_min;
  const double hi = std::isfinite(c.hi) ? c.hi : h_max;
  if (!(hi > lo) || segments < 3) return;
  // (e1, e2, axis) right-handed: the side's triangles face away from the axis, the caps'
  // outwards along it.
  const Vec3 e1 = perpendicular(c.axis);
  const Vec3 e2 = cross(c.axis, e1);
  const auto n = static_cast<std::uint32_t>(segments);
  const auto ring_lo = static_cast<std::uint32_t>(points.size()), ring_hi = ring_lo + n;
  for (const double h : {lo, hi})
    for (std::uint32_t j = 0; j < n; ++j) {
      const double phi = c.omega * t + 2.0 * std::numbers::pi * j / n;
      points.push_back(center + h * c.axis + c.radius * (std::cos(phi) * e1 + std::sin(phi) * e2));
    }
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t d) {
    triangles.push_back({a, b, d});
    force.push_back({});
    wall.push_back(wall_index);
  };
  for (std::uint32_t j = 0; j < n; ++j) {
    const std::uint32_t next = (j + 1) % n;
    add(ring_lo + j, ring_lo + next, ring_hi + next);
    add(ring_lo + j, ring_hi + next, ring_hi + j);
  }
  if (!c.capped) return;
  if (std::isfinite(c.lo)) {
    const auto centre = static_cast<std::uint32_t>(points.size());
    points.push_back(center + c.lo * c.axis);
    for (std::uint32_t j = 0; j < n; ++j) add(centre, ring_lo + (j + 1) % n, ring_lo + j);
  }
  if (std::isfinite(c.hi)) {
    const auto centre = static_cast<std::uint32_t>(points.size());
    points.push_back(center + c.hi * c.axis);
    for (std::uint32_t j = 0; j < n; ++j) add(centre, ring_hi + j, ring_hi + (j + 1) % n);
  }
}

double WallSurface::pressure(std::size_t k) const {
  const auto& t = triangles[k];
  const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]); // 2 area
  const double n2 = norm2(n);
  // |f . n / |n|| / (|n| / 2)
  return n2 > 0.0 ? 2.0 * std::abs(dot(force[k], n)) / n2 : 0.0;
}

void write_vtp(const std::filesystem::path& path, const WallSurface& s) {
  // Shortest decimal forms that read back to the same doubles.
  std::string xml;
  auto out = std::back_inserter(xml);
  const auto open_array = [&](const char* type, const char* name, int components) {
    fmt::format_to(out,
                   "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
                   "format=\"ascii\">\n",
                   type, name, components);
  };
  constexpr const char* close_array = "        </DataArray>\n";
  xml += "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PolyData>\n";
  fmt::format_to(out,
                 "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
                 "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
                 s.points.size(), s.triangles.size());
  xml += "      <CellData Scalars=\"pressure\" Vectors=\"force\">\n";
  open_array("Float64", "force", 3);
  for (const Vec3& f : s.force) fmt::format_to(out, "          {} {} {}\n", f.x, f.y, f.z);
  xml += close_array;
  open_array("Float64", "pressure", 1);
  for (std::size_t k = 0; k < s.triangles.size(); ++k)
    fmt::format_to(out, "          {}\n", s.pressure(k));
  xml += close_array;
  open_array("Int32", "wall", 1);
  for (const std::int32_t w : s.wall) fmt::format_to(out, "          {}\n", w);
  xml += close_array;
  xml += "      </CellData>\n      <Points>\n";
  open_array("Float64", "Points", 3);
  for (const Vec3& p : s.points) fmt::format_to(out, "          {} {} {}\n", p.x, p.y, p.z);
  xml += close_array;
  xml += "      </Points>\n      <Polys>\n";
  open_array("Int64", "connectivity", 1);
  for (const auto& t : s.triangles) fmt::format_to(out, "          {} {} {}\n", t[0], t[1], t[2]);
  xml += close_array;
  open_array("Int64", "offsets", 1); // where each triangle's points end in the connectivity
  for (std::size_t k = 1; k <= s.triangles.size(); ++k)
    fmt::format_to(out, "          {}\n", 3 * k);
  xml += close_array;
  xml += "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";

  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(xml.data(), static_cast<std::streamsize>(xml.size()));
  file.close();
  if (!file) throw std::runtime_error("cannot write " + path.string());
}

} // namespace yuxi
