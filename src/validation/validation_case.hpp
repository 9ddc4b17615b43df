// The validation suite: published and analytic cases (spec: docs/models/validation.md), each a
// function that runs the engine and returns rows of (quantity, expected, measured, tolerance). The
// same cases drive the test suite (tests/validation) and `yuxi validate`, which prints the table.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace yuxi::validation {

struct Check {
  std::string quantity;
  double expected = 0;
  double measured = 0;
  double tolerance = 0; // absolute
  bool pass() const { return std::abs(measured - expected) <= tolerance; }
};

struct CaseResult {
  std::vector<Check> checks;
  void add(std::string quantity, double expected, double measured, double tolerance) {
    checks.push_back({std::move(quantity), expected, measured, tolerance});
  }
  // A relative tolerance.
  void add_relative(std::string quantity, double expected, double measured, double relative) {
    add(std::move(quantity), expected, measured, relative * std::abs(expected));
  }
};

// Where the cases find their input data.
struct Paths {
  std::filesystem::path scenes;         // the repository's scenes/ (chute-lammps.toml)
  std::filesystem::path reference_data; // tests/validation/data (LAMMPS output)
};

struct Case {
  std::string id; // "L1", "CO4", ...
  std::string title;
  std::string source; // where the expected numbers come from
  bool long_running = false;
  std::function<CaseResult(const Paths&)> run;
  // Runs a whole scene (seconds to minutes): its own ctest entry, kept from the sanitizer tier,
  // instead of one of the quick gtest cases.
  bool heavy = false;
};

// Every case, in the order of docs/models/validation.md.
const std::vector<Case>& all_cases();

// Collects the cases of one group (each file registers its own).
std::vector<Case> impact_cases();
std::vector<Case> gravity_cases();
std::vector<Case> chute_cases();
std::vector<Case> bulk_cases();

} // namespace yuxi::validation
