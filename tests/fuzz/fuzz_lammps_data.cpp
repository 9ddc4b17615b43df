// libFuzzer target: the LAMMPS data reader. A file may be refused (DataFileError); anything
// else is a finding.
#include "io/lammps_data_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    yuxi::parse_lammps_data(text, "fuzz.data");
  } catch (const yuxi::DataFileError&) {
  }
  return 0;
}
