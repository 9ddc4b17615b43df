// The union's moments by slices (sphere_union.hpp for the method and its accuracy).
#include "scene/sphere_union.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace yuxi {
namespace {

constexpr double pi = std::numbers::pi;

// Gauss-Legendre nodes and weights on [0, 1] (Newton's iteration on P_n from Tricomi's first
// guess), exact for polynomials of degree 2 n - 1.
struct Quadrature {
  std::vector<double> nodes, weights;
};
Quadrature gauss_legendre(int n) {
  Quadrature g;
  for (int i = 1; i <= n; ++i) {
    double x = std::cos(pi * (i - 0.25) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    g.nodes.push_back(0.5 * (1 - x));
    g.weights.push_back(1.0 / ((1 - x * x) * dp * dp));
  }
  return g;
}

const Quadrature& arc_rule() {
  static const Quadrature g = gauss_legendre(16);
  return g;
}
const Quadrature& height_rule() {
  static const Quadrature g = gauss_legendre(24);
  return g;
}

struct Disc {
  double x = 0, y = 0, r = 0;
};

// The integrals over a plane region of 1, x, y, x^2, y^2 and x y.
struct AreaMoments {
  double a = 0, mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
};

// The boundary integrals of Green's theorem along the arc theta0..theta1 of a circle, traversed
// counterclockwise: A = 1/2 (x dy - y dx), M_x = x^2/2 dy, M_y = -y^2/2 dx, S_xx = x^3/3 dy,
// S_yy = -y^3/3 dx, S_xy = x^2 y/2 dy. The integrands are trigonometric polynomials of degree
// 4 or less; 16 Gauss points on pieces of at most pi/2 integrate them to round-off.
void add_arc(AreaMoments& m, const Disc& c, double theta0, double theta1) {
  const Quadrature& g = arc_rule();
  const int pieces = std::max(1, static_cast<int>(std::ceil((theta1 - theta0) / (0.5 * pi))));
  const double h = (theta1 - theta0) / pieces;
  for (int piece = 0; piece < pieces; ++piece)
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
      const double theta = theta0 + h * (piece + g.nodes[k]);
      const double cs = std::cos(theta), sn = std::sin(theta);
      const double x = c.x + c.r * cs, y = c.y + c.r * sn;
      const double dx = -c.r * sn * h * g.weights[k], dy = c.r * cs * h * g.weights[k];
      m.a += 0.5 * (x * dy - y * dx);
      m.mx += 0.5 * x * x * dy;
      m.my -= 0.5 * y * y * dx;
      m.sxx += x * x * x * dy / 3.0;
      m.syy -= y * y * y * dx / 3.0;
      m.sxy += 0.5 * x * x * y * dy;
    }
}

// The moments of a union of discs: each circle's arcs that no other disc covers. Of two equal
// discs the first counts; a circle inside another, or touching it from inside, is covered.
AreaMoments union_of_discs(const std::vector<Disc>& discs) {
  AreaMoments m;
  std::vector<std::pair<double, double>> covered;
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const Disc& c = discs[i];
    covered.clear();
    bool inside = false;
    for (std::size_t j = 0; j < discs.size() && !inside; ++j) {
      if (j == i) continue;
      const Disc& o = discs[j];
      const double dx = o.x - c.x, dy = o.y - c.y, d = std::hypot(dx, dy);
      if (d >= c.r + o.r) continue;
      if (d == 0 && o.r == c.r) {
        inside = j < i;
        continue;
      }
      if (d + c.r <= o.r) {
        inside = true;
        continue;
      }
      if (d + o.r <= c.r) continue;
      const double phi = std::atan2(dy, dx);
      const double cos_alpha =
          std::clamp((c.r * c.r + d * d - o.r * o.r) / (2 * c.r * d), -1.0, 1.0);
      const double alpha = std::acos(cos_alpha);
      double from = std::fmod(phi - alpha, 2 * pi);
      if (from < 0) from += 2 * pi;
      const double to = from + 2 * alpha;
      if (to <= 2 * pi)
        covered.emplace_back(from, to);
      else {
        covered.emplace_back(from, 2 * pi);
        covered.emplace_back(0.0, to - 2 * pi);
      }
    }
    if (inside) continue;
    std::sort(covered.begin(), covered.end());
    double open_from = 0; // the exposed arcs: the gaps between the merged covered intervals
    for (const auto& [from, to] : covered) {
      if (from > open_from) add_arc(m, c, open_from, from);
      open_from = std::max(open_from, to);
    }
    if (open_from < 2 * pi) add_arc(m, c, open_from, 2 * pi);
  }
  return m;
}

// The ten volume integrals of a slab, as one vector: 1, x, y, z, xx, yy, zz, xy, xz, yz.
using Slab = std::array<double, 10>;

Slab slice_at(const std::vector<SphereMember>& members, double z, std::vector<Disc>& discs) {
  discs.clear();
  for (const SphereMember& s : members) {
    const double h = z - s.centre.z, rr = s.radius * s.radius - h * h;
    if (rr > 0) discs.push_back({s.centre.x, s.centre.y, std::sqrt(rr)});
  }
  const AreaMoments m = union_of_discs(discs);
  return {m.a, m.mx, m.my, z * m.a, m.sxx, m.syy, z * z * m.a, m.sxy, z * m.mx, z * m.my};
}

// The integral over z in [a, b] with the substitution z = a + (b - a) sin^2(pi u / 2).
Slab integrate_segment(const std::vector<SphereMember>& members, double a, double b,
                       std::vector<Disc>& discs) {
  const Quadrature& g = height_rule();
  Slab sum{};
  for (std::size_t k = 0; k < g.nodes.size(); ++k) {
    const double u = g.nodes[k], s = std::sin(0.5 * pi * u);
    const double z = a + (b - a) * s * s;
    const double jacobian = (b - a) * 0.5 * pi * std::sin(pi * u);
    const Slab f = slice_at(members, z, discs);
    for (std::size_t c = 0; c < f.size(); ++c) sum[c] += g.weights[k] * jacobian * f[c];
  }
  return sum;
}

// The segment's integral, halved until two estimates agree to `tolerance` (of the volume
// scale, each component scaled by the clump's size to the power of its order).
Slab integrate_adaptively(const std::vector<SphereMember>& members, double a, double b,
                          const Slab& scale, int depth, std::vector<Disc>& discs) {
  const Slab whole = integrate_segment(members, a, b, discs);
  const double m = 0.5 * (a + b);
  Slab halves = integrate_segment(members, a, m, discs);
  const Slab upper = integrate_segment(members, m, b, discs);
  bool agree = true;
  for (std::size_t c = 0; c < halves.size(); ++c) {
    halves[c] += upper[c];
    if (std::abs(halves[c] - whole[c]) > 1e-14 * scale[c]) agree = false;
  }
  if (agree || depth >= 12) return halves;
  Slab lower = integrate_adaptively(members, a, m, scale, depth + 1, discs);
  const Slab top = integrate_adaptively(members, m, b, scale, depth + 1, discs);
  for (std::size_t c = 0; c < lower.size(); ++c) lower[c] += top[c];
  return lower;
}

// The heights where a slice's boundary changes its make-up: each member's poles, the top and
// bottom of each circle where two members' surfaces meet, and the points where three meet.
std::vector<double> breakpoints(const std::vector<SphereMember>& s) {
  std::vector<double> z;
  for (const SphereMember& m : s) {
    z.push_back(m.centre.z - m.radius);
    z.push_back(m.centre.z + m.radius);
  }
  const std::size_t n = s.size();
  const auto meet = [&](std::size_t i, std::size_t j) {
    const double d = norm(s[j].centre - s[i].centre);
    return d < s[i].radius + s[j].radius && d > std::abs(s[i].radius - s[j].radius);
  };
  // The plane where the surfaces of i and j meet: n . x = c, n = 2 (c_j - c_i).
  const auto radical_plane = [&](std::size_t i, std::size_t j) {
    const Vec3 normal = 2.0 * (s[j].centre - s[i].centre);
    const double c = norm2(s[j].centre) - norm2(s[i].centre) - s[j].radius * s[j].radius +
                     s[i].radius * s[i].radius;
    return std::pair{normal, c};
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!meet(i, j)) continue;
      const Vec3 axis = s[j].centre - s[i].centre;
      const double d = norm(axis);
      const Vec3 u = axis / d;
      const double a = (d * d + s[i].radius * s[i].radius - s[j].radius * s[j].radius) / (2 * d);
      const double h = std::sqrt(std::max(0.0, s[i].radius * s[i].radius - a * a));
      const double centre_z = s[i].centre.z + a * u.z;
      const double reach = h * std::sqrt(std::max(0.0, 1 - u.z * u.z));
      z.push_back(centre_z - reach);
      z.push_back(centre_z + reach);
      for (std::size_t k = j + 1; k < n; ++k) {
        if (!meet(i, k) || !meet(j, k)) continue;
        // The line where the two radical planes cross, then its points on sphere i.
        const auto [n1, c1] = radical_plane(i, j);
        const auto [n2, c2] = radical_plane(i, k);
        const Vec3 dir = cross(n1, n2);
        const double dd = norm2(dir);
        if (dd < 1e-24 * norm2(n1) * norm2(n2)) continue;
        const Vec3 p0 = cross(c1 * n2 - c2 * n1, dir) / dd; // a point on both planes
        const Vec3 w = p0 - s[i].centre;
        const double b = dot(w, dir) / dd, c = (norm2(w) - s[i].radius * s[i].radius) / dd;
        const double disc = b * b - c;
        if (disc < 0) continue;
        const double root = std::sqrt(disc);
        z.push_back(p0.z + (-b - root) * dir.z);
        z.push_back(p0.z + (-b + root) * dir.z);
      }
    }
  std::sort(z.begin(), z.end());
  z.erase(std::unique(z.begin(), z.end()), z.end());
  return z;
}

} // namespace

VolumeMoments sphere_union_moments(std::span<const SphereMember> span) {
  const std::vector<SphereMember> members(span.begin(), span.end());
  VolumeMoments out;
  if (members.empty()) return out;
  const std::vector<double> z = breakpoints(members);
  // The scales the agreement of the adaptive halving is measured against: the members' summed
  // volume times their extent to the power of each component's order.
  double volume = 0, lo = z.front(), hi = z.back();
  for (const SphereMember& m : members) {
    volume += 4.0 / 3.0 * pi * m.radius * m.radius * m.radius;
    for (int a = 0; a < 3; ++a) {
      lo = std::min(lo, m.centre[a] - m.radius);
      hi = std::max(hi, m.centre[a] + m.radius);
    }
  }
  const double size = std::max(std::abs(lo), std::abs(hi));
  Slab scale;
  for (std::size_t c = 0; c < scale.size(); ++c)
    scale[c] = volume * (c == 0 ? 1.0 : c < 4 ? size : size * size);
  std::vector<Disc> discs;
  Slab total{};
  for (std::size_t k = 0; k + 1 < z.size(); ++k) {
    if (!(z[k + 1] > z[k])) continue;
    const Slab part = integrate_adaptively(members, z[k], z[k + 1], scale, 0, discs);
    for (std::size_t c = 0; c < total.size(); ++c) total[c] += part[c];
  }
  out.volume = total[0];
  out.first = {total[1], total[2], total[3]};
  out.second = {{{total[4], total[7], total[8]},
                 {total[7], total[5], total[9]},
                 {total[8], total[9], total[6]}}};
  return out;
}

} // namespace yuxi
