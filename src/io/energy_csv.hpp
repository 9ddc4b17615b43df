// energies.csv: one row per energy interval with the full energy books (EnergyBooks); and any
// other table whose rows start with the step (walls.csv). Each row is flushed, so the file
// holds everything up to a crash.
#pragma once

#include "sim/energy_books.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

namespace yuxi {

class EnergyCsv {
public:
  // A new file; or, with `resume_after`, the existing one cut back to the rows of steps up to
  // it and continued (a new one if there is none).
  // `header`: the column names (EnergyBooks' by default); the first column is the step.
  explicit EnergyCsv(const std::filesystem::path& path,
                     std::optional<std::int64_t> resume_after = std::nullopt,
                     const std::string& header = EnergyBooks::csv_header());
  ~EnergyCsv();
  EnergyCsv(const EnergyCsv&) = delete;
  EnergyCsv& operator=(const EnergyCsv&) = delete;

  void write(const EnergyBooks& e);
  void write_row(const std::string& row); // without the line's end

private:
  std::FILE* file_;
};

} // namespace yuxi
