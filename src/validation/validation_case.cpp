#include "validation/validation_case.hpp"

namespace yuxi::validation {

const std::vector<Case>& all_cases() {
  static const std::vector<Case> cases = [] {
    std::vector<Case> all;
    for (auto group : {impact_cases, gravity_cases, chute_cases, bulk_cases})
      for (auto& c : group()) all.push_back(std::move(c));
    return all;
  }();
  return cases;
}

} // namespace yuxi::validation
