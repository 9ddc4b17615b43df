// Particle data as a structure of arrays: owned particles first (indices [0, n_owned)), then
// ghosts (periodic images here, copies from neighbour ranks under MPI) in [n_owned, size()).
//
// Every per-particle field is listed once (core/particle_fields.hpp), and for_each_field() and
// view() are made from that list, so that resizing, reordering, ghost copies, migration,
// checkpoints and the loops' plain views handle all fields without per-field code.
#pragma once

#include "core/particle_fields.hpp"
#include "core/particle_view.hpp"
#include "core/vec3.hpp"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace yuxi {

// What a caller provides to create one particle.
struct ParticleSpec {
  Vec3 position;
  Vec3 velocity;
  Vec3 angular_velocity;
  double radius = 1.0;
  double mass = 1.0;
  Kind kind = Kind::grain;
  std::uint8_t material = 0;
  std::uint16_t motion = 0; // index into the scene's wall motions (wall particles only)
  bool spins = true;        // false: infinite moment of inertia (rotation locked)
  // A clump's member (sim/clump_bodies.hpp): the clump's id, and its mass, which the member
  // takes in contacts (0: the particle's own mass).
  GlobalId body = -1;
  double contact_mass = 0.0;
};

class ParticleStore {
public:
  // One vector per field of the field list (core/particle_fields.hpp): x, v, w, f, torque,
  // x_rest, x_build, radius, mass, inv_mass, inv_inertia, gid, kind, material, motion, body.
#define YUXI_STORE_VECTOR(type, name) std::vector<type> name;
  YUXI_PARTICLE_FIELDS(YUXI_STORE_VECTOR)
#undef YUXI_STORE_VECTOR

  // Plain views of the fields (core/particle_view.hpp), valid until the next resize or reorder.
  ParticleView view() {
    return view_of<ParticleView>(*this);
  }
  ConstParticleView view() const {
    return view_of<ConstParticleView>(*this);
  }

  // Calls fn(field) for every field, in the list's order.
#define YUXI_APPLY_TO_FIELD(type, name) fn(name);
  template <class F> void for_each_field(F&& fn) {
    YUXI_PARTICLE_FIELDS(YUXI_APPLY_TO_FIELD)
  }
  template <class F> void for_each_field(F&& fn) const {
    YUXI_PARTICLE_FIELDS(YUXI_APPLY_TO_FIELD)
  }
#undef YUXI_APPLY_TO_FIELD
  // Appends a copy of particle i of `other` as an owned particle (only while there are no
  // ghosts).
  void append_copy(const ParticleStore& other, std::size_t i) {
#define YUXI_APPEND_FIELD(type, name) name.push_back(other.name[i]);
    YUXI_PARTICLE_FIELDS(YUXI_APPEND_FIELD)
#undef YUXI_APPEND_FIELD
    n_owned_ = size();
  }

  std::size_t size() const {
    return x.size();
  }
  // Bytes held by the fields (capacity, owned and ghosts).
  std::size_t memory_bytes() const {
    std::size_t b = 0;
    for_each_field([&](const auto& field) { b += field.capacity() * sizeof(field[0]); });
    return b;
  }
  std::size_t n_owned() const {
    return n_owned_;
  }
  std::size_t n_ghost() const {
    return size() - n_owned_;
  }

  // Appends an owned particle (only while there are no ghosts) and returns its index.
  std::size_t add(const ParticleSpec& spec, GlobalId id);
  // Appends `count` ghosts (every field grown, values to be filled in); returns the first's
  // index.
  std::size_t add_ghosts(std::size_t count) {
    const std::size_t first = size();
    resize_all(first + count);
    return first;
  }
  void clear_ghosts() {
    resize_all(n_owned_);
  }
  // Gives back spare capacity beyond an eighth of the size: ghosts are appended swap by swap,
  // and a vector's doubling would otherwise leave up to half of every field unused.
  void trim_capacity() {
    const std::size_t n = size(), keep = n + n / 16;
    for_each_field([n, keep](auto& field) {
      if (field.capacity() > n + n / 8 + 64) {
        field.shrink_to_fit();
        field.reserve(keep);
      }
    });
  }
  // Reorders the owned particles: new index k holds old particle order[k]. Ghosts are dropped.
  void permute_owned(std::span<const std::uint32_t> order);
  // Removes the owned particles `removed` (ascending indices); ghosts are dropped.
  void remove_owned(std::span<const std::size_t> removed);
  // The same without keeping the order of the others: the last owned particles fill the gaps,
  // so the cost is that of the few removed, not of the many that stay (migration, before the
  // particles are sorted by cell anyway).
  void remove_owned_unordered(std::span<const std::size_t> removed);

  bool is_grain(std::size_t i) const {
    return kind[i] == Kind::grain;
  }

  // Saves or loads the owned particles, in their order (ghosts are not part of the state).
  // `with_body` false: a state saved before particles had the `body` field (every particle
  // loads as no clump's member).
  template <class Archive> void checkpoint(Archive& ar, bool with_body = true) {
    static_assert(!std::is_const_v<Archive>);
    std::uint64_t n = n_owned_;
    ar.value(n);
    if constexpr (Archive::loading) {
      ar.check_room(n, sizeof(Vec3));
      resize_all(n);
      n_owned_ = n;
    }
    for_each_field([&](auto& field) {
      if constexpr (Archive::loading)
        if (!with_body && static_cast<void*>(&field) == static_cast<void*>(&body)) {
          std::fill(body.begin(), body.end(), GlobalId{-1});
          return;
        }
      ar.elements(field.data(), n);
    });
  }
  // The saving half of checkpoint() for a store that stays as it is.
  template <class Writer> void save(Writer& ar) const {
    static_assert(!Writer::loading);
    const std::uint64_t n = n_owned_;
    ar.value(n);
    for_each_field([&](const auto& field) { ar.elements(field.data(), n); });
  }
  double max_radius() const;
  // Indices of the owned particles in ascending global id (the order of the output files).
  std::vector<std::uint32_t> owned_in_id_order() const;

private:
  template <class View, class Store> static View view_of(Store& s) {
    View p;
#define YUXI_VIEW_OF(type, name) p.name = s.name.data();
    YUXI_PARTICLE_FIELDS(YUXI_VIEW_OF)
#undef YUXI_VIEW_OF
    p.owned = s.n_owned_;
    p.total = s.size();
    return p;
  }
  void resize_all(std::size_t n);
  std::size_t n_owned_ = 0;
};

// Moment of inertia of a solid sphere, J = (2/5) m r^2.
inline double solid_sphere_inertia(double mass, double radius) {
  return 0.4 * mass * radius * radius;
}

} // namespace yuxi
