#include "run/bed_measurements.hpp"

#include "analysis/free_surface.hpp"
#include "analysis/line_fit.hpp"
#include "core/free_rotation.hpp"
#include "core/particle_energy.hpp"
#include "core/units.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace yuxi {
namespace {

using Quantity = MeasureSpec::Quantity;

// Whether a grain is in the measure's region. Between list builds a grain that crossed a
// periodic face stands beyond it: its place in the domain is its wrapped position.
bool in_region(const MeasureSpec& m, const Box& box, const Vec3& x) {
  return !m.region || m.region->contains(box.wrap(x));
}

// The columns over the region's part of the domain, `bin` wide (at least one).
analysis::XYGrid columns_for(const MeasureSpec& m, const Box& box, double bin) {
  Vec3 lo = box.lo, hi = box.hi;
  if (m.region) m.region->bounds_in(box, lo, hi);
  const auto count = [&](double extent) {
    return static_cast<std::size_t>(std::max(1.0, std::floor(extent / bin)));
  };
  return analysis::XYGrid(lo, hi, count(hi.x - lo.x), count(hi.y - lo.y));
}

// The highest grain top over each column, reduced over the ranks (NaN: an empty column).
analysis::GridField column_tops(const MeasureSpec& m, const Simulation& sim, double bin) {
  const ParticleStore& p = sim.particles();
  std::vector<Vec3> x;
  std::vector<double> r;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (const Vec3 at = sim.config().box.wrap(p.x[i]);
        p.is_grain(i) && in_region(m, sim.config().box, at)) {
      x.push_back(at);
      r.push_back(p.radius[i]);
    }
  analysis::GridField tops = analysis::free_surface(columns_for(m, sim.config().box, bin), x, r);
  for (double& v : tops.values)
    if (std::isnan(v)) v = -HUGE_VAL;
  sim.comm().max(tops.values.data(), static_cast<int>(tops.values.size()));
  for (double& v : tops.values)
    if (v == -HUGE_VAL) v = NAN;
  return tops;
}

double median_height(const analysis::GridField& tops) {
  std::vector<double> h;
  for (double v : tops.values)
    if (!std::isnan(v)) h.push_back(v);
  if (h.empty()) return NAN;
  std::sort(h.begin(), h.end());
  const std::size_t n = h.size();
  return n % 2 ? h[n / 2] : 0.5 * (h[n / 2 - 1] + h[n / 2]);
}

// The bed's angle [degrees] and R^2 of the line through the column tops.
std::pair<double, double> bed_angle(const MeasureSpec& m, const analysis::GridField& tops) {
  std::vector<double> s, h;
  const auto& g = tops.grid;
  for (std::size_t j = 0; j < g.ny(); ++j)
    for (std::size_t i = 0; i < g.nx(); ++i) {
      const double top = tops.at(i, j);
      if (std::isnan(top)) continue;
      const Vec3 d{g.x_center(i) - m.point.x, g.y_center(j) - m.point.y, 0.0};
      const double along = m.about_axis ? norm(d) : dot(d, m.direction);
      if (along < m.from || along > m.to) continue;
      s.push_back(along);
      h.push_back(top);
    }
  const analysis::LineFit f = analysis::fit_line(s, h);
  return {std::atan(std::abs(f.slope)) * 180.0 / pi, f.r2};
}

} // namespace

BedMeasurements::BedMeasurements(std::vector<MeasureSpec> specs, const Simulation& sim,
                                 double largest_radius)
    : specs_(std::move(specs)), walls_(specs_.size()), default_bin_(4.0 * largest_radius) {
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (specs_[k].quantity != Quantity::wall_force) continue;
    const std::string& name = specs_[k].wall;
    bool found = false;
    for (std::size_t w = 0; w < sim.shaped_walls().size() && !found; ++w)
      if (wall_name(sim.shaped_walls()[w]) == name) walls_[k] = {false, w}, found = true;
    for (std::size_t w = 0; w < sim.planes().size() && !found; ++w)
      if (sim.planes()[w].name == name) walls_[k] = {true, w}, found = true;
    if (!found)
      throw std::invalid_argument(
          fmt::format("measure {}: no wall is named '{}'", specs_[k].name, name));
  }
}

std::string BedMeasurements::header() const {
  std::string h = "step,time";
  for (const MeasureSpec& m : specs_)
    for (const std::string& c : m.columns()) h += "," + c;
  return h;
}

std::vector<double> BedMeasurements::values(const Simulation& sim) const {
  // Sums over grains: mass, count and kinetic energy per measure, in one reduction.
  const ParticleStore& p = sim.particles();
  std::vector<double> sums(3 * specs_.size(), 0.0);
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const Quantity q = specs_[k].quantity;
    if (q != Quantity::mass && q != Quantity::grains && q != Quantity::kinetic_per_grain) continue;
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      if (!p.is_grain(i) || p.body[i] >= 0 || !in_region(specs_[k], sim.config().box, p.x[i]))
        continue;
      sums[3 * k] += p.mass[i];
      sums[3 * k + 1] += 1.0;
      sums[3 * k + 2] += 0.5 * p.mass[i] * norm2(p.v[i]) + sim.rotational_energy(i);
    }
    // A clump is one grain, where its centre of mass stands, with its body's mass and its
    // energy of motion, turning included (its members, with no inertia of their own, left out
    // above). Each rank adds the bodies it owns.
    for (const ClumpBody& b : sim.clumps()) {
      if (!in_region(specs_[k], sim.config().box, b.x)) continue;
      sums[3 * k] += b.mass;
      sums[3 * k + 1] += 1.0;
      sums[3 * k + 2] += translational_energy(b.mass, b.v) + rotor_energy(b.q, b.p, b.inertia);
    }
  }
  sim.comm().sum(sums.data(), static_cast<int>(sums.size()));
  const bool any_wall = std::any_of(specs_.begin(), specs_.end(), [](const MeasureSpec& m) {
    return m.quantity == Quantity::wall_force;
  });
  std::vector<WallLoad> wall_loads, plane_loads;
  if (any_wall) {
    if (!sim.shaped_walls().empty()) wall_loads = sim.shaped_wall_loads(); // collective
    if (!sim.planes().empty()) plane_loads = sim.plane_loads();            // collective
  }
  std::vector<double> out;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    const MeasureSpec& m = specs_[k];
    const double bin = m.bin > 0 ? m.bin : default_bin_;
    switch (m.quantity) {
    case Quantity::mass:
      out.push_back(sums[3 * k]);
      break;
    case Quantity::grains:
      out.push_back(sums[3 * k + 1]);
      break;
    case Quantity::kinetic_per_grain:
      out.push_back(sums[3 * k + 1] > 0 ? sums[3 * k + 2] / sums[3 * k + 1] : 0.0);
      break;
    case Quantity::surface_height:
      out.push_back(median_height(column_tops(m, sim, bin)));
      break;
    case Quantity::angle: {
      const auto [angle, r2] = bed_angle(m, column_tops(m, sim, bin));
      out.insert(out.end(), {angle, r2});
      break;
    }
    case Quantity::wall_force: {
      const WallRef w = walls_[k];
      const Vec3 f = (w.plane ? plane_loads : wall_loads)[w.index].force;
      out.insert(out.end(), {f.x, f.y, f.z});
      break;
    }
    }
  }
  return out;
}

} // namespace yuxi
