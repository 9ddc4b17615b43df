// Grains that come and go while a run goes on: [[insert]] pours grains into a region at a rate,
// an [[outlet]] removes every grain whose centre enters its region (docs/scene-format.md).
//
// An insertion happens in batches, one every `interval`: the grains due by then (rate x time
// since `start`, up to `total`) are drawn from the source's own random stream, batch by batch
// (radius, velocity, and up to `attempts` places for each), so the candidates are the same on
// every number of ranks. A candidate is taken where its whole ball lies in the region and
// overlaps no particle of any rank, no flat wall and no candidate taken before it; a grain that
// finds no place is owed to the next batch.
//
// An insert of a clump shape pours clumps: the radius drawn is the clump's bounding radius, the
// candidate ball is judged as a sphere's, and the clump placed in it is turned uniformly at
// random (drawn from the batch's stream after its places, in the order the grains are taken).
#pragma once

#include "scene/clump_shape.hpp"
#include "scene/particle_fill.hpp"
#include "scene/region.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

namespace yuxi {

struct InsertSpec {
  std::string name; // for messages and inflow.csv ("insert[1]" by default)
  Region region;
  GrainKind grains;
  double rate = 0; // grains per time, or mass per time when by_mass
  bool by_mass = false;
  double start = 0; // [time]
  double end = std::numeric_limits<double>::infinity();
  std::int64_t total = -1; // grains at most (-1: no limit)
  double interval = 0;     // time between batches (the reader sets it)
  int attempts = 20;       // places tried for each grain of a batch
  bool held = false;       // waits for Simulation::start_insert (Python's sim.start_insert)
  // Clumps of the scene's shape of this index (-1: spheres), `clump` its shape; a shape of one
  // member pours spheres.
  std::int32_t shape = -1;
  ClumpShape clump;
  bool pours_clumps() const { return shape >= 0 && clump.members.size() > 1; }
  // The radius of the largest and of the smallest sphere it pours: with clumps, a member's, the
  // shape scaled to the size drawn.
  double largest_sphere() const { return grains.size.largest() * sphere_scale(false); }
  double smallest_sphere() const { return grains.size.smallest() * sphere_scale(true); }
  // The diameter of the largest clump's bounding sphere (0: spheres).
  double clump_span() const {
    if (!pours_clumps()) return 0.0;
    return 2.0 * clump.scaled(grains.size.largest() / clump.bounding_radius).bounding_radius;
  }
  // The farthest a member's centre stands from its clump's centre of mass (0: spheres).
  double clump_reach() const {
    if (!pours_clumps()) return 0.0;
    return clump.scaled(grains.size.largest() / clump.bounding_radius).member_reach();
  }

private:
  // A member's radius over the bounding radius: the smallest or largest member's (1: spheres).
  double sphere_scale(bool smallest) const {
    if (!pours_clumps()) return 1.0;
    double r = clump.members[0].radius;
    for (const SphereMember& m : clump.members)
      r = smallest ? std::min(r, m.radius) : std::max(r, m.radius);
    return r / clump.bounding_radius;
  }
};

struct OutletSpec {
  std::string name; // for messages and outflow.csv ("outlet[1]" by default)
  Region region;
};

} // namespace yuxi
