// Probability densities on logarithmic bins and power-law fits (Li & Cai 2008, Fig. 10: the
// per-grain kinetic energy E_k, elastic energy E_s and E_k + E_s over the first excitation
// period, with straight regions A = [0.2, 2] and B = [10, 1e4] in a log-log plot).
//
// Bins: edges e_min * 10^(k / bins_per_decade), k = 0 .. n, n = ceil(bins_per_decade *
// log10(e_max / e_min)) (so the last edge is >= e_max, = e_max for whole bins). A value v is in
// bin k when edge_k <= v < edge_{k+1}. N counts every finite sample added, including those
// below e_min (zeros: grains without contacts) and above the last edge, so
//   density_k = count_k / (N (edge_{k+1} - edge_k))
// is the probability density of the whole sample. Samples accumulate over any number of
// snapshots (a time window), as in the paper. Empty bins are left out of a Density.
//
// Fit: least squares of log10(density) against log10(e_center) over the non-empty bins whose
// geometric centre lies in [e_lo, e_hi]: density ~ 10^intercept * E^slope. slope_error is the
// usual standard error of the slope, sqrt(residual variance / sum (x - mean x)^2), NaN with
// fewer than 3 bins; slope and intercept are NaN with fewer than 2. energy_fraction is the
// energy of the samples in the bins used over the energy of all samples, sum E / sum E.
//
// CSV of a density (write_density_csv), analysis/pdf_kinetic.csv, pdf_elastic.csv,
// pdf_total.csv (E_k, E_s, E_k + E_s):
//   e_lo,e_hi,e_center,count,density,energy      one row per non-empty bin; energy = sum of the
//                                                samples in the bin.
// CSV of fits (write_fits_csv), analysis/fits.csv:
//   quantity,range,e_lo,e_hi,slope,intercept,slope_error,bins,energy_fraction,e_lo_used,e_hi_used
//   quantity: kinetic | elastic | total; range: a label (A, B); e_lo, e_hi: the requested range;
//   e_lo_used, e_hi_used: the outer edges of the bins used.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace yuxi::analysis {

struct DensityBin {
  double e_lo, e_hi; // edges
  double e_center;   // geometric centre sqrt(e_lo e_hi)
  std::size_t count; // samples in the bin
  double density;    // count / (N (e_hi - e_lo))
  double energy;     // sum of the samples in the bin
};

struct Density {
  std::vector<DensityBin> bins; // non-empty bins, increasing
  std::size_t samples = 0;      // N: finite samples
  std::size_t below = 0;        // finite samples < e_min (zeros included)
  std::size_t above = 0;        // samples >= the last edge
  std::size_t non_finite = 0;   // NaN or infinite samples, not counted in N
  double total_energy = 0.0;    // sum of all finite samples
};

class LogHistogram {
public:
  // Throws std::invalid_argument unless 0 < e_min < e_max and bins_per_decade >= 1.
  LogHistogram(double e_min, double e_max, int bins_per_decade);

  void add(double value);
  void add(std::span<const double> values);

  std::size_t bins() const { return counts_.size(); }
  const std::vector<double>& edges() const { return edges_; } // bins() + 1 edges
  std::size_t samples() const { return samples_; }
  Density density() const;
  // Adds up the histograms of several processes: `sum_in_place(values, n)` must sum n doubles
  // over them, in place.
  void combine(const std::function<void(double*, int)>& sum_in_place);

private:
  std::vector<double> edges_;
  std::vector<std::size_t> counts_;
  std::vector<double> energies_;
  std::size_t samples_ = 0, below_ = 0, above_ = 0, non_finite_ = 0;
  double total_ = 0.0;
};

// The density of one sample (a LogHistogram filled with `values`).
Density log_density(std::span<const double> values, double e_min, double e_max,
                    int bins_per_decade);

struct PowerLawFit {
  double slope;
  double intercept;       // log10 of the density at E = 1
  double slope_error;     // standard error of the slope
  std::size_t bins;       // bins used
  double energy_fraction; // energy in the bins used / all energy
  double e_lo_used;       // lower edge of the first bin used (NaN if none)
  double e_hi_used;       // upper edge of the last bin used (NaN if none)
};

// Throws std::invalid_argument unless e_lo < e_hi.
PowerLawFit fit_power_law(const Density& density, double e_lo, double e_hi);

// sum of the values in [e_lo, e_hi] / sum of all finite values (exact, from the raw sample);
// NaN when the sum of all values is 0.
double energy_fraction(std::span<const double> values, double e_lo, double e_hi);

void write_density_csv(const std::filesystem::path& path, const Density& density);

struct NamedFit {
  std::string quantity; // kinetic | elastic | total
  std::string range;    // A | B
  double e_lo, e_hi;    // the range asked for
  PowerLawFit fit;
};

void write_fits_csv(const std::filesystem::path& path, std::span<const NamedFit> fits);

} // namespace yuxi::analysis
