// Turns a validated Scene into a ready Simulation, from its start or continuing a saved state,
// and checks the time step against the contact time of the stiffest contact.
#pragma once

#include "io/scene.hpp"
#include "io/scene_error.hpp"
#include "run/impact_speed.hpp"
#include "sim/simulation.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace yuxi {

struct BuildReport {
  std::size_t walls = 0, grains = 0;
  std::size_t filled = 0; // the particles (grains or walls) the [[fill]] tables placed
  ImpactSpeed impact;     // the speed at which the time-step check lets grains meet
  StiffestContact stiffest;
  double dt_over_tc = 0.0;
  std::vector<std::string> warnings; // for the log: what the scene does that may be a mistake
};

// Where the stiffest contact's t_c depends on the impact speed, ", meeting at V: why" (for
// the time-step messages); else "".
std::string speed_note(const BuildReport& r);

// Throws TimeStepError if dt > t_c / 10 for the stiffest contact, unless the scene sets
// run.allow_large_dt or `force_dt` is given; SceneError for another fault of the scene.
// `comm`: the ranks that share the simulation (all of them by default).
std::unique_ptr<Simulation> build_simulation(const Scene& scene, bool force_dt,
                                             BuildReport* report = nullptr,
                                             Comm comm = Comm::world());

// The scene without its particles: what a checkpoint's state continues under.
SimulationFrame scene_frame(const Scene& scene);
// How many wall particles the scene builds (the basin's, those of [[particle]] and the wall
// fills'), for a branch's check of the walls it continues.
std::size_t scene_wall_particles(const Scene& scene);

// Collective: `saved` continued under `scene`, built straight from the state (the scene's
// initial particles are never made): as a resume, or with `branch` as a branch
// (Simulation's constructor from a SavedState). `report` counts the state's particles; the
// time step is checked against them as build_simulation() does. Throws std::invalid_argument on
// every rank where the state does not load or fit, TimeStepError or SceneError as
// build_simulation().
std::unique_ptr<Simulation> continue_simulation(const Scene& scene, const SavedState& saved,
                                                std::optional<Simulation::BranchCheck> branch,
                                                bool force_dt, BuildReport* report = nullptr,
                                                Comm comm = Comm::world());

// The time-step check against the grains `sim` holds now (a branch's, once loaded), at the
// impact speed in `report`; fills in its stiffest contact. Collective.
void check_time_step(const Scene& scene, const Simulation& sim, bool force_dt, BuildReport& report);
// The same for a simulation under way (collective): the impact speed of its grains and of what
// its inserts pour, over every rank, then check_time_step. A run continued from a state, or one
// given another insert, is checked as a scene is at its start.
void check_running_time_step(const Scene& scene, const Simulation& sim, bool force_dt,
                             BuildReport& report);

} // namespace yuxi
