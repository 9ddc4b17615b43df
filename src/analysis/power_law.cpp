#include "analysis/power_law.hpp"

#include "analysis/analysis_csv.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace yuxi::analysis {

LogHistogram::LogHistogram(double e_min, double e_max, int bins_per_decade) {
  if (!(e_min > 0.0 && e_max > e_min && std::isfinite(e_max)) || bins_per_decade < 1)
    throw std::invalid_argument("LogHistogram: need 0 < e_min < e_max and bins_per_decade >= 1");
  const double decades = std::log10(e_max / e_min);
  // The tolerance keeps whole decades from gaining a sliver of a bin to rounding.
  const auto n = static_cast<std::size_t>(std::ceil(bins_per_decade * decades - 1e-9));
  edges_.resize(n + 1);
  for (std::size_t k = 0; k <= n; ++k)
    edges_[k] = e_min * std::pow(10.0, static_cast<double>(k) / bins_per_decade);
  counts_.assign(n, 0);
  energies_.assign(n, 0.0);
}

void LogHistogram::add(double value) {
  if (!std::isfinite(value)) {
    ++non_finite_;
    return;
  }
  ++samples_;
  total_ += value;
  if (value < edges_.front()) {
    ++below_;
    return;
  }
  if (value >= edges_.back()) {
    ++above_;
    return;
  }
  // The last edge <= value: edges are exact comparisons, whatever log10 would round to.
  const auto k = static_cast<std::size_t>(std::upper_bound(edges_.begin(), edges_.end(), value) -
                                          edges_.begin() - 1);
  ++counts_[k];
  energies_[k] += value;
}

void LogHistogram::add(std::span<const double> values) {
  for (const double v : values) add(v);
}

void LogHistogram::combine(const std::function<void(double*, int)>& sum_in_place) {
  // Counts travel as doubles: exact up to 2^53.
  std::vector<double> packed;
  for (const auto c : counts_) packed.push_back(static_cast<double>(c));
  packed.insert(packed.end(), energies_.begin(), energies_.end());
  for (const auto c : {samples_, below_, above_, non_finite_})
    packed.push_back(static_cast<double>(c));
  packed.push_back(total_);
  sum_in_place(packed.data(), static_cast<int>(packed.size()));
  const std::size_t n = counts_.size();
  for (std::size_t k = 0; k < n; ++k) {
    counts_[k] = static_cast<std::size_t>(packed[k]);
    energies_[k] = packed[n + k];
  }
  samples_ = static_cast<std::size_t>(packed[2 * n]);
  below_ = static_cast<std::size_t>(packed[2 * n + 1]);
  above_ = static_cast<std::size_t>(packed[2 * n + 2]);
  non_finite_ = static_cast<std::size_t>(packed[2 * n + 3]);
  total_ = packed[2 * n + 4];
}

Density LogHistogram::density() const {
  Density d;
  d.samples = samples_;
  d.below = below_;
  d.above = above_;
  d.non_finite = non_finite_;
  d.total_energy = total_;
  for (std::size_t k = 0; k < counts_.size(); ++k) {
    if (counts_[k] == 0) continue;
    const double lo = edges_[k], hi = edges_[k + 1];
    d.bins.push_back({lo, hi, std::sqrt(lo * hi), counts_[k],
                      static_cast<double>(counts_[k]) / (static_cast<double>(samples_) * (hi - lo)),
                      energies_[k]});
  }
  return d;
}

Density log_density(std::span<const double> values, double e_min, double e_max,
                    int bins_per_decade) {
  LogHistogram h(e_min, e_max, bins_per_decade);
  h.add(values);
  return h.density();
}

PowerLawFit fit_power_law(const Density& density, double e_lo, double e_hi) {
  if (!(e_lo < e_hi)) throw std::invalid_argument("fit_power_law: need e_lo < e_hi");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PowerLawFit fit{nan, nan, nan, 0, 0.0, nan, nan};
  std::vector<double> x, y;
  double energy = 0.0;
  for (const auto& b : density.bins) {
    if (b.e_center < e_lo || b.e_center > e_hi || !(b.density > 0.0)) continue;
    x.push_back(std::log10(b.e_center));
    y.push_back(std::log10(b.density));
    energy += b.energy;
    if (std::isnan(fit.e_lo_used)) fit.e_lo_used = b.e_lo;
    fit.e_hi_used = b.e_hi;
  }
  fit.bins = x.size();
  fit.energy_fraction = density.total_energy != 0.0 ? energy / density.total_energy : nan;
  const std::size_t n = x.size();
  if (n < 2) return fit;
  double mx = 0.0, my = 0.0;
  for (std::size_t k = 0; k < n; ++k) mx += x[k], my += y[k];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    sxx += (x[k] - mx) * (x[k] - mx);
    sxy += (x[k] - mx) * (y[k] - my);
  }
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  if (n >= 3) {
    double ssr = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double r = y[k] - (fit.intercept + fit.slope * x[k]);
      ssr += r * r;
    }
    fit.slope_error = std::sqrt(ssr / static_cast<double>(n - 2) / sxx);
  }
  return fit;
}

double energy_fraction(std::span<const double> values, double e_lo, double e_hi) {
  double inside = 0.0, total = 0.0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    total += v;
    if (v >= e_lo && v <= e_hi) inside += v;
  }
  return total != 0.0 ? inside / total : std::numeric_limits<double>::quiet_NaN();
}

void write_density_csv(const std::filesystem::path& path, const Density& density) {
  CsvWriter csv(path, {"e_lo", "e_hi", "e_center", "count", "density", "energy"});
  for (const auto& b : density.bins)
    csv.row({b.e_lo, b.e_hi, b.e_center, static_cast<double>(b.count), b.density, b.energy});
  csv.close();
}

void write_fits_csv(const std::filesystem::path& path, std::span<const NamedFit> fits) {
  CsvWriter csv(path, {"quantity", "range", "e_lo", "e_hi", "slope", "intercept", "slope_error",
                       "bins", "energy_fraction", "e_lo_used", "e_hi_used"});
  for (const auto& f : fits) {
    const std::vector<std::string> cells{f.quantity,
                                         f.range,
                                         csv_number(f.e_lo),
                                         csv_number(f.e_hi),
                                         csv_number(f.fit.slope),
                                         csv_number(f.fit.intercept),
                                         csv_number(f.fit.slope_error),
                                         std::to_string(f.fit.bins),
                                         csv_number(f.fit.energy_fraction),
                                         csv_number(f.fit.e_lo_used),
                                         csv_number(f.fit.e_hi_used)};
    csv.row(std::span<const std::string>(cells));
  }
  csv.close();
}

} // namespace yuxi::analysis
