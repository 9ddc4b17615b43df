#include "validation/collision_study.hpp"

#include "io/scene_reader.hpp"
#include "validation/binary_collision.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>

namespace yuxi::validation {
namespace {

AnyContactLaw builtin_law(const std::string& model) {
  AnyContactLaw law = make_contact_law(model, 1);
  std::visit(
      [](auto& l) {
        using Model = typename std::decay_t<decltype(l)>::model_type;
        l.coeffs.set(0, 0, ModelScene<Model>::example());
      },
      law);
  return law;
}

std::string model_name(const AnyContactLaw& law) {
  return std::visit(
      [](const auto& l) { return std::string(std::decay_t<decltype(l)>::model_type::name); }, law);
}

} // namespace

std::vector<std::string> built_in_models() {
  return {contact_model_names.begin(), contact_model_names.end()};
}

std::vector<StudyLaw> study_laws(const std::string& scene_path,
                                 const std::vector<std::string>& models) {
  std::vector<StudyLaw> out;
  if (!scene_path.empty()) {
    const Scene scene = read_scene_file(scene_path);
    out.push_back({model_name(scene.law), scene.law});
    return out;
  }
  const std::vector<std::string> known = built_in_models();
  for (const auto& n : models.empty() ? known : models) {
    if (std::find(known.begin(), known.end(), n) == known.end())
      throw std::invalid_argument(
          fmt::format("unknown contact model \"{}\" (known: {})", n, fmt::join(known, ", ")));
    out.push_back({n, builtin_law(n)});
  }
  return out;
}

std::vector<double> study_speeds(double v0_min, double v0_max, int per_decade) {
  if (!(v0_min > 0 && v0_max >= v0_min))
    throw std::invalid_argument("--v0-min and --v0-max must satisfy 0 < min <= max");
  if (per_decade < 1) throw std::invalid_argument("--per-decade must be at least 1");
  const double decades = std::log10(v0_max / v0_min);
  const int n = static_cast<int>(std::lround(decades * per_decade));
  std::vector<double> v;
  for (int k = 0; k <= n; ++k) v.push_back(v0_min * std::pow(10.0, k * decades / std::max(n, 1)));
  return v;
}

std::optional<thermo::TwoGrainSetup> exact_setup(const AnyContactLaw& law, double mass,
                                                 double radius) {
  const auto* l = std::get_if<ContactLaw<Thermodynamic>>(&law);
  if (!l) return std::nullopt;
  const auto& c = l->coeffs(0, 0);
  thermo::TwoGrainSetup s;
  s.m1 = s.m2 = mass;
  s.a1 = s.a2 = radius;
  s.k = Thermodynamic::spring_constant(c, 0.5 * radius);
  s.xi = thermo::xi_of_friction(c.friction);
  s.transport = thermo::Transport::example(c.model(), s.k, 0.5 * mass, 2 * radius);
  return s;
}

std::vector<RestitutionRow> restitution_sweep(const std::vector<StudyLaw>& laws,
                                              const std::vector<double>& speeds, double mass,
                                              double radius, double steps_per_contact) {
  std::vector<RestitutionRow> rows;
  for (const auto& s : laws) {
    const auto exact = exact_setup(s.law, mass, radius);
    for (double v0 : speeds) {
      BinaryCollision c;
      c.law = s.law;
      c.radius = radius;
      c.mass = mass;
      c.v0 = v0;
      c.steps_per_contact = steps_per_contact;
      const auto r = collide_binary(c);
      if (!r.separated) throw std::runtime_error(fmt::format("{}: no separation", s.name));
      rows.push_back({s.name, "engine", v0, 2 * v0, r.e_n, r.contact_time, r.peak_force,
                      r.max_overlap, r.heat, r.max_drift, r.final_drift});
      if (exact) {
        auto e = *exact;
        e.v0 = v0;
        const auto x = thermo::collide(e);
        rows.push_back({s.name, "exact", v0, 2 * v0, x.restitution, x.contact_time, x.peak_force,
                        x.max_overlap, (x.final_heat + x.final_w_relax) / x.initial_energy,
                        x.max_energy_error, x.max_energy_error});
      }
    }
  }
  return rows;
}

std::optional<thermo::TwoGrainResult> head_on_series(const AnyContactLaw& law, double mass,
                                                     double radius, double v0) {
  auto e = exact_setup(law, mass, radius);
  if (!e) return std::nullopt;
  e->v0 = v0;
  const double t_c = contact_time(law, mass, radius, 2 * v0);
  e->sample_interval = t_c / 400;
  e->after_separation = 3 * t_c;
  return thermo::collide(*e);
}

} // namespace yuxi::validation
