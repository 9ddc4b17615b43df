// Ghost images across periodic faces, for a single process owning the whole box.
//
// After build(), particles [n_owned, size) are copies of owned particles shifted by a box
// length; each step forward() refreshes their positions and velocities from their sources and
// reverse() adds the forces and torques computed on them back to the sources. Under MPI the
// same three operations are done by the domain decomposition, with neighbour ranks as sources.
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"

#include <cstdint>
#include <vector>

namespace yuxi {

class PeriodicHalo {
public:
  // Makes ghosts of every particle within `cutoff` of a periodic face, axis by axis (ghosts of
  // ghosts fill the edges and corners). Requires each periodic length >= 2 * cutoff.
  void build(ParticleStore& s, const Box& box, double cutoff);
  void forward(ParticleStore& s) const;
  void reverse(ParticleStore& s) const;
  std::size_t n_ghosts() const { return source_.size(); }

private:
  std::vector<std::uint32_t> source_; // owned index of each ghost
  std::vector<Vec3> shift_;           // ghost position = source position + shift
};

} // namespace yuxi
