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

#include "core/vec3.hpp"

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
  double at(double r2) const;
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
  // closed form), without along's work in three dimensions.
  double along_axis(double q, double b) const;

private:
  CgKind kind_;
  double width_, cutoff_;
  int dimension_;
  double norm_;        // 1 / N_d, or A_d
  double shift_ = 0.0; // the Gaussian's value at the cutoff, taken off it
};

} // namespace yuxi::analysis
