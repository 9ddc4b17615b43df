#include "analysis/line_fit.hpp"

#include <cmath>
#include <stdexcept>

namespace yuxi::analysis {

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_line: x and y differ in length");
  const std::size_t n = x.size();
  LineFit f{NAN, NAN, NAN, n};
  if (n < 2) return f;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0)) return f;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  const double residual = syy - f.slope * sxy; // sum (y - fit)^2
  f.r2 = syy > 0 ? 1.0 - residual / syy : 1.0;
  return f;
}

} // namespace yuxi::analysis
