// The sources and sinks of a simulation, one part of it: grains poured in while the run goes on
// ([[insert]]) and taken out ([[outlet]]; scene/particle_source.hpp), each one's progress, and
// the counter of global ids for new grains. Both happen at list builds, where particles may be
// added and removed: a batch due forces a list build at its step. The part saves its section
// of a checkpoint; loading matches inserts and outlets with the saved ones by name.
#pragma once

#include "core/archive.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "domain/decomposition.hpp"
#include "scene/particle_source.hpp"
#include "scene/plane_wall.hpp"
#include "sim/clump_bodies.hpp"
#include "sim/simulation_config.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace yuxi {

class Sources {
public:
  // Each insert's or outlet's cumulative grains and mass.
  struct Tally {
    std::string name;
    std::int64_t grains = 0; // cumulative
    double mass = 0;         // cumulative
    std::int64_t owed = 0;   // grains due but not placed yet (inserts: no free place found)
  };

  // The scene's sources (before the first step, or before a checkpoint is loaded). Held
  // inserts wait for start_insert().
  void set(std::vector<InsertSpec> inserts, std::vector<OutletSpec> outlets);
  const std::vector<InsertSpec>& inserts() const { return inserts_; }
  bool has_outlets() const { return !outlets_.empty(); }

  // The id of the next new grain (the same on every rank); ids taken from it.
  GlobalId next_id() const { return next_gid_; }
  GlobalId take_id() { return next_gid_++; }
  // No id below `next` is given out (the particles present, or a saved run's).
  void ids_from(GlobalId next) { next_gid_ = std::max(next_gid_, next); }

  // Whether any insert pours a batch at this step (every rank answers the same).
  bool insertion_due(std::int64_t step, double dt) const;

  // What a batch or an outlet changes, beside the particles: the energy books.
  struct Books {
    double& inserted; // the new grains' mechanical energy
    double& removed;  // the leaving grains'
  };
  // Inserts every batch due at this step into `s` (each rank keeps the grains it owns), the
  // bodies of clumps poured into `clumps`: the same candidates and choices on every rank.
  // Collective (one reduction per batch).
  void insert_due_batches(ParticleStore& s, ClumpBodies& clumps, const SimulationConfig& config,
                          const Decomposition& decomp, const Comm& comm,
                          const std::vector<PlaneWall>& planes, double t, std::int64_t step,
                          Books books);
  // Takes out the grains whose centre is in an outlet, and the clumps whose centre of mass is
  // (whole, members and body), their mechanical energy booked as removed; a clump counts as one
  // grain in the outlet's tally.
  void drain_outlets(ParticleStore& s, ClumpBodies& clumps, const Box& box, const Vec3& g_potential,
                     Books books);

  // An insert's pouring steered from outside the scene (the Python API), by the insert's index,
  // at step `step` of a run of time step `dt`. start: it pours from the next step on, at its
  // rate, until its total (or the scene's end); what it poured before counts towards the total.
  // pause: no batch until started again. stop: no batch ever again. Each throws
  // std::invalid_argument where the insert cannot (a stopped insert started, an insert whose
  // total is poured or whose end has passed).
  void start_insert(std::size_t insert, std::int64_t step, double dt);
  void pause_insert(std::size_t insert);
  void stop_insert(std::size_t insert);
  // A new insert from the next step on (at its start, if that is later); its name must be new
  // (the caller has checked its grains against the cells and the contact pairs).
  void add_insert(InsertSpec insert, std::int64_t step, double dt);
  // Takes back the insert added last, before it poured (a check of it failed).
  void withdraw_last_insert();
  // Throws std::invalid_argument where an insert of this name exists.
  void check_new_name(const std::string& name) const;

  std::vector<Tally> inflow() const;
  // Summed over the ranks. Collective.
  std::vector<Tally> outflow(const Comm& comm) const;

  // The sources' section of a checkpoint: the next global id, each insert's name and progress
  // (the same on every rank) and each outlet's name and part on this rank; from layout 11 each
  // insert's owed grains (their sizes and velocities; before it, owed grains are drawn afresh).
  // Loading matches them by name: a scene's insert or outlet that the checkpoint does not name
  // starts afresh, and one the scene does not have is left behind (its grains stay). Layouts before
  // 6 hold no section (nothing was under way); 6 and 7 hold the states by position, unnamed.
  void save(ArchiveWriter& ar) const;
  void load(ArchiveReader& ar, std::uint32_t layout);

  // Several ranks' sections loaded in turn onto one rank: the outlets' parts summed (add the
  // part of each section after loading it), and the inserts' progress and the next id, the
  // same in every section, agreed over the ranks from those that loaded one. Collective.
  struct OutletParts {
    std::vector<std::int64_t> grains;
    std::vector<double> mass;
  };
  void add_outlet_parts(OutletParts& sum) const;
  void set_outlet_parts(const OutletParts& sum);
  void agree_over(const Comm& comm, bool loaded);

private:
  struct InsertProgress { // the same on every rank
    std::int64_t batches = 0, grains = 0, owed = 0;
    double mass = 0;
    // Set from outside the scene (start_insert, add_insert...): the step of the first batch of
    // the pouring under way (-1: the scene's start) and what was poured before it began; the
    // insert paused (1) or stopped (2).
    std::int64_t first_step = -1, grains_before = 0;
    double mass_before = 0;
    std::int64_t halted = 0;
    static constexpr int n_numbers = 8; // (the fields as numbers, for agree_over)
  };
  struct InsertProgressV6 { // layouts 6 and 7
    std::int64_t batches = 0, grains = 0, owed = 0;
    double mass = 0;
  };
  // A grain drawn for a batch that found no place: it is owed to the next batch with the size
  // and velocity it was drawn with (drawn afresh, the grains that fail, the larger ones where
  // the region is crowded, would be replaced by an unbiased draw, and the poured sizes would
  // drift small).
  struct OwedGrain {
    double radius = 0;
    Vec3 velocity;
  };
  struct OutletPart { // this rank's
    std::int64_t grains = 0;
    double mass = 0;
  };
  // The steps of insert k's batches as they stand: its first batch, the steps between batches
  // and its last step.
  struct BatchSteps {
    std::int64_t first, every, last;
  };
  BatchSteps batch_steps(std::size_t k, double dt) const;
  bool batch_due(std::size_t k, std::int64_t step, double dt) const;
  void insert_batch(std::size_t k, ParticleStore& s, ClumpBodies& clumps,
                    const SimulationConfig& config, const Decomposition& decomp, const Comm& comm,
                    const std::vector<PlaneWall>& planes, double t, std::int64_t step, Books books);
  // Takes the saved sources' state by name: each insert and outlet of this scene takes the
  // saved one of its name, and starts afresh where none has it.
  void adopt(const std::vector<std::string>& insert_names,
             const std::vector<InsertProgress>& inserts,
             const std::vector<std::vector<OwedGrain>>& owed,
             const std::vector<std::string>& outlet_names, const std::vector<OutletPart>& outlets);

  // Each insert's owed grains in an archive (a checkpoint's section, the ranks' agreement), and
  // back for `inserts` inserts; throws ArchiveError where a grain is impossible.
  void write_owed(ArchiveWriter& ar) const;
  static std::vector<std::vector<OwedGrain>> read_owed(ArchiveReader& ar, std::size_t inserts);

  std::vector<InsertSpec> inserts_;
  std::vector<OutletSpec> outlets_;
  std::vector<InsertProgress> insert_progress_;
  std::vector<std::vector<OwedGrain>> owed_grains_; // each insert's, in the order drawn
  std::vector<OutletPart> outlet_part_;
  GlobalId next_gid_ = 0; // of the next new grain (the same on every rank)
};

} // namespace yuxi
