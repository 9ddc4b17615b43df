// `yuxi validate`: runs the validation suite and prints case, quantity, expected, measured,
// tolerance and pass/fail for every check.
#pragma once

#include <string>
#include <vector>

namespace yuxi {

struct ValidateOptions {
  std::vector<std::string> cases; // empty: all (long ones only with include_long)
  bool include_long = false;
  bool list = false;
  std::string scenes_dir;
  std::string reference_dir;
};

// 0 if every check passed, 1 otherwise, 2 for an unknown case.
int validate_command(const ValidateOptions& options);

} // namespace yuxi
