#include "io/npy_records.hpp"

#include "domain/shared_file.hpp"

#include <fmt/format.h>
#include <stdexcept>

namespace yuxi {

std::size_t NpyField::bytes() const {
  if (type == "<f4") return 4;
  if (type == "<f8" || type == "<i8") return 8;
  throw std::invalid_argument(fmt::format("npy: unknown field type {}", type));
}

std::string npy_header(const std::vector<NpyField>& fields, std::uint64_t n) {
  std::string descr;
  for (const auto& f : fields) descr += fmt::format("('{}', '{}'), ", f.name, f.type);
  std::string dict =
      fmt::format("{{'descr': [{}], 'fortran_order': False, 'shape': ({},), }}", descr, n);
  // magic (6) + version (2) + length (2) + dict + padding + '\n': a multiple of 64
  const std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  if (dict.size() > 65535) throw std::invalid_argument("npy: the header is too long");
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(dict.size() & 0xFF);
  out += static_cast<char>(dict.size() >> 8);
  return out + dict;
}

void write_npy_records(const Comm& comm, const std::filesystem::path& path,
                       const std::vector<NpyField>& fields, std::string_view records) {
  std::size_t record = 0;
  for (const auto& f : fields) record += f.bytes();
  if (record == 0 || records.size() % record != 0)
    throw std::invalid_argument("npy: the records are not a whole number");
  const auto n =
      static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(records.size() / record)));
  const std::string header = npy_header(fields, n);
  SharedFile file(comm, path, SharedFile::Mode::truncate);
  if (comm.root()) file.write_at(0, header);
  file.write_in_rank_order(header.size(), records);
  file.close(false);
}

} // namespace yuxi
