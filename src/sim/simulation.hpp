// A DEM simulation: the particle store, time and step counters, and the parts that own the
// rest (docs/ARCHITECTURE.md, "The engine's parts"):
//   exchange   the ranks, cut planes, ghosts and linked cells          (sim/exchange.hpp)
//   search     the neighbour list, near pairs, displacement tracking   (sim/neighbor_search.hpp)
//   contacts   the contact law, pair loop, contact history, tallies    (sim/contact_compute.hpp)
//   walls      wall particles' motions, planes, shaped walls           (sim/walls.hpp)
//   sources    inserts, outlets, the id counter                        (sim/sources.hpp)
//   ledger     the energy books and health errors                      (sim/energy_ledger.hpp)
//   clumps     the rigid bodies of clumps of spheres                    (sim/clump_bodies.hpp)
// It advances them with velocity Verlet (Allen & Tildesley 3.2.1; rotation likewise for
// spheres, whose inertia tensor is isotropic; NO_SQUISH for the orientation of clumps). One
// step, phase by phase (see step()):
//   1. kick_drift(): half kick and drift of grains and clumps, the clumps' members placed;
//      walls placed at t + dt by their motion
//   2. agree_on_list_build(): the step's one collective (list build due anywhere, health,
//      displacement)
//   3. build_lists() if due (history stashed by global ids, escapes, sources, periodic wrap,
//      migration, particles sorted by cell, ghosts, lists, history restored:
//      simulation_list_build.cpp), else ghosts refreshed
//   4. compute_forces(): gravity, contacts with other particles and walls; ghost forces summed
//      back; the members' forces added onto their clumps
//   5. final_kick(): second half kick; the walls' work booked, servos steered
// Saving and loading the state (checkpoints, resuming on any number of ranks) is in
// simulation_state.cpp, changes from outside between steps in simulation_edits.cpp.
#pragma once

#include "contact/contact_model.hpp"
#include "core/archive.hpp"
#include "core/box.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "scene/particle_source.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "scene/wall_motion.hpp"
#include "sim/clump_bodies.hpp"
#include "sim/contact_compute.hpp"
#include "sim/energy_ledger.hpp"
#include "sim/engine_state.hpp"
#include "sim/exchange.hpp"
#include "sim/neighbor_search.hpp"
#include "sim/phase_times.hpp"
#include "sim/simulation_config.hpp"
#include "sim/simulation_error.hpp"
#include "sim/sources.hpp"
#include "sim/state_layout.hpp"
#include "sim/walls.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace yuxi {

// The contact that limits the time step.
struct StiffestContact {
  double contact_time = 0; // t_c [time]
  std::uint8_t material_a = 0, material_b = 0;
  double m_eff = 0;
  bool depends_on_speed = false; // t_c depends on the impact speed (Hertzian laws)
};

// This rank's share of a checkpoint's state sections (Simulation::save_state of each rank of
// the run that wrote it, which had `written_on` ranks; the share is a block of consecutive
// ones), in state layout `layout` (sim/state_layout.hpp).
struct SavedState {
  std::vector<std::string> share;
  std::uint64_t written_on = 0;
  std::uint32_t layout = state_layout;
};

// What a scene sets besides its particles: the settings, the planes, the wall particles'
// motions, the contact law, the shaped walls (triangle meshes and cylinders) and the sources.
// A state continued from a checkpoint brings the particles.
struct SimulationFrame {
  SimulationConfig config;
  std::vector<PlaneWall> planes;
  std::vector<WallMotion> motions;
  AnyContactLaw law;
  std::vector<ShapedWall> shaped_walls;
  std::vector<InsertSpec> inserts;
  std::vector<OutletSpec> outlets;
  // The scene's [[shape]] names, in order: a clump's `shape` indexes them (a state continued
  // under this frame has its clumps' shapes found again by name).
  std::vector<std::string> shape_names;
};

class Simulation {
public:
  // A state continued under another scene (a branch: `yuxi run SCENE --from CHECKPOINT`).
  struct BranchCheck {
    std::size_t walls = 0; // the wall particles this scene builds
    bool keep_history = true;
  };

  // Every rank is given all particles; each keeps those of its sub-domain. `comm` is the group
  // of ranks that share the simulation (a group of one: serial).
  // `shaped_walls`: the triangle meshes and cylinders (every rank is given all of them).
  // `clumps`: the bodies of the clumps whose members are among `particles` (make_clump(),
  // sim/clump_bodies.hpp); clumps run on one rank for now (std::invalid_argument on more).
  Simulation(SimulationConfig config, ParticleStore particles, std::vector<PlaneWall> planes,
             std::vector<WallMotion> motions, AnyContactLaw law, Comm comm = Comm::world(),
             std::vector<ShapedWall> shaped_walls = {}, std::vector<ClumpBody> clumps = {});
  // Collective: a checkpoint's state continued under `frame`, built straight from it (no
  // initial state of the scene is made first). Without `branch`, a resume (see load()): the
  // state's cells, skin and, on as many ranks, cut planes are the saved run's. With `branch`, the
  // state continues under this scene's law, motions, gravity, time step and outputs: the shares
  // load as on another number of ranks (cells sized for the saved particles and this scene's
  // skin, cut planes by particle count, a new list from the current positions), the walls are
  // placed at the saved time by this scene's motions, and the forces are evaluated afresh
  // without advancing any spring; the change of mechanical energy that the new scene gives the
  // same state is booked as `inserted`, so the books carry on closed. `keep_history` false drops
  // every contact's state (another contact model). Throws std::invalid_argument on every rank
  // where a section does not load or fit the frame, where the saved wall particles are not the
  // `walls` a branch's scene builds, or where a branched grain stands outside the domain.
  Simulation(SimulationFrame frame, const SavedState& saved, Comm comm = Comm::world(),
             std::optional<BranchCheck> branch = std::nullopt);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void step();
  void run(std::int64_t n_steps) {
    for (std::int64_t k = 0; k < n_steps; ++k) step();
  }

  double time() const { return time_; }
  std::int64_t step_count() const { return step_; }
  const SimulationConfig& config() const { return config_; }
  // This rank's particles (all of them when serial).
  const ParticleStore& particles() const { return store_; }
  // The clumps' bodies (their members are among the particles).
  const std::vector<ClumpBody>& clumps() const { return clumps_.bodies(); }
  // The names of the shapes that the clumps' `shape` indexes (the scene's [[shape]] tables, in
  // order). Name them before a state is loaded: a checkpoint keeps the names its clumps' shapes
  // had, and a state loaded under other names (a branch into another scene) has each clump's
  // shape found again by its name, -1 where the names lack it.
  void name_shapes(std::vector<std::string> names) { shape_names_ = std::move(names); }
  const std::vector<std::string>& shape_names() const { return shape_names_; }
  // Every rank's owned particles, sorted by global id, on rank 0 (empty elsewhere). Collective.
  ParticleStore gather_particles() const;
  const Comm& comm() const { return exchange_.comm(); }
  const Decomposition& decomposition() const { return exchange_.decomposition(); }
  // Owned particles per rank, max over mean (1 when serial). Collective.
  double imbalance() const;
  const std::vector<PlaneWall>& planes() const { return walls_.planes(); }
  // The wall particles' motions (scene/wall_motion.hpp) and the contact law with its
  // coefficients per material pair: what another engine (the device engine) needs to run on.
  const std::vector<WallMotion>& wall_motions() const { return walls_.motions(); }
  const AnyContactLaw& contact_law() const { return contacts_.law(); }
  bool has_outlets() const { return sources_.has_outlets(); }
  // The meshes (placed at the current time) and cylinders.
  const std::vector<ShapedWall>& shaped_walls() const { return walls_.shaped(); }
  // What the grains did to each shaped wall at the last force evaluation, and each wall's
  // cumulative work on the grains (in `work`), summed over the ranks onto every rank.
  // Collective.
  std::vector<WallLoad> shaped_wall_loads() const { return walls_.shaped_loads(comm()); }
  // The same for the planes (the scene's, then the box's faces; torque zero). Collective.
  std::vector<WallLoad> plane_loads() const {
    return walls_.plane_loads(comm(), contacts_.plane_loads());
  }
  // The force on each triangle of mesh `shaped_wall` at the last force evaluation, summed over
  // the ranks onto every rank (zero where nothing touches). Collective.
  std::vector<Vec3> triangle_forces(std::size_t shaped_wall) const {
    return walls_.triangle_forces(comm(), shaped_wall);
  }
  const NeighborList& neighbor_list() const { return search_.list(); }
  const Halo& halo() const { return exchange_.halo(); }
  // The pairs the last force evaluation scanned, where they held (core/near_pairs.hpp).
  const NearPairs& near_pairs() const { return search_.near_pairs(); }
  // The meshes' near triangles picked with them (sim/near_wall_elements.hpp).
  const NearWallElements& near_wall_elements() const { return search_.near_wall_elements(); }
  const CellGrid& grid() const { return exchange_.grid(); }
  // The energy books, summed over the ranks. Collective.
  EnergyBooks energies() const;
  const ContactTally& last_tally() const { return contacts_.tally(); }
  // True where books `e` (of this run: this simulation's or another engine's running it) gained
  // energy that nothing put in: the check that stops an unstable run.
  bool books_unstable(const EnergyBooks& e) const { return ledger_.unstable_gain(e).has_value(); }
  // This rank's cumulative books (inserted, removed, dissipated, ...), and the same put back:
  // an edit taken back whole (grains added, then removed again) leaves the books as it found
  // them, not with the energy booked in and out.
  EnergyBooks cumulative_books() const { return ledger_.books(); }
  void put_back_books(const EnergyBooks& books) { ledger_.books() = books; }
  // Records every contact's force and stored energy at each force evaluation (costs memory
  // and time; for stress and per-grain energy analyses). Aligned with neighbor_list().
  void record_contacts(bool on) { contacts_.record_contacts(on); }
  const ContactRecord& contact_record() const { return contacts_.record(); }
  // Every contact's state under the scene's model (aligned with neighbor_list()).
  const ContactStates& contact_states() const { return contacts_.history(); }
  // J w^2 / 2 of owned particle i (0 when its rotation is locked).
  double rotational_energy(std::size_t i) const { return yuxi::rotational_energy(store_, i); }
  // Bytes of this rank's simulation data: particles (with ghosts), cells, neighbour list,
  // contact states; the libraries and the scene's input are not counted.
  std::size_t memory_bytes() const;
  const PhaseTimes& timers() const { return timers_; }
  // List builds since the start of the run (the saved run's included).
  std::int64_t list_builds() const { return list_builds_; }
  // The contact of the shortest duration t_c among the materials present: grains (those inserts
  // will pour included) with each other and with wall particles, planes and shaped walls,
  // meeting at `impact_speed` where the law's t_c depends on it (run/impact_speed.hpp).
  // Collective.
  StiffestContact stiffest_contact(double impact_speed) const;

  // Saves the whole dynamic state of this rank (its section of a checkpoint): time, step,
  // particles in the order of the last list build (with where each stood then, x_build),
  // contact history, the last forces and energy tally, the energy books, the walls' and the
  // sources' state, the cut planes. Save after any step: a run continued from the state goes
  // on bit for bit, and saving changes nothing in the run that saves.
  void save_state(ArchiveWriter& ar) const;

  // Collective: continues from a checkpoint's state, in place of this simulation's (the
  // constructor from a SavedState does the same without building a state first). The cells and
  // the skin are the saved run's (a state of layout 8 or older: sized for its particles). On as
  // many ranks as wrote it, each rank's share is its own section: the list of the run's last
  // build is made again, and the run continues bit for bit. On another number, each rank loads its
  // block, the cut planes are set afresh by particle count, and the particles go to their new
  // owners with copies of their contacts' states (the migration of a list build, repeated until
  // none is left astray); the energy books are summed onto rank 0. A correct continuation, not a
  // bitwise one (the summation order changes with the decomposition). The stored forces are kept
  // (they were computed with the half-step velocities) and none is computed. A section that does
  // not load or does not fit the scene throws std::invalid_argument on every rank.
  void load(const SavedState& saved);

  // Continues from the state of a run that another engine advanced from this one's (the device
  // engine: run/device_stepper.hpp). The particles, contacts and books become `state`'s, and the
  // list of that engine's last build is made again, as a checkpoint's is: outputs and
  // checkpoints then see that state, and a checkpoint saved now continues it on either engine.
  // Only in one process; a particle of `state` that is not here throws std::invalid_argument.
  // Books that gained energy nothing put in throw SimulationError with the diagnosis, as the CPU
  // engine's own check does.
  void take_engine_state(const EngineState& state);

  // Sources and sinks of grains while the run goes on ([[insert]], [[outlet]]; the scene
  // builder sets them before the first step, and before a checkpoint is loaded). Insertions
  // happen at list builds (a batch due forces one); grains that an outlet holds leave at the
  // next list build, their mechanical energy booked as removed, as escaped grains'.
  // An insert of a clump shape pours clumps; an outlet takes a clump whole once its centre of
  // mass enters. Collective.
  void set_sources(std::vector<InsertSpec> inserts, std::vector<OutletSpec> outlets);
  using SourceTally = Sources::Tally;
  // Each insert's cumulative grains and mass, and each outlet's (collective).
  std::vector<SourceTally> inflow() const { return sources_.inflow(); }
  std::vector<SourceTally> outflow() const { return sources_.outflow(comm()); }
  // An insert's pouring steered from outside the scene (the Python API), by the insert's index
  // (Sources::start_insert). The same call on every rank. A checkpoint keeps the state, and a
  // resume or a branch continues it.
  void start_insert(std::size_t insert) { sources_.start_insert(insert, step_, config_.dt); }
  void pause_insert(std::size_t insert) { sources_.pause_insert(insert); }
  void stop_insert(std::size_t insert) { sources_.stop_insert(insert); }
  // A new insert from the next step on (at its start, if that is later); its name must be new.
  // Collective.
  void add_insert(InsertSpec insert);
  // Takes back the insert added last, before any step (a check of it failed: the time step).
  void withdraw_last_insert() {
    sources_.withdraw_last_insert();
    update_clump_reach();
  }
  const std::vector<InsertSpec>& inserts() const { return sources_.inserts(); }

  // Counts the changes made from outside the equations of motion (the edits below, and load()):
  // another engine that runs this simulation's state starts again from it where they changed.
  std::uint64_t edits() const { return edits_; }

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
  // a plane.
  std::vector<GlobalId> add_grains(std::span<const ParticleSpec> grains);
  // Removes the grains of these ids that this rank owns (others are passed over); returns how
  // many went on all ranks. Collective.
  std::int64_t remove_grains(std::span<const GlobalId> ids);
  // Clumps, by their ids (a clump's id is its member 0's, ClumpBody::id; simulation_clump_edits
  // .cpp). Velocities and angular velocities (lab frame) of clumps this rank owns (an id that is
  // not such a clump throws std::invalid_argument naming it); the members move with them.
  // Nothing else changes.
  void set_clump_velocities(std::span<const GlobalId> ids, std::span<const Vec3> v);
  void set_clump_angular_velocities(std::span<const GlobalId> ids, std::span<const Vec3> w);
  // Centres of mass `x` of clumps this rank owns and, where `q` is not empty, their orientations
  // (unit quaternions, the principal frame onto the lab's, one a clump); each keeps its velocity
  // and its angular velocity in the lab frame, and its members are placed anew. Collective, as
  // set_positions().
  void set_clump_poses(std::span<const GlobalId> ids, std::span<const Vec3> x,
                       std::span<const Quaternion> q);
  // New clumps (make_clump(), made with any first id: each takes its ids from the counter of
  // inserted grains, member k id + k), the same list on every rank, each kept by the rank of its
  // anchor member; returns their ids. Collective. Throws std::invalid_argument, adding none,
  // where a member overlaps a particle, a member of a new clump before it or a plane.
  std::vector<GlobalId> add_clumps(std::vector<PlacedClump> clumps);
  // Removes the clumps of these ids that this rank owns, whole (the ids of other ranks' clumps
  // are passed over; a free grain's or a member's other than member 0 throws); returns how many
  // went on all ranks. Collective.
  std::int64_t remove_clumps(std::span<const GlobalId> ids);
  // Gives a controlled mesh (one with a controller: a servo, or `controlled = true`) another
  // controller. Throws std::invalid_argument if shaped wall `shaped_wall` is not such a mesh.
  void set_servo_controller(std::size_t shaped_wall, std::shared_ptr<WallController> controller) {
    walls_.set_controller(shaped_wall, std::move(controller));
  }
  // The speed along its axis that a controlled mesh moved at in the last step, and how far it
  // has moved along it [length/time, length].
  std::pair<double, double> servo_state(std::size_t shaped_wall) const {
    return walls_.servo_state(shaped_wall);
  }

  // Makes the next step build the lists (and re-sort particles) whatever the skin criterion
  // says; the trajectory must not change.
  void request_list_build() { list_build_requested_ = true; }
  // Collective: throws SimulationError on every rank if the last force evaluation on any rank
  // found an overlap beyond the limit (a step finds out at its next collective; a checkpoint
  // must not keep such a state). It also checks the energy books of the last list build, if
  // still due.
  void stop_if_unhealthy() {
    stop_if_unhealthy_together();
    settle_energy_books();
  }

  // Setup access: changes to particles must be followed by refresh(), before the first step.
  ParticleStore& particles_mutable() { return store_; }
  // Builds the lists and evaluates forces for the current state. Evaluating contacts advances
  // their history (tangential springs), so call it only after changing particles by hand.
  // Collective.
  void refresh();

private:
  // How a list build is made: in a step (the history stashed from the current list, escapes,
  // sources, balancing when due); for a change between steps (`edit`, made once the history
  // is stashed: no balancing, no sources, no books left due); after loading a state, whose
  // contact states are in the stash already and whose cut planes are the saved ones; or after
  // loading one saved at any step, built from the positions of its last build (x, which the
  // build leaves in x_build as it found it).
  struct ListBuildPlan {
    enum class After { step, edit, load, load_at_last_build } after = After::step;
    const std::function<void()>* edit = nullptr;
  };
  // How a state section is read: in layout `layout`; `keep_history` false drops the contacts'
  // states (a branch under another model).
  struct SectionPlan {
    std::uint32_t layout = state_layout;
    bool keep_history = true;
  };

  // The phases of a step (see the top of this file).
  struct Drift {
    bool list_build_due = false;
    double moved2 = 0.0; // largest squared displacement of a particle in the step
  };
  Drift kick_drift();
  bool agree_on_list_build(const Drift& drift);
  void exchange_or_build_lists(bool build_now);
  void final_kick();
  void book_step();

  void build_lists(const ListBuildPlan& plan);
  // Whether members standing outside their owner's sub-domain need the ghosts to reach
  // farther: on several ranks, or along a periodic axis (a clump stays whole across it).
  bool ghosts_reach_for_clumps() const;
  // Collective, where ghosts_reach_for_clumps(): the clumps' reach (Exchange::set_clump_reach)
  // from the scene's, the clumps' here and the inserts'.
  void update_clump_reach();
  // Refuses a clump (`what`) wider than the box along a periodic axis: its members would meet
  // their own periodic images, and the members of one clump never touch (ClumpBody::span).
  void check_clump_span(double span, const std::string& what) const;
  // The box that a clump's centre (with its members) is wrapped into: periodic only along axes
  // that one rank spans (across ranks the migration shifts them).
  Box member_wrap_box() const;
  // Evaluates all forces; `advance_history` false for a setup pass (no time elapses, so no
  // spring is incremented and nothing is dissipated).
  void start_forces_from_gravity();
  void compute_forces(bool advance_history = true);
  // Notes (in the ledger) an overlap beyond max_overlap_ratio; the next collective stops every
  // rank with it.
  void check_health();
  void handle_escapes();
  void handle_escapes_here();
  void stop_together(const std::string& local_error) const;
  // stop_together() with the health error of the last force evaluation, an overlap's cause
  // added (collective).
  void stop_if_unhealthy_together() const;

  // What a section says of the cells: the cut planes, and (layout 9 on) the cells' edge and
  // the skin; `edge` 0 where it does not say.
  struct SavedCells {
    std::array<std::vector<double>, 3> cuts;
    double edge = 0.0, skin = 0.0;
  };
  // Reads one state section into the parts (no list build, no collective).
  SavedCells read_section(ArchiveReader& ar, const SectionPlan& plan);
  SavedCells read_own_section(const std::string& section, std::uint32_t layout);
  SavedCells merge_sections(const std::vector<std::string>& share, const SectionPlan& plan);
  void validate_loaded_particles() const;
  // Collective: the ranks laid out and the cells sized for the state just read, as the saved
  // run had them (`own`) or afresh for this run (`cells.edge` 0: for the particles loaded).
  void lay_out_for_loaded(const SavedCells& cells, bool own);
  void check_branched_particles(const BranchCheck& check) const;
  // The constructor from a SavedState and load(): the sections read, the ranks laid out, the
  // scalars agreed, the lists built; a branch's forces evaluated and the change booked.
  void continue_from(const SavedState& saved, const BranchCheck* branch);
  void evaluate_branched_forces();
  // `as_saved`: the state of as many ranks as saved it, continued bit for bit; otherwise
  // particles merged from other ranks' sections, given a new list.
  void build_lists_after_load(bool as_saved);
  // The clumps' motion and loads from another engine's state (take_engine_state); the clumps it
  // lacks (removed on escape) leave.
  void take_clump_motion(const std::vector<EngineState::ClumpMotion>& motion);

  // Runs `check` on every rank (an std::invalid_argument on any rank throws on all), then
  // applies `change` to this rank's particles in a list build, evaluates the forces without
  // advancing any spring, and books the change of energy. Collective.
  void edit_particles(const std::function<void()>& check, const std::function<void()>& change);
  // The indices of the owned grains of these global ids; throws std::invalid_argument naming
  // an id that is not one.
  std::vector<std::size_t> grain_indices(std::span<const GlobalId> ids) const;
  // Throws std::invalid_argument naming the first new grain that overlaps a particle this rank
  // owns, a new grain before it or a plane (add_grains()). With `clump_of` (one entry a grain:
  // the index of the new clump it is a member of, ascending), the grains are the new clumps'
  // members, named as such, and a clump's members may overlap one another (add_clumps()).
  void check_clear_of_particles(std::span<const ParticleSpec> grains,
                                std::span<const std::size_t> clump_of = {}) const;
  // The indices in clumps_ of the clumps of these ids that this rank owns; throws
  // std::invalid_argument naming an id that is a particle here but no clump's, and, unless
  // `others_passed`, an id that is no clump here.
  std::vector<std::size_t> clump_indices(std::span<const GlobalId> ids, bool others_passed) const;
  // add_clumps()'s edit: the checks on every rank, then the clumps in the list build.
  void add_clumps_in_edit(std::vector<PlacedClump>& clumps, std::span<const ParticleSpec> members,
                          std::span<const std::size_t> clump_of);
  // Writes `values` into the clumps of `ids` by `write` (a velocity, an angular velocity),
  // booking the change of their energy, and places their members' velocities.
  void set_clump_motions(std::span<const GlobalId> ids, std::span<const Vec3> values,
                         const char* what,
                         const std::function<void(ClumpBody&, const Vec3&)>& write);
  // Throws std::invalid_argument, naming `who`, where grains of `material` could touch a
  // material (a particle's of this rank, a wall's, their own) with no contact pair.
  void check_pairs_for(std::uint8_t material, const std::string& who) const;

  // This rank's part of the energy books (their sums over the ranks are the books).
  EnergyBooks energy_parts() const;
  // Collective: sums and checks the books that a list build left due.
  void settle_energy_books();
  // Throws SimulationError if the books have gained energy (an unstable integration).
  void check_energy_books(const EnergyBooks& e) const;
  std::string describe_particle(std::size_t i) const;
  std::string describe_contacts(std::size_t i) const;

  SimulationConfig config_;
  ParticleStore store_;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  std::int64_t list_builds_ = 0;
  // Owned particles [0, n_grains_) are free grains, [n_grains_, n_movers_) members of clumps,
  // the rest wall particles.
  std::size_t n_grains_ = 0, n_movers_ = 0;
  bool list_build_requested_ = false;
  PhaseTimes timers_;
  Exchange exchange_;
  NeighborSearch search_;
  ContactCompute contacts_;
  std::uint64_t edits_ = 0; // edits(): changes from outside the equations of motion
  Walls walls_;
  Sources sources_;
  EnergyLedger ledger_;
  ClumpBodies clumps_;
  std::vector<std::string> shape_names_;
  // The speed of the grain of the deepest overlap where it went beyond the limit, else -1.
  double overlap_speed_ = -1.0;
};

} // namespace yuxi
