// Turns a validated Scene into a ready Simulation, and checks the time step against the
// contact time of the stiffest contact.
#pragma once

#include "io/scene.hpp"
#include "io/scene_error.hpp"
#include "run/impact_speed.hpp"
#include "sim/simulation.hpp"

#include <memory>
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

// The time-step check against the grains `sim` holds now (a branch's, once loaded), at the
// impact speed in `report`; fills in its stiffest contact. Collective.
void check_time_step(const Scene& scene, const Simulation& sim, bool force_dt, BuildReport& report);

} // namespace yuxi
