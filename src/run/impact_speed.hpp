// The speed at which the time-step check lets grains meet, for the contact laws whose duration
// depends on it (Hertzian laws: t_c ~ v^(-1/5); docs/scene-format.md, "The time-step check").
#pragma once

#include "core/particle_store.hpp"
#include "io/scene.hpp"
#include "scene/wall_motion.hpp"

#include <string>
#include <vector>

namespace yuxi {

struct ImpactSpeed {
  double speed = 0.0; // [length/time]
  std::string source; // what sets it, for the log and the time-step error
};

// The fastest of what the scene sets in motion: a fall from the top of the domain to its bottom
// under gravity, sqrt(2 |g| H) with H the domain's extent along g (non-periodic axes); the
// particles' initial velocities; the surface speeds of moving walls (wall particles, meshes,
// cylinders, oscillating planes: omega times the farthest point from the axis, drifts,
// amplitude times frequency); and the velocities inserts give their grains (mean plus spread).
// Where nothing moves, 1 length/time (1 sigma/tau, 1 m/s), and `source` says so.
ImpactSpeed impact_speed(const Scene& scene, const ParticleStore& particles,
                         const std::vector<WallMotion>& motions);

} // namespace yuxi
