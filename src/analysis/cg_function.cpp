#include "analysis/cg_function.hpp"

#include "analysis/erf_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace yuxi::analysis {
namespace {

constexpr double pi = std::numbers::pi;

// Gauss-Legendre nodes and weights on [-1, 1] (Newton's method on P_n; Numerical Recipes'
// gauleg), computed once. Written here: no packaged library yuxi uses has a quadrature rule.
struct GaussLegendre {
  static constexpr int n = 16;
  std::array<double, n> node{}, weight{};
  GaussLegendre() {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p1 = 1.0, p2 = 0.0;
        for (int k = 1; k <= n; ++k) {
          const double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * k - 1.0) * z * p2 - (k - 1.0) * p3) / k;
        }
        dp = n * (z * p1 - p2) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-16) break;
      }
      node[static_cast<std::size_t>(i)] = z;
      weight[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

const GaussLegendre& gauss_legendre() {
  static const GaussLegendre rule;
  return rule;
}

// erf(b) - erf(a), from the table (erf_table.hpp): to 2e-15 absolute. (Far in the tails, where
// both are near 1, the difference loses its relative precision, but it is then itself below
// erfc(3) = 2e-5 of a branch's whole weight.)
double erf_difference(double a, double b) {
  return table_erf(b) - table_erf(a);
}

} // namespace

std::string_view to_string(CgKind k) {
  switch (k) {
  case CgKind::gaussian:
    return "gaussian";
  case CgKind::lucy:
    return "lucy";
  case CgKind::bins:
    return "bins";
  }
  return "?";
}

CgFunction::CgFunction(CgKind kind, double width, double cutoff, int dimension)
    : kind_(kind), width_(width), cutoff_(cutoff), dimension_(dimension) {
  if (kind == CgKind::bins)
    throw std::invalid_argument("coarse-graining: plain bins are not a function of distance");
  if (!(width > 0.0) || !std::isfinite(width))
    throw std::invalid_argument("coarse-graining: the width must be positive (got " +
                                std::to_string(width) + ")");
  if (!(cutoff > 0.0) || !std::isfinite(cutoff))
    throw std::invalid_argument("coarse-graining: the cutoff must be positive (got " +
                                std::to_string(cutoff) + ")");
  if (dimension < 1 || dimension > 3)
    throw std::invalid_argument("coarse-graining: a grid resolves 1, 2 or 3 axes (got " +
                                std::to_string(dimension) + ")");
  const double c = cutoff, w = width;
  if (kind == CgKind::lucy) {
    norm_ = dimension == 1   ? 5.0 / (4.0 * c)
            : dimension == 2 ? 5.0 / (pi * c * c)
                             : 105.0 / (16.0 * pi * c * c * c);
    return;
  }
  // The truncated Gaussian's integral over the d-ball of radius c, less the shift's.
  const double a = c / (std::numbers::sqrt2 * w);
  shift_ = std::exp(-a * a);
  double gaussian = std::pow(2.0 * pi, 1.5) * w * w * w *
                    (std::erf(a) - 2.0 / std::sqrt(pi) * a * std::exp(-a * a));
  double ball = 4.0 / 3.0 * pi * c * c * c;
  if (dimension == 1) gaussian = std::sqrt(2.0 * pi) * w * std::erf(a), ball = 2.0 * c;
  if (dimension == 2) gaussian = 2.0 * pi * w * w * -std::expm1(-a * a), ball = pi * c * c;
  norm_ = 1.0 / (gaussian - shift_ * ball);
}

double CgFunction::along(const Vec3& q, const Vec3& b) const {
  const double length2 = norm2(b);
  if (length2 == 0.0) return at(norm2(q));
  const double length = std::sqrt(length2);
  // Along the segment, |q - s b|^2 = across2 + (t0 - s L)^2.
  const double t0 = dot(q, b) / length;
  const double across2 = std::max(0.0, norm2(q) - t0 * t0);
  const double half2 = cutoff_ * cutoff_ - across2;
  if (!(half2 > 0.0)) return 0.0;
  const double half = std::sqrt(half2);
  const double s0 = std::max(0.0, (t0 - half) / length), s1 = std::min(1.0, (t0 + half) / length);
  if (!(s1 > s0)) return 0.0;
  if (kind_ == CgKind::gaussian) {
    const double scale = std::numbers::sqrt2 * width_;
    const double full = std::exp(-across2 / (scale * scale)) * scale * std::sqrt(pi) / 2.0 /
                        length *
                        erf_difference((s0 * length - t0) / scale, (s1 * length - t0) / scale);
    return norm_ * (full - shift_ * (s1 - s0));
  }
  // Lucy: on each side of the closest approach the integrand is smooth.
  const GaussLegendre& rule = gauss_legendre();
  const double closest = std::clamp(t0 / length, s0, s1);
  double sum = 0.0;
  for (const auto& [from, to] : {std::pair{s0, closest}, std::pair{closest, s1}}) {
    if (!(to > from)) continue;
    const double mid = 0.5 * (from + to), half_width = 0.5 * (to - from);
    double part = 0.0;
    for (int k = 0; k < GaussLegendre::n; ++k) {
      const double s = mid + half_width * rule.node[static_cast<std::size_t>(k)];
      const double t = t0 - s * length;
      part += rule.weight[static_cast<std::size_t>(k)] * at(across2 + t * t);
    }
    sum += part * half_width;
  }
  return sum;
}

} // namespace yuxi::analysis
