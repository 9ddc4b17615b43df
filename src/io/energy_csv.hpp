// energies.csv: one row per energy interval with the full energy books (EnergyBooks).
// Each row is flushed, so the file holds everything up to a crash.
#pragma once

#include "sim/energy_books.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace yuxi {

class EnergyCsv {
public:
  // A new file; or, with `resume_after`, the existing one cut back to the rows of steps up to
  // it and continued.
  explicit EnergyCsv(const std::filesystem::path& path,
                     std::optional<std::int64_t> resume_after = std::nullopt);
  ~EnergyCsv();
  EnergyCsv(const EnergyCsv&) = delete;
  EnergyCsv& operator=(const EnergyCsv&) = delete;

  void write(const EnergyBooks& e);

private:
  std::FILE* file_;
};

} // namespace yuxi
