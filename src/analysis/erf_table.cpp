#include "analysis/erf_table.hpp"

#include <numbers>

namespace yuxi::analysis {

ErfTable::ErfTable() {
  const double h = 1.0 / per_unit;
  // erf' = 2 / sqrt(pi) exp(-x^2), erf'' = -2 x erf'.
  const auto slope = [](double x) { return 2.0 / std::sqrt(std::numbers::pi) * std::exp(-x * x); };
  for (int j = 0; j < intervals; ++j) {
    const double x0 = j * h, x1 = (j + 1) * h;
    const double f0 = std::erf(x0), f1 = std::erf(x1);
    const double d0 = h * slope(x0), d1 = h * slope(x1);
    const double s0 = h * h * -2.0 * x0 * slope(x0), s1 = h * h * -2.0 * x1 * slope(x1);
    const double a2 = 0.5 * s0;
    const double value = f1 - (f0 + d0 + a2), rate = d1 - (d0 + 2.0 * a2), curve = s1 - s0;
    auto& c = a[static_cast<std::size_t>(j)];
    c = {f0,
         d0,
         a2,
         10.0 * value - 4.0 * rate + 0.5 * curve,
         -15.0 * value + 7.0 * rate - curve,
         6.0 * value - 3.0 * rate + 0.5 * curve};
  }
}

const ErfTable& erf_table() {
  static const ErfTable table;
  return table;
}

} // namespace yuxi::analysis
