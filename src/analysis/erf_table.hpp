// erf(x) from a table: quintic Hermite interpolation between nodes 1/128 apart on [0, 6], each
// holding erf, its first and its second derivative (erf(x) = +-1 to double precision beyond:
// erfc(6) = 2e-17). Within 1e-15 of std::erf everywhere (a test), at a few multiplications.
//
// Why by hand: coarse-graining integrates a Gaussian along every contact's branch at every grid
// point it reaches (docs/coarse-graining.md, "Contact stress"), two erf a point; the C library's
// erf is the larger part of a sample's cost, and no packaged library offers a faster one at
// full precision. The evaluation is inline, so that a run of points' erfs overlap.
#pragma once

#include <array>
#include <cmath>

namespace yuxi::analysis {

// On each interval [x_j, x_j + h], erf(x_j + t h) = a0 + a1 t + ... + a5 t^5, the quintic that
// matches erf, h erf' and h^2 erf'' at both ends. Its error is at most
// max|erf^(6)| h^6 / 46080 (the Hermite remainder, |t (1 - t)|^3 <= 1/64): about 1e-16 here.
struct ErfTable {
  static constexpr int per_unit = 128;
  static constexpr double top = 6.0;
  static constexpr int intervals = static_cast<int>(top) * per_unit;
  std::array<std::array<double, 6>, intervals> a{};

  ErfTable();

  double operator()(double x) const {
    const double ax = std::abs(x);
    if (!(ax < top)) return std::isnan(x) ? x : std::copysign(1.0, x);
    const double u = ax * per_unit;
    const auto j = static_cast<int>(u);
    const double t = u - j;
    const auto& c = a[static_cast<std::size_t>(j)];
    const double value = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
    return std::copysign(value, x);
  }
};

// The one table, made on first use.
const ErfTable& erf_table();

inline double table_erf(double x) {
  return erf_table()(x);
}

} // namespace yuxi::analysis
