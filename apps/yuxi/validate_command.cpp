#include "validate_command.hpp"

#include "validation/validation_case.hpp"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>

namespace yuxi {

int validate_command(const ValidateOptions& o) {
  using namespace validation;
  const auto& cases = all_cases();
  if (o.list) {
    for (const auto& c : cases)
      fmt::print("{:<5} {}{}\n      source: {}\n", c.id, c.title, c.long_running ? " (long)" : "",
                 c.source);
    return 0;
  }
  for (const auto& id : o.cases)
    if (std::none_of(cases.begin(), cases.end(), [&](const Case& c) { return c.id == id; })) {
      fmt::print(stderr, "error: unknown case \"{}\" (see yuxi validate --list)\n", id);
      return 2;
    }
  const Paths paths{o.scenes_dir, o.reference_dir};
  int passed = 0, failed = 0;
  fmt::print("{:<5} {:<58} {:>14} {:>14} {:>11}  {}\n", "case", "quantity", "expected", "measured",
             "tolerance", "result");
  for (const auto& c : cases) {
    const bool chosen = o.cases.empty()
                            ? (!c.long_running || o.include_long)
                            : std::find(o.cases.begin(), o.cases.end(), c.id) != o.cases.end();
    if (!chosen) continue;
    const auto start = std::chrono::steady_clock::now();
    CaseResult r;
    try {
      r = c.run(paths);
    } catch (const std::exception& e) {
      fmt::print("{:<5} {:<58} {}\n", c.id, "could not run", e.what());
      ++failed;
      continue;
    }
    for (const auto& k : r.checks) {
      fmt::print("{:<5} {:<58} {:>14.7g} {:>14.7g} {:>11.3g}  {}\n", c.id, k.quantity, k.expected,
                 k.measured, k.tolerance, k.pass() ? "pass" : "FAIL");
      (k.pass() ? passed : failed) += 1;
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print("{:<5} {} ({:.1f} s; {})\n\n", "", c.title, s, c.source);
  }
  fmt::print("{} passed, {} failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}

} // namespace yuxi
