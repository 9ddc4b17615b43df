// A coarse-graining function phi: the weight with which a grain at distance r from a point counts
// in the fields there (docs/coarse-graining.md, "The function").
//
// Every function integrates to 1 over the space of its dimension d, the number of resolved axes
// of the grid (1, 2 or 3); averaged axes are integrated out and divided out by the grid.
//   gaussian: phi(r) = (exp(-r^2 / (2 w^2)) - exp(-c^2 / (2 w^2))) / N_d for r < c, 0 beyond;
//             w the width, c the cutoff (3 w by default), N_d the integral of the numerator over
//             the d-ball of radius c, so that the cut function integrates to 1 exactly. The
//             shift makes it continuous at c: cut without it, the Gaussian would jump there by
//             1.1 % of its peak (at 3 w), and the mass balance would fail on that sphere;
//   lucy:     phi(r) = A_d (1 + 3 u)(1 - u)^3, u = r / c < 1 (Lucy, Astron. J. 82:1013, 1977),
//             A_1 = 5 / (4 c), A_2 = 5 / (pi c^2), A_3 = 105 / (16 pi c^3); c = 3 w by default,
//             which makes its standard deviation along an axis 0.87 w in 3-D (c / sqrt(12)).
// Plain bins are no function of distance: see CgGrid and coarse_grain.hpp.
#pragma once

#include "analysis/erf_table.hpp"
#include "core/vec3.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

namespace yuxi::analysis {

enum class CgKind { gaussian, lucy, bins };

std::string_view to_string(CgKind k);

class CgFunction {
public:
  // kind gaussian or lucy; width w > 0; cutoff c > 0 (the support's radius); dimension 1 to 3.
  // Throws std::invalid_argument otherwise.
  CgFunction(CgKind kind, double width, double cutoff, int dimension);

  CgKind kind() const { return kind_; }
  double width() const { return width_; }
  double cutoff() const { return cutoff_; }
  int dimension() const { return dimension_; }

  // phi at squared distance r2 (in the resolved axes), 1/length^d.
  double at(double r2) const {
    if (!(r2 < cutoff_ * cutoff_)) return 0.0;
    if (kind_ == CgKind::gaussian)
      return norm_ * (std::exp(-r2 / (2.0 * width_ * width_)) - shift_);
    const double u = std::sqrt(r2) / cutoff_, v = 1.0 - u;
    return norm_ * (1.0 + 3.0 * u) * v * v * v;
  }
  // The Gaussian's phi at a distance r < c where exp(-r^2 / (2 w^2)) = g, computed by the caller
  // (along each axis, for a grid: the exponential is a product over the axes).
  double gaussian_from(double g) const { return norm_ * (g - shift_); }

  // The line integral psi = int_0^1 phi(q - s b) ds, for q the point's position relative to the
  // segment's start and b the segment (both in the resolved axes): the weight with which a
  // contact's branch vector b counts at the point (docs/coarse-graining.md, "Contact stress").
  // Exact for the Gaussian (error functions on the part of the segment within the cutoff); for
  // Lucy's polynomial, 16-point Gauss-Legendre on each side of the closest approach, exact
  // wherever the segment passes through the point's axis and otherwise accurate to ~1e-12.
  double along(const Vec3& q, const Vec3& b) const;
  // The same on a grid that resolves one axis: q and b the components along it. Exact for both
  // functions (Lucy's is a polynomial in |u| along a line through the point: it integrates in
  // closed form), without along's work in three dimensions. (Inline: a profile calls it at
  // every point of every branch.)
  double along_axis(double q, double b) const {
    if (b == 0.0) return at(q * q);
    // psi = (1 / |b|) times the integral of phi over the u between q - b and q, within [-c, c].
    const double lo = std::max(std::min(q - b, q), -cutoff_),
                 hi = std::min(std::max(q - b, q), cutoff_);
    if (!(hi > lo)) return 0.0;
    const double length = std::abs(b);
    if (kind_ == CgKind::gaussian) {
      const double scale = std::numbers::sqrt2 * width_;
      const ErfTable& erf = *erf_;
      return norm_ *
             (scale * std::sqrt(std::numbers::pi) / 2.0 * (erf(hi / scale) - erf(lo / scale)) -
              shift_ * (hi - lo)) /
             length;
    }
    // Lucy in 1-D: phi = A (1 - 6 t^2 + 8 t^3 - 3 t^4), t = |u| / c, whose integral from 0 to u
    // is sign(u) A c (t - 2 t^3 + 2 t^4 - 3 t^5 / 5).
    const auto integral = [this](double u) {
      const double t = std::abs(u) / cutoff_;
      const double value = norm_ * cutoff_ * t * (1.0 + t * t * (-2.0 + t * (2.0 - 0.6 * t)));
      return u < 0.0 ? -value : value;
    };
    return (integral(hi) - integral(lo)) / length;
  }

  // along_axis for one branch b != 0 at many points: its constants made once, no division a
  // point (the same integral; the last bits may differ from along_axis's).
  class AxisBranch {
  public:
    AxisBranch(const CgFunction& f, double b) : f_(f), b_(b) {
      const double length = std::abs(b);
      if (f.kind_ == CgKind::gaussian) {
        const double scale = std::numbers::sqrt2 * f.width_;
        inverse_scale_ = 1.0 / scale;
        erf_factor_ = f.norm_ * scale * std::sqrt(std::numbers::pi) / 2.0 / length;
        shift_factor_ = f.norm_ * f.shift_ / length;
      } else {
        inverse_cutoff_ = 1.0 / f.cutoff_;
        erf_factor_ = f.norm_ * f.cutoff_ / length;
      }
    }
    double operator()(double q) const {
      const double c = f_.cutoff_;
      const double lo = std::max(std::min(q - b_, q), -c), hi = std::min(std::max(q - b_, q), c);
      if (!(hi > lo)) return 0.0;
      if (f_.kind_ == CgKind::gaussian) {
        const ErfTable& erf = *f_.erf_;
        return erf_factor_ * (erf(hi * inverse_scale_) - erf(lo * inverse_scale_)) -
               shift_factor_ * (hi - lo);
      }
      const auto integral = [this](double u) {
        const double t = std::abs(u) * inverse_cutoff_;
        const double value = t * (1.0 + t * t * (-2.0 + t * (2.0 - 0.6 * t)));
        return u < 0.0 ? -value : value;
      };
      return erf_factor_ * (integral(hi) - integral(lo));
    }

  private:
    const CgFunction& f_;
    double b_;
    double inverse_scale_ = 0.0, inverse_cutoff_ = 0.0, erf_factor_ = 0.0, shift_factor_ = 0.0;
  };

private:
  CgKind kind_;
  double width_, cutoff_;
  int dimension_;
  double norm_;        // 1 / N_d, or A_d
  double shift_ = 0.0; // the Gaussian's value at the cutoff, taken off it
  const ErfTable* erf_ = &erf_table();
};

} // namespace yuxi::analysis
