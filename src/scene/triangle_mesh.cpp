#include "scene/triangle_mesh.hpp"

#include "scene/rigid_motion.hpp"

#include <bit>
#include <cmath>
#include <map>
#include <numbers>
#include <unordered_map>

namespace yuxi {
namespace {

struct CoordinateBits {
  std::uint64_t x, y, z;
  bool operator==(const CoordinateBits&) const = default;
};
struct CoordinateBitsHash {
  std::size_t operator()(const CoordinateBits& c) const noexcept {
    std::uint64_t h = c.x * 0x9E3779B97F4A7C15ull;
    h ^= c.y + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2);
    h ^= c.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

} // namespace

TriangleMesh TriangleMesh::weld(const std::vector<std::array<Vec3, 3>>& soup) {
  TriangleMesh mesh;
  std::unordered_map<CoordinateBits, std::uint32_t, CoordinateBitsHash> index;
  index.reserve(soup.size());
  mesh.triangles.reserve(soup.size());
  for (const auto& corners : soup) {
    std::array<std::uint32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = corners[k];
      // +0.0 and -0.0 are one place
      const CoordinateBits key{std::bit_cast<std::uint64_t>(p.x + 0.0),
                               std::bit_cast<std::uint64_t>(p.y + 0.0),
                               std::bit_cast<std::uint64_t>(p.z + 0.0)};
      const auto [it, fresh] = index.emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
      if (fresh) mesh.vertices.push_back(p);
      tri[k] = it->second;
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

void TriangleMesh::transform(double scale, const Vec3& axis, double degrees, const Vec3& shift) {
  RigidMotion turn;
  turn.axis = axis;
  turn.omega = degrees * std::numbers::pi / 180.0;
  const RigidMotion::AtTime r = turn.at_time(1.0); // a turn by omega * 1
  for (Vec3& v : vertices) {
    const Vec3 scaled = scale * v;
    v = (degrees == 0.0 ? scaled : r.turn(scaled)) + shift;
  }
}

bool TriangleMesh::finite() const {
  for (const Vec3& v : vertices)
    if (!is_finite(v)) return false;
  return true;
}

std::size_t TriangleMesh::non_manifold_edges() const {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  std::size_t n = 0;
  for (const auto& [edge, c] : count) n += c > 2 ? 1 : 0;
  return n;
}

TriangleMesh TriangleMesh::subset(std::span<const std::uint32_t> kept) const {
  constexpr std::uint32_t unused = ~std::uint32_t{0};
  std::vector<std::uint32_t> renumbered(vertices.size(), unused);
  for (const std::uint32_t t : kept)
    for (const std::uint32_t v : triangles[t]) renumbered[v] = 0;
  TriangleMesh part;
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (renumbered[v] != unused) {
      renumbered[v] = static_cast<std::uint32_t>(part.vertices.size());
      part.vertices.push_back(vertices[v]);
    }
  part.triangles.reserve(kept.size());
  for (const std::uint32_t t : kept)
    part.triangles.push_back(
        {renumbered[triangles[t][0]], renumbered[triangles[t][1]], renumbered[triangles[t][2]]});
  return part;
}

} // namespace yuxi
