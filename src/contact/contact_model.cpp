#include "contact/contact_model.hpp"

#include <stdexcept>
#include <string>

namespace yuxi {
namespace {

template <std::size_t I = 0> AnyContactLaw make_law(std::string_view model, std::size_t n) {
  if constexpr (I < std::variant_size_v<AnyContactLaw>) {
    using Law = std::variant_alternative_t<I, AnyContactLaw>;
    if (Law::model_type::name == model) return Law{PairTable<typename Law::model_type::Coeffs>(n)};
    return make_law<I + 1>(model, n);
  } else {
    throw std::out_of_range("unknown contact model \"" + std::string(model) + "\"");
  }
}

} // namespace

AnyContactLaw make_contact_law(std::string_view model, std::size_t n_materials) {
  return make_law(model, n_materials);
}

} // namespace yuxi
