#include "analysis/sector_profile.hpp"

#include "core/units.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace yuxi::analysis {
namespace {

void check(const ModeSectors& s) {
  if (s.mode < 1) throw std::invalid_argument("sector profile: the mode must be at least 1");
  if (!(s.half_width > 0.0 && s.half_width <= pi / (2.0 * s.mode) * (1.0 + 1e-12)))
    throw std::invalid_argument("sector profile: the half-width must lie in (0, pi / (2m)]");
  if (!(s.r_max > 0.0)) throw std::invalid_argument("sector profile: r_max must be positive");
}

// Azimuth of p about the axis in [0, 2 pi), and its distance from the axis.
void polar(const ModeSectors& s, const Vec3& p, double& alpha, double& r) {
  const double dx = p.x - s.axis.x, dy = p.y - s.axis.y;
  r = std::hypot(dx, dy);
  alpha = std::atan2(dy, dx);
  if (alpha < 0.0) alpha += 2.0 * pi;
}

} // namespace

double sector_azimuth(const ModeSectors& s, SectorKind kind, int k) {
  return (k + (kind == SectorKind::node ? 0.5 : 0.0)) * pi / s.mode;
}

int sector_of(const ModeSectors& s, SectorKind kind, const Vec3& p) {
  double alpha = 0, r = 0;
  polar(s, p, alpha, r);
  if (r >= s.r_max) return -1;
  const double spacing = pi / s.mode;
  const double shift = kind == SectorKind::node ? 0.5 : 0.0;
  // The nearest direction of the kind, and the angle to it.
  const double u = alpha / spacing - shift;
  const long k = std::lround(u);
  if (std::abs(u - static_cast<double>(k)) * spacing > s.half_width) return -1;
  const int sectors = 2 * s.mode;
  return static_cast<int>(((k % sectors) + sectors) % sectors);
}

RadialProfile radial_profile(const GridField& field, const ModeSectors& s, SectorKind kind,
                             double dr) {
  check(s);
  if (!(dr > 0.0)) throw std::invalid_argument("sector profile: dr must be positive");
  const auto bins = static_cast<std::size_t>(std::ceil(s.r_max / dr));
  std::vector<std::vector<double>> values(bins);
  const XYGrid& g = field.grid;
  for (std::size_t j = 0; j < g.ny(); ++j)
    for (std::size_t i = 0; i < g.nx(); ++i) {
      const double v = field.at(i, j);
      const Vec3 c{g.x_center(i), g.y_center(j), 0.0};
      if (std::isnan(v) || sector_of(s, kind, c) < 0) continue;
      const double r = std::hypot(c.x - s.axis.x, c.y - s.axis.y);
      values[std::min(bins - 1, static_cast<std::size_t>(r / dr))].push_back(v);
    }
  RadialProfile p;
  p.dr = dr;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (auto& bin : values) {
    p.count.push_back(bin.size());
    if (bin.empty()) {
      p.mean.push_back(nan), p.median.push_back(nan), p.max.push_back(nan);
      continue;
    }
    std::sort(bin.begin(), bin.end());
    double sum = 0;
    for (double v : bin) sum += v;
    const std::size_t n = bin.size();
    p.mean.push_back(sum / static_cast<double>(n));
    p.median.push_back(n % 2 ? bin[n / 2] : 0.5 * (bin[n / 2 - 1] + bin[n / 2]));
    p.max.push_back(bin.back());
  }
  return p;
}

std::vector<SectorPeak> sector_peaks(const GridField& field, const ModeSectors& s) {
  check(s);
  std::vector<SectorPeak> peaks(static_cast<std::size_t>(2 * s.mode));
  for (std::size_t k = 0; k < peaks.size(); ++k) {
    peaks[k].sector = static_cast<int>(k);
    peaks[k].azimuth = sector_azimuth(s, SectorKind::antinode, static_cast<int>(k));
    peaks[k].value = std::numeric_limits<double>::quiet_NaN();
  }
  const XYGrid& g = field.grid;
  for (std::size_t j = 0; j < g.ny(); ++j)
    for (std::size_t i = 0; i < g.nx(); ++i) {
      const double v = field.at(i, j);
      if (std::isnan(v)) continue;
      const Vec3 c{g.x_center(i), g.y_center(j), 0.0};
      const int k = sector_of(s, SectorKind::antinode, c);
      if (k < 0) continue;
      SectorPeak& p = peaks[static_cast<std::size_t>(k)];
      if (std::isnan(p.value) || v > p.value) {
        p.value = v;
        p.r = std::hypot(c.x - s.axis.x, c.y - s.axis.y);
      }
    }
  return peaks;
}

} // namespace yuxi::analysis
