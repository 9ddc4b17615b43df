// Sums over all contacts of one force evaluation.
#pragma once

#include "core/vec3.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace yuxi {

struct ContactTally {
  double elastic = 0.0;    // energy stored in all contact springs [energy]
  double dissipated = 0.0; // energy dissipated during this step [energy]
  double relaxation = 0.0; // energy held in relaxation buffers (thermodynamic model) [energy]
  double wall_work = 0.0; // work of moving walls on grains this step: sum F_wall->grain . v_wall dt
  std::size_t touching = 0;       // contacts carrying load
  double max_overlap_ratio = 0.0; // largest overlap / smaller radius (blow-up diagnosis)
  std::size_t worst_particle = 0; // owned particle of that contact
};

// The contacts with shaped walls (meshes, cylinders) that began already deep, since the
// simulation was built: a contact with no state from the step before whose overlap exceeds
// twice what its grain came nearer the wall in that step (and a millionth of its radius). Its
// spring's energy then comes from nothing the equations of motion did: a wall that appears
// over grains (its active window), grains placed inside a wall, or a contact rule that lets a
// contact appear where none was (docs/walls.md section 2). When the energy books gain, this
// record tells a wall's contacts from an unstable integration (Simulation::check_energy_books).
struct DeepStarts {
  double energy = 0.0; // the elastic energy they began with, summed [energy]
  // The one that began with the most energy:
  double worst = 0.0; // its elastic energy [energy]
  double time = 0.0;
  std::int64_t grain = 0; // the grain's global id
  std::uint32_t wall = 0, element = 0;
  double overlap = 0.0;  // its overlap then [length]
  double approach = 0.0; // how much nearer the wall its grain came in the step [length]

  void add(double elastic, double t, std::int64_t gid, std::uint32_t w, std::uint32_t e,
           double deep, double near) {
    energy += elastic;
    if (!(elastic > worst)) return;
    worst = elastic, time = t, grain = gid, wall = w, element = e, overlap = deep, approach = near;
  }
  // The overlap of a new contact where it began deep (else 0): `approach` is how much nearer
  // the wall the grain came in the step, |min(0, v_rel . n)| dt.
  static double deep_overlap(double overlap, double approach, double radius) {
    return overlap > 2.0 * approach + 1e-6 * radius ? overlap : 0.0;
  }
};

// What the grains do to one shaped wall in one force evaluation (walls.csv).
struct WallLoad {
  Vec3 force;      // on the wall [force]
  Vec3 torque;     // on the wall about its torque point [force length]
  double work = 0; // the wall's work on the grains this step: sum F_wall->grain . v_wall dt
  std::size_t contacts = 0;
};

// The force of one grain-wall contact on its wall's element (a mesh's triangle, a cylinder's
// patch), for the meshes' loads in snapshots.
struct ElementForce {
  std::uint32_t wall;
  std::uint32_t element;
  Vec3 force; // on the wall [force]
};

// One grain's contact with a shaped wall (a mesh or a cylinder) at a force evaluation.
struct WallContactRecord {
  std::uint32_t candidate = 0; // index in NeighborList::walls (grain and wall)
  std::uint32_t contact = 0;   // of that candidate's contacts (the slot of its state)
  std::uint32_t element = 0;   // triangle of a mesh, patch of a cylinder
  Vec3 point;                  // the wall's surface point [length]
  Vec3 normal;                 // unit, from the wall to the grain's centre
  Vec3 force;                  // on the grain [force]
  double elastic = 0;          // energy stored in the contact [energy]
  double overlap = 0;          // [length]
  double dissipated = 0;       // energy the contact turned to heat this step [energy]
  double relaxation = 0;       // energy in its relaxation buffer (thermodynamic model) [energy]
  double wall_work = 0;        // work of the wall's motion on the grain this step [energy]
};

// A touching pair's results, as the record keeps them.
struct PairContactRecord {
  std::uint32_t pair = 0;                // index in NeighborList::partners (and rows)
  Vec3 force;                            // on the row particle i from its partner j [force]
  double elastic = 0;                    // energy stored in the contact [energy]
  double dissipated = 0, relaxation = 0; // as WallContactRecord's
  double wall_work = 0; // of a moving wall particle on its grain (0 between grains) [energy]
};

// Per-contact results of one force evaluation, recorded only on request (stress and per-grain
// energy analyses): the touching pairs as a list, in the order the evaluation met them (list
// order, or the ghost pairs' then the owned pairs' where the evaluation is split in two); the
// plane candidates aligned with NeighborList::planes; the contacts with shaped walls as a list.
// A plane candidate apart has zero force and energy. Only the plane slots the step writes are
// stamped with its generation (holds_plane): the others keep what an earlier record left, so
// that a record costs the contacts it holds, not a clearing of every candidate. The pairs are
// a list for the same reason, and so that a reader visits the touching pairs alone: a record
// aligned with the list wrote and scanned about 60 bytes a listed pair, a dozen listed pairs
// a touching one in a dense flow.
// (The energy that a contact's ending releases is booked as dissipated by the engine, not
// recorded at a contact: the record holds the contacts that touch after the step.)
struct ContactRecord {
  bool enabled = false;
  std::vector<PairContactRecord> pairs; // the touching pairs (a nonzero force or energy)
  std::vector<Vec3> plane_force;        // force on the grain from the flat wall
  std::vector<double> plane_elastic, plane_dissipated, plane_relaxation, plane_wall_work;
  std::vector<WallContactRecord> wall;
  std::uint32_t generation = 0; // of the record now held
  std::vector<std::uint32_t> plane_stamp;

  // A new record for `planes` plane candidates.
  void start(std::size_t planes) {
    if (++generation == 0) { // wrapped: no stale stamp may equal a new generation
      std::fill(plane_stamp.begin(), plane_stamp.end(), 0u);
      generation = 1;
    }
    pairs.clear();
    plane_force.resize(planes);
    for (auto* v : {&plane_elastic, &plane_dissipated, &plane_relaxation, &plane_wall_work})
      v->resize(planes);
    plane_stamp.resize(planes);
    wall.clear();
  }
  // Whether plane candidate k holds a touching contact of this record.
  bool holds_plane(std::size_t k) const {
    return k < plane_stamp.size() && plane_stamp[k] == generation &&
           touched(plane_force[k], plane_elastic[k]);
  }

  void keep_pair(std::size_t p, const Vec3& force, double elastic, double dissipated,
                 double relaxation, double wall_work) {
    if (enabled && touched(force, elastic))
      pairs.push_back(
          {static_cast<std::uint32_t>(p), force, elastic, dissipated, relaxation, wall_work});
  }
  void keep_plane(std::size_t k, const Vec3& force, double elastic, double dissipated,
                  double relaxation, double wall_work) {
    if (!enabled) return;
    plane_force[k] = force;
    plane_elastic[k] = elastic;
    plane_dissipated[k] = dissipated;
    plane_relaxation[k] = relaxation;
    plane_wall_work[k] = wall_work;
    plane_stamp[k] = generation;
  }
  void keep_wall(const WallContactRecord& r) {
    if (enabled) wall.push_back(r);
  }
  // Whether a pair's or a plane's results are a touching contact's (a listed pair or
  // candidate apart has a zero force and no energy).
  static bool touched(const Vec3& force, double elastic) {
    return !(force.x == 0 && force.y == 0 && force.z == 0 && elastic == 0);
  }
};

} // namespace yuxi
