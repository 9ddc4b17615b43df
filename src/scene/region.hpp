// A region of space, one syntax for every table that needs one: where [[fill]] places grains,
// where [[insert]] pours them, where an [[outlet]] removes them and what a [[measure]] counts.
//
// Shapes:
//   box        lo <= p <= hi
//   cylinder   a point c on the axis, unit axis k, radius R, heights lo <= (p - c).k <= hi
//              (a disc is a short cylinder)
//   sphere     |p - c| <= R
//   mesh       the inside of a closed triangle mesh (an STL file's): a point is inside when a
//              ray from it crosses the surface an odd number of times
//   half_space (p - point).n >= 0, on the side the normal points to
//
// contains_sphere(p, r) asks for the whole ball of radius r inside the region (a grain placed
// there touches none of its faces). Volumes are exact for the analytic shapes and, for a closed
// mesh, the divergence theorem's sum over its triangles.
#pragma once

#include "core/box.hpp"
#include "core/random.hpp"
#include "core/vec3.hpp"
#include "scene/triangle_mesh.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace yuxi {

struct BoxRegion {
  Vec3 lo, hi;
};

struct CylinderRegion {
  Vec3 center;           // c: a point on the axis
  Vec3 axis{0, 0, 1};    // k: unit
  double radius = 1;     // R
  double lo = 0, hi = 1; // heights along k from c
};

struct SphereRegion {
  Vec3 center;
  double radius = 1;
};

// The inside of a closed mesh, with its triangles binned on a uniform grid for the ray and
// distance queries.
class MeshRegion {
public:
  MeshRegion() = default;
  // `mesh` must be closed (every edge shared by two triangles): throws std::invalid_argument
  // naming the number of open edges otherwise.
  explicit MeshRegion(TriangleMesh mesh, std::string file = {});
  // How the file's triangles were placed (TriangleMesh::transform), for the resolved scene.
  double scale = 1.0;
  Vec3 rotate_axis{0, 0, 1};
  double rotate_degrees = 0.0;
  Vec3 translate;
  bool contains(const Vec3& p) const;
  // Distance from p to the nearest point of the surface.
  double distance_to_surface(const Vec3& p) const;
  double volume() const { return volume_; }
  const Vec3& lo() const { return lo_; }
  const Vec3& hi() const { return hi_; }
  const std::string& file() const { return file_; }
  const TriangleMesh& mesh() const { return mesh_; }

private:
  std::vector<std::uint32_t> near(const Vec3& p, double reach) const;
  TriangleMesh mesh_;
  std::string file_;
  Vec3 lo_, hi_;
  double volume_ = 0;
  // Triangles binned on a grid of cells over the bounding box (CSR by cell).
  std::array<int, 3> dims_{1, 1, 1};
  Vec3 cell_;
  std::vector<std::uint32_t> start_, members_;
};

struct HalfSpaceRegion {
  Vec3 point;
  Vec3 normal{0, 0, 1}; // unit, towards the inside
};

using RegionShape =
    std::variant<BoxRegion, CylinderRegion, SphereRegion, MeshRegion, HalfSpaceRegion>;

class Region {
public:
  Region() = default;
  explicit Region(RegionShape shape) : shape_(std::make_shared<RegionShape>(std::move(shape))) {}

  bool contains(const Vec3& p) const;
  bool contains_sphere(const Vec3& p, double r) const;
  // contains_sphere() within `domain`: along a periodic axis that the region spans end to end,
  // a ball may cross the periodic face (it wraps around), and the region is taken at the
  // domain's mid-plane along that axis (exact for a box, and for a cylinder along that axis).
  bool contains_sphere_in(const Vec3& p, double r, const Box& domain) const;
  // The region's volume within `domain` (a half-space's, and any other's part outside the
  // domain, is cut off; estimated by sampling where no closed form applies).
  double volume_in(const Box& domain) const;
  // Corners of a box around the region's part inside `domain`.
  void bounds_in(const Box& domain, Vec3& lo, Vec3& hi) const;
  // A point uniformly distributed in the region's part inside `domain` (rejection sampling in
  // bounds_in); nothing after many misses (a region that barely meets the domain).
  std::optional<Vec3> sample(Random& rng, const Box& domain) const;
  const RegionShape& shape() const { return *shape_; }
  std::string describe() const;

private:
  std::shared_ptr<const RegionShape> shape_; // (a mesh's grid is shared, not copied)
};

} // namespace yuxi
