// Ghosts and migration across sub-domain faces (and periodic images), as plans of swaps.
//
// build(): for x, then y, then z, and towards the lower then the upper neighbour, every
// particle (owned, or a ghost from an earlier axis, so edges and corners are covered) within
// `cutoff` of that face is sent; what arrives is appended as ghosts. Crossing the periodic
// boundary shifts positions by a box length. With one rank along a periodic axis the
// neighbour is the rank itself, and the swap makes its periodic images.
// forward(): the same swaps again, moving positions and velocities only.
// reverse(): the swaps backwards, moving forces and torques on ghosts back to the particles
// they copy, where they are added (each pair force was computed once, on one rank).
// migrate(): at a rebuild, owned particles that have left the sub-domain go to the neighbour
// that owns them now (one hop per axis: nothing moves more than skin/2 between rebuilds),
// each with an opaque payload (its contact history, packed by the caller).
#pragma once

#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "domain/decomposition.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace yuxi {

class Halo {
public:
  void build(ParticleStore& s, const Decomposition& d, const Comm& comm, double cutoff);
  void forward(ParticleStore& s, const Comm& comm) const;
  void reverse(ParticleStore& s, const Comm& comm) const;
  // The same for one quantity per particle (owned, then ghosts): ghosts' values are added to
  // the particles they copy (a per-particle sum of pair contributions, like the forces).
  void reverse_sum(std::vector<double>& per_particle, const Comm& comm) const;
  std::size_t n_ghosts() const { return n_ghosts_; }

  // Sends owned particles outside the sub-domain to their new owners. `payloads(leaving)`
  // packs what travels with each of the particles `leaving` (called before they leave);
  // `arrived(i, bytes)` receives the payload of a particle that arrived as owned particle i.
  static void
  migrate(ParticleStore& s, const Decomposition& d, const Comm& comm,
          const std::function<std::vector<std::string>(const std::vector<std::size_t>&)>& payloads,
          const std::function<void(std::size_t, const std::string&)>& arrived);

private:
  template <class... Field> void reverse_add(const Comm& comm, Field&... fields) const;
  struct Swap {
    int send_to = -1, receive_from = -1;
    Vec3 shift;                         // added to what is sent (crossing a periodic boundary)
    std::vector<std::uint32_t> sends;   // local indices sent
    std::uint32_t first = 0, count = 0; // where the received ghosts were put
  };
  std::vector<Swap> swaps_;
  std::size_t n_ghosts_ = 0;
  mutable std::string out_, in_; // message buffers of forward() and reverse(), kept between steps
};

} // namespace yuxi
