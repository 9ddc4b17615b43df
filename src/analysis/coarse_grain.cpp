#include "analysis/coarse_grain.hpp"

#include "analysis/cg_accumulate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace yuxi::analysis {
namespace {

// The weights of one grain, contact point or branch at the grid's points: phi or psi for a
// function, 1 / V_cell or the branch's share of a cell for plain bins. Each point's index and
// weight go to a visitor.
class Weights {
public:
  explicit Weights(const CgSettings& s) : grid_(s.grid), reach_(s.cutoff) {
    if (s.kind != CgKind::bins)
      function_.emplace(s.kind, s.width, s.cutoff, grid_.dimension());
    else
      reach_ = 0.0;
    inverse_extent_ = 1.0 / grid_.averaged_extent();
    inverse_cell_ = 1.0 / grid_.cell_volume();
    if (function_ && function_->kind() == CgKind::gaussian) {
      // (fill_gaussian()'s constants: 1 / (2 w^2), and along each axis the ratio of neighbours'
      // ratios, exp(-h^2 / w^2))
      inverse_2w2_ = 0.5 / (function_->width() * function_->width());
      for (int a = 0; a < 3; ++a)
        if (!grid_.averaged[static_cast<std::size_t>(a)])
          step_ratio_[static_cast<std::size_t>(a)] =
              std::exp(-2.0 * grid_.spacing(a) * grid_.spacing(a) * inverse_2w2_);
    }
    for (std::size_t a = 0; a < 3; ++a)
      if (grid_.averaged[a]) {
        axes_[a].hold(1);
        axes_[a].index[0] = 0, axes_[a].d2[0] = 0.0, axes_[a].gauss[0] = 1.0;
      } else {
        profile_axis_ = static_cast<int>(a);
      }
    if (grid_.dimension() != 1) profile_axis_ = -1;
    for (int a = 0; a < 3; ++a)
      inverse_spacing_[static_cast<std::size_t>(a)] = 1.0 / grid_.spacing(a);
  }

  // f(index, weight) for each point that a grain (or contact point) at x weighs on.
  template <class F> void at_point(const Vec3& x, F&& f) const {
    if (!within_averaged(x)) return;
    if (function_ && profile_axis_ >= 0) {
      at_point_on_axis(x[profile_axis_], f);
      return;
    }
    if (!function_) {
      std::array<int, 3> k{};
      for (int a = 0; a < 3; ++a) {
        if (grid_.averaged[a]) continue;
        auto cell = static_cast<long>(std::floor((x[a] - grid_.lo[a]) / grid_.spacing(a)));
        // A bounded axis's last cell holds its upper end: a wall's contact point on the face.
        if (!grid_.periodic[static_cast<std::size_t>(a)] &&
            cell == grid_.n[static_cast<std::size_t>(a)] && x[a] <= grid_.hi[a])
          cell -= 1;
        const std::optional<int> at = wrap(a, cell);
        if (!at) return;
        k[static_cast<std::size_t>(a)] = *at;
      }
      f(grid_.index(k[0], k[1], k[2]), inverse_cell_);
      return;
    }
    // The resolved axes' points within reach, then their products: a grain weighs on about
    // (2 c / h)^d points, but the Gaussian needs exponentials along each axis only.
    for (int a = 0; a < 3; ++a)
      if (!reach_along(a, x[a], axes_[static_cast<std::size_t>(a)])) return;
    const AxisReach &ax = axes_[0], &ay = axes_[1], &az = axes_[2];
    const double c2 = reach_ * reach_;
    const bool gaussian = function_->kind() == CgKind::gaussian;
    for (std::size_t k = 0; k < az.count; ++k)
      for (std::size_t j = 0; j < ay.count; ++j) {
        const double r2_zy = az.d2[k] + ay.d2[j];
        if (!(r2_zy < c2)) continue;
        const double g_zy = az.gauss[k] * ay.gauss[j];
        const std::size_t row = grid_.index(0, ay.index[j], az.index[k]);
        for (std::size_t i = 0; i < ax.count; ++i) {
          const double r2 = r2_zy + ax.d2[i];
          if (!(r2 < c2)) continue;
          const double w =
              gaussian ? function_->gaussian_from(g_zy * ax.gauss[i]) : function_->at(r2);
          if (w != 0.0) f(row + static_cast<std::size_t>(ax.index[i]), w * inverse_extent_);
        }
      }
  }

  // at_point on a profile (one resolved axis, profile_axis_), without reach_along's scratch
  // arrays; xa the position's coordinate along the axis.
  template <class F> void at_point_on_axis(double xa, F&& f) const {
    const int a = profile_axis_;
    const auto s = static_cast<std::size_t>(a);
    const double h = grid_.spacing(a), lo = grid_.lo[a];
    const auto [first, last, start] = run_along(a, xa, xa);
    if (last < first) return;
    const long n = grid_.n[s];
    long wrapped = start;
    const double c2 = reach_ * reach_;
    const auto offset = [&](long k) { return lo + (static_cast<double>(k) + 0.5) * h - xa; };
    // f for the point at squared offset d2 (the next along the axis) with weight w.
    const auto visit = [&](double d2, double w) {
      const auto at = static_cast<std::size_t>(wrapped);
      if (++wrapped == n) wrapped = 0;
      if (d2 < c2 && w != 0.0) f(at, w * inverse_extent_);
    };
    if (function_->kind() != CgKind::gaussian) {
      for (long k = first; k <= last; ++k) {
        const double d = offset(k);
        visit(d * d, function_->at(d * d));
      }
      return;
    }
    // fill_gaussian's recurrence, point by point.
    const double inv_2w2 = inverse_2w2_, step_ratio = step_ratio_[s];
    double ratio = 0.0, gauss = 0.0;
    for (long k = first; k <= last; ++k) {
      const double d = offset(k);
      if ((k - first) % 8 == 0) {
        gauss = std::exp(-(d * d) * inv_2w2);
        if (k < last) {
          const double next = offset(k + 1);
          ratio = std::exp(-(next * next - d * d) * inv_2w2);
        }
      } else {
        gauss *= ratio;
        ratio *= step_ratio;
      }
      visit(d * d, function_->gaussian_from(gauss));
    }
  }

  // f(index, weight) for each point that the segment from `from` to `from + b` weighs on.
  template <class F> void along(const Vec3& whole_from, const Vec3& whole_b, F&& f) const {
    // The part of the segment within the averaged axes' span, as its own segment: psi over it
    // is (s1 - s0) times psi of the part (ds = (s1 - s0) ds').
    const auto [s0, s1] = averaged_part(whole_from, whole_b);
    if (!(s1 > s0)) return;
    const Vec3 from = whole_from + whole_b * s0, b = whole_b * (s1 - s0);
    const double part = s1 - s0;
    const Vec3 to = from + b;
    const Vec3 low{std::min(from.x, to.x), std::min(from.y, to.y), std::min(from.z, to.z)};
    const Vec3 high{std::max(from.x, to.x), std::max(from.y, to.y), std::max(from.z, to.z)};
    if (!function_) {
      each_cell(low, high, [&](std::size_t index, const Vec3& cell_lo) {
        const double share = share_in_cell(from, b, cell_lo);
        if (share > 0.0) f(index, part * share * inverse_cell_);
      });
      return;
    }
    if (profile_axis_ >= 0) {
      // One resolved axis a: psi in closed form along it, for a run of points at a time (its
      // weights first, each point's apart from the others', then their sums).
      const int a = profile_axis_;
      const auto s = static_cast<std::size_t>(a);
      const double h = grid_.spacing(a), lo = grid_.lo[a], from_a = from[a], b_a = b[a];
      // (a profile's index is the point's along its axis; a branch longer than the axis's
      // period visits a point more than once)
      const auto [first, last, start] = run_along(a, low[a], high[a]);
      const long n = grid_.n[s];
      long wrapped = start;
      constexpr long run = 16;
      std::array<double, run> w; // (filled before it is read)
      const std::optional<CgFunction::AxisBranch> branch =
          b_a != 0.0 ? std::optional<CgFunction::AxisBranch>(std::in_place, *function_, b_a)
                     : std::nullopt;
      for (long k0 = first; k0 <= last; k0 += run) {
        const long count = std::min(run, last - k0 + 1);
        for (long m = 0; m < count; ++m) {
          const double q = lo + (static_cast<double>(k0 + m) + 0.5) * h - from_a;
          w[static_cast<std::size_t>(m)] = branch ? (*branch)(q) : function_->at(q * q);
        }
        for (long m = 0; m < count; ++m) {
          const auto at = static_cast<std::size_t>(wrapped);
          if (++wrapped == n) wrapped = 0;
          const double psi = w[static_cast<std::size_t>(m)];
          if (psi != 0.0) f(at, part * psi * inverse_extent_);
        }
      }
      return;
    }
    const Vec3 branch = resolved(b);
    each_point(low, high, [&](std::size_t index, const Vec3& p) {
      const double w = function_->along(resolved(p - from), branch);
      if (w != 0.0) f(index, part * w * inverse_extent_);
    });
  }

private:
  // The points of one axis within reach of a coordinate: their indices (wrapped on a periodic
  // axis), their squared offsets and, for the Gaussian, exp(-d^2 / (2 w^2)) (1 for Lucy's
  // polynomial). An averaged axis has its one point, at offset 0, filled once.
  struct AxisReach {
    std::size_t count = 0;
    std::vector<int> index;
    std::vector<double> d2, gauss;
    void hold(std::size_t n) {
      count = n;
      if (index.size() < n) index.resize(n), d2.resize(n), gauss.resize(n);
    }
  };
  // The points along axis a (unwrapped, unclamped indices) within reach of [low, high].
  // (A point at the reach's very edge weighs nothing, so the rounding of the product with 1 / h
  // can take it or leave it.)
  std::pair<long, long> within_reach(int a, double low, double high) const {
    const auto s = static_cast<std::size_t>(a);
    const double per_h = inverse_spacing_[s], lo = grid_.lo[a];
    return {static_cast<long>(std::ceil((low - reach_ - lo) * per_h - 0.5)),
            static_cast<long>(std::floor((high + reach_ - lo) * per_h - 0.5))};
  }
  // The points along axis a within reach of [low, high] on the grid: first..last (unwrapped
  // indices, clamped to the grid along a bounded axis) and first's index on the grid (wrapped
  // along a periodic one). Empty where last < first.
  struct AxisRun {
    long first, last, start;
  };
  AxisRun run_along(int a, double low, double high) const {
    const auto s = static_cast<std::size_t>(a);
    auto [first, last] = within_reach(a, low, high);
    const long n = grid_.n[s];
    if (!grid_.periodic[s])
      return {std::max(first, 0L), std::min(last, n - 1), std::max(first, 0L)};
    return {first, last, ((first % n) + n) % n};
  }
  // Fills `out` for coordinate x along axis a; false where no point is within reach.
  bool reach_along(int a, double x, AxisReach& out) const {
    const auto s = static_cast<std::size_t>(a);
    if (grid_.averaged[s]) return true;
    const double h = grid_.spacing(a), lo = grid_.lo[a];
    const auto [first, last, start] = run_along(a, x, x);
    if (last < first) return false;
    const long n = grid_.n[s];
    out.hold(static_cast<std::size_t>(last - first + 1));
    long wrapped = start;
    for (long k = first; k <= last; ++k) {
      const auto m = static_cast<std::size_t>(k - first);
      const double d = lo + (static_cast<double>(k) + 0.5) * h - x;
      out.index[m] = static_cast<int>(wrapped);
      out.d2[m] = d * d;
      if (++wrapped == n) wrapped = 0;
    }
    if (function_->kind() == CgKind::gaussian)
      fill_gaussian(out.d2.data(), out.gauss.data(), out.count, a);
    else
      std::fill_n(out.gauss.begin(), out.count, 1.0);
    return true;
  }
  // exp(-d^2 / (2 w^2)) at offsets d spaced by h (d2 their squares, in order), by the ratio of
  // neighbours, exp(-(2 d h + h^2) / (2 w^2)), whose own ratio is exp(-h^2 / w^2): two
  // exponentials for the run, and a fresh one every 8 points to bound the rounding (the
  // Greengard-Lee "fast Gaussian gridding" recurrence, SIAM Review 46:443, 2004).
  void fill_gaussian(const double* d2, double* gauss, std::size_t count, int axis) const {
    const double inv_2w2 = inverse_2w2_;
    const double step_ratio = step_ratio_[static_cast<std::size_t>(axis)];
    double ratio = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      if (k % 8 == 0) {
        gauss[k] = std::exp(-d2[k] * inv_2w2);
        if (k + 1 < count) ratio = std::exp(-(d2[k + 1] - d2[k]) * inv_2w2);
      } else {
        gauss[k] = gauss[k - 1] * ratio;
        ratio *= step_ratio;
      }
    }
  }

  // Whether x lies within the span of every bounded averaged axis (the average is over that
  // span: a grain beside it does not count; along a periodic axis every grain does).
  bool within_averaged(const Vec3& x) const {
    for (int a = 0; a < 3; ++a) {
      const auto s = static_cast<std::size_t>(a);
      if (grid_.averaged[s] && !grid_.periodic[s] && !(x[a] >= grid_.lo[a] && x[a] <= grid_.hi[a]))
        return false;
    }
    return true;
  }
  // The range [s0, s1] of the segment from + s b within the bounded averaged axes' span.
  std::pair<double, double> averaged_part(const Vec3& from, const Vec3& b) const {
    double s0 = 0.0, s1 = 1.0;
    for (int a = 0; a < 3; ++a) {
      const auto s = static_cast<std::size_t>(a);
      if (grid_.averaged[s] && !grid_.periodic[s] &&
          !clip_to_slab(a, from, b, grid_.lo[a], grid_.hi[a], true, s0, s1))
        return {0.0, 0.0};
    }
    return {s0, s1};
  }
  // Narrows [s0, s1] to where from + s b lies between c0 and c1 along axis a. A segment across
  // the axis is in where from[a] is: in [c0, c1) (or [c0, c1] where `closed`), else false.
  static bool clip_to_slab(int a, const Vec3& from, const Vec3& b, double c0, double c1,
                           bool closed, double& s0, double& s1) {
    if (b[a] == 0.0) return from[a] >= c0 && (closed ? from[a] <= c1 : from[a] < c1);
    double e0 = (c0 - from[a]) / b[a], e1 = (c1 - from[a]) / b[a];
    if (e0 > e1) std::swap(e0, e1);
    s0 = std::max(s0, e0);
    s1 = std::min(s1, e1);
    return true;
  }
  // v with its averaged components zeroed.
  Vec3 resolved(Vec3 v) const {
    for (int a = 0; a < 3; ++a)
      if (grid_.averaged[a]) v[a] = 0.0;
    return v;
  }
  // Point k along axis a, wrapped on a periodic axis; nothing outside a bounded one.
  std::optional<int> wrap(int a, long k) const {
    const long n = grid_.n[static_cast<std::size_t>(a)];
    if (grid_.periodic[static_cast<std::size_t>(a)]) return static_cast<int>(((k % n) + n) % n);
    if (k < 0 || k >= n) return std::nullopt;
    return static_cast<int>(k);
  }
  // g(index, {i, j, k}) for the unwrapped indices in [first, last] along each axis, clamped to
  // the grid along a bounded axis (an averaged axis has its one point).
  template <class G>
  void each_index(std::array<long, 3> first, std::array<long, 3> last, G&& g) const {
    for (std::size_t a = 0; a < 3; ++a) {
      if (grid_.averaged[a]) {
        first[a] = last[a] = 0;
      } else if (!grid_.periodic[a]) {
        first[a] = std::max(first[a], 0L);
        last[a] = std::min(last[a], static_cast<long>(grid_.n[a]) - 1);
      }
    }
    for (long k = first[2]; k <= last[2]; ++k)
      for (long j = first[1]; j <= last[1]; ++j)
        for (long i = first[0]; i <= last[0]; ++i)
          g(grid_.index(*wrap(0, i), *wrap(1, j), *wrap(2, k)), std::array<long, 3>{i, j, k});
  }
  // g(index, point) for the points within reach of the box [low, high] (resolved axes; on a
  // periodic axis every image, its coordinate unwrapped; on an averaged axis, low's).
  template <class G> void each_point(const Vec3& low, const Vec3& high, G&& g) const {
    std::array<long, 3> first{}, last{};
    for (int a = 0; a < 3; ++a)
      std::tie(first[static_cast<std::size_t>(a)], last[static_cast<std::size_t>(a)]) =
          within_reach(a, low[a], high[a]);
    each_index(first, last, [&](std::size_t index, const std::array<long, 3>& k) {
      Vec3 p = low;
      for (int a = 0; a < 3; ++a)
        if (!grid_.averaged[static_cast<std::size_t>(a)])
          p[a] = grid_.coordinate(a, static_cast<int>(k[static_cast<std::size_t>(a)]));
      g(index, p);
    });
  }
  // g(index, the cell's low corner, unwrapped) for the cells that the box [low, high] meets.
  template <class G> void each_cell(const Vec3& low, const Vec3& high, G&& g) const {
    std::array<long, 3> first{}, last{};
    for (int a = 0; a < 3; ++a) {
      const double h = grid_.spacing(a);
      first[static_cast<std::size_t>(a)] =
          static_cast<long>(std::floor((low[a] - grid_.lo[a]) / h));
      last[static_cast<std::size_t>(a)] =
          static_cast<long>(std::floor((high[a] - grid_.lo[a]) / h));
    }
    each_index(first, last, [&](std::size_t index, const std::array<long, 3>& k) {
      Vec3 corner = low;
      for (int a = 0; a < 3; ++a)
        if (!grid_.averaged[static_cast<std::size_t>(a)])
          corner[a] =
              grid_.lo[a] + static_cast<double>(k[static_cast<std::size_t>(a)]) * grid_.spacing(a);
      g(index, corner);
    });
  }
  // The share of the segment from + s b, s in [0, 1), that lies in the cell whose low corner is
  // cell_lo (resolved axes; the slabs' intersection).
  double share_in_cell(const Vec3& from, const Vec3& b, const Vec3& cell_lo) const {
    double s0 = 0.0, s1 = 1.0;
    for (int a = 0; a < 3; ++a)
      if (!grid_.averaged[static_cast<std::size_t>(a)] &&
          !clip_to_slab(a, from, b, cell_lo[a], cell_lo[a] + grid_.spacing(a), false, s0, s1))
        return 0.0;
    return s1 > s0 ? s1 - s0 : 0.0;
  }

  const CgGrid& grid_;
  double reach_;
  int profile_axis_ = -1; // a profile's one resolved axis (-1: two or three resolved)
  std::array<double, 3> inverse_spacing_{}; // 1 / h along each axis
  mutable std::array<AxisReach, 3> axes_;   // scratch of at_point
  std::optional<CgFunction> function_;
  double inverse_extent_ = 1.0, inverse_cell_ = 1.0;
  double inverse_2w2_ = 0.0;                        // 1 / (2 w^2) of the Gaussian
  std::array<double, 3> step_ratio_{1.0, 1.0, 1.0}; // exp(-h^2 / w^2) along each axis
};

} // namespace

CgParts parts_for(std::span<const std::string> names) {
  const auto named = [&](std::initializer_list<std::string_view> any) {
    return std::any_of(names.begin(), names.end(), [&](const std::string& n) {
      return std::find(any.begin(), any.end(), n) != any.end();
    });
  };
  return {named({"contact_stress", "stress"}),
          named({"wall_force_density", "elastic_energy_density", "dissipation_rate_density",
                 "relaxation_energy_density", "wall_power_density"}),
          named({"coordination", "fabric"})};
}

std::vector<double> coarse_grain_sums(const CgGrains& grains, std::span<const CgContact> contacts,
                                      const CgSettings& settings) {
  settings.grid.check();
  const Weights weights(settings);
  std::vector<double> sums(cg_sums_per_point * settings.grid.size(), 0.0);
  detail::add_sums(grains, contacts, weights, sums, settings.parts);
  return sums;
}

std::vector<double> coarse_grain_densities(std::span<const Vec3> x,
                                           std::span<const std::span<const double>> quantities,
                                           const CgSettings& settings) {
  settings.grid.check();
  for (const auto& q : quantities)
    if (q.size() != x.size())
      throw std::invalid_argument("coarse-graining: a quantity has " + std::to_string(q.size()) +
                                  " values for " + std::to_string(x.size()) + " grains");
  const Weights weights(settings);
  const std::size_t n = quantities.size();
  std::vector<double> out(n * settings.grid.size(), 0.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    weights.at_point(x[i], [&](std::size_t p, double w) {
      for (std::size_t k = 0; k < n; ++k) out[n * p + k] += quantities[k][i] * w;
    });
  return out;
}

CgFields coarse_grain_fields(std::span<const double> sums, const CgGrid& grid) {
  return coarse_grain_fields(sums, grid.size());
}

CgFields coarse_grain_fields(std::span<const double> sums, std::size_t points) {
  using detail::add_outer;
  using detail::Sum;
  if (sums.size() != cg_sums_per_point * points)
    throw std::invalid_argument("coarse-graining: the sums do not fit the grid");
  CgFields out;
  for (auto* scalar : {&out.density, &out.number_density, &out.volume_fraction, &out.temperature,
                       &out.coordination, &out.kinetic_energy, &out.elastic_energy,
                       &out.dissipation, &out.relaxation, &out.wall_power})
    scalar->assign(points, 0.0);
  for (auto* vector : {&out.momentum, &out.velocity, &out.wall_force})
    vector->assign(3 * points, 0.0);
  for (auto* tensor : {&out.kinetic_stress, &out.contact_stress, &out.stress, &out.fabric})
    tensor->assign(9 * points, 0.0);
  for (std::size_t p = 0; p < points; ++p) {
    const double* s = &sums[cg_sums_per_point * p];
    const double rho = s[Sum::mass], number = s[Sum::number];
    out.density[p] = rho;
    out.number_density[p] = number;
    out.volume_fraction[p] = s[Sum::volume];
    out.kinetic_energy[p] = s[Sum::kinetic];
    out.elastic_energy[p] = s[Sum::elastic];
    out.dissipation[p] = s[Sum::dissipation];
    out.relaxation[p] = s[Sum::relaxation];
    out.wall_power[p] = s[Sum::wall_power];
    out.coordination[p] = number > 0.0 ? s[Sum::contacts] / number : 0.0;
    Vec3 velocity;
    for (int a = 0; a < 3; ++a) {
      out.momentum[3 * p + a] = s[Sum::momentum + a];
      out.wall_force[3 * p + a] = s[Sum::wall_force + a];
      if (rho > 0.0) velocity[a] = s[Sum::momentum + a] / rho;
      out.velocity[3 * p + a] = velocity[a];
    }
    // The fluctuations' stress: sum m v v phi - rho V V.
    double* kinetic = &out.kinetic_stress[9 * p];
    for (int k = 0; k < 9; ++k) {
      kinetic[k] = s[Sum::momentum_flux + k];
      out.contact_stress[9 * p + k] = s[Sum::contact_stress + k];
      out.fabric[9 * p + k] = s[Sum::fabric + k];
    }
    add_outer(kinetic, velocity, velocity, -rho);
    for (int k = 0; k < 9; ++k) out.stress[9 * p + k] = kinetic[k] + s[Sum::contact_stress + k];
    out.temperature[p] = rho > 0.0 ? (kinetic[0] + kinetic[4] + kinetic[8]) / (3.0 * rho) : 0.0;
  }
  return out;
}

std::vector<CgNamedField> named_fields(const CgFields& f) {
  return {{"density", &f.density, 1},
          {"number_density", &f.number_density, 1},
          {"volume_fraction", &f.volume_fraction, 1},
          {"momentum", &f.momentum, 3},
          {"velocity", &f.velocity, 3},
          {"kinetic_stress", &f.kinetic_stress, 9},
          {"contact_stress", &f.contact_stress, 9},
          {"stress", &f.stress, 9},
          {"wall_force_density", &f.wall_force, 3},
          {"temperature", &f.temperature, 1},
          {"coordination", &f.coordination, 1},
          {"fabric", &f.fabric, 9},
          {"kinetic_energy_density", &f.kinetic_energy, 1},
          {"elastic_energy_density", &f.elastic_energy, 1},
          {"dissipation_rate_density", &f.dissipation, 1},
          {"relaxation_energy_density", &f.relaxation, 1},
          {"wall_power_density", &f.wall_power, 1}};
}

CgFields coarse_grain(const CgGrains& grains, std::span<const CgContact> contacts,
                      const CgSettings& settings) {
  return coarse_grain_fields(coarse_grain_sums(grains, contacts, settings), settings.grid);
}

} // namespace yuxi::analysis
