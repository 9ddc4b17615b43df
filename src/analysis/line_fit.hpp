// A straight line y = intercept + slope x fitted by least squares, with the coefficient of
// determination R^2 = 1 - sum (y - fit)^2 / sum (y - mean y)^2 (NaN for fewer than 2 points or
// no spread in x; R^2 = 1 when y has no spread and the line passes through every point).
#pragma once

#include <cstddef>
#include <span>

namespace yuxi::analysis {

struct LineFit {
  double slope, intercept, r2;
  std::size_t points;
};

LineFit fit_line(std::span<const double> x, std::span<const double> y);

} // namespace yuxi::analysis
