#include "analysis/cg_cylinder.hpp"

#include "analysis/cg_accumulate.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace yuxi::analysis {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

// Narrows [s0, s1] to where c0 + s c1 >= 0 (or > 0 where `strict`); false where nothing is left.
bool clip_linear(double c0, double c1, bool strict, double& s0, double& s1) {
  if (c1 == 0.0) return strict ? c0 > 0.0 : c0 >= 0.0;
  const double root = -c0 / c1;
  if (c1 > 0.0)
    s0 = std::max(s0, root);
  else
    s1 = std::min(s1, root);
  return s1 > s0;
}

// The points of the grid as the sums see them: every point, and where theta is averaged, the
// samples around each circle (their sums are turned into the local basis and averaged).
class CylinderWeights {
public:
  explicit CylinderWeights(const CgCylinderSettings& s) : g_(s.grid), reach_(s.cutoff) {
    if (s.kind != CgKind::bins)
      function_.emplace(s.kind, s.width, s.cutoff, g_.z_averaged ? 2 : 3);
    else
      reach_ = 0.0;
    h_r_ = (g_.r_hi - g_.r_lo) / g_.n[0];
    h_z_ = (g_.z_hi - g_.z_lo) / g_.n[2];
    inverse_extent_ = g_.z_averaged ? 1.0 / (g_.z_hi - g_.z_lo) : 1.0;
    // Around an averaged circle: the function sampled w / 8 apart at r_hi (at least 32 samples;
    // the trapezoidal rule, of second order at the cut function's kink); bins as 256 sectors,
    // each turned into the basis at its middle.
    samples_ = !g_.theta_averaged ? g_.n[1]
               : function_
                   ? std::max(32, static_cast<int>(std::ceil(two_pi * g_.r_hi / (0.125 * s.width))))
                   : 256;
    d_theta_ = two_pi / samples_;
    for (int j = 0; j < samples_; ++j) {
      const double t = (j + 0.5) * d_theta_;
      cos_.push_back(std::cos(t)), sin_.push_back(std::sin(t));
    }
  }

  int samples() const { return samples_; }
  std::size_t size() const {
    return static_cast<std::size_t>(g_.n[0]) * static_cast<std::size_t>(samples_) * g_.n[2];
  }
  // The sample's index: (k * samples + j) * n_r + i.
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * samples_ + j) * g_.n[0] + i;
  }
  double cos_of(int j) const { return cos_[static_cast<std::size_t>(j)]; }
  double sin_of(int j) const { return sin_[static_cast<std::size_t>(j)]; }

  template <class F> void at_point(const Vec3& x, F&& f) const {
    if (g_.z_averaged && !(x.z >= g_.z_lo && x.z <= g_.z_hi)) return;
    const double dx = x.x - g_.x0, dy = x.y - g_.y0, rho = std::hypot(dx, dy);
    if (!function_) {
      auto i = static_cast<long>(std::floor((rho - g_.r_lo) / h_r_));
      if (i == g_.n[0] && rho <= g_.r_hi) i -= 1; // a point on the outer face
      if (i < 0 || i >= g_.n[0]) return;
      long k = 0;
      if (!g_.z_averaged) {
        k = static_cast<long>(std::floor((x.z - g_.z_lo) / h_z_));
        if (k == g_.n[2] && x.z <= g_.z_hi) k -= 1;
        if (k < 0 || k >= g_.n[2]) return;
      }
      const double angle = std::atan2(dy, dx);
      const long j = samples_ == 1 ? 0 : wrap(static_cast<long>(std::floor(angle / d_theta_)));
      f(index(static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)),
        1.0 / sample_volume(static_cast<int>(i)));
      return;
    }
    const double angle = std::atan2(dy, dx), c2 = reach_ * reach_;
    const auto [k0, k1] = z_range(x.z, x.z);
    for (long k = k0; k <= k1; ++k) {
      const double dz = g_.z_averaged ? 0.0 : g_.z(static_cast<int>(k)) - x.z;
      const double within2 = c2 - dz * dz;
      if (!(within2 > 0.0)) continue;
      const auto [i0, i1] = r_range(rho, rho);
      for (long i = i0; i <= i1; ++i) {
        const double r = g_.r(static_cast<int>(i));
        each_angle(r, rho, angle, within2, [&](long j) {
          const double px = r * cos_of(static_cast<int>(j)) - dx,
                       py = r * sin_of(static_cast<int>(j)) - dy;
          const double w = function_->at(px * px + py * py + dz * dz);
          if (w != 0.0)
            f(index(static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)),
              w * inverse_extent_);
        });
      }
    }
  }

  template <class F> void along(const Vec3& whole_from, const Vec3& whole_b, F&& f) const {
    // The part within an averaged z's span, as its own segment (psi scales with its share).
    double s0 = 0.0, s1 = 1.0;
    if (g_.z_averaged && (!clip_linear(whole_from.z - g_.z_lo, whole_b.z, false, s0, s1) ||
                          !clip_linear(g_.z_hi - whole_from.z, -whole_b.z, false, s0, s1)))
      return;
    const Vec3 from = whole_from + whole_b * s0, b = whole_b * (s1 - s0);
    const double part = s1 - s0;
    const double px = from.x - g_.x0, py = from.y - g_.y0;
    // The segment's distances from the axis (in x, y) and its heights.
    const double bb = b.x * b.x + b.y * b.y;
    const double closest = bb > 0.0 ? std::clamp(-(px * b.x + py * b.y) / bb, 0.0, 1.0) : 0.0;
    const double rho_min = std::hypot(px + closest * b.x, py + closest * b.y);
    const double rho_max = std::max(std::hypot(px, py), std::hypot(px + b.x, py + b.y));
    const auto [k0, k1] = z_range(std::min(from.z, from.z + b.z), std::max(from.z, from.z + b.z));
    const auto [i0, i1] = r_range(rho_min, rho_max);
    if (!function_) {
      for (long k = k0; k <= k1; ++k)
        for (long i = i0; i <= i1; ++i)
          for (int j = 0; j < samples_; ++j) {
            const double share =
                share_in_cell(px, py, from.z, b, static_cast<int>(i), j, static_cast<int>(k));
            if (share > 0.0)
              f(index(static_cast<int>(i), j, static_cast<int>(k)),
                part * share / sample_volume(static_cast<int>(i)));
          }
      return;
    }
    // The angles the segment spans seen from the axis (all where it passes within reach of it).
    const double a0 = std::atan2(py, px);
    const double turn = std::remainder(std::atan2(py + b.y, px + b.x) - a0, two_pi);
    const bool all_around = rho_min <= reach_;
    const Vec3 branch{b.x, b.y, g_.z_averaged ? 0.0 : b.z};
    for (long k = k0; k <= k1; ++k) {
      const double qz = g_.z_averaged ? 0.0 : g_.z(static_cast<int>(k)) - from.z;
      for (long i = i0; i <= i1; ++i) {
        const double r = g_.r(static_cast<int>(i));
        const auto visit = [&](long j) {
          const Vec3 q{r * cos_of(static_cast<int>(j)) - px, r * sin_of(static_cast<int>(j)) - py,
                       qz};
          const double w = function_->along(q, branch);
          if (w != 0.0)
            f(index(static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)),
              part * w * inverse_extent_);
        };
        if (all_around || r <= reach_) {
          for (long j = 0; j < samples_; ++j) visit(j);
          continue;
        }
        const double margin = std::asin(std::min(1.0, reach_ / r));
        const double lo = std::min(a0, a0 + turn) - margin, hi = std::max(a0, a0 + turn) + margin;
        each_sample_between(lo, hi, visit);
      }
    }
  }

private:
  // A sample's cell: the grid's cell, or its sector where theta is averaged.
  double sample_volume(int i) const { return g_.cell_volume(i) * g_.n[1] / samples_; }
  long wrap(long j) const { return ((j % samples_) + samples_) % samples_; }
  // The indices of n points (cells) of spacing h from `origin` within reach of [lo, hi].
  std::pair<long, long> within_reach(double lo, double hi, double origin, double h, int n) const {
    if (!function_)
      return {std::max(0L, static_cast<long>(std::floor((lo - origin) / h))),
              std::min<long>(n - 1, static_cast<long>(std::floor((hi - origin) / h)))};
    return {std::max(0L, static_cast<long>(std::ceil((lo - reach_ - origin) / h - 0.5))),
            std::min<long>(n - 1, static_cast<long>(std::floor((hi + reach_ - origin) / h - 0.5)))};
  }
  // The z indices within reach of heights [lo, hi] (the one point where z is averaged).
  std::pair<long, long> z_range(double lo, double hi) const {
    if (g_.z_averaged) return {0, 0};
    return within_reach(lo, hi, g_.z_lo, h_z_, g_.n[2]);
  }
  // The r indices within reach of distances [lo, hi] from the axis.
  std::pair<long, long> r_range(double lo, double hi) const {
    return within_reach(lo, hi, g_.r_lo, h_r_, g_.n[0]);
  }
  // v(j) for the samples whose angle lies in [lo, hi] (unwrapped, at most a turn).
  template <class V> void each_sample_between(double lo, double hi, V&& v) const {
    if (hi - lo >= two_pi) {
      for (long j = 0; j < samples_; ++j) v(j);
      return;
    }
    const auto first = static_cast<long>(std::ceil(lo / d_theta_ - 0.5));
    const auto last = static_cast<long>(std::floor(hi / d_theta_ - 0.5));
    for (long j = first; j <= last; ++j) v(wrap(j));
  }
  // v(j) for the samples at radius r within sqrt(within2) (in x, y) of the point at distance rho
  // and angle `angle` from the axis.
  template <class V>
  void each_angle(double r, double rho, double angle, double within2, V&& v) const {
    if (r * rho == 0.0) {
      if (std::abs(r - rho) * std::abs(r - rho) < within2)
        for (long j = 0; j < samples_; ++j) v(j);
      return;
    }
    const double cosine = (r * r + rho * rho - within2) / (2.0 * r * rho);
    if (cosine >= 1.0) return;
    if (cosine <= -1.0) {
      for (long j = 0; j < samples_; ++j) v(j);
      return;
    }
    const double half = std::acos(cosine);
    each_sample_between(angle - half, angle + half, v);
  }
  // The share of the segment (from (px, py, z) relative to the axis, along b) within cell
  // (i, j, k): where its distance from the axis, its angle and its height are the cell's.
  double share_in_cell(double px, double py, double z, const Vec3& b, int i, int j, int k) const {
    double s0 = 0.0, s1 = 1.0;
    if (!g_.z_averaged) {
      const double lo = g_.z_lo + k * h_z_;
      if (!clip_linear(z - lo, b.z, false, s0, s1) ||
          !clip_linear(lo + h_z_ - z, -b.z, true, s0, s1))
        return 0.0;
    }
    if (samples_ > 1) {
      // Between the rays at theta_j and theta_j+1 (a wedge of at most half a turn).
      const double t0 = j * d_theta_, t1 = t0 + d_theta_;
      const double c0 = std::cos(t0), n0 = std::sin(t0), c1 = std::cos(t1), n1 = std::sin(t1);
      if (!clip_linear(c0 * py - n0 * px, c0 * b.y - n0 * b.x, false, s0, s1) ||
          !clip_linear(px * n1 - py * c1, b.x * n1 - b.y * c1, true, s0, s1))
        return 0.0;
    }
    // r(s)^2 = A s^2 + 2 B s + C: inside the outer circle and outside the inner one.
    const double a = b.x * b.x + b.y * b.y, half_b = px * b.x + py * b.y, c = px * px + py * py;
    const double inner = g_.r_lo + i * h_r_, outer = inner + h_r_;
    const auto roots = [&](double radius) -> std::optional<std::pair<double, double>> {
      if (a == 0.0) return std::nullopt;
      const double disc = half_b * half_b - a * (c - radius * radius);
      if (!(disc > 0.0)) return std::nullopt;
      const double root = std::sqrt(disc);
      return std::pair{(-half_b - root) / a, (-half_b + root) / a};
    };
    // Inside the outer circle (strictly: its rim belongs to the next cell).
    if (a == 0.0) {
      if (!(c < outer * outer && c >= inner * inner)) return 0.0;
      return s1 - s0;
    }
    const auto out = roots(outer);
    if (!out) return 0.0;
    s0 = std::max(s0, out->first), s1 = std::min(s1, out->second);
    if (!(s1 > s0)) return 0.0;
    // Less the part inside the inner circle.
    double length = s1 - s0;
    if (const auto in = roots(inner))
      length -= std::max(0.0, std::min(s1, in->second) - std::max(s0, in->first));
    return length;
  }

  const CgCylinder& g_;
  double reach_;
  std::optional<CgFunction> function_;
  double h_r_ = 1.0, h_z_ = 1.0, inverse_extent_ = 1.0, d_theta_ = 1.0;
  int samples_ = 1;
  std::vector<double> cos_, sin_;
};

} // namespace

void CgCylinder::check() const {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("coarse-graining cylindrical grid: " + what);
  };
  if (!(r_lo >= 0.0)) fail("r_lo must be 0 or more (got " + std::to_string(r_lo) + ")");
  if (!(r_hi > r_lo) || !std::isfinite(r_hi))
    fail("r_hi (" + std::to_string(r_hi) + ") must exceed r_lo (" + std::to_string(r_lo) + ")");
  if (!(z_hi > z_lo) || !std::isfinite(z_hi - z_lo))
    fail("z_hi (" + std::to_string(z_hi) + ") must exceed z_lo (" + std::to_string(z_lo) + ")");
  if (!std::isfinite(x0) || !std::isfinite(y0)) fail("the axis must be finite");
  static constexpr const char* names[] = {"r", "theta", "z"};
  for (int a = 0; a < 3; ++a)
    if (n[static_cast<std::size_t>(a)] < 1)
      fail(std::string("the number of points along ") + names[a] + " must be at least 1");
  if (theta_averaged && n[1] != 1) fail("theta is averaged, so it has one point");
  if (z_averaged && n[2] != 1) fail("z is averaged, so it has one point");
}

double CgCylinder::theta(int j) const {
  return theta_averaged ? std::numbers::pi : (j + 0.5) * two_pi / n[1];
}

double CgCylinder::cell_volume(int i) const {
  const double h = (r_hi - r_lo) / n[0], inner = r_lo + i * h, outer = inner + h;
  return 0.5 * (outer * outer - inner * inner) * (two_pi / n[1]) * (z_hi - z_lo) / n[2];
}

std::vector<double> coarse_grain_sums(const CgGrains& grains, std::span<const CgContact> contacts,
                                      const CgCylinderSettings& settings) {
  const CgCylinder& g = settings.grid;
  g.check();
  const CylinderWeights weights(settings);
  std::vector<double> samples(cg_sums_per_point * weights.size(), 0.0);
  detail::add_sums(grains, contacts, weights, samples, settings.parts);
  // Each sample's vectors and tensors in its local basis (e_r, e_theta, e_z), then the samples
  // around an averaged circle averaged into its point.
  using detail::Sum;
  std::vector<double> sums(cg_sums_per_point * g.size(), 0.0);
  const int m = weights.samples();
  const double share = g.theta_averaged ? 1.0 / m : 1.0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < m; ++j) {
      const double c = weights.cos_of(j), s = weights.sin_of(j);
      // rows: e_r, e_theta, e_z in x, y, z
      const double rot[3][3] = {{c, s, 0.0}, {-s, c, 0.0}, {0.0, 0.0, 1.0}};
      for (int i = 0; i < g.n[0]; ++i) {
        const double* in = &samples[cg_sums_per_point * weights.index(i, j, k)];
        double* out = &sums[cg_sums_per_point * g.index(i, g.theta_averaged ? 0 : j, k)];
        for (const std::size_t scalar :
             {Sum::mass, Sum::number, Sum::volume, Sum::contacts, Sum::kinetic, Sum::elastic,
              Sum::dissipation, Sum::relaxation, Sum::wall_power})
          out[scalar] += share * in[scalar];
        for (const std::size_t vector : {Sum::momentum, Sum::wall_force})
          for (int a = 0; a < 3; ++a)
            for (int q = 0; q < 3; ++q) out[vector + a] += share * rot[a][q] * in[vector + q];
        for (const std::size_t tensor : {Sum::momentum_flux, Sum::contact_stress, Sum::fabric})
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
              double t = 0.0;
              for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q) t += rot[a][p] * in[tensor + 3 * p + q] * rot[b][q];
              out[tensor + 3 * a + b] += share * t;
            }
      }
    }
  return sums;
}

CgFields coarse_grain(const CgGrains& grains, std::span<const CgContact> contacts,
                      const CgCylinderSettings& settings) {
  return coarse_grain_fields(coarse_grain_sums(grains, contacts, settings), settings.grid.size());
}

} // namespace yuxi::analysis
