#include "io/energy_csv.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>
#include <string>

namespace yuxi {

EnergyCsv::EnergyCsv(const std::filesystem::path& path, std::optional<std::int64_t> resume_after,
                     const std::string& header_line)
    : file_(nullptr) {
  // (a table the saved run had not begun yet starts afresh)
  if (resume_after && !std::filesystem::exists(path)) resume_after.reset();
  if (resume_after) {
    // Keep the header and the complete rows up to the checkpoint; later ones (and a row cut
    // short by a crash) belong to the lost run.
    std::ifstream in(path);
    std::string kept, line, header;
    std::getline(in, header);
    kept = header + '\n';
    const auto fields = std::count(header.begin(), header.end(), ',');
    while (std::getline(in, line)) {
      if (in.eof() || std::count(line.begin(), line.end(), ',') != fields) break; // cut short
      if (std::stoll(line.substr(0, line.find(','))) <= *resume_after) kept += line + '\n';
    }
    in.close();
    // Replaced atomically: a crash here must not lose the rows up to the checkpoint.
    const auto tmp = path.string() + ".tmp";
    std::ofstream(tmp, std::ios::trunc) << kept;
    std::filesystem::rename(tmp, path);
    file_ = std::fopen(path.c_str(), "a");
  } else {
    file_ = std::fopen(path.c_str(), "w");
  }
  if (!file_) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  if (!resume_after) fmt::print(file_, "{}\n", header_line);
}

EnergyCsv::~EnergyCsv() {
  std::fclose(file_);
}

void EnergyCsv::write(const EnergyBooks& e) {
  write_row(e.csv_row());
}

void EnergyCsv::write_row(const std::string& row) {
  fmt::print(file_, "{}\n", row);
  if (std::fflush(file_) != 0) throw std::runtime_error("error while writing a table of rows");
}

} // namespace yuxi
