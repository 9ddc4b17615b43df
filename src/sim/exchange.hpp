// The exchange between ranks of a simulation, one part of it: the group of ranks, the cut
// planes (domain/decomposition.hpp), the ghosts (domain/halo.hpp) and this rank's linked cells,
// which the cut planes bound. It moves particles to their owners with their contacts' states
// (migrate), moves the cut planes (balance) and makes the ghosts. On one rank every call but
// the periodic images is a no-op.
#pragma once

#include "contact/contact_history.hpp"
#include "core/cell_grid.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "domain/decomposition.hpp"
#include "domain/halo.hpp"
#include "sim/clump_bodies.hpp"
#include "sim/simulation_config.hpp"

#include <array>
#include <vector>

namespace yuxi {

class Exchange {
public:
  // `layout`: ranks per axis (zeros chosen for the `occupied` lengths); `cell_edge`: the linked
  // cells' edge [length], at least the largest contact distance plus the skin.
  Exchange(const Box& box, Comm comm, std::array<int, 3> layout, Vec3 occupied, double cell_edge);
  Exchange(const Exchange&) = delete;
  Exchange& operator=(const Exchange&) = delete;
  // Waits for the last forces sent back to another rank to be taken (Halo::close).
  ~Exchange() { halo_.close(comm_); }

  const Comm& comm() const { return comm_; }
  const Decomposition& decomposition() const { return decomp_; }
  const Halo& halo() const { return halo_; }
  const CellGrid& grid() const { return grid_; }
  CellGrid& grid() { return grid_; }
  double cell_edge() const { return cell_edge_; }

  // Lays the ranks out afresh (as the constructor does) for cells of `cell_edge`: a state
  // continued from a checkpoint, whose particles and cells are known only once it is read.
  void lay_out(std::array<int, 3> layout, Vec3 occupied, double cell_edge);

  // How far a clump's member may stand from its clump's anchor member [length] (the same on
  // every rank; 0 without clumps, or on one rank without periodic axes). A clump's owner is the
  // rank whose sub-domain holds its anchor member (the member nearest its centre of mass:
  // scene/clump_shape.hpp), and it owns every member and the body, so members stand up to
  // `reach` outside the sub-domain (or the periodic box: a clump is never cut by a face): the
  // ghosts reach that much farther, the cells cover that much more, and no sub-domain is cut
  // narrower than the cells' edge plus it. The anchor's own position decides, as a sphere's
  // does, so a run resumed from its last list build's positions makes the same owners.
  void set_clump_reach(double reach);
  double clump_reach() const { return clump_reach_; }

  // Collective, where every rank holds every particle (a scene's start): cuts by particle count
  // where `balance`, keeps this sub-domain's particles (and clumps: members and body go with
  // the anchor member) and sets its cells.
  void take_share(ParticleStore& s, ClumpBodies& clumps, bool balance);
  // Collective, where the ranks hold shares of the particles in no order (sections of another
  // run merged): cuts by particle count and sets this sub-domain's cells; the next migrate()
  // takes every particle to its owner.
  void cut_by_count(const ParticleStore& s);
  // The cut planes of a saved run of the same layout, and their cells (throws
  // std::invalid_argument for another layout).
  void set_cuts(const std::array<std::vector<double>, 3>& cuts);
  std::array<std::vector<double>, 3> cuts() const;

  // Collective: particles to the rank that owns their place now, each with copies of the states
  // of its contacts (contact_history.hpp: the rank that computes a pair after the list build
  // may be either partner's); repeated until every rank holds only its own (one round unless
  // the cut planes have just moved).
  // A clump goes whole, with its body, to the rank of its anchor member.
  void migrate(ParticleStore& s, ContactStates& history, ClumpBodies& clumps);
  // Collective: moves the cut planes so that each rank carries an equal share of the load:
  // each particle's pairs in `list`, or (BalanceBy::time) the seconds `busy` this rank computed
  // since the last balancing spread over its particles by their pairs.
  void balance(const ParticleStore& s, const NeighborList& list, BalanceBy by, double busy);
  // Collective: the ghosts of the owned particles, each with copies of the contact states it
  // may be needed for on its receiver.
  void make_ghosts(ParticleStore& s, ContactStates& history);

  // The ghosts' positions and velocities from their owners, and their forces back (in two
  // halves where the pairs with ghosts are computed first).
  void forward(ParticleStore& s) const { halo_.forward(s, comm_); }
  void reverse(ParticleStore& s) const { halo_.reverse(s, comm_); }
  void reverse_start(ParticleStore& s) const { halo_.reverse_start(s, comm_); }
  void reverse_finish(ParticleStore& s) const { halo_.reverse_finish(s, comm_); }

private:
  // This sub-domain's cells: its box, grown by the clumps' reach.
  CellGrid local_grid() const;
  // Of each owned particle, the one whose place decides its owner: itself, or its clump's
  // anchor member (ClumpBody::anchor; throws std::logic_error where that is not here).
  std::vector<std::size_t> anchors(const ParticleStore& s, const ClumpBodies& clumps) const;
  // Those places (empty without clumps).
  std::vector<Vec3> owner_places(const ParticleStore& s, const ClumpBodies& clumps) const;

  Comm comm_;
  Decomposition decomp_;
  Halo halo_;
  double cell_edge_;
  CellGrid grid_;
  double clump_reach_ = 0.0;
  double busy_at_balance_ = 0.0; // the `busy` of the last balancing
  bool cuts_moved_ = false;      // since the last migrate() (which then checks for strays)
};

} // namespace yuxi
