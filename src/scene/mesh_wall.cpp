#include "scene/mesh_wall.hpp"

#include "scene/closest_point_on_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace yuxi {

namespace {

// The feature a touch lies on, as wall_touch.hpp's rules name it.
FeatureTouch feature_of(const WallTouch& touch, TriangleFeature feature, std::uint32_t t,
                        const std::array<std::uint32_t, 3>& tri) {
  FeatureTouch f;
  f.touch = touch;
  switch (feature) {
  case TriangleFeature::face:
    f.kind = 0, f.a = t;
    break;
  case TriangleFeature::edge_ab:
  case TriangleFeature::edge_bc:
  case TriangleFeature::edge_ca: {
    const int k = static_cast<int>(feature) - static_cast<int>(TriangleFeature::edge_ab);
    const std::uint32_t va = tri[k], vb = tri[(k + 1) % 3];
    f.kind = 1, f.a = std::min(va, vb), f.b = std::max(va, vb);
    break;
  }
  default:
    f.kind = 2;
    f.a = tri[static_cast<int>(feature) - static_cast<int>(TriangleFeature::vertex_a)];
    break;
  }
  return f;
}

} // namespace

void MeshWall::touches(const Vec3& c, double r, std::span<const std::uint32_t> triangles,
                       std::vector<FeatureTouch>& scratch, std::vector<std::uint32_t>& order,
                       WallTouches& out) const {
  // The first touch is written straight into out.at[0] (most grains touch one triangle, and
  // need no rules); from a second on, every touch goes to `scratch` with its feature.
  std::size_t found = 0;
  TriangleFeature first_feature = TriangleFeature::face;
  std::uint32_t first_triangle = 0;
  const double r2 = r * r;
  const bool still = !moves(); // every vertex velocity zero
  const bool conveyor = surface_velocity != Vec3{};
  for (const std::uint32_t t : triangles) {
    const PlacedTriangle& p = placed[t];
    // A triangle whose plane is out of reach cannot be touched.
    const Vec3 from_a = c - p.a;
    const double above = dot(p.normal, from_a); // signed distance from the plane
    if (!(above * above < r2)) continue;
    // A quick look, whose outcome is the closest point's (docs/walls.md section 1): the
    // barycentric weights (u, v, w) of the centre's projection tell a centre well inside the
    // face (by more than their round-off, `slack`), and a triangle out of reach: the
    // projection lies at least -u times the altitude from a beyond the edge bc (and so on),
    // so the triangle is no closer than sqrt(above^2 + that^2).
    constexpr double slack = 1e-9;
    const double bv = dot(p.e1, from_a), bw = dot(p.e2, from_a), bu = 1.0 - bv - bw;
    TrianglePoint q{};
    if (still && bu > slack && bv > slack && bw > slack) {
      q.feature = TriangleFeature::face; // (a still mesh's face needs no point or weights)
    } else {
      double beyond2 = 0.0; // a lower bound on the squared distance in the plane
      const double beyond[3] = {-bu - slack, -bv - slack, -bw - slack};
      for (int k = 0; k < 3; ++k)
        if (beyond[k] > 0.0) beyond2 = std::max(beyond2, beyond[k] * beyond[k] * p.altitude2[k]);
      if (above * above + beyond2 > r2 * (1.0 + slack)) continue;
      // The face's point and weights come from the plane (below) unless the mesh moves.
      q = still ? closest_point_on_triangle<false>(c, p.a, p.b, p.c)
                : closest_point_on_triangle<true>(c, p.a, p.b, p.c);
    }
    WallTouch touch;
    if (q.feature == TriangleFeature::face) {
      // On the face the contact is the plane's: the distance |above| along the normal, with
      // no square root and no round-off in its direction.
      touch.distance = std::abs(above);
      touch.normal = above < 0.0 ? -p.normal : p.normal;
      touch.point = c - above * p.normal;
    } else {
      const Vec3 d = c - q.point;
      const double d2 = norm2(d);
      if (!(d2 < r2)) continue;
      touch.distance = std::sqrt(d2);
      // (The centre on an edge or a vertex: the face normal.)
      touch.normal = touch.distance > 0.0 ? d * (1.0 / touch.distance) : p.normal;
      touch.point = q.point;
    }
    const auto& tri = mesh.triangles[t];
    Vec3 vel = still ? Vec3{}
                     : q.weight[0] * v[tri[0]] + q.weight[1] * v[tri[1]] + q.weight[2] * v[tri[2]];
    if (conveyor) vel += surface_velocity - dot(surface_velocity, touch.normal) * touch.normal;
    touch.velocity = vel;
    touch.element = element_of(t);
    if (found == 0) {
      out.at[0] = touch;
      first_feature = q.feature, first_triangle = t;
    } else {
      if (found == 1)
        scratch.assign(1, feature_of(out.at[0], first_feature, first_triangle,
                                     mesh.triangles[first_triangle]));
      scratch.push_back(feature_of(touch, q.feature, t, tri));
    }
    ++found;
  }
  out.dropped = 0;
  if (found <= 1) { // (the rules keep a lone touch)
    out.n = found;
    return;
  }
  select_touches(
      scratch, cos_merge_, [&](std::uint32_t t) { return mesh.triangles[t]; },
      [&](const FeatureTouch& f) { return feature_closest(f); }, order, out);
}

bool MeshWall::feature_closest(const FeatureTouch& f) const {
  // A point p of a triangle is its closest point to the centre x exactly when
  // (x - p) . (q - p) <= 0 for each of its corners q (the projection onto a convex set), and
  // n = (x - p) / |x - p| is the touch's normal. The triangles that hold an edge are those of
  // its first vertex's star that hold the second; the corners on the feature itself give zero
  // and are passed over. No slack: round-off decides only where the touch nearly repeats
  // another (a foot on the feature itself, the boundary of two regions), and where it drops
  // every touch, select_touches() keeps the deepest.
  const Vec3& n = f.touch.normal;
  const Vec3& p = f.touch.point;
  const bool on_edge = f.kind == 1;
  for (const std::uint32_t t : stars_.around(f.a)) {
    const auto& tri = mesh.triangles[t];
    if (on_edge && tri[0] != f.b && tri[1] != f.b && tri[2] != f.b) continue;
    for (const std::uint32_t q : tri)
      if (q != f.a && !(on_edge && q == f.b) && dot(n, x[q] - p) > 0.0) return false;
  }
  return true;
}

bool MeshWall::within(const Vec3& c, double reach, std::uint32_t t) const {
  const PlacedTriangle& p = placed[t];
  const double above = dot(p.normal, c - p.a), reach2 = reach * reach;
  if (!(above * above < reach2)) return false;
  const TrianglePoint q = closest_point_on_triangle(c, p.a, p.b, p.c);
  return q.feature == TriangleFeature::face || norm2(c - q.point) < reach2;
}

std::vector<Vec3> MeshWall::placed_whole() const {
  const TriangleMesh& all = whole_mesh();
  const WallMotionAtTime now = at_time(motion, placed_at);
  const Vec3 shift = servo_offset * servo_axis;
  std::vector<Vec3> at(all.vertices.size());
  for (std::size_t k = 0; k < at.size(); ++k)
    at[k] = yuxi::place(now, all.vertices[k]).position + shift;
  return at;
}

std::array<Vec3, 8> MeshWall::placed_box_corners() const {
  const WallMotionAtTime now = at_time(motion, placed_at);
  const Vec3 shift = servo_offset * servo_axis;
  std::array<Vec3, 8> corners;
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{k & 1 ? rest_hi_.x : rest_lo_.x, k & 2 ? rest_hi_.y : rest_lo_.y,
                 k & 4 ? rest_hi_.z : rest_lo_.z};
    corners[k] = yuxi::place(now, p).position + shift;
  }
  return corners;
}

void MeshWall::mark_built() {
  servo_offset_built = servo_offset;
  if (const auto* mode = std::get_if<RadialCosineMotion>(&motion))
    built_radial_ = mode->at_time(placed_at).radial;
  else
    built_corners_ = placed_box_corners();
}

double MeshWall::moved2_since_build() const {
  if (const auto* mode = std::get_if<RadialCosineMotion>(&motion)) {
    const double most = std::abs(mode->at_time(placed_at).radial - built_radial_) +
                        std::abs(servo_offset - servo_offset_built);
    return std::isnan(most) ? std::numeric_limits<double>::infinity() : most * most;
  }
  const std::array<Vec3, 8> now = placed_box_corners();
  double most2 = 0.0;
  for (int k = 0; k < 8; ++k) {
    const double d2 = norm2(now[k] - built_corners_[k]);
    if (!(d2 <= most2)) most2 = std::isnan(d2) ? std::numeric_limits<double>::infinity() : d2;
  }
  return most2;
}

bool MeshWall::hold_near(const Vec3& lo, const Vec3& hi, double reach) {
  const std::vector<Vec3> at = placed_whole();
  if (!whole) {
    whole = std::make_shared<const TriangleMesh>(std::move(mesh));
    rest_lo_ = rest_hi_ = whole->vertices.empty() ? Vec3{} : whole->vertices[0];
    for (const Vec3& p : whole->vertices)
      for (int a = 0; a < 3; ++a) {
        rest_lo_[a] = std::min(rest_lo_[a], p[a]);
        rest_hi_[a] = std::max(rest_hi_[a], p[a]);
      }
  }
  const TriangleMesh& all = *whole;
  std::vector<std::uint32_t> near;
  for (std::uint32_t t = 0; t < all.n_triangles(); ++t) {
    const auto [t_lo, t_hi] = all.box_of(t, at);
    bool is_near = true;
    for (int a = 0; a < 3; ++a)
      is_near = is_near && t_hi[a] >= lo[a] - reach && t_lo[a] <= hi[a] + reach;
    if (is_near) near.push_back(t);
  }
  const bool all_near = near.size() == all.n_triangles();
  if (all_near) near.clear(); // (all of it: the whole mesh again, numbered as it is)
  if (near == held && mesh.n_triangles() == (all_near ? all.n_triangles() : near.size()))
    return false;
  mesh = all_near ? all : all.subset(near);
  held = std::move(near);
  rest_normals_.clear();
  stars_ = VertexStars{};
  x.clear();
  place(placed_at);
  return true;
}

} // namespace yuxi
