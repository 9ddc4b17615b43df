// The per-particle fields, listed once. ParticleStore (core/particle_store.hpp) holds one
// std::vector per field; ParticleView (core/particle_view.hpp) one pointer per field, the plain
// form the force and integration loops take and a device kernel can be given. A new field is
// one line here. Host and device: nothing here but plain types.
#pragma once

#include "core/vec3.hpp"

#include <cstdint>

namespace yuxi {

enum class Kind : std::uint8_t {
  grain = 0, // free grain, integrated by the equations of motion
  wall = 1,  // wall particle: prescribed motion, infinite mass in contacts
};

using GlobalId = std::int64_t;

// FIELD(type, name): every per-particle field, in the order of the checkpoint's bytes (a new
// field is appended, with a new state layout: sim/state_layout.hpp).
//   x            position
//   v            velocity
//   w            angular velocity
//   f            force
//   torque       torque about the centre
//   x_rest       rest position of a wall particle (its motion is relative to it)
//   x_build      position at the last list build (the skin criterion)
//   radius
//   mass         finite for walls too (used in output only)
//   inv_mass     0 for wall particles: infinite mass in contacts
//   inv_inertia  1 / J, J = (2/5) m r^2 for a solid sphere; 0 for walls and locked rotation
//   gid          global id, never changes
//   kind         grain or wall
//   material     index into the scene's materials
//   motion       index into the scene's wall motions (wall particles only)
//   body         the clump a grain is a member of (its id: sim/clump_bodies.hpp); -1 for a free
//                grain or a wall particle
#define YUXI_PARTICLE_FIELDS(FIELD)                                                                \
  FIELD(Vec3, x)                                                                                   \
  FIELD(Vec3, v)                                                                                   \
  FIELD(Vec3, w)                                                                                   \
  FIELD(Vec3, f)                                                                                   \
  FIELD(Vec3, torque)                                                                              \
  FIELD(Vec3, x_rest)                                                                              \
  FIELD(Vec3, x_build)                                                                             \
  FIELD(double, radius)                                                                            \
  FIELD(double, mass)                                                                              \
  FIELD(double, inv_mass)                                                                          \
  FIELD(double, inv_inertia)                                                                       \
  FIELD(GlobalId, gid)                                                                             \
  FIELD(Kind, kind)                                                                                \
  FIELD(std::uint8_t, material)                                                                    \
  FIELD(std::uint16_t, motion)                                                                     \
  FIELD(GlobalId, body)

} // namespace yuxi
