// The validation suite (src/validation, spec: docs/models/validation.md): one test per case, one
// assertion per published or analytic number. `yuxi validate` prints the same cases as a table.
#include "validation/validation_case.hpp"

#include <gtest/gtest.h>
#include <ostream>

namespace yuxi::validation {
namespace {

class Validation : public ::testing::TestWithParam<Case> {};

} // namespace

// ctest lists a case by its id and title, not by a dump of the parameter's bytes.
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.id << ": " << c.title;
}

namespace {

TEST_P(Validation, MatchesTheReference) {
  const Case& c = GetParam();
  const Paths paths{YUXI_SCENES_DIR, YUXI_REFERENCE_DIR};
  const CaseResult result = c.run(paths);
  ASSERT_FALSE(result.checks.empty());
  for (const Check& k : result.checks)
    EXPECT_TRUE(k.pass()) << c.id << " " << k.quantity << ": expected " << k.expected
                          << ", measured " << k.measured << ", tolerance " << k.tolerance;
}

std::vector<Case> quick_cases() {
  std::vector<Case> out;
  for (const auto& c : all_cases())
    if (!c.long_running && !c.heavy) out.push_back(c);
  return out;
}

INSTANTIATE_TEST_SUITE_P(Cases, Validation, ::testing::ValuesIn(quick_cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.id; });

} // namespace
} // namespace yuxi::validation
