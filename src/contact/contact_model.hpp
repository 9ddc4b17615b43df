// The registry of contact models: the one place that lists them. A scene picks one model for
// the whole simulation; its coefficients are given per pair of materials.
//
// Every model is a struct with: a `name`, `Coeffs` (per material pair), a trivially copyable
// `State` (per contact) with operator== and mirrored(), contact_time() for the time-step check,
// a pure `evaluate(geometry, coeffs, state)` for a touching contact, and `release(coeffs, state)`
// for a contact that opens (resets the state, returns the energy it still held). The pair loop is
// templated on the model and dispatched once per step through the variant, so the inner loop has no
// virtual call.
#pragma once

#include "contact/hertz_mindlin.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/luding.hpp"
#include "contact/pair_table.hpp"
#include "contact/thermodynamic.hpp"

#include <string_view>
#include <type_traits>
#include <variant>

namespace yuxi {

template <class Model> struct ContactLaw {
  using model_type = Model;
  PairTable<typename Model::Coeffs> coeffs;
};

using AnyContactLaw = std::variant<ContactLaw<LinearSpringDashpot>, ContactLaw<HertzMindlin>,
                                   ContactLaw<Luding>, ContactLaw<Thermodynamic>>;

// The names a scene may give as [contact] model, in the order of AnyContactLaw.
inline constexpr std::string_view contact_model_names[] = {
    LinearSpringDashpot::name, HertzMindlin::name, Luding::name, Thermodynamic::name};

// An empty law of the named model for n materials (throws std::out_of_range if unknown).
AnyContactLaw make_contact_law(std::string_view model, std::size_t n_materials);

template <class Model>
concept ContactModel = requires(const ContactGeometry& g, const typename Model::Coeffs& c,
                                typename Model::State& s) {
  { Model::name } -> std::convertible_to<std::string_view>;
  { Model::evaluate(g, c, s) } -> std::same_as<ContactResult>;
  { s.mirrored() } -> std::same_as<typename Model::State>;
  { Model::contact_time(c, 1.0, 1.0, 1.0) } -> std::same_as<double>;
  { Model::release(c, s) } -> std::same_as<double>;
}
&&std::is_trivially_copyable_v<typename Model::State>;

static_assert(ContactModel<LinearSpringDashpot>);
static_assert(ContactModel<HertzMindlin>);
static_assert(ContactModel<Luding>);
static_assert(ContactModel<Thermodynamic>);

} // namespace yuxi
