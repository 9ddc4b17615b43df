#include "domain/periodic_halo.hpp"

#include <stdexcept>

namespace yuxi {

void PeriodicHalo::build(ParticleStore& s, const Box& box, double cutoff) {
  s.clear_ghosts();
  source_.clear();
  shift_.clear();
  const std::size_t n_owned = s.n_owned();
  for (int a = 0; a < 3; ++a) {
    if (!box.periodic(a)) continue;
    const double l = box.length(a);
    if (l < 2.0 * cutoff)
      throw std::invalid_argument("periodic box length must be at least twice the cutoff");
    const std::size_t n_now = s.size();
    for (std::size_t k = 0; k < n_now; ++k) {
      const double p = s.x[k][a];
      for (double sign : {1.0, -1.0}) {
        const bool near = sign > 0 ? p < box.lo[a] + cutoff : p >= box.hi[a] - cutoff;
        if (!near) continue;
        Vec3 shift;
        shift[a] = sign * l;
        const bool ghost = k >= n_owned;
        const std::uint32_t src = ghost ? source_[k - n_owned] : static_cast<std::uint32_t>(k);
        const Vec3 total = ghost ? shift_[k - n_owned] + shift : shift;
        s.add_ghost(k, shift);
        source_.push_back(src);
        shift_.push_back(total);
      }
    }
  }
}

void PeriodicHalo::forward(ParticleStore& s) const {
  const std::size_t n_owned = s.n_owned();
  for (std::size_t g = 0; g < source_.size(); ++g) {
    const std::uint32_t src = source_[g];
    s.x[n_owned + g] = s.x[src] + shift_[g];
    s.v[n_owned + g] = s.v[src];
    s.w[n_owned + g] = s.w[src];
  }
}

void PeriodicHalo::reverse(ParticleStore& s) const {
  const std::size_t n_owned = s.n_owned();
  for (std::size_t g = 0; g < source_.size(); ++g) {
    s.f[source_[g]] += s.f[n_owned + g];
    s.torque[source_[g]] += s.torque[n_owned + g];
  }
}

} // namespace yuxi
