// A DEM simulation: owns the particles, walls, neighbour list and contact model, and advances
// them with velocity Verlet (Allen & Tildesley 3.2.1; rotation likewise for spheres, whose
// inertia tensor is isotropic). One step, phase by phase (see step()):
//   1. kick_drift(): half kick and drift of grains; walls placed at t + dt by their motion
//   2. exchange_or_rebuild(): the neighbour list rebuilt if some particle moved more than
//      skin/2 (history stashed by global ids, periodic wrap, particles sorted by cell, ghosts,
//      list, history restored: simulation_rebuild.cpp); otherwise ghosts refreshed
//   3. compute_forces(): gravity, contacts with other particles and flat walls; ghost forces
//      summed back
//   4. final_kick(): second half kick
// Saving and loading the state (checkpoints, resuming on any number of ranks) is in
// simulation_restart.cpp.
#pragma once

#include "contact/contact_model.hpp"
#include "core/archive.hpp"
#include "core/box.hpp"
#include "core/cell_grid.hpp"
#include "core/near_pairs.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "domain/decomposition.hpp"
#include "domain/halo.hpp"
#include "scene/particle_source.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "scene/wall_motion.hpp"
#include "sim/contact_forces.hpp"
#include "sim/energy_books.hpp"
#include "sim/near_wall_elements.hpp"
#include "sim/phase_times.hpp"
#include "sim/simulation_config.hpp"
#include "sim/state_layout.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace yuxi {

// The run cannot go on; what() holds the diagnosis (step, grain, position, velocity).
class SimulationError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The contact that limits the time step.
struct StiffestContact {
  double contact_time = 0; // t_c [time]
  std::uint8_t material_a = 0, material_b = 0;
  double m_eff = 0;
  bool depends_on_speed = false; // t_c depends on the impact speed (Hertzian laws)
};

class Simulation {
public:
  // The layout of checkpoint() (sim/state_layout.hpp).
  static constexpr std::uint32_t state_layout = yuxi::state_layout,
                                 oldest_state_layout = yuxi::oldest_state_layout;

  // Every rank is given all particles; each keeps those of its sub-domain. `comm` is the group
  // of ranks that share the simulation (a group of one: serial).
  // `walls`: the triangle meshes and cylinders (every rank is given all of them).
  Simulation(SimulationConfig config, ParticleStore particles, std::vector<PlaneWall> planes,
             std::vector<WallMotion> motions, AnyContactLaw law, Comm comm = Comm::world(),
             std::vector<ShapedWall> walls = {});
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
  // The meshes (placed at the current time) and cylinders.
  const std::vector<ShapedWall>& walls() const { return walls_; }
  // What the grains did to each shaped wall at the last force evaluation, and each wall's
  // cumulative work on the grains (in `work`), summed over the ranks onto every rank.
  // Collective.
  std::vector<WallLoad> wall_loads() const;
  // The same for the flat walls (planes(): the scene's, then the box's faces; torque zero).
  // Collective.
  std::vector<WallLoad> plane_loads() const;
  // The force on each triangle of mesh `wall` at the last force evaluation, summed over the
  // ranks onto every rank (zero where nothing touches). Collective.
  std::vector<Vec3> triangle_forces(std::size_t wall) const;
  const NeighborList& neighbor_list() const { return list_; }
  const Halo& halo() const { return halo_; }
  // The pairs the last force evaluation scanned, where they held (core/near_pairs.hpp).
  const NearPairs& near_pairs() const { return near_; }
  // The meshes' near triangles picked with them (sim/near_wall_elements.hpp).
  const NearWallElements& near_wall_elements() const { return near_walls_; }
  const CellGrid& grid() const { return grid_; }
  // The energy books, summed over the ranks. Collective.
  EnergyBooks energies() const;
  const ContactTally& last_tally() const { return tally_; }
  // Records every contact's force and stored energy at each force evaluation (costs memory
  // and time; for stress and per-grain energy analyses). Aligned with neighbor_list().
  void record_contacts(bool on) { record_.enabled = on; }
  const ContactRecord& contact_record() const { return record_; }
  // Every contact's state under the scene's model (aligned with neighbor_list()).
  const ContactStates& contact_states() const { return *history_; }
  // J w^2 / 2 of owned particle i (0 when its rotation is locked).
  double rotational_energy(std::size_t i) const;
  // Bytes of this rank's simulation data: particles (with ghosts), cells, neighbour list,
  // contact states; the libraries and the scene's input are not counted.
  std::size_t memory_bytes() const;
  const PhaseTimes& timers() const { return timers_; }
  std::int64_t rebuilds() const { return rebuilds_; }
  // The contact of the shortest duration t_c among the materials present: grains (those inserts
  // will pour included) with each other and with wall particles, planes, meshes and cylinders,
  // meeting at `impact_speed` where the law's t_c depends on it (run/impact_speed.hpp).
  // Collective.
  StiffestContact stiffest_contact(double impact_speed) const;

  // Saves or loads the whole dynamic state: time, step, particles in the order of the last list
  // build (with where each stood then, x_build), contact history, the last forces and energy
  // tally, and the energy books. Save after any step: loading builds the list of the run's last
  // build again (rebuild_after_load), so a resumed run continues bit for bit, and saving
  // changes nothing in the run that saves. Loading keeps the stored forces (they were computed
  // with the half-step velocities) and computes none.
  template <class Archive> void checkpoint(Archive& ar) {
    ar.value(time_);
    ar.value(step_);
    ar.value(books_);
    ar.value(rebuilds_);
    ar.value(initial_balance_);
    ar.value(tally_);
    checkpoint_walls(ar);
    checkpoint_sources(ar);
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
    if constexpr (Archive::loading) {
      if (!branch_ || branch_->keep_history) {
        history_->load(ar);
      } else {
        history_->forget();
        ar.skip_to_end();
      }
    } else {
      history_->save(ar, store_, list_);
    }
    if constexpr (Archive::loading)
      if (loading_ == Loading::whole) {
        validate_loaded_particles();
        rebuild_after_load(true);
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
  // `layout`: the state layout of the file (state_layout or older).
  void load(const std::vector<std::string>& share, std::uint64_t written_on,
            std::uint32_t layout = state_layout);

  // Collective: continues another run's saved state under this simulation's scene (a branch:
  // `yuxi run SCENE --from CHECKPOINT`). The particles, their contacts' history, the walls'
  // state, the time and the energy books come from the checkpoint; everything else (the contact
  // law, the motions, gravity, the time step, the outputs) is this scene's. The shares load as
  // on another number of ranks (cut planes by particle count, a new list from the current
  // positions), the walls are placed at the saved time by this scene's motions, and the forces
  // are evaluated afresh without advancing any spring; the change of mechanical energy that the
  // new scene gives the same state is booked as `inserted`, so the books carry on closed.
  // `keep_history` false drops every contact's state (another contact model). The grains are
  // the checkpoint's (the scene's own fills and particles give way to them). Throws
  // std::invalid_argument on every rank where the saved wall particles are not the `walls`
  // this scene builds, or a saved grain stands outside the domain.
  struct BranchCheck {
    std::size_t walls = 0; // the wall particles this scene builds
    bool keep_history = true;
  };
  void branch(const std::vector<std::string>& share, std::uint64_t written_on,
              const BranchCheck& check, std::uint32_t layout = state_layout);

  // Sources and sinks of grains while the run goes on ([[insert]], [[outlet]]; the scene
  // builder sets them before the first step, and before a checkpoint is loaded). Insertions
  // happen at list builds (a batch due forces one); grains that an outlet holds leave at the
  // next list build, their mechanical energy booked as removed, as escaped grains'.
  void set_sources(std::vector<InsertSpec> inserts, std::vector<OutletSpec> outlets);
  struct SourceTally {
    std::string name;
    std::int64_t grains = 0; // cumulative
    double mass = 0;         // cumulative
    std::int64_t owed = 0;   // grains due but not placed yet (inserts: no free place found)
  };
  // Each insert's and each outlet's cumulative grains and mass. Collective.
  std::vector<SourceTally> inflow() const;
  std::vector<SourceTally> outflow() const;
  // An insert's pouring steered from outside the scene (the Python API), by the insert's index.
  // start: it pours from the next step on, at its rate, until its total (or the scene's end);
  // what it poured before counts towards the total. pause: no batch until started again.
  // stop: no batch ever again. Each throws std::invalid_argument where the insert cannot (a
  // stopped insert started, an insert whose total is poured or whose end has passed). The same
  // call on every rank. A checkpoint keeps the state, and a resume or a branch continues it.
  void start_insert(std::size_t insert);
  void pause_insert(std::size_t insert);
  void stop_insert(std::size_t insert);
  // A new insert from the next step on (at its start, if that is later); its name must be new.
  void add_insert(InsertSpec insert);
  const std::vector<InsertSpec>& inserts() const { return inserts_; }

  // Changes from outside the equations of motion between steps (the Python API:
  // simulation_edits.cpp). Each books the change of mechanical energy it makes as `inserted`
  // (removed grains' as `removed`), so the books keep closing and the blow-up check is not
  // tripped.
  // Velocities and angular velocities of grains this rank owns, by global id (an id that is not
  // such a grain throws std::invalid_argument naming it). Nothing else changes.
  void set_velocities(std::span<const GlobalId> ids, std::span<const Vec3> v);
  void set_angular_velocities(std::span<const GlobalId> ids, std::span<const Vec3> w);
  // Positions of grains this rank owns. Collective: the list is built afresh and the forces
  // evaluated without advancing any spring (every rank calls it, with its own grains or none).
  void set_positions(std::span<const GlobalId> ids, std::span<const Vec3> x);
  // New grains, the same list on every rank (each keeps those in its sub-domain), with ids
  // from the counter of inserted grains; returns their ids. Collective. Throws
  // std::invalid_argument, adding none, where one overlaps a particle, a new grain before it or
  // a flat wall.
  std::vector<GlobalId> add_grains(std::span<const ParticleSpec> grains);
  // Removes the grains of these ids that this rank owns (others are passed over); returns how
  // many went on all ranks. Collective.
  std::int64_t remove_grains(std::span<const GlobalId> ids);
  // Gives a controlled mesh (one with a controller: a servo, or `controlled = true`) another
  // controller. Throws std::invalid_argument if wall `wall` is not such a mesh.
  void set_wall_controller(std::size_t wall, std::shared_ptr<WallController> controller);
  // The speed along its axis that a controlled mesh moved at in the last step, and how far it
  // has moved along it [length/time, length].
  std::pair<double, double> wall_servo_state(std::size_t wall) const;

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
  // The phases of a step: the half kick and drift (true if the list must be rebuilt), the
  // step's one collective (every rank learns whether any must rebuild), the rebuild or ghost
  // refresh, and the second half kick.
  bool kick_drift();
  bool agree_on_rebuild(bool rebuild_here);
  void exchange_or_rebuild(bool rebuild_now);
  void final_kick();
  // Walls to their prescribed place at t; true if one moved more than half the skin.
  // `every_one` false skips those of a motion at rest: placed before, they stay there.
  // `moved2`, if given, gets the largest squared displacement of a wall particle.
  bool place_walls(double t, bool every_one = false, double* moved2 = nullptr);
  // Meshes and cylinders to their place at t; true if a vertex or a cylinder moved more than
  // half the skin since the last list build (simulation_walls.cpp).
  bool place_shaped_walls(double t, bool every_one);
  // The grain-wall candidates of a list build, from the triangles binned on the cells.
  void list_wall_candidates();
  // Servo-controlled meshes: each controller is told the grains' force on its wall (summed
  // over the ranks: one reduction per step, only where such walls are) and sets the wall's
  // speed for the next step; the wall moves by it over that step.
  void steer_servo_walls();
  // The walls' part of a checkpoint: each mesh file's CRC-32 (a resume with another file is
  // refused), the time of the last list build (where the meshes stood), the work of each wall.
  template <class Archive> void checkpoint_walls(Archive& ar) {
    std::vector<std::uint32_t> crcs; // this scene's, replaced by the saved ones on loading
    for (const ShapedWall& w : walls_)
      crcs.push_back(std::holds_alternative<MeshWall>(w) ? std::get<MeshWall>(w).file_crc32 : 0);
    ar.vector(crcs);
    if constexpr (Archive::loading) check_wall_files(crcs);
    ar.value(walls_built_at_);
    ar.vector(wall_work_);
    if (!Archive::loading || loading_layout_ >= 6) ar.vector(plane_work_);
    plane_work_.resize(planes_.size(), 0.0);
    // Each mesh's servo: its offset and speed, and its offset at the last list build.
    const std::size_t per_mesh = Archive::loading && loading_layout_ < 7 ? 2 : 3;
    std::vector<double> servo;
    for (const ShapedWall& w : walls_)
      if (const auto* m = std::get_if<MeshWall>(&w))
        servo.insert(servo.end(), {m->servo_offset, m->servo_speed, m->servo_offset_built});
    ar.vector(servo);
    if constexpr (Archive::loading) {
      std::size_t k = 0;
      for (ShapedWall& w : walls_)
        if (auto* m = std::get_if<MeshWall>(&w)) {
          if (k + per_mesh > servo.size())
            throw std::invalid_argument("the checkpoint's walls are not this scene's");
          m->servo_offset = servo[k], m->servo_speed = servo[k + 1];
          m->servo_offset_built = per_mesh == 3 ? servo[k + 2] : servo[k];
          k += per_mesh;
        }
    }
    if constexpr (Archive::loading)
      if (wall_work_.size() != walls_.size())
        throw std::invalid_argument("the checkpoint's walls are not this scene's");
  }
  void check_wall_files(const std::vector<std::uint32_t>& saved) const;
  // The sources' part of a checkpoint: the next global id, each insert's name and progress
  // (the same on every rank) and each outlet's name and part on this rank. Loading matches
  // them by name: a scene's insert or outlet that the checkpoint does not name starts afresh,
  // and one the scene does not have is left behind (its grains stay).
  template <class Archive> void checkpoint_sources(Archive& ar) {
    if constexpr (Archive::loading)
      if (loading_layout_ < 6) return; // (none under way)
    ar.value(next_gid_);
    std::vector<std::string> insert_names, outlet_names;
    for (const InsertSpec& s : inserts_) insert_names.push_back(s.name);
    for (const OutletSpec& s : outlets_) outlet_names.push_back(s.name);
    std::vector<InsertProgress> inserts = insert_progress_;
    std::vector<OutletPart> outlets = outlet_part_;
    if (Archive::loading && loading_layout_ < 8) { // by position, unnamed
      std::vector<InsertProgressV6> old;
      ar.vector(old);
      ar.vector(outlets);
      inserts.assign(old.size(), InsertProgress{});
      for (std::size_t k = 0; k < old.size(); ++k)
        inserts[k].batches = old[k].batches, inserts[k].grains = old[k].grains,
        inserts[k].owed = old[k].owed, inserts[k].mass = old[k].mass;
      if (inserts.size() != inserts_.size()) inserts.clear(), insert_names.clear();
      if (outlets.size() != outlets_.size()) outlets.clear(), outlet_names.clear();
    } else {
      strings(ar, insert_names);
      ar.vector(inserts);
      strings(ar, outlet_names);
      ar.vector(outlets);
    }
    if constexpr (Archive::loading) {
      if (insert_names.size() != inserts.size() || outlet_names.size() != outlets.size())
        throw ArchiveError("the sources' names and states differ in number (corrupt)");
      adopt_sources(insert_names, inserts, outlet_names, outlets);
    }
  }
  template <class Archive> static void strings(Archive& ar, std::vector<std::string>& v) {
    std::uint64_t n = v.size();
    ar.value(n);
    if constexpr (Archive::loading) {
      if (n > (std::uint64_t{1} << 24)) throw ArchiveError("an impossible count of names");
      v.assign(n, std::string{});
    }
    for (std::string& s : v) ar.string(s);
  }
  // At a list build, after the escapes: grains in an outlet leave, a due batch is inserted.
  void handle_outlets();
  void insert_due_batches();
  bool insertion_due(std::int64_t step) const;
  void insert_batch(std::size_t source);
  // How a list build starts: in a step (the history stashed from the current list, balancing
  // when due); after loading a state, whose contact states are in the stash already and whose
  // cut planes are the saved ones (the run's next build balances as it would have); or after
  // loading one saved at any step, built from the positions of its last build (x, which the
  // build leaves in x_build as it found it: rebuild_after_load).
  // `edit`: a change between steps (simulation_edits.cpp), like a step's build but with no
  // balancing, no sources and no books left due.
  enum class BuildAfter { step, edit, load, load_at_last_build };
  void rebuild(BuildAfter after = BuildAfter::step);
  void migrate();
  void rebalance();
  void stop_together(const std::string& local_error) const;
  // `as_saved`: the state of as many ranks as saved it, continued bit for bit; otherwise
  // particles merged from other ranks' sections, given a new list.
  void rebuild_after_load(bool as_saved);
  // Runs `check` on every rank (an std::invalid_argument on any rank throws on all), then
  // applies `change` to this rank's particles in a list build (edit_), evaluates the forces
  // without advancing any spring, and books the change of energy. Collective.
  void edit_particles(const std::function<void()>& check, std::function<void()> change);
  // The indices of the owned grains of these global ids; throws std::invalid_argument naming
  // an id that is not one.
  std::vector<std::size_t> owned_grains(std::span<const GlobalId> ids) const;
  // load()'s parts on this rank: its own section, or the merge of its share.
  void load_own_section(const std::string& section);
  void merge_sections(const std::vector<std::string>& share);
  void validate_loaded_particles() const;
  // A branch's checks of the loaded particles against its scene (branch()).
  void check_branched_particles(const BranchCheck& check) const;
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
  // This rank's part of the energy books (their sums over the ranks are the books).
  EnergyBooks energy_parts() const;
  // Throws SimulationError if the books have gained energy (an unstable integration).
  void check_energy_books(const EnergyBooks& e) const;
  // Throws std::invalid_argument naming the first new grain that overlaps a particle this rank
  // owns, a new grain before it or a flat wall (add_grains()).
  void check_clear_of_particles(std::span<const ParticleSpec> grains) const;
  // Throws std::invalid_argument, naming `who`, where grains of `material` could touch a
  // material (a particle's of this rank, a wall's, their own) with no contact pair.
  void check_pairs_for(std::uint8_t material, const std::string& who) const;
  // Collective: sums and checks the books that a list build left due.
  void settle_energy_books();
  std::string describe_particle(std::size_t i) const;
  std::string describe_contacts(std::size_t i) const;
  // Where the wall contact that began deepest began (DeepStarts), for a diagnosis.
  std::string describe_deep_start(const DeepStarts& deep) const;
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
  std::vector<ShapedWall> walls_;
  std::vector<WallLoad> wall_loads_;         // this rank's, of the last force evaluation
  std::vector<ElementForce> element_forces_; // this rank's wall contacts, of the same
  std::vector<double> wall_work_;  // this rank's part of each shaped wall's cumulative work
  std::vector<double> plane_work_; // and of each flat wall's
  // Each mesh's triangles binned on the cells (CSR by cell), reused while a still mesh and the
  // cells stay as they were.
  struct MeshBins {
    std::vector<std::uint32_t> start, members;
    bool valid = false;
    double reach = 0.0;
    Vec3 origin;
    std::array<int, 3> dims{};
    // The box (the grains' grown by a cell edge) and the reach for which a mesh's held
    // triangles were chosen.
    Vec3 held_lo, held_hi;
    double held_reach = -1.0;
  };
  std::vector<MeshBins> mesh_bins_;
  // Each moving mesh's vertices (where a rank holds a part of it, the held vertices, then the
  // eight corners of its box), or moving cylinder's shift, at the last build.
  std::vector<std::vector<Vec3>> mesh_x_build_;
  double walls_built_at_ = 0.0; // time of the last list build
  AnyContactLaw law_;
  Forces forces_;
  ContactStates* history_;  // the contact states of forces_ (per-rebuild operations)
  std::size_t n_materials_; // of the contact law's table
  double cell_edge_ = 0.0;  // linked-cell edge >= largest contact distance + skin
  CellGrid grid_;
  double range_ = 0.0;           // neighbour range beyond touching (the skin)
  std::size_t owned_grains_ = 0; // owned particles [0, owned_grains_) are grains, the rest walls
  NeighborList list_;
  NearPairs near_;
  NearWallElements near_walls_;     // picked with near_ (sim/near_wall_elements.hpp)
  double moved2_ = 0.0;             // largest squared displacement of a particle this step
  double last_displacement_ = 0.0;  // largest displacement of a particle in the last step
  double position_round_off_ = 0.0; // bound on the round-off of one step's displacement
  bool walls_still_ = false;        // every wall particle at rest (place_walls)
  Halo halo_;
  ContactTally tally_;
  ContactRecord record_;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  // This rank's cumulative books: dissipated, wall work, removed energy and grains, and the
  // work of gravity along periodic axes (the other totals are of an instant: energy_parts()).
  EnergyBooks books_;
  double initial_balance_ = 0.0; // energy books at the start (blow-up diagnosis)
  double busy_at_balance_ = 0.0; // timers_.busy() at the last balancing
  std::int64_t rebuilds_ = 0;
  bool rebuild_requested_ = false;
  std::string health_error_; // this rank's diagnosis of the last force evaluation ("" if sound)
  // This rank's parts of the energy books at the last list build, until the next collective
  // sums and checks them (settle_energy_books).
  std::optional<EnergyBooks> books_due_;
  bool cuts_moved_ = false; // since the last list build (migrate() then checks for strays)
  // How checkpoint() loads: a whole state (rebuilt at once), one section whose rebuild load()
  // does once every rank has loaded, or one of several sections that load() merges (the cut
  // planes are set afresh).
  enum class Loading { whole, deferred, merged };
  Loading loading_ = Loading::whole;
  std::vector<InsertSpec> inserts_;
  std::vector<OutletSpec> outlets_;
  struct InsertProgress { // the same on every rank
    std::int64_t batches = 0, grains = 0, owed = 0;
    double mass = 0;
    // Set from outside the scene (start_insert, add_insert...): the step of the first batch of
    // the pouring under way (-1: the scene's start) and what was poured before it began; the
    // insert paused (1) or stopped (2).
    std::int64_t first_step = -1, grains_before = 0;
    double mass_before = 0;
    std::int64_t halted = 0;
    static constexpr int n_numbers = 8; // (the fields as numbers, for sums over sections)
  };
  struct InsertProgressV6 { // layouts 6 and 7
    std::int64_t batches = 0, grains = 0, owed = 0;
    double mass = 0;
  };
  struct OutletPart { // this rank's
    std::int64_t grains = 0;
    double mass = 0;
  };
  std::vector<InsertProgress> insert_progress_;
  std::vector<OutletPart> outlet_part_;
  // The steps of insert k's batches as they stand: its first batch, the steps between batches
  // and its last step.
  struct BatchSteps {
    std::int64_t first, every, last;
  };
  BatchSteps batch_steps(std::size_t k) const;
  bool batch_due(std::size_t k, std::int64_t step) const;
  // Takes the saved sources' state by name: each insert and outlet of this scene takes the
  // saved one of its name, and starts afresh where none has it (checkpoint_sources()).
  void adopt_sources(const std::vector<std::string>& insert_names,
                     const std::vector<InsertProgress>& inserts,
                     const std::vector<std::string>& outlet_names,
                     const std::vector<OutletPart>& outlets);
  GlobalId next_gid_ = 0;      // of the next inserted grain (the same on every rank)
  std::function<void()> edit_; // the change of edit_particles(), made in its list build
  // While branch() loads: the state continues under another scene (what it must hold).
  std::optional<BranchCheck> branch_;
  std::uint32_t loading_layout_ = state_layout; // of the state load() takes
  PhaseTimes timers_;
};

} // namespace yuxi
