// A DEM simulation: owns the particles, walls, neighbour list and contact model, and advances
// them with velocity Verlet (Allen & Tildesley 3.2.1; rotation likewise for spheres, whose
// inertia tensor is isotropic). One step, phase by phase (see step()):
//   1. half kick and drift of grains; walls placed at t + dt by their prescribed motion
//   2. neighbour list rebuilt if some particle moved more than skin/2 (history stashed by
//      global ids, periodic wrap, particles sorted by cell, ghosts, list, history restored);
//      otherwise ghosts refreshed
//   3. forces: gravity, contacts with other particles and flat walls; ghost forces summed back
//   4. second half kick
#pragma once

#include "analysis/energy_report.hpp"
#include "contact/contact_model.hpp"
#include "core/box.hpp"
#include "core/cell_grid.hpp"
#include "core/near_pairs.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "domain/decomposition.hpp"
#include "domain/halo.hpp"
#include "scene/plane_wall.hpp"
#include "scene/wall_motion.hpp"
#include "sim/contact_forces.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace yuxi {

// What to do with a grain that leaves the box through an open face.
enum class EscapePolicy { stop, remove };

// The load the cut planes of a multi-rank run balance (SimulationConfig::balance_by).
enum class BalanceBy { pairs, time };

struct SimulationConfig {
  Box box;
  Vec3 gravity;
  double dt = 1e-4;
  double skin = 0.2;      // Verlet skin [length]
  double cell_size = 0.0; // linked-cell edge; 0 = the smallest valid (2 r_max + skin)
  EscapePolicy on_escape = EscapePolicy::stop;
  std::uint8_t box_wall_material = 0; // material of the flat walls on Boundary::wall faces
  double max_overlap_ratio = 1.0;     // stop if an overlap exceeds this times the smaller radius
  std::array<int, 3> ranks{0, 0, 0};  // MPI ranks per axis; 0 = chosen automatically
  int rebalance_every = 50;           // move the cut planes every this many rebuilds (0: never)
  // What the cut planes balance: each particle's count of listed pairs (the same cuts on every
  // run: reproducible to the bit), or the compute time each rank measured since the last
  // balancing (a rank on a slower or busier core gets less; the cuts, and so the round-off of
  // the sums, then differ from run to run).
  BalanceBy balance_by = BalanceBy::pairs;
  // The near pairs' margin as a fraction of the skin (core/near_pairs.hpp; 0: scan the whole
  // list every step). The trajectory is the same either way.
  double near_fraction = 0.25;
};

// The run cannot go on; what() holds the diagnosis (step, grain, position, velocity).
class SimulationError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Wall-clock seconds spent in each phase.
struct PhaseTimes {
  double integrate = 0, neighbor = 0, pair = 0, comm = 0;
  // The part of `neighbor` this rank spends on its own work (sorting, binning, the lists, the
  // contact states), without the rebuild's exchanges and waits for other ranks.
  double neighbor_local = 0;
  double total() const { return integrate + neighbor + pair + comm; }
  // What balancing by time evens out: the time a rank computes, waiting for no other.
  double busy() const { return pair + neighbor_local + integrate; }
};

// The contact that limits the time step.
struct StiffestContact {
  double contact_time = 0; // t_c [time]
  std::uint8_t material_a = 0, material_b = 0;
  double m_eff = 0;
};

class Simulation {
public:
  // Every rank is given all particles; each keeps those of its sub-domain. `comm` is the group
  // of ranks that share the simulation (a group of one: serial).
  Simulation(SimulationConfig config, ParticleStore particles, std::vector<PlaneWall> planes,
             std::vector<WallMotion> motions, AnyContactLaw law, Comm comm = Comm::world());
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;
  // Waits for the last forces sent back to another rank to be taken (halo.hpp: close()).
  ~Simulation() { halo_.close(comm_); }

  void step();
  void run(std::int64_t n_steps) {
    for (std::int64_t k = 0; k < n_steps; ++k) step();
  }

  double time() const { return time_; }
  std::int64_t step_count() const { return step_; }
  const SimulationConfig& config() const { return config_; }
  // This rank's particles (all of them when serial).
  const ParticleStore& particles() const { return store_; }
  // Every rank's owned particles, sorted by global id, on rank 0 (empty elsewhere). Collective.
  ParticleStore gather_particles() const;
  const Comm& comm() const { return comm_; }
  const Decomposition& decomposition() const { return decomp_; }
  // Owned particles per rank, max over mean (1 when serial). Collective.
  double imbalance() const;
  const std::vector<PlaneWall>& planes() const { return planes_; }
  const NeighborList& neighbor_list() const { return list_; }
  const Halo& halo() const { return halo_; }
  // The pairs the last force evaluation scanned, where they held (core/near_pairs.hpp).
  const NearPairs& near_pairs() const { return near_; }
  const CellGrid& grid() const { return grid_; }
  double cell_edge() const { return cell_edge_; }
  const AnyContactLaw& contact_law() const { return law_; }
  EnergyReport energies() const;
  const ContactTally& last_tally() const { return tally_; }
  // Records every contact's force and stored energy at each force evaluation (costs memory
  // and time; for stress and per-grain energy analyses). Aligned with neighbor_list().
  void record_contacts(bool on) { record_.enabled = on; }
  const ContactRecord& contact_record() const { return record_; }
  // Elastic energy per owned particle at the last force evaluation: half of each contact's
  // stored energy to each partner (flat walls keep theirs). Needs record_contacts(true) during
  // that evaluation. Collective.
  std::vector<double> particle_elastic_energy() const;
  // J w^2 / 2 of owned particle i (0 when its rotation is locked).
  double rotational_energy(std::size_t i) const;
  // Bytes of this rank's simulation data: particles (with ghosts), cells, neighbour list,
  // contact states; the libraries and the scene's input are not counted.
  std::size_t memory_bytes() const;
  const PhaseTimes& timers() const { return timers_; }
  std::int64_t rebuilds() const { return rebuilds_; }
  std::size_t escaped() const { return escaped_; }
  std::size_t n_grains() const;
  StiffestContact stiffest_contact() const;

  // Saves or loads the whole dynamic state: time, step, particles in their order, contact
  // history, the last forces and energy tally, and the energy books. Save only right after a
  // step that rebuilt the neighbour list (request_rebuild() before it): loading then rebuilds
  // the identical list, so a resumed run continues bit for bit. Loading keeps the stored forces
  // (they were computed with the half-step velocities) and computes none.
  template <class Archive> void checkpoint(Archive& ar) {
    ar.value(time_);
    ar.value(step_);
    ar.value(dissipated_);
    ar.value(wall_work_);
    ar.value(removed_energy_);
    ar.value(gravity_work_);
    ar.value(rebuilds_);
    ar.value(escaped_);
    ar.value(initial_balance_);
    ar.value(tally_);
    for (int a = 0; a < 3; ++a) {
      std::vector<double> cuts = decomp_.cuts(a);
      ar.vector(cuts);
      if constexpr (Archive::loading)
        if (loading_ != Loading::merged) decomp_.set_cuts(a, cuts);
    }
    // The cells of the saved sub-domain: the list build then sorts and bins as the saved run.
    if constexpr (Archive::loading)
      if (loading_ != Loading::merged) grid_ = CellGrid(decomp_.local_box(), cell_edge_);
    if constexpr (Archive::loading) store_.clear_ghosts();
    store_.checkpoint(ar);
    std::visit([&](auto& f) { f.history.checkpoint(ar, store_, list_); }, forces_);
    if constexpr (Archive::loading)
      if (loading_ == Loading::whole) {
        validate_loaded_particles();
        rebuild_after_load();
      }
  }

  // Collective: loads this rank's share of a checkpoint's sections (Simulation::checkpoint of
  // each rank of the run that wrote it, which had `written_on` ranks; `share` holds a block of
  // consecutive ones). On as many ranks, the share is this rank's own section, and the run
  // continues bit for bit. On another number, each rank loads its block, the cut planes are set
  // afresh by particle count, and the particles go to their new owners with copies of their
  // contacts' states (the migration of a rebuild, repeated until none is left astray); the
  // energy books are summed onto rank 0. A correct continuation, not a bitwise one (the
  // summation order changes with the decomposition). A section that does not load or does not
  // fit the scene throws std::invalid_argument on every rank.
  void load(const std::vector<std::string>& share, std::uint64_t written_on);

  // Makes the next step rebuild the neighbour list (and re-sort particles) whatever the skin
  // criterion says; the trajectory must not change.
  void request_rebuild() { rebuild_requested_ = true; }
  // Collective: throws SimulationError on every rank if the last force evaluation on any rank
  // found an overlap beyond the limit (a step finds out at its next collective; a checkpoint
  // must not keep such a state).
  // It also checks the energy books of the last list build, if still due.
  void stop_if_unhealthy() {
    stop_together(health_error_);
    settle_energy_books();
  }

  // Setup access: changes to particles must be followed by refresh(), before the first step.
  ParticleStore& particles_mutable() { return store_; }
  // Rebuilds lists and evaluates forces for the current state. Evaluating contacts advances
  // their history (tangential springs), so call it only after changing particles by hand.
  void refresh();

private:
  // Walls to their prescribed place at t; true if one moved more than half the skin.
  // `every_one` false skips those of a motion at rest: placed before, they stay there.
  // `moved2`, if given, gets the largest squared displacement of a wall particle.
  bool place_walls(double t, bool every_one = false, double* moved2 = nullptr);
  // `after_load`: the rebuild of a loaded state, whose contact states are in the stash already
  // and whose cut planes are the saved ones (the run's next rebuild balances as it would have).
  void rebuild(bool after_load = false);
  void migrate();
  void rebalance();
  void stop_together(const std::string& local_error) const;
  void rebuild_after_load();
  // load()'s parts on this rank: its own section, or the merge of its share.
  void load_own_section(const std::string& section);
  void merge_sections(const std::vector<std::string>& share);
  void validate_loaded_particles() const;
  void handle_escapes();
  void handle_escapes_here();
  // Evaluates all forces; `advance_history` false for a setup pass (no time elapses, so no
  // spring is incremented and nothing is dissipated).
  void start_forces_from_gravity();
  void compute_forces(bool advance_history = true);
  // Picks the near pairs again where those held have lapsed and new ones would last a few
  // steps; drops them where they would not.
  void refresh_near_pairs();
  // Notes (in health_error_) an overlap beyond max_overlap_ratio; the next collective stops
  // every rank with it.
  void check_health();
  // The energy books (EnergyReport) as sums of the ranks' parts: this rank's parts, and the
  // report of their sums over the ranks.
  static constexpr int energy_sums = 12;
  std::array<double, energy_sums> energy_parts() const;
  EnergyReport report_of(const std::array<double, energy_sums>& sums) const;
  // Throws SimulationError if the books have gained energy (an unstable integration).
  void check_energy_books(const EnergyReport& e) const;
  // Collective: sums and checks the books that a list build left due.
  void settle_energy_books();
  std::string describe_particle(std::size_t i) const;
  std::string describe_contacts(std::size_t i) const;
  double mechanical_energy(std::size_t i) const; // kinetic + gravitational of one grain
  // Gravity's components along periodic axes (no potential) and along the others.
  Vec3 periodic_gravity() const;
  Vec3 potential_gravity() const { return config_.gravity - periodic_gravity(); }

  template <class> struct ForcesOf;
  template <class... M> struct ForcesOf<std::variant<ContactLaw<M>...>> {
    using type = std::variant<ContactForces<M>...>;
  };
  using Forces = typename ForcesOf<AnyContactLaw>::type;

  SimulationConfig config_;
  Comm comm_;
  Decomposition decomp_;
  ParticleStore store_;
  std::vector<PlaneWall> planes_;
  std::vector<WallMotion> motions_;
  AnyContactLaw law_;
  Forces forces_;
  double cell_edge_ = 0.0; // linked-cell edge >= largest contact distance + skin
  CellGrid grid_;
  double range_ = 0.0;           // neighbour range beyond touching (the skin)
  std::size_t owned_grains_ = 0; // owned particles [0, owned_grains_) are grains, the rest walls
  NeighborList list_;
  NearPairs near_;
  double last_displacement_ = 0.0;  // largest displacement of a particle in the last step
  double position_round_off_ = 0.0; // bound on the round-off of one step's displacement
  bool walls_still_ = false;        // every wall particle at rest (place_walls)
  Halo halo_;
  ContactTally tally_;
  ContactRecord record_;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  double dissipated_ = 0.0;
  double wall_work_ = 0.0;
  double removed_energy_ = 0.0;
  double gravity_work_ = 0.0;    // work of gravity along periodic axes
  double initial_balance_ = 0.0; // energy books at the start (blow-up diagnosis)
  double busy_at_balance_ = 0.0; // timers_.busy() at the last balancing
  std::int64_t rebuilds_ = 0;
  bool rebuild_requested_ = false;
  std::string health_error_; // this rank's diagnosis of the last force evaluation ("" if sound)
  // This rank's parts of the energy books at the last list build, until the next collective
  // sums and checks them (settle_energy_books).
  std::optional<std::array<double, energy_sums>> books_due_;
  bool cuts_moved_ = false; // since the last list build (migrate() then checks for strays)
  // How checkpoint() loads: a whole state (rebuilt at once), one section whose rebuild load()
  // does once every rank has loaded, or one of several sections that load() merges (the cut
  // planes are set afresh).
  enum class Loading { whole, deferred, merged };
  Loading loading_ = Loading::whole;
  std::size_t escaped_ = 0;
  PhaseTimes timers_;
};

} // namespace yuxi
