// NumPy .npy files of records (a structured array, one record per grain), which every rank of a
// group writes its part of: `numpy.load(path)` returns them as one array with named fields.
//
// Format 1.0 of the .npy specification (numpy.lib.format): the magic string "\x93NUMPY", the
// version (1, 0), a little-endian uint16 header length, then the header, a Python dict literal
// {'descr': [(name, type), ...], 'fortran_order': False, 'shape': (n,), } padded with spaces
// and a newline so that the data start at a multiple of 64 bytes; then the n records, packed,
// little-endian. Written by hand: the format is a few lines, and no Debian package writes it
// from C++ (cnpy is not packaged).
#pragma once

#include "domain/comm.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi {

// One field of a record: its name and NumPy type ("<f4", "<f8", "<i8"; little-endian).
struct NpyField {
  std::string name;
  std::string type;
  std::size_t bytes() const;
};

// The header (magic to newline) of an array of n records.
std::string npy_header(const std::vector<NpyField>& fields, std::uint64_t n);

// Collective: writes every rank's records (packed bytes, a whole number of records) into one
// file, rank 0's first. Throws std::runtime_error on every rank if any rank failed.
void write_npy_records(const Comm& comm, const std::filesystem::path& path,
                       const std::vector<NpyField>& fields, std::string_view records);

} // namespace yuxi
