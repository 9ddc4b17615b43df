// Runs one sphere (gid 0) into a partner and records what the collision did.
#pragma once

#include "test_support.hpp"

namespace yuxi::test {

struct CollisionRecord {
  Vec3 v_before, v_after, w_after;
  double contact_time = 0; // first touching step to first separated step, interpolated
};

// Steps until the contact has formed and ended again (or max_steps), timing it.
inline CollisionRecord collide(Simulation& sim, int max_steps) {
  CollisionRecord rec;
  const auto i0 = index_of(sim, 0);
  rec.v_before = sim.particles().v[i0];
  double t_start = -1, t_end = -1;
  for (int k = 0; k < max_steps; ++k) {
    const double t_prev = sim.time();
    sim.step();
    const bool touching = sim.last_tally().touching > 0;
    if (touching && t_start < 0) t_start = t_prev;
    if (!touching && t_start >= 0) {
      t_end = t_prev;
      break;
    }
  }
  const auto i = index_of(sim, 0);
  rec.v_after = sim.particles().v[i];
  rec.w_after = sim.particles().w[i];
  // Contact begins somewhere in the step before the first touching sample and ends somewhere
  // in the step after the last: on average half a step each, so the count of touching steps
  // (t_end - t_start) estimates t_c with an error of under one step.
  rec.contact_time = t_end - t_start;
  return rec;
}

} // namespace yuxi::test
