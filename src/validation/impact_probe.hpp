// Runs a few bodies into each other (or onto flat walls) until every contact has opened again,
// and records what the impact did: the validation cases' measuring device.
#pragma once

#include "contact/contact_model.hpp"
#include "scene/plane_wall.hpp"
#include "sim/simulation.hpp"

#include <vector>

namespace yuxi::validation {

struct Body {
  Vec3 x, v, w;
  double radius = 1.0;
  double mass = 1.0;
  std::uint8_t material = 0;
  Kind kind = Kind::grain;
  bool spins = true; // false: rotation locked (infinite inertia)
};

struct Impact {
  std::vector<Body> bodies;
  std::vector<PlaneWall> planes;
  std::vector<ShapedWall> walls; // meshes and cylinders
  AnyContactLaw law;
  double dt = 1e-4;
  Vec3 gravity;
  int max_steps = 1000000;
};

struct ImpactOutcome {
  std::vector<Vec3> v, w;    // after the impact, per body (in the order given)
  double contact_time = 0.0; // touching steps times dt
  double peak_force = 0.0;   // largest |contact force| on body 0
  double max_overlap = 0.0;  // largest overlap of body 0 with anything
  bool separated = false;
};

ImpactOutcome run_impact(const Impact& setup);

// Index of the owned particle with global id `id` (the simulation reorders particles); throws
// std::logic_error if it is not there (it left the simulation).
std::size_t owned_index(const Simulation& sim, GlobalId id);

// A flat wall through `point` with inward `normal`, of material `material`.
PlaneWall flat_wall(Vec3 point, Vec3 normal, std::uint8_t material);

// Builds a simulation of the given bodies in a box that holds them with room to spare.
Simulation make_simulation(const Impact& setup);

// Linear-model coefficients for a pair, common shortcut.
AnyContactLaw linear_law(const LinearSpringDashpot::Coeffs& c, std::size_t n_materials);

} // namespace yuxi::validation
