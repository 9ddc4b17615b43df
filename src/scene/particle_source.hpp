// Grains that come and go while a run goes on: [[insert]] pours grains into a region at a rate,
// an [[outlet]] removes every grain whose centre enters its region (docs/scene-format.md).
//
// An insertion happens in batches, one every `interval`: the grains due by then (rate x time
// since `start`, up to `total`) are drawn from the source's own random stream, batch by batch
// (radius, velocity, and up to `attempts` places for each), so the candidates are the same on
// every number of ranks. A candidate is taken where its whole ball lies in the region and
// overlaps no particle of any rank, no flat wall and no candidate taken before it; a grain that
// finds no place is owed to the next batch.
#pragma once

#include "scene/particle_fill.hpp"
#include "scene/region.hpp"

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
};

struct OutletSpec {
  std::string name; // for messages and outflow.csv ("outlet[1]" by default)
  Region region;
};

} // namespace yuxi
