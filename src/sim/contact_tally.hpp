// Sums over all contacts of one force evaluation.
#pragma once

#include <cstddef>

namespace yuxi {

struct ContactTally {
  double elastic = 0.0;    // energy stored in all contact springs [energy]
  double dissipated = 0.0; // energy dissipated during this step [energy]
  double wall_work = 0.0; // work of moving walls on grains this step: sum F_wall->grain . v_wall dt
  std::size_t touching = 0;       // contacts carrying load
  double max_overlap_ratio = 0.0; // largest overlap / smaller radius (blow-up diagnosis)
  std::size_t worst_particle = 0; // owned particle of that contact
};

} // namespace yuxi
