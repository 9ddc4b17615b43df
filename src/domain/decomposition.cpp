#include "domain/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

namespace yuxi {

std::array<int, 3> choose_layout(Vec3 lengths, int n, std::array<int, 3> fixed) {
  std::array<int, 3> best{0, 0, 0};
  double best_surface = std::numeric_limits<double>::infinity();
  for (int px = 1; px <= n; ++px)
    for (int py = 1; px * py <= n; ++py) {
      if (n % (px * py) != 0) continue;
      const int pz = n / (px * py);
      const std::array<int, 3> p{px, py, pz};
      bool ok = true;
      for (int a = 0; a < 3; ++a) ok = ok && (fixed[a] == 0 || fixed[a] == p[a]);
      if (!ok) continue;
      const double lx = lengths.x / px, ly = lengths.y / py, lz = lengths.z / pz;
      const double surface = lx * ly + ly * lz + lz * lx;
      if (surface < best_surface - 1e-12) best_surface = surface, best = p;
    }
  if (best[0] == 0)
    throw std::invalid_argument(
        fmt::format("no layout of {} ranks matches {} x {} x {}", n, fixed[0], fixed[1], fixed[2]));
  return best;
}

Decomposition::Decomposition(const Box& box, const Comm& comm, std::array<int, 3> layout,
                             Vec3 occupied)
    : box_(box) {
  Vec3 lengths;
  for (int a = 0; a < 3; ++a) lengths[a] = occupied[a] > 0 ? occupied[a] : box.length(a);
  dims_ = choose_layout(lengths, comm.size(), layout);
  int r = comm.rank();
  coords_ = {r % dims_[0], (r / dims_[0]) % dims_[1], r / (dims_[0] * dims_[1])};
  for (int a = 0; a < 3; ++a) {
    cuts_[a].resize(static_cast<std::size_t>(dims_[a]) + 1);
    for (int k = 0; k <= dims_[a]; ++k)
      cuts_[a][static_cast<std::size_t>(k)] = box.lo[a] + box.length(a) * k / dims_[a];
    for (int side = 0; side < 2; ++side) {
      auto c = coords_;
      c[a] += side == 0 ? -1 : 1;
      const bool outside = c[a] < 0 || c[a] >= dims_[a];
      wraps_[a][side] = outside;
      if (outside && !box.periodic(a)) {
        neighbor_[a][side] = -1;
        continue;
      }
      c[a] = (c[a] + dims_[a]) % dims_[a];
      neighbor_[a][side] = rank_of(c);
    }
  }
  update_region();
}

void Decomposition::update_region() {
  const double inf = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const auto c = static_cast<std::size_t>(coords_[a]);
    lo_[a] = cuts_[a][c];
    hi_[a] = cuts_[a][c + 1];
    if (!box_.periodic(a)) {
      if (coords_[a] == 0) lo_[a] = -inf;
      if (coords_[a] == dims_[a] - 1) hi_[a] = inf;
    }
  }
}

Box Decomposition::local_box() const {
  Box b = box_;
  for (int a = 0; a < 3; ++a) {
    const auto c = static_cast<std::size_t>(coords_[a]);
    b.lo[a] = cuts_[a][c];
    b.hi[a] = cuts_[a][c + 1];
  }
  return b;
}

bool Decomposition::owns(const Vec3& x) const {
  for (int a = 0; a < 3; ++a)
    if (x[a] < lo_[a] || x[a] >= hi_[a]) return false;
  return true;
}

double Decomposition::min_width(int axis) const {
  double w = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < cuts_[axis].size(); ++k)
    w = std::min(w, cuts_[axis][k + 1] - cuts_[axis][k]);
  return w;
}

void Decomposition::balance(const std::vector<Vec3>& positions, const std::vector<double>& cost,
                            const Comm& comm) {
  constexpr int bins = 4096;
  for (int a = 0; a < 3; ++a) {
    if (dims_[a] == 1) continue;
    std::vector<double> hist(bins, 0.0);
    const double lo = box_.lo[a], len = box_.length(a);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const double f =
          (box_.periodic(a) ? box_.wrap(positions[i])[a] - lo : positions[i][a] - lo) / len;
      const int b = std::clamp(static_cast<int>(f * bins), 0, bins - 1);
      hist[static_cast<std::size_t>(b)] += cost[i];
    }
    comm.sum(hist.data(), bins);
    double total = 0;
    for (double h : hist) total += h;
    if (total <= 0) continue;
    // Cut k where the cumulative load reaches k / p of the total.
    double running = 0;
    int k = 1;
    for (int b = 0; b < bins && k < dims_[a]; ++b) {
      const double next = running + hist[static_cast<std::size_t>(b)];
      while (k < dims_[a] && next >= total * k / dims_[a]) {
        const double frac =
            hist[static_cast<std::size_t>(b)] > 0
                ? (total * k / dims_[a] - running) / hist[static_cast<std::size_t>(b)]
                : 0.0;
        cuts_[a][static_cast<std::size_t>(k)] = lo + len * (b + frac) / bins;
        ++k;
      }
      running = next;
    }
    // Keep every slab at least `min_slab` wide (ghosts come from the next rank only).
    const double min_slab = std::min(min_slab_, len / dims_[a]);
    for (int j = 1; j < dims_[a]; ++j)
      cuts_[a][static_cast<std::size_t>(j)] =
          std::max(cuts_[a][static_cast<std::size_t>(j)],
                   cuts_[a][static_cast<std::size_t>(j - 1)] + min_slab);
    for (int j = dims_[a] - 1; j >= 1; --j)
      cuts_[a][static_cast<std::size_t>(j)] =
          std::min(cuts_[a][static_cast<std::size_t>(j)],
                   cuts_[a][static_cast<std::size_t>(j + 1)] - min_slab);
  }
  update_region();
}

void Decomposition::set_cuts(int axis, const std::vector<double>& cuts) {
  if (cuts.size() != cuts_[axis].size())
    throw std::invalid_argument(
        fmt::format("the checkpoint was written by a run with {} ranks along {}, this run has {}",
                    cuts.size() - 1, "xyz"[axis], cuts_[axis].size() - 1));
  cuts_[axis] = cuts;
  update_region();
}

std::string Decomposition::describe() const {
  std::string out = fmt::format("{} x {} x {} ranks", dims_[0], dims_[1], dims_[2]);
  for (int a = 0; a < 3; ++a)
    if (dims_[a] > 1) out += fmt::format("; {} cuts {:.4g}", "xyz"[a], fmt::join(cuts_[a], " "));
  return out;
}

} // namespace yuxi
