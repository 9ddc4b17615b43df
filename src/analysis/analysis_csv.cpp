#include "analysis/analysis_csv.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace yuxi::analysis {

std::string csv_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string timed_file_name(std::string_view stem, double time, int decimals,
                            std::string_view extension) {
  if (decimals < 0 || decimals > 12) throw std::invalid_argument("timed_file_name: bad decimals");
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, time);
  return std::string(stem) + "_t" + buffer + std::string(extension);
}

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("CsvWriter: no columns");
  if (path_.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path_.parent_path(), ec);
  }
  out_.open(path_, std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write " + path_.string());
  row(std::span<const std::string>(columns_));
}

void CsvWriter::check_width(std::size_t cells) const {
  if (cells != columns_.size())
    throw std::invalid_argument(path_.string() + ": a row of " + std::to_string(cells) +
                                " cells for " + std::to_string(columns_.size()) + " columns");
}

void CsvWriter::row(std::span<const std::string> cells) {
  check_width(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k) out_ << ',';
    out_ << cells[k];
  }
  out_ << '\n';
}

void CsvWriter::row(std::span<const double> numbers) {
  check_width(numbers.size());
  for (std::size_t k = 0; k < numbers.size(); ++k) {
    if (k) out_ << ',';
    out_ << csv_number(numbers[k]);
  }
  out_ << '\n';
}

void CsvWriter::row(std::initializer_list<double> numbers) {
  row(std::span<const double>(numbers.begin(), numbers.size()));
}

void CsvWriter::close() {
  out_.flush();
  const bool good = static_cast<bool>(out_);
  out_.close();
  if (!good || out_.fail()) throw std::runtime_error("error while writing " + path_.string());
}

} // namespace yuxi::analysis
