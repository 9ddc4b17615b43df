// The union's moments by slices (sphere_union.hpp for the method and its accuracy).
#include "scene/sphere_union.hpp"

#include "core/units.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace yuxi {
namespace {

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
// discs (to round-off) the first counts; a circle inside another, or touching it from inside,
// is covered.
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
      // Each inside the other: the same disc to round-off (equal radii, centres within an ulp);
      // the first counts.
      if (d + c.r <= o.r && d + o.r <= c.r) {
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

// The segment's integral, given its estimate `whole` by one rule over it: halved until the two
// halves' sum agrees with it to 1e-14 of `scale` (the clump's volume times its size to the power
// of each component's order), at most 12 times.
Slab integrate_adaptively(const std::vector<SphereMember>& members, double a, double b,
                          const Slab& whole, const Slab& scale, int depth,
                          std::vector<Disc>& discs) {
  const double m = 0.5 * (a + b);
  const Slab lower = integrate_segment(members, a, m, discs);
  const Slab upper = integrate_segment(members, m, b, discs);
  Slab halves;
  bool agree = true;
  for (std::size_t c = 0; c < halves.size(); ++c) {
    halves[c] = lower[c] + upper[c];
    if (std::abs(halves[c] - whole[c]) > 1e-14 * scale[c]) agree = false;
  }
  if (agree || depth >= 12) return halves;
  Slab sum = integrate_adaptively(members, a, m, lower, scale, depth + 1, discs);
  const Slab top = integrate_adaptively(members, m, b, upper, scale, depth + 1, discs);
  for (std::size_t c = 0; c < sum.size(); ++c) sum[c] += top[c];
  return sum;
}

// The heights where a slice's boundary changes its make-up: each member's poles, the top and
// bottom of each circle where two members' surfaces meet, and the points where three meet;
// each only where it lies on the union's surface, not buried inside a further member (a buried
// one changes nothing, and a dense clump has far more of them than of the others).
std::vector<double> breakpoints(const std::vector<SphereMember>& s) {
  std::vector<double> z;
  const std::size_t n = s.size(), none = n;
  // Whether point p lies strictly inside a member other than a, b and c.
  const auto buried = [&](const Vec3& p, std::size_t a, std::size_t b, std::size_t c) {
    for (std::size_t m = 0; m < n; ++m)
      if (m != a && m != b && m != c && norm(p - s[m].centre) < s[m].radius * (1 - 1e-9))
        return true;
    return false;
  };
  const auto add = [&](const Vec3& p, std::size_t a, std::size_t b, std::size_t c) {
    if (!buried(p, a, b, c)) z.push_back(p.z);
  };
  for (std::size_t i = 0; i < n; ++i) {
    add(s[i].centre - Vec3{0, 0, s[i].radius}, i, none, none);
    add(s[i].centre + Vec3{0, 0, s[i].radius}, i, none, none);
  }
  const auto meet = [&](std::size_t i, std::size_t j) {
    const double d = norm(s[j].centre - s[i].centre);
    return d < s[i].radius + s[j].radius && d > std::abs(s[i].radius - s[j].radius);
  };
  // The plane where the surfaces of i and j meet, relative to c_i: n . (x - c_i) = c with
  // n = 2 (c_j - c_i), c = |c_j - c_i|^2 + r_i^2 - r_j^2.
  const auto radical_plane = [&](std::size_t i, std::size_t j) {
    const Vec3 normal = 2.0 * (s[j].centre - s[i].centre);
    const double c =
        norm2(s[j].centre - s[i].centre) + s[i].radius * s[i].radius - s[j].radius * s[j].radius;
    return std::pair{normal, c};
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!meet(i, j)) continue;
      // The circle where i and j meet: centre p, unit normal u, radius h; its highest and
      // lowest points lie along the part of z across u.
      const Vec3 axis = s[j].centre - s[i].centre;
      const double d = norm(axis);
      const Vec3 u = axis / d;
      const double a = (d * d + s[i].radius * s[i].radius - s[j].radius * s[j].radius) / (2 * d);
      const double h = std::sqrt(std::max(0.0, s[i].radius * s[i].radius - a * a));
      const Vec3 p = s[i].centre + a * u;
      const Vec3 across = Vec3{0, 0, 1} - u.z * u;
      const double length = norm(across);
      if (length > 1e-12) {
        add(p + (h / length) * across, i, j, none);
        add(p - (h / length) * across, i, j, none);
      } else {
        z.push_back(p.z); // a level circle: one height
      }
      for (std::size_t k = j + 1; k < n; ++k) {
        if (!meet(i, k) || !meet(j, k)) continue;
        // The line where the two radical planes cross, then its points on sphere i.
        const auto [n1, c1] = radical_plane(i, j);
        const auto [n2, c2] = radical_plane(i, k);
        const Vec3 dir = cross(n1, n2);
        const double dd = norm2(dir);
        if (dd < 1e-24 * norm2(n1) * norm2(n2)) continue;
        const Vec3 w = cross(c1 * n2 - c2 * n1, dir) / dd; // on both planes, from c_i
        const double b = dot(w, dir) / dd, c = (norm2(w) - s[i].radius * s[i].radius) / dd;
        const double disc = b * b - c;
        if (disc < 0) continue;
        const double root = std::sqrt(disc);
        add(s[i].centre + w + (-b - root) * dir, i, j, k);
        add(s[i].centre + w + (-b + root) * dir, i, j, k);
      }
    }
  std::sort(z.begin(), z.end());
  z.erase(std::unique(z.begin(), z.end()), z.end());
  return z;
}

} // namespace

VolumeMoments sphere_union_moments(std::span<const SphereMember> span) {
  VolumeMoments out;
  if (span.empty()) return out;
  // The members measured from their mean centre o in units of the clump's size L: the
  // quadrature's tolerances are then the same at every size and place, and no digit goes to
  // the parallel-axis terms, which are added back exactly below.
  Vec3 o;
  for (const SphereMember& m : span) o += m.centre / static_cast<double>(span.size());
  double size = 0;
  for (const SphereMember& m : span) size = std::max(size, norm(m.centre - o) + m.radius);
  std::vector<SphereMember> members;
  for (const SphereMember& m : span) members.push_back({(m.centre - o) / size, m.radius / size});
  const std::vector<double> z = breakpoints(members);
  // The scales the adaptive halving's agreement is measured against: the members' summed
  // volume (the extent is 1).
  double volume = 0;
  for (const SphereMember& m : members) volume += 4.0 / 3.0 * pi * m.radius * m.radius * m.radius;
  Slab scale;
  scale.fill(volume);
  std::vector<Disc> discs;
  Slab total{};
  for (std::size_t k = 0; k + 1 < z.size(); ++k) {
    if (!(z[k + 1] > z[k])) continue;
    const Slab whole = integrate_segment(members, z[k], z[k + 1], discs);
    const Slab part = integrate_adaptively(members, z[k], z[k + 1], whole, scale, 0, discs);
    for (std::size_t c = 0; c < total.size(); ++c) total[c] += part[c];
  }
  // Back to the given units and origin: V L^3, the first moment L^4 F + V o, the second
  // L^5 S + o F^T + F o^T + V o o^T (F the first moment about o).
  const double l3 = size * size * size, l4 = l3 * size, l5 = l4 * size;
  out.volume = total[0] * l3;
  const Vec3 f{total[1] * l4, total[2] * l4, total[3] * l4};
  out.first = f + out.volume * o;
  const double second[3][3] = {{total[4], total[7], total[8]},
                               {total[7], total[5], total[9]},
                               {total[8], total[9], total[6]}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out.second[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] =
          second[a][b] * l5 + o[a] * f[b] + f[a] * o[b] + out.volume * o[a] * o[b];
  return out;
}

} // namespace yuxi
