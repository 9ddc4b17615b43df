#include "scene/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <stdexcept>

namespace yuxi {
namespace {

// The parameters of ln r for a lognormal radius of the given mean and sd.
void log_parameters(double mean, double sd, double& mu, double& s) {
  const double s2 = std::log1p(sd * sd / (mean * mean));
  s = std::sqrt(s2);
  mu = std::log(mean) - 0.5 * s2;
}

// Number probabilities of the listed radii.
std::vector<double> number_weights(const SizeDistribution& d) {
  std::vector<double> p(d.radii.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    p[k] = d.by_mass ? d.weights[k] / (d.radii[k] * d.radii[k] * d.radii[k]) : d.weights[k];
  const double sum = std::accumulate(p.begin(), p.end(), 0.0);
  for (double& x : p) x /= sum;
  return p;
}

} // namespace

double SizeDistribution::draw(Random& rng) const {
  switch (kind) {
  case Kind::constant:
    return radius;
  case Kind::uniform:
    return rng.uniform(min, max);
  case Kind::normal:
  case Kind::lognormal: {
    double mu = mean, s = sd;
    if (kind == Kind::lognormal) log_parameters(mean, sd, mu, s);
    for (int attempt = 0; attempt < 100000; ++attempt) {
      const double x = mu + s * rng.normal();
      const double r = kind == Kind::lognormal ? std::exp(x) : x;
      if (r >= min && r <= max) return r;
    }
    return std::clamp(kind == Kind::lognormal ? std::exp(mu) : mu, min, max);
  }
  case Kind::discrete: {
    const auto p = number_weights(*this);
    double u = rng.uniform();
    for (std::size_t k = 0; k + 1 < p.size(); ++k) {
      if (u < p[k]) return radii[k];
      u -= p[k];
    }
    return radii.back();
  }
  }
  return radius;
}

double SizeDistribution::largest() const {
  switch (kind) {
  case Kind::constant:
    return radius;
  case Kind::discrete:
    return *std::max_element(radii.begin(), radii.end());
  default:
    return max;
  }
}

double SizeDistribution::smallest() const {
  switch (kind) {
  case Kind::constant:
    return radius;
  case Kind::discrete:
    return *std::min_element(radii.begin(), radii.end());
  default:
    return min;
  }
}

double SizeDistribution::mean_cube() const {
  switch (kind) {
  case Kind::constant:
    return radius * radius * radius;
  case Kind::uniform: // (max^4 - min^4) / (4 (max - min))
    return max > min ? (std::pow(max, 4) - std::pow(min, 4)) / (4.0 * (max - min))
                     : min * min * min;
  case Kind::discrete: {
    const auto p = number_weights(*this);
    double m = 0;
    for (std::size_t k = 0; k < p.size(); ++k) m += p[k] * std::pow(radii[k], 3);
    return m;
  }
  default: { // the truncated density, by the midpoint rule on 4096 intervals
    double mu = mean, s = sd;
    if (kind == Kind::lognormal) log_parameters(mean, sd, mu, s);
    if (!(s > 0))
      return std::pow(std::clamp(kind == Kind::lognormal ? std::exp(mu) : mu, min, max), 3);
    constexpr int n = 4096;
    double weight = 0, moment = 0;
    for (int k = 0; k < n; ++k) {
      const double r = min + (max - min) * (k + 0.5) / n;
      const double x = kind == Kind::lognormal ? std::log(r) : r;
      double density = std::exp(-0.5 * (x - mu) * (x - mu) / (s * s));
      if (kind == Kind::lognormal) density /= r;
      weight += density;
      moment += density * r * r * r;
    }
    return weight > 0 ? moment / weight : std::pow(mean, 3);
  }
  }
}

void SizeDistribution::validate() const {
  switch (kind) {
  case Kind::constant:
    if (!(radius > 0))
      throw std::invalid_argument(fmt::format("radius {} must be positive", radius));
    return;
  case Kind::uniform:
  case Kind::normal:
  case Kind::lognormal:
    if (!(min > 0)) throw std::invalid_argument(fmt::format("min = {} must be positive", min));
    if (!(max >= min))
      throw std::invalid_argument(fmt::format("max = {} is below min = {}", max, min));
    if (kind == Kind::uniform) return;
    if (!(sd >= 0)) throw std::invalid_argument(fmt::format("sd = {} must not be negative", sd));
    if (!(mean > 0)) throw std::invalid_argument(fmt::format("mean = {} must be positive", mean));
    if (sd == 0 && (mean < min || mean > max))
      throw std::invalid_argument(
          fmt::format("sd = 0 and the mean {} lies outside [min, max] = [{}, {}]", mean, min, max));
    if (kind == Kind::normal && sd > 0 && (max < mean - 8 * sd || min > mean + 8 * sd))
      throw std::invalid_argument(fmt::format(
          "[min, max] = [{}, {}] lies more than 8 sd from the mean {}: nothing would be drawn", min,
          max, mean));
    return;
  case Kind::discrete:
    if (radii.empty()) throw std::invalid_argument("radii: no radius listed");
    if (weights.size() != radii.size())
      throw std::invalid_argument(
          fmt::format("weights: {} given for {} radii", weights.size(), radii.size()));
    for (double r : radii)
      if (!(r > 0)) throw std::invalid_argument(fmt::format("radii: {} must be positive", r));
    double sum = 0;
    for (double w : weights) {
      if (!(w >= 0)) throw std::invalid_argument(fmt::format("weights: {} is negative", w));
      sum += w;
    }
    if (!(sum > 0)) throw std::invalid_argument("weights: they must sum to a positive number");
    return;
  }
}

std::string SizeDistribution::describe() const {
  switch (kind) {
  case Kind::constant:
    return fmt::format("radius {}", radius);
  case Kind::uniform:
    return fmt::format("uniform radii in [{}, {}]", min, max);
  case Kind::normal:
    return fmt::format("normal radii (mean {}, sd {}) in [{}, {}]", mean, sd, min, max);
  case Kind::lognormal:
    return fmt::format("lognormal radii (mean {}, sd {}) in [{}, {}]", mean, sd, min, max);
  case Kind::discrete:
    return fmt::format("radii {} with weights {} by {}", fmt::join(radii, ", "),
                       fmt::join(weights, ", "), by_mass ? "mass" : "number");
  }
  return {};
}

} // namespace yuxi
