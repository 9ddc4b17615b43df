// The collision study of `yuxi collide` and the Python API's yuxi.collide(): two equal grains
// thrown at each other in the engine at a sweep of speeds, for any contact model, and for the
// thermodynamic model also with the exact two-grain solver (Jiang & Liu's Figs. 3 and 4).
#pragma once

#include "contact/contact_model.hpp"
#include "thermo/two_grain.hpp"

#include <optional>
#include <string>
#include <vector>

namespace yuxi::validation {

// A contact law of the study: a built-in model's example coefficients
// (ModelScene<Model>::example(), in the model units of contact/example_units.hpp) or a scene's
// first material pair.
struct StudyLaw {
  std::string name;
  AnyContactLaw law;
};
// The models with a built-in parameter set: every registered contact model.
std::vector<std::string> built_in_models();
// `models` (all built-in ones when empty), or the law of the scene at `scene_path` when given.
std::vector<StudyLaw> study_laws(const std::string& scene_path,
                                 const std::vector<std::string>& models);
// Speeds from v0_min to v0_max, `per_decade` to a decade (log-spaced). Throws
// std::invalid_argument for an empty or reversed range.
std::vector<double> study_speeds(double v0_min, double v0_max, int per_decade);

// The exact two-grain setup of a thermodynamic law (none for the other models).
std::optional<thermo::TwoGrainSetup> exact_setup(const AnyContactLaw& law, double mass,
                                                 double radius);

// One head-on collision at v0, in the engine ("engine") or by the exact solver ("exact").
struct RestitutionRow {
  std::string model, source;
  double v0 = 0, impact_speed = 0, e_n = 0, contact_time = 0, peak_force = 0, max_overlap = 0;
  double heat_fraction = 0, energy_drift = 0, final_drift = 0;
};
std::vector<RestitutionRow> restitution_sweep(const std::vector<StudyLaw>& laws,
                                              const std::vector<double>& speeds, double mass,
                                              double radius, double steps_per_contact);

// The exact head-on collision of a thermodynamic law at v0 with its time series (t_c / 400
// apart, on for 3 t_c after separation); none for the other models.
std::optional<thermo::TwoGrainResult> head_on_series(const AnyContactLaw& law, double mass,
                                                     double radius, double v0 = 1e-3);

} // namespace yuxi::validation
