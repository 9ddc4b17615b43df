// The registry of contact models: the one place that lists them (ContactModels below). A scene
// picks one model for the whole simulation; its coefficients are given per pair of materials.
// The scene reader and writer, `yuxi collide` and the pair loop take every model from here.
//
// Every model is a struct (ContactModel below), its law in one header of plain data and YUXI_HD
// functions that any backend compiles (docs/ARCHITECTURE.md, "The seam for a second backend"):
//   name                            the scene's [contact] model, unique
//   Coeffs                          the coefficients of one pair of materials
//   State                           per contact: trivially copyable (saved as bytes), with
//                                   operator== and mirrored() (the contact seen from j)
//   contact_time(c, m*, R*, v)      for the time-step check (host)
//   evaluate(geometry, c, state)    a touching contact: force, torques and energies, pure
//   release(c, state)               a contact that opens: resets the state and returns the
//                                   energy it still held
// and optionally
//   using Batch = ...               SIMD lanes for the pair loop (sim/contact_forces.hpp)
// and, beside the law in <model>_scene.hpp, its scene side ModelScene<Model> (model_scene.hpp):
//   fields(visitor, coeffs)         the scene keys (scene_fields.hpp)
//   example()                       coefficients in the model units of `yuxi collide`
//                                   (example_units.hpp)
//   with_materials(c, E1, nu1, E2, nu2)  (optional) coefficients that also depend on the two
//                                   materials' youngs_modulus and poisson_ratio
//   lammps_preset(c)                (optional) the defaults of the scene's preset = "lammps"
//   columns(state, f)               the state's fields as named columns (state_columns.hpp)
// The pair loop is templated on the model and dispatched once per step through the variant, so
// the inner loop has no virtual call. docs/adding-a-contact-model.md walks through adding one.
#pragma once

#include "contact/hertz_mindlin_scene.hpp"
#include "contact/hooke_scene.hpp"
#include "contact/linear_batch.hpp" // (the linear law's CPU batches, host only)
#include "contact/linear_spring_dashpot_scene.hpp"
#include "contact/luding_scene.hpp"
#include "contact/pair_table.hpp"
#include "contact/scene_fields.hpp"
#include "contact/thermodynamic_scene.hpp"

#include <array>
#include <concepts>
#include <string_view>
#include <type_traits>
#include <variant>

namespace yuxi {

template <class Model>
concept ContactModel = requires(const ContactGeometry& g, typename Model::Coeffs& c,
                                typename Model::State& s, IgnoreFields& v) {
  { Model::name } -> std::convertible_to<std::string_view>;
  ModelScene<Model>::fields(v, c);
  { ModelScene<Model>::example() } -> std::same_as<typename Model::Coeffs>;
  { Model::evaluate(g, c, s) } -> std::same_as<ContactResult>;
  { s.mirrored() } -> std::same_as<typename Model::State>;
  { s == s } -> std::convertible_to<bool>;
  { Model::contact_time(c, 1.0, 1.0, 1.0) } -> std::same_as<double>;
  { Model::release(c, s) } -> std::same_as<double>;
}
&&std::is_trivially_copyable_v<typename Model::State>;

template <class Model> struct ContactLaw {
  using model_type = Model;
  PairTable<typename Model::Coeffs> coeffs;
};

template <class... Models> struct ContactModelList {
  static_assert((ContactModel<Models> && ...));

  // A law of any of the models.
  using AnyLaw = std::variant<ContactLaw<Models>...>;
  // Their names, in the order of the list.
  static constexpr std::array<std::string_view, sizeof...(Models)> names{Models::name...};
  // Calls f(std::type_identity<Model>{}) for each model, in the order of the list.
  template <class F> static constexpr void for_each(F&& f) {
    (f(std::type_identity<Models>{}), ...);
  }

  static constexpr bool names_are_unique() {
    for (std::size_t a = 0; a < names.size(); ++a)
      for (std::size_t b = a + 1; b < names.size(); ++b)
        if (names[a] == names[b]) return false;
    return true;
  }
  static_assert(names_are_unique(), "two contact models have the same name");
};

// The models, in the order in which the CLI lists them.
using ContactModels =
    ContactModelList<LinearSpringDashpot, HertzMindlin, Luding, Thermodynamic, Hooke>;

using AnyContactLaw = ContactModels::AnyLaw;

// The names a scene may give as [contact] model, in the order of AnyContactLaw.
inline constexpr auto contact_model_names = ContactModels::names;

// An empty law of the named model for n materials (throws std::out_of_range if unknown).
AnyContactLaw make_contact_law(std::string_view model, std::size_t n_materials);

} // namespace yuxi
