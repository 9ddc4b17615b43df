// Two equal grains thrown at each other in the engine, each at speed v0, centres offset by an
// impact parameter b (in units of the contact distance d = 2a) across the motion: what any
// contact model does in one collision. The measuring device of `yuxi collide` and of the
// contact-model tests.
#pragma once

#include "contact/contact_model.hpp"
#include "core/vec3.hpp"

namespace yuxi::validation {

struct BinaryCollision {
  AnyContactLaw law; // coefficients of material pair (0, 0) are used
  double radius = 0.5, mass = 1.0;
  double v0 = 1e-3;               // each grain's speed toward the other [length/time]
  double impact_parameter = 0.0;  // b, in units of d = 2 radius, in [0, 1)
  double steps_per_contact = 200; // dt = t_c / this, t_c the model's contact time at 2 v0
  bool spins = true;              // false: rotation locked (the two-grain solver's setting)
};

struct BinaryOutcome {
  double e_n = 0;          // -(v_rel . n) after / before, n along the centres at that moment
  double e_t = 0;          // tangential velocity of the centres after / before (NaN head-on)
  double contact_time = 0; // touching steps times dt
  double dt = 0;
  double peak_force = 0;  // largest |contact force|
  double max_overlap = 0; // largest overlap
  double initial_energy = 0;
  double heat = 0;          // dissipated at the end / initial energy
  double max_drift = 0;     // largest |E_total - E_0| / E_0 over the run (energy books)
  double final_drift = 0;   // (E_total - E_0) / E_0 after separation
  double max_mech_rise = 0; // largest step-to-step rise of mechanical energy / E_0
  double peak_relax = 0;    // largest relaxation energy / E_0 (thermodynamic model)
  Vec3 v_after[2], w_after[2];
  bool separated = false;
};

// The model's contact time for an impact at relative speed v of two grains (mass, radius).
double contact_time(const AnyContactLaw& law, double mass, double radius, double v);

BinaryOutcome collide_binary(const BinaryCollision& setup);

} // namespace yuxi::validation
