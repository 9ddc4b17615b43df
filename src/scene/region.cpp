#include "scene/region.hpp"

#include "core/units.hpp"
#include "scene/closest_point_on_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <stdexcept>

namespace yuxi {
namespace {

template <class... F> struct Overloaded : F... { using F::operator()...; };
template <class... F> Overloaded(F...) -> Overloaded<F...>;

// A ray's crossing of triangle (a, b, c) at distance t > 0 along d (Moeller & Trumbore 1997).
bool ray_crosses(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, h = cross(d, e2);
  const double det = dot(e1, h);
  if (det == 0.0) return false; // the ray runs parallel to the triangle's plane
  const double f = 1.0 / det;
  const Vec3 s = o - a;
  const double u = f * dot(s, h);
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = cross(s, e1);
  const double v = f * dot(d, q);
  if (v < 0.0 || u + v > 1.0) return false;
  return f * dot(e2, q) > 0.0;
}

} // namespace

MeshRegion::MeshRegion(TriangleMesh mesh, std::string file)
    : mesh_(std::move(mesh)), file_(std::move(file)) {
  if (mesh_.triangles.empty()) throw std::invalid_argument("the mesh of a region has no triangles");
  // Closed: every edge is shared by exactly two triangles.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : mesh_.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::size_t open = 0;
  for (const auto& [e, n] : edges) open += n != 2;
  if (open > 0)
    throw std::invalid_argument(fmt::format(
        "the mesh is not closed: {} of its {} edges do not join exactly two triangles (a region "
        "needs an inside)",
        open, edges.size()));
  lo_ = hi_ = mesh_.vertices.front();
  for (const Vec3& v : mesh_.vertices)
    for (int a = 0; a < 3; ++a) {
      lo_[a] = std::min(lo_[a], v[a]);
      hi_[a] = std::max(hi_[a], v[a]);
    }
  for (const auto& t : mesh_.triangles) {
    const Vec3 &a = mesh_.vertices[t[0]], &b = mesh_.vertices[t[1]], &c = mesh_.vertices[t[2]];
    volume_ += dot(a, cross(b, c)) / 6.0; // divergence theorem, signed by orientation
  }
  volume_ = std::abs(volume_);
  // Cells: about one triangle per cell, at most 64 a side.
  const double n = std::cbrt(static_cast<double>(mesh_.triangles.size()));
  for (int a = 0; a < 3; ++a) {
    dims_[a] = std::clamp(static_cast<int>(std::ceil(n)), 1, 64);
    cell_[a] = std::max(hi_[a] - lo_[a], 1e-12) / dims_[a];
  }
  const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  std::vector<std::vector<std::uint32_t>> bins(cells);
  const auto cell_of = [&](double x, int a) {
    return std::clamp(static_cast<int>(std::floor((x - lo_[a]) / cell_[a])), 0, dims_[a] - 1);
  };
  for (std::uint32_t k = 0; k < mesh_.triangles.size(); ++k) {
    const auto& t = mesh_.triangles[k];
    int from[3], to[3];
    for (int a = 0; a < 3; ++a) {
      const double x0 = mesh_.vertices[t[0]][a], x1 = mesh_.vertices[t[1]][a],
                   x2 = mesh_.vertices[t[2]][a];
      from[a] = cell_of(std::min({x0, x1, x2}), a);
      to[a] = cell_of(std::max({x0, x1, x2}), a);
    }
    for (int i = from[0]; i <= to[0]; ++i)
      for (int j = from[1]; j <= to[1]; ++j)
        for (int l = from[2]; l <= to[2]; ++l)
          bins[(static_cast<std::size_t>(l) * dims_[1] + j) * dims_[0] + i].push_back(k);
  }
  start_.assign(cells + 1, 0);
  for (std::size_t c = 0; c < cells; ++c)
    start_[c + 1] = start_[c] + static_cast<std::uint32_t>(bins[c].size());
  for (const auto& b : bins) members_.insert(members_.end(), b.begin(), b.end());
}

std::vector<std::uint32_t> MeshRegion::near(const Vec3& p, double reach) const {
  int from[3], to[3];
  for (int a = 0; a < 3; ++a) {
    from[a] = std::max(0, static_cast<int>(std::floor((p[a] - reach - lo_[a]) / cell_[a])));
    to[a] =
        std::min(dims_[a] - 1, static_cast<int>(std::floor((p[a] + reach - lo_[a]) / cell_[a])));
  }
  std::vector<std::uint32_t> out;
  for (int i = from[0]; i <= to[0]; ++i)
    for (int j = from[1]; j <= to[1]; ++j)
      for (int l = from[2]; l <= to[2]; ++l) {
        const std::size_t c = (static_cast<std::size_t>(l) * dims_[1] + j) * dims_[0] + i;
        out.insert(out.end(), members_.begin() + start_[c], members_.begin() + start_[c + 1]);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool MeshRegion::contains(const Vec3& p) const {
  for (int a = 0; a < 3; ++a)
    if (!(p[a] >= lo_[a] && p[a] <= hi_[a])) return false;
  // A ray upwards, tilted by irrational small amounts so that it meets no edge or vertex of a
  // mesh laid out on a grid; the triangles of the columns of cells it passes on its way to the
  // top of the box.
  const Vec3 d = normalized(Vec3{1e-3 * std::sqrt(2.0), 1e-3 * std::sqrt(3.0), 1.0});
  const Vec3 end = p + ((hi_.z - p.z) / d.z) * d;
  int from[2], to[2];
  for (int a = 0; a < 2; ++a) {
    const auto column = [&](double x) {
      return std::clamp(static_cast<int>(std::floor((x - lo_[a]) / cell_[a])), 0, dims_[a] - 1);
    };
    from[a] = column(std::min(p[a], end[a]));
    to[a] = column(std::max(p[a], end[a]));
  }
  std::vector<std::uint32_t> candidates;
  for (int i = from[0]; i <= to[0]; ++i)
    for (int j = from[1]; j <= to[1]; ++j)
      for (int l = 0; l < dims_[2]; ++l) {
        const std::size_t c = (static_cast<std::size_t>(l) * dims_[1] + j) * dims_[0] + i;
        candidates.insert(candidates.end(), members_.begin() + start_[c],
                          members_.begin() + start_[c + 1]);
      }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  int crossings = 0;
  for (std::uint32_t k : candidates) {
    const auto& t = mesh_.triangles[k];
    crossings +=
        ray_crosses(p, d, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]);
  }
  return crossings % 2 == 1;
}

double MeshRegion::distance_to_surface(const Vec3& p) const {
  double best = HUGE_VAL;
  double reach = std::max({cell_.x, cell_.y, cell_.z});
  // Widen the search until a triangle is found within it (every triangle lies in some cell).
  for (int round = 0; round < 64 && !(best <= reach); ++round, reach *= 2) {
    for (std::uint32_t k : near(p, reach)) {
      const auto& t = mesh_.triangles[k];
      const auto c = closest_point_on_triangle(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]],
                                               mesh_.vertices[t[2]]);
      best = std::min(best, norm(c.point - p));
    }
  }
  return best;
}

bool Region::contains(const Vec3& p) const {
  return std::visit(
      Overloaded{[&](const BoxRegion& b) {
                   return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y &&
                          p.z >= b.lo.z && p.z <= b.hi.z;
                 },
                 [&](const CylinderRegion& c) {
                   const Vec3 d = p - c.center;
                   const double h = dot(d, c.axis);
                   return h >= c.lo && h <= c.hi && norm2(d - h * c.axis) <= c.radius * c.radius;
                 },
                 [&](const SphereRegion& s) { return norm2(p - s.center) <= s.radius * s.radius; },
                 [&](const MeshRegion& m) { return m.contains(p); },
                 [&](const HalfSpaceRegion& h) { return dot(p - h.point, h.normal) >= 0.0; }},
      *shape_);
}

bool Region::contains_sphere_in(const Vec3& p, double r, const Box& domain) const {
  Vec3 at = domain.wrap(p);
  bool wraps = false;
  Vec3 lo, hi;
  for (int a = 0; a < 3; ++a)
    if (domain.periodic(a)) {
      if (!wraps) bounds_in(domain, lo, hi);
      wraps = true;
      if (lo[a] <= domain.lo[a] && hi[a] >= domain.hi[a])
        at[a] = 0.5 * (domain.lo[a] + domain.hi[a]);
    }
  return contains_sphere(at, r);
}

bool Region::contains_sphere(const Vec3& p, double r) const {
  return std::visit(
      Overloaded{
          [&](const BoxRegion& b) {
            for (int a = 0; a < 3; ++a)
              if (!(p[a] - r >= b.lo[a] && p[a] + r <= b.hi[a])) return false;
            return true;
          },
          [&](const CylinderRegion& c) {
            const Vec3 d = p - c.center;
            const double h = dot(d, c.axis);
            return h - r >= c.lo && h + r <= c.hi && c.radius >= r &&
                   norm2(d - h * c.axis) <= (c.radius - r) * (c.radius - r);
          },
          [&](const SphereRegion& s) {
            return s.radius >= r && norm2(p - s.center) <= (s.radius - r) * (s.radius - r);
          },
          [&](const MeshRegion& m) { return m.contains(p) && m.distance_to_surface(p) >= r; },
          [&](const HalfSpaceRegion& h) { return dot(p - h.point, h.normal) >= r; }},
      *shape_);
}

void Region::bounds_in(const Box& domain, Vec3& lo, Vec3& hi) const {
  lo = domain.lo, hi = domain.hi;
  const auto clip = [&](const Vec3& a, const Vec3& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max(lo[k], a[k]);
      hi[k] = std::min(hi[k], b[k]);
    }
  };
  std::visit(Overloaded{[&](const BoxRegion& b) { clip(b.lo, b.hi); },
                        [&](const CylinderRegion& c) {
                          // Each end disc's extent along an axis a: R sqrt(1 - k_a^2).
                          Vec3 a = c.center + c.lo * c.axis, b = c.center + c.hi * c.axis, l, h;
                          for (int k = 0; k < 3; ++k) {
                            const double e =
                                c.radius * std::sqrt(std::max(0.0, 1.0 - c.axis[k] * c.axis[k]));
                            l[k] = std::min(a[k], b[k]) - e;
                            h[k] = std::max(a[k], b[k]) + e;
                          }
                          clip(l, h);
                        },
                        [&](const SphereRegion& s) {
                          const Vec3 r{s.radius, s.radius, s.radius};
                          clip(s.center - r, s.center + r);
                        },
                        [&](const MeshRegion& m) { clip(m.lo(), m.hi()); },
                        [&](const HalfSpaceRegion&) {}},
             *shape_);
}

namespace {

// The volume of {y in [lo, hi] : n . (y - p) >= 0}, exactly. Along the axes where n_i != 0 put
// y_i = base_i + sign(n_i) t_i with t_i in [0, L_i], so that the condition reads
// sum a_i t_i >= c with a_i = |n_i|. The volume where sum a_i t_i <= s in that k-box is, by
// inclusion and exclusion over its corners,
//   V(s) = sum over subsets S of the axes of (-1)^|S| max(0, s - sum_{i in S} a_i L_i)^k
//          / (k! prod a_i),
// and the half-space keeps the rest, times the extents along the axes that n does not see.
double half_space_volume(const HalfSpaceRegion& h, const Vec3& lo, const Vec3& hi) {
  double across = 1, c = dot(h.normal, h.point), kept = 1, denominator = 1;
  std::array<double, 3> reach{};
  int k = 0;
  for (int i = 0; i < 3; ++i) {
    const double length = hi[i] - lo[i], n = h.normal[i];
    if (std::abs(n) < 1e-14) {
      across *= length;
      continue;
    }
    c -= n * (n > 0 ? lo[i] : hi[i]);
    reach[k++] = std::abs(n) * length;
    kept *= length;
    denominator *= std::abs(n) * k;
  }
  if (k == 0) return c <= 0 ? across : 0.0;
  double below = 0;
  for (int subset = 0; subset < (1 << k); ++subset) {
    double s = c;
    int sign = 1;
    for (int i = 0; i < k; ++i)
      if (subset & (1 << i)) s -= reach[i], sign = -sign;
    if (s > 0) below += sign * std::pow(s, k);
  }
  return across * std::clamp(kept - below / denominator, 0.0, kept);
}

} // namespace

double Region::volume_in(const Box& domain) const {
  Vec3 lo, hi;
  bounds_in(domain, lo, hi);
  for (int a = 0; a < 3; ++a)
    if (!(hi[a] > lo[a])) return 0.0;
  const double bounds = (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  // Closed forms where the whole region lies inside the domain.
  Vec3 full_lo, full_hi;
  bounds_in(Box{{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, {HUGE_VAL, HUGE_VAL, HUGE_VAL}, {}}, full_lo,
            full_hi);
  const bool whole = full_lo.x >= domain.lo.x && full_lo.y >= domain.lo.y &&
                     full_lo.z >= domain.lo.z && full_hi.x <= domain.hi.x &&
                     full_hi.y <= domain.hi.y && full_hi.z <= domain.hi.z;
  if (std::holds_alternative<BoxRegion>(*shape_)) return bounds;
  if (whole) {
    if (const auto* c = std::get_if<CylinderRegion>(&*shape_))
      return pi * c->radius * c->radius * (c->hi - c->lo);
    if (const auto* s = std::get_if<SphereRegion>(&*shape_))
      return 4.0 / 3.0 * pi * s->radius * s->radius * s->radius;
    if (const auto* m = std::get_if<MeshRegion>(&*shape_)) return m->volume();
  }
  if (const auto* h = std::get_if<HalfSpaceRegion>(&*shape_)) return half_space_volume(*h, lo, hi);
  // Otherwise the share of a fixed sample of the bounds that falls inside.
  Random rng(12345);
  constexpr int n = 200000;
  int inside = 0;
  for (int k = 0; k < n; ++k)
    inside += contains({rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)});
  return bounds * inside / n;
}

std::optional<Vec3> Region::sample(Random& rng, const Box& domain) const {
  Vec3 lo, hi;
  bounds_in(domain, lo, hi);
  for (int a = 0; a < 3; ++a)
    if (!(hi[a] >= lo[a])) return std::nullopt;
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Vec3 p{rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
    if (contains(p)) return p;
  }
  return std::nullopt;
}

std::string Region::describe() const {
  return std::visit(
      Overloaded{
          [](const BoxRegion& b) {
            return fmt::format("box [{}, {}] x [{}, {}] x [{}, {}]", b.lo.x, b.hi.x, b.lo.y, b.hi.y,
                               b.lo.z, b.hi.z);
          },
          [](const CylinderRegion& c) {
            return fmt::format("cylinder of radius {} about ({}, {}, {}) + h ({}, {}, {}), h in "
                               "[{}, {}]",
                               c.radius, c.center.x, c.center.y, c.center.z, c.axis.x, c.axis.y,
                               c.axis.z, c.lo, c.hi);
          },
          [](const SphereRegion& s) {
            return fmt::format("sphere of radius {} about ({}, {}, {})", s.radius, s.center.x,
                               s.center.y, s.center.z);
          },
          [](const MeshRegion& m) {
            return fmt::format("inside of the mesh {} ({} triangles)", m.file(),
                               m.mesh().n_triangles());
          },
          [](const HalfSpaceRegion& h) {
            return fmt::format("half-space (p - ({}, {}, {})) . ({}, {}, {}) >= 0", h.point.x,
                               h.point.y, h.point.z, h.normal.x, h.normal.y, h.normal.z);
          }},
      *shape_);
}

} // namespace yuxi
