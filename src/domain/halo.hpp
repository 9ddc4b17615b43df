// Ghosts and migration across sub-domain faces (and periodic images), as plans of swaps.
//
// The ghosts form a half shell: of every pair of particles on different ranks (or on one rank
// and a periodic image), exactly one side receives the other as a ghost and computes the pair.
// A ghost's offset is the sum of the unit steps between sub-domains that carried it here; the
// side that computes the pair is the one that sees the other particle at an "upper" offset,
// whose first non-zero component (x, then y, then z) is positive. The opposite side sees the
// negated offset, so exactly one side holds the ghost. The rule is topological (no
// floating-point comparison decides it), and each rank receives half the ghosts of a full
// shell, so forward and reverse exchanges move half the bytes.
//
// build(): for x, then y, then z, particles within `cutoff` of a face are sent across it; what
// arrives is appended as ghosts. Towards the lower neighbour go owned particles and ghosts
// from earlier axes (the receiver sees them at an upper offset); towards the upper neighbour
// only ghosts from earlier axes, whose offset is upper already (an owned particle sent there
// would be at a lower offset). A ghost that is not upper never becomes upper on a later axis,
// so no rank relays one it does not need itself. This is the import region of the half-shell
// method: the slab above the upper x face (spanning y and z with their ghost layers), the slab
// above the upper y face (spanning z), and the slab above the upper z face. Crossing the
// periodic boundary shifts positions by a box length; with one rank along a periodic axis the
// neighbour is the rank itself, and the swap makes its periodic images.
// forward(): the same swaps again, moving positions and velocities only.
// reverse(): the swaps backwards, moving forces and torques on ghosts back to the particles
// they copy, where they are added (each pair force was computed once, on one rank).
// reverse_start() and reverse_finish() split it around other work: the swaps back run up to
// the last one that is a message to another rank, which is left travelling; the finish adds
// what it brought and runs the swaps back after it (periodic images on this rank).
// migrate(): at a list build, owned particles that have left the sub-domain go to the neighbour
// that owns them now (one hop per axis: nothing moves more than skin/2 between list builds),
// each with an opaque payload (its contact history, packed by the caller).
#pragma once

#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "domain/decomposition.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace yuxi {

// What travels with the ghosts at a build besides their fields: the contact states of their
// pairs with particles of other ranks, packed by the contact history (the domain layer never
// sees contact models).
struct GhostPayload {
  // The bytes that go with the particles `sent` (local indices, in send order).
  std::function<std::string(std::span<const std::uint32_t> sent)> pack;
  // The bytes that came with the ghosts first, first + 1, ... (in the sender's order).
  std::function<void(std::uint32_t first, const std::string& bytes)> unpack;
};

class Halo {
public:
  void build(ParticleStore& s, const Decomposition& d, const Comm& comm, double cutoff,
             const GhostPayload* payload = nullptr);
  void forward(ParticleStore& s, const Comm& comm) const;
  void reverse(ParticleStore& s, const Comm& comm) const;
  // reverse() in two halves. The ghosts' forces leave at the start; between the halves the
  // caller may add forces to owned particles, and the finish adds what came back.
  void reverse_start(ParticleStore& s, const Comm& comm) const;
  void reverse_finish(ParticleStore& s, const Comm& comm) const;
  // Waits until the other rank has taken the forces reverse_start() sent (reverse_finish()
  // waits only for those coming here; the next reverse_start() settles the last one).
  void settle(const Comm& comm) const { comm.wait_send(back_); }
  // At the end: withdraws forces still expected (an error between start and finish), then
  // settles.
  void close(const Comm& comm) const {
    comm.cancel_receive(back_);
    settle(comm);
  }
  // Whether forces on ghosts go back to another rank: reverse_start() then leaves a message
  // travelling that the caller can compute beside.
  bool sends_to_other_ranks() const { return last_message_ < swaps_.size(); }
  // The same for one quantity per particle (owned, then ghosts): ghosts' values are added to
  // the particles they copy (a per-particle sum of pair contributions, like the forces).
  void reverse_sum(std::vector<double>& per_particle, const Comm& comm) const;
  std::size_t n_ghosts() const { return n_ghosts_; }
  // Of those, the copies of other ranks' particles (the rest are periodic images made here):
  // what forward() receives and reverse() sends back in messages.
  std::size_t n_ghosts_from_other_ranks() const { return n_from_other_ranks_; }
  // The bytes of one ghost in forward() (position, velocity, angular velocity) and in
  // reverse() (force, torque).
  static constexpr std::size_t forward_bytes_per_ghost = 3 * sizeof(Vec3);
  static constexpr std::size_t reverse_bytes_per_ghost = 2 * sizeof(Vec3);
  static_assert(sizeof(ParticleStore{}.f[0]) + sizeof(ParticleStore{}.torque[0]) ==
                reverse_bytes_per_ghost);

  // Sends owned particles outside the sub-domain to their new owners. `where[i]`, if given,
  // is the place that decides owned particle i's owner (a clump's member goes where its
  // clump's centre of mass goes; by default its own position). `payloads(leaving)` packs what
  // travels with each of the particles `leaving` (called before they leave);
  // `arrived(i, bytes, shift)` receives the payload of a particle that arrived as owned
  // particle i, its position shifted by `shift` (a periodic boundary crossed).
  static void
  migrate(ParticleStore& s, const Decomposition& d, const Comm& comm,
          const std::function<std::vector<std::string>(const std::vector<std::size_t>&)>& payloads,
          const std::function<void(std::size_t, const std::string&, const Vec3&)>& arrived,
          std::span<const Vec3> where = {});

private:
  // The swaps back from swap `from` - 1 down to swap `down_to`, one after the other.
  template <class... Field>
  void reverse_add(const Comm& comm, std::size_t from, std::size_t down_to, Field&... fields) const;
  struct Swap;
  // The ghosts' values of swap w, one block per field, into `out`.
  template <class... Field>
  static void pack_back(const Swap& w, std::string& out, Field&... fields);
  // Adds what in_ holds (pack_back() of the other side) to the particles w sent.
  template <class... Field> void add_back(const Swap& w, Field&... fields) const;
  struct Swap {
    // With this rank itself (a periodic image): copied, no message.
    bool local(const Comm& comm) const {
      return send_to == comm.rank() && receive_from == comm.rank();
    }
    int send_to = -1, receive_from = -1;
    Vec3 shift;                         // added to what is sent (crossing a periodic boundary)
    std::vector<std::uint32_t> sends;   // local indices sent
    std::uint32_t first = 0, count = 0; // where the received ghosts were put
  };
  std::vector<Swap> swaps_;
  std::size_t last_message_ = 0; // the last swap back that is a message (the size: none)
  std::size_t n_ghosts_ = 0;
  std::size_t n_from_other_ranks_ = 0;
  mutable std::string out_, in_; // message buffers of forward() and reverse(), kept between steps
  mutable Comm::Exchange back_;  // the last swap back, from reverse_start() until settled
  mutable std::string back_out_; // what it sends
};

} // namespace yuxi
