// The state of a run that another engine advanced (the device engine, in one process), as the
// simulation takes it back (Simulation::take_engine_state) for its outputs and checkpoints.
#pragma once

#include "core/particle_fields.hpp"
#include "core/quaternion.hpp"
#include "core/vec3.hpp"
#include "sim/contact_tally.hpp"
#include "sim/energy_books.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace yuxi {

struct EngineState {
  double time = 0.0;
  std::int64_t step = 0;
  std::int64_t list_builds = 0; // since the start of the run
  // The particles that remain, in ascending global id: where each stands and stood at the last
  // list build, its velocities and the forces of the last evaluation. The others (grains removed
  // on escape) leave.
  std::vector<GlobalId> gid;
  std::vector<Vec3> x, x_build, v, w, f, torque;
  // The clumps that remain, ids ascending: their motion and their loads of the last evaluation
  // (ClumpBody's fields of the same names). The others (removed on escape) leave.
  struct ClumpMotion {
    GlobalId id = -1;
    Vec3 x, v;
    Quaternion q, p;
    Vec3 force, torque;
  };
  std::vector<ClumpMotion> clumps;
  // The open contacts' states, as ContactStates::give() takes them (ContactHistory::pack_entries).
  std::string contact_stash;
  // The contacts' stored energies at the last evaluation, and how many touch.
  double elastic = 0.0, relaxation = 0.0;
  std::size_t touching = 0;
  // What the grains did to each plane at the last evaluation (force and contacts), and each
  // plane's cumulative work on the grains since the start of the run.
  std::vector<WallLoad> plane_loads;
  std::vector<double> plane_work;
  // The cumulative books: dissipated, wall_work, removed, gravity_work, inserted and escaped are
  // taken; the others follow from the particles and the contacts.
  EnergyBooks books;
};

} // namespace yuxi
