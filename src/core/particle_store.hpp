// Particle data as a structure of arrays: owned particles first (indices [0, n_owned)), then
// ghosts (periodic images here, copies from neighbour ranks under MPI) in [n_owned, size()).
//
// Every per-particle field is listed once, in for_each_field(), so that resizing, reordering,
// ghost copies, migration and checkpoints handle all fields without per-field code.
#pragma once

#include "core/vec3.hpp"

#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

namespace yuxi {

enum class Kind : std::uint8_t {
  grain = 0, // free grain, integrated by the equations of motion
  wall = 1,  // wall particle: prescribed motion, infinite mass in contacts
};

using GlobalId = std::int64_t;

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
};

class ParticleStore {
public:
  // Fields (one entry per particle).
  std::vector<Vec3> x;       // position
  std::vector<Vec3> v;       // velocity
  std::vector<Vec3> w;       // angular velocity
  std::vector<Vec3> f;       // force
  std::vector<Vec3> torque;  // torque about the centre
  std::vector<Vec3> x_rest;  // rest position of a wall particle (its motion is relative to it)
  std::vector<Vec3> x_build; // position at the last neighbour-list build (skin criterion)
  std::vector<double> radius;
  std::vector<double> mass;        // finite for walls too (used in output only)
  std::vector<double> inv_mass;    // 0 for wall particles: infinite mass in contacts
  std::vector<double> inv_inertia; // 1 / J, J = (2/5) m r^2 for a solid sphere; 0 for walls
  std::vector<GlobalId> gid;
  std::vector<Kind> kind;
  std::vector<std::uint8_t> material;
  std::vector<std::uint16_t> motion;

  // The list of fields: the one place that names them all.
  static constexpr auto fields =
      std::make_tuple(&ParticleStore::x, &ParticleStore::v, &ParticleStore::w, &ParticleStore::f,
                      &ParticleStore::torque, &ParticleStore::x_rest, &ParticleStore::x_build,
                      &ParticleStore::radius, &ParticleStore::mass, &ParticleStore::inv_mass,
                      &ParticleStore::inv_inertia, &ParticleStore::gid, &ParticleStore::kind,
                      &ParticleStore::material, &ParticleStore::motion);

  template <class F> void for_each_field(F&& fn) {
    std::apply([&](auto... member) { (fn(this->*member), ...); }, fields);
  }
  template <class F> void for_each_field(F&& fn) const {
    std::apply([&](auto... member) { (fn(this->*member), ...); }, fields);
  }
  // Appends a copy of particle i of `other` as an owned particle (only while there are no
  // ghosts).
  void append_copy(const ParticleStore& other, std::size_t i) {
    std::apply([&](auto... member) { ((this->*member).push_back((other.*member)[i]), ...); },
               fields);
    n_owned_ = size();
  }

  std::size_t size() const { return x.size(); }
  // Bytes held by the fields (capacity, owned and ghosts).
  std::size_t memory_bytes() const {
    std::size_t b = 0;
    for_each_field([&](const auto& field) { b += field.capacity() * sizeof(field[0]); });
    return b;
  }
  std::size_t n_owned() const { return n_owned_; }
  std::size_t n_ghost() const { return size() - n_owned_; }

  // Appends an owned particle (only while there are no ghosts) and returns its index.
  std::size_t add(const ParticleSpec& spec, GlobalId id);
  // Appends `count` ghosts (every field grown, values to be filled in); returns the first's
  // index.
  std::size_t add_ghosts(std::size_t count) {
    const std::size_t first = size();
    resize_all(first + count);
    return first;
  }
  void clear_ghosts() { resize_all(n_owned_); }
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

  bool is_grain(std::size_t i) const { return kind[i] == Kind::grain; }

  // Saves or loads the owned particles, in their order (ghosts are not part of the state).
  template <class Archive> void checkpoint(Archive& ar) {
    static_assert(!std::is_const_v<Archive>);
    std::uint64_t n = n_owned_;
    ar.value(n);
    if constexpr (Archive::loading) {
      ar.check_room(n, sizeof(Vec3));
      resize_all(n);
      n_owned_ = n;
    }
    for_each_field([&](auto& field) { ar.elements(field.data(), n); });
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
  void resize_all(std::size_t n);
  std::size_t n_owned_ = 0;
};

// Moment of inertia of a solid sphere, J = (2/5) m r^2.
inline double solid_sphere_inertia(double mass, double radius) {
  return 0.4 * mass * radius * radius;
}

} // namespace yuxi
