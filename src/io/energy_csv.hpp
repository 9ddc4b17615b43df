// energies.csv: one row per energy interval with the full energy books (EnergyReport).
// Each row is flushed, so the file holds everything up to a crash.
#pragma once

#include "analysis/energy_report.hpp"

#include <cstdio>
#include <filesystem>

namespace yuxi {

class EnergyCsv {
public:
  explicit EnergyCsv(const std::filesystem::path& path);
  ~EnergyCsv();
  EnergyCsv(const EnergyCsv&) = delete;
  EnergyCsv& operator=(const EnergyCsv&) = delete;

  void write(const EnergyReport& e);

private:
  std::FILE* file_;
};

} // namespace yuxi
