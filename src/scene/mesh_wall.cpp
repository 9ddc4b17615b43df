#include "scene/mesh_wall.hpp"

#include "scene/closest_point_on_triangle.hpp"

namespace yuxi {

void MeshWall::touches(const Vec3& c, double r, std::span<const std::uint32_t> triangles,
                       std::vector<FeatureTouch>& scratch, std::vector<std::uint32_t>& order,
                       WallTouches& out) const {
  scratch.clear();
  const double r2 = r * r;
  const bool still = !moves(); // every vertex velocity zero
  for (const std::uint32_t t : triangles) {
    const auto& tri = mesh.triangles[t];
    const Vec3 &a = x[tri[0]], &b = x[tri[1]], &cc = x[tri[2]];
    const TrianglePoint q = closest_point_on_triangle(c, a, b, cc);
    const Vec3 d = c - q.point;
    const double d2 = norm2(d);
    if (!(d2 < r2)) continue;
    FeatureTouch f;
    f.touch.distance = std::sqrt(d2);
    if (f.touch.distance > 0.0) {
      f.touch.normal = d * (1.0 / f.touch.distance);
    } else { // the centre on the triangle: the face normal
      f.touch.normal = normalized(cross(b - a, cc - a));
    }
    f.touch.point = q.point;
    Vec3 vel = still ? Vec3{}
                     : q.weight[0] * v[tri[0]] + q.weight[1] * v[tri[1]] + q.weight[2] * v[tri[2]];
    if (surface_velocity != Vec3{})
      vel += surface_velocity - dot(surface_velocity, f.touch.normal) * f.touch.normal;
    f.touch.velocity = vel;
    f.touch.element = t;
    switch (q.feature) {
    case TriangleFeature::face:
      f.kind = 0, f.a = t;
      break;
    case TriangleFeature::edge_ab:
    case TriangleFeature::edge_bc:
    case TriangleFeature::edge_ca: {
      const int k = static_cast<int>(q.feature) - static_cast<int>(TriangleFeature::edge_ab);
      const std::uint32_t va = tri[k], vb = tri[(k + 1) % 3];
      f.kind = 1, f.a = std::min(va, vb), f.b = std::max(va, vb);
      break;
    }
    default:
      f.kind = 2;
      f.a = tri[static_cast<int>(q.feature) - static_cast<int>(TriangleFeature::vertex_a)];
      break;
    }
    scratch.push_back(f);
  }
  if (scratch.size() <= 1) { // (the rules keep a lone touch)
    out.n = scratch.size();
    out.dropped = 0;
    if (out.n == 1) out.at[0] = scratch[0].touch;
    return;
  }
  select_touches(
      scratch, cos_merge_, [&](std::uint32_t t) { return mesh.triangles[t]; }, order, out);
}

} // namespace yuxi
