#include "core/particle_store.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace yuxi {

void ParticleStore::resize_all(std::size_t n) {
  for_each_field([this, n](auto& field) {
    if (static_cast<void*>(&field) == static_cast<void*>(&body))
      body.resize(n, GlobalId{-1}); // (a new particle is no clump's member)
    else
      field.resize(n);
  });
}

std::size_t ParticleStore::add(const ParticleSpec& s, GlobalId id) {
  if (n_ghost() != 0) throw std::logic_error("ParticleStore::add called while ghosts exist");
  if (!(s.radius > 0.0) || !(s.mass > 0.0))
    throw std::invalid_argument("particle radius and mass must be positive");
  const std::size_t i = size();
  resize_all(i + 1);
  x[i] = s.position;
  v[i] = s.velocity;
  w[i] = s.angular_velocity;
  x_rest[i] = s.position;
  x_build[i] = s.position;
  radius[i] = s.radius;
  mass[i] = s.mass;
  const bool wall = s.kind == Kind::wall;
  inv_mass[i] = wall ? 0.0 : 1.0 / (s.contact_mass > 0.0 ? s.contact_mass : s.mass);
  inv_inertia[i] = wall || !s.spins ? 0.0 : 1.0 / solid_sphere_inertia(s.mass, s.radius);
  gid[i] = id;
  kind[i] = s.kind;
  material[i] = s.material;
  motion[i] = s.motion;
  body[i] = s.body;
  n_owned_ = i + 1;
  return i;
}

void ParticleStore::permute_owned(std::span<const std::uint32_t> order) {
  if (order.size() != n_owned_) throw std::logic_error("permutation size mismatch");
  clear_ghosts();
  for_each_field([&order](auto& field) {
    auto copy = field;
    for (std::size_t k = 0; k < order.size(); ++k) field[k] = copy[order[k]];
  });
}

void ParticleStore::remove_owned(std::span<const std::size_t> removed) {
  clear_ghosts();
  if (removed.empty()) return;
  // Members before the first removed one stay where they are.
  for_each_field([&removed, n = n_owned_](auto& field) {
    std::size_t to = removed.front(), r = 0;
    for (std::size_t i = removed.front(); i < n; ++i) {
      if (r < removed.size() && removed[r] == i) {
        ++r;
        continue;
      }
      field[to++] = field[i];
    }
    field.resize(to);
  });
  n_owned_ -= removed.size();
}

void ParticleStore::remove_owned_unordered(std::span<const std::size_t> removed) {
  clear_ghosts();
  // From the highest index down: the particle moved into a gap is never one still to remove
  // (those below the gap stay where they are, those above it are gone already).
  for (std::size_t k = removed.size(); k-- > 0;) {
    const std::size_t gap = removed[k], last = n_owned_ - 1;
    for_each_field([gap, last](auto& field) {
      field[gap] = field[last];
      field.pop_back();
    });
    --n_owned_;
  }
}

double ParticleStore::max_radius() const {
  double r = 0.0;
  for (std::size_t i = 0; i < n_owned_; ++i) r = std::max(r, radius[i]);
  return r;
}

std::vector<std::uint32_t> ParticleStore::owned_in_id_order() const {
  std::vector<std::uint32_t> order(n_owned_);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return gid[a] < gid[b]; });
  return order;
}

} // namespace yuxi
