// CSV output of the analyses: a header line naming the columns, then one row per record, numbers
// in the shortest form that reads back to the same double ("nan" for an empty grid cell, which
// numpy.genfromtxt and Python's float() both read).
//
// File names of analyses taken at one instant carry the time: timed_file_name("surface", 10.25)
// is "surface_t10.25.csv"; plots/plot_basin.py finds them by the "_t<time>.csv" suffix.
#pragma once

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi::analysis {

// A number as CSV text: shortest round-trip form; "nan", "inf", "-inf" for the others.
std::string csv_number(double value);

// "<stem>_t<time with `decimals` digits><extension>", e.g. ("velocity", 10.5) ->
// "velocity_t10.50.csv".
std::string timed_file_name(std::string_view stem, double time, int decimals = 2,
                            std::string_view extension = ".csv");

class CsvWriter {
public:
  // Creates the file (and its parent folders) and writes the header line.
  // Throws std::runtime_error when the file cannot be written.
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns);

  // One row; throws std::invalid_argument unless it has one cell per column.
  void row(std::span<const std::string> cells);
  void row(std::initializer_list<double> numbers);
  void row(std::span<const double> numbers);

  // Flushes and closes; throws std::runtime_error if any write failed. The destructor closes
  // without checking.
  void close();

  std::size_t columns() const { return columns_.size(); }

private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::ofstream out_;
  void check_width(std::size_t cells) const;
};

} // namespace yuxi::analysis
