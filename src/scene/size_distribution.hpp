// The radii of the grains a source makes ([[fill]], [[insert]]), drawn from a seeded stream:
//   constant     r
//   uniform      r in [min, max], uniform
//   normal       Normal(mean, sd) truncated to [min, max] (redrawn until inside)
//   lognormal    a radius whose logarithm is normal, with the given mean and sd of the radius
//                itself: s^2 = ln(1 + sd^2 / mean^2), mu = ln(mean) - s^2 / 2; truncated to
//                [min, max]
//   discrete     radii r_k with weights w_k, by number (P(r_k) = w_k / sum w) or by mass
//                (the mass fraction of r_k is w_k / sum w, so P(r_k) ~ w_k / r_k^3 at one
//                density)
// The largest radius a distribution can give (max, or the largest listed) sets the linked
// cells' edge of a run whose grains come later.
#pragma once

#include "core/random.hpp"

#include <string>
#include <vector>

namespace yuxi {

struct SizeDistribution {
  enum class Kind { constant, uniform, normal, lognormal, discrete };
  Kind kind = Kind::constant;
  double radius = 1.0;         // constant
  double mean = 1.0, sd = 0.0; // normal, lognormal
  double min = 1.0, max = 1.0; // uniform; the truncation of normal and lognormal
  std::vector<double> radii;   // discrete
  std::vector<double> weights; // discrete, as given
  bool by_mass = false;        // discrete: weights are mass fractions

  // One radius from the stream.
  double draw(Random& rng) const;
  double largest() const;
  double smallest() const;
  // The mean of r^3 (the mean grain volume is 4/3 pi <r^3>), by quadrature or exactly.
  double mean_cube() const;
  std::string describe() const;

  // Throws std::invalid_argument naming the problem (negative sd, min > max, a non-positive
  // radius, weights that do not sum to a positive number, a truncation that keeps nothing).
  void validate() const;
};

} // namespace yuxi
