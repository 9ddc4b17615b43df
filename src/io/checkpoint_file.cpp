#include "io/checkpoint_file.hpp"

#include "core/archive.hpp"
#include "domain/shared_file.hpp"

#include <algorithm>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unistd.h>
#include <utility>
#include <zlib.h>

namespace yuxi {
namespace {

constexpr char magic[8] = {'Y', 'U', 'X', 'I', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t byte_order_mark = 0x01020304;
constexpr std::size_t header_size = 8 + 4 + 4 + 8;

// CRC-32 of `bytes`, continuing from the CRC of what came before (zlib's crc32 chains; the CRC
// of nothing is 0).
std::uint32_t crc_of(std::string_view bytes, std::uint32_t crc = 0) {
  uLong c = crc;
  const auto* p = reinterpret_cast<const Bytef*>(bytes.data());
  std::size_t n = bytes.size();
  while (n > 0) { // zlib takes uInt lengths
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

template <class T> void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T> T get(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  return v;
}

} // namespace

void write_checkpoint(const std::filesystem::path& file, const std::string& scene_text,
                      Simulation& sim) {
  sim.stop_if_unhealthy(); // only good states are kept
  const Comm& comm = sim.comm();
  // Every rank writes its own section into the one file (SharedFile), in rank order:
  //   header (magic, version, byte order, payload size) | head (scene, step, time, number of
  //   sections) | per rank: section length, section | CRC-32 of the payload
  // Rank 0's part starts with the head. The CRC is combined from the ranks' CRCs of their parts.
  ArchiveWriter section;
  sim.checkpoint(section);
  std::string part; // what precedes the section in this rank's part
  if (comm.root()) {
    ArchiveWriter head;
    std::string scene = scene_text;
    head.string(scene);
    std::int64_t step = sim.step_count();
    double time = sim.time();
    head.value(step);
    head.value(time);
    auto n = static_cast<std::uint64_t>(comm.size());
    head.value(n);
    part = head.release();
  }
  put(part, static_cast<std::uint64_t>(section.data().size())); // as ArchiveWriter::string
  const std::uint64_t part_bytes = part.size() + section.data().size();
  const std::uint32_t part_crc = crc_of(section.data(), crc_of(part));
  const std::uint64_t payload =
      static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(part_bytes)));
  std::string crc_and_length;
  put(crc_and_length, part_crc);
  put(crc_and_length, part_bytes);
  const std::vector<std::string> crcs = comm.gather(crc_and_length);

  // Written under a temporary name, flushed to the disk and renamed, so that a crash mid-write
  // leaves the previous checkpoint intact.
  const std::string tmp = file.string() + ".tmp";
  std::string error;
  try {
    SharedFile out(comm, tmp, SharedFile::Mode::truncate);
    const std::uint64_t at = header_size + comm.sum_below(part_bytes);
    out.write_at(at, part);
    out.write_at(at + part.size(), section.data());
    if (comm.root()) {
      std::string header(magic, sizeof magic);
      put(header, checkpoint_format_version);
      put(header, byte_order_mark);
      put(header, payload);
      out.write_at(0, header);
      uLong crc = 0; // of nothing
      for (const auto& c : crcs)
        crc = crc32_combine64(crc, get<std::uint32_t>(c, 0),
                              static_cast<z_off64_t>(get<std::uint64_t>(c, 4)));
      std::string tail;
      put(tail, static_cast<std::uint32_t>(crc));
      out.write_at(header_size + payload, tail);
    }
    out.close(true);
  } catch (const std::runtime_error& e) { // the same on every rank (SharedFile::close)
    error = e.what();
  }
  if (error.empty() && comm.root()) {
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) error = fmt::format("{}: cannot rename to {}: {}", tmp, file.string(), ec.message());
    const int dir = ::open(file.parent_path().c_str(), O_RDONLY);
    if (dir >= 0) {
      ::fsync(dir); // makes the rename itself durable
      ::close(dir);
    }
  }
  error = comm.first_error(error);
  if (!error.empty()) {
    std::error_code ignored; // (the error to report is the one above)
    if (comm.root()) std::filesystem::remove(tmp, ignored);
    throw CheckpointError(error);
  }
}

CheckpointData parse_checkpoint(std::string bytes, const std::string& name) {
  auto fail = [&](const std::string& what) {
    throw CheckpointError(fmt::format("{}: {}", name, what));
  };
  if (bytes.size() < header_size || std::memcmp(bytes.data(), magic, sizeof magic) != 0)
    fail("not a yuxi checkpoint (no YUXICKPT header)");
  const auto version = get<std::uint32_t>(bytes, 8);
  if (version != checkpoint_format_version)
    fail(fmt::format("checkpoint format version {}; this yuxi reads version {}", version,
                     checkpoint_format_version));
  if (get<std::uint32_t>(bytes, 12) != byte_order_mark)
    fail("written on a machine of another byte order");
  const auto size = get<std::uint64_t>(bytes, 16);
  if (size > bytes.size() - header_size || bytes.size() - header_size - size < 4)
    fail(fmt::format("truncated: the header announces {} bytes of data, the file holds {}", size,
                     bytes.size() - header_size));
  if (bytes.size() - header_size - size != 4) fail("trailing bytes after the checksum (corrupt)");
  const auto stored = get<std::uint32_t>(bytes, header_size + size);
  if (crc_of(std::string_view(bytes).substr(header_size, size)) != stored)
    fail("checksum mismatch: the file is corrupt");
  CheckpointData d;
  d.file = name;
  try {
    ArchiveReader ar(std::string_view(bytes).substr(header_size, size));
    ar.string(d.scene_text);
    ar.value(d.step);
    ar.value(d.time);
    std::uint64_t n = 0;
    ar.value(n);
    ar.check_room(n, sizeof(std::uint64_t));
    d.sections.resize(n);
    for (auto& sec : d.sections) ar.string(sec);
    if (!ar.at_end()) fail("unread data after the last section (corrupt)");
  } catch (const ArchiveError& e) {
    fail(e.what());
  }
  return d;
}

CheckpointData read_checkpoint(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CheckpointError(fmt::format("{}: cannot open", file.string()));
  std::ostringstream s;
  s << in.rdbuf();
  return parse_checkpoint(s.str(), file.string());
}

void apply_checkpoint(const CheckpointData& data, Simulation& sim) {
  const auto ranks = static_cast<std::size_t>(sim.comm().size());
  try {
    if (data.sections.empty()) throw ArchiveError("no rank's state in the file");
    if (data.sections.size() != ranks) { // written on another number of ranks: redistribute
      sim.load_redistributed(data.sections);
      return;
    }
    ArchiveReader ar(data.sections[static_cast<std::size_t>(sim.comm().rank())]);
    sim.checkpoint(ar);
    if (!ar.at_end()) throw ArchiveError("unread data after the state");
  } catch (const ArchiveError& e) {
    throw CheckpointError(fmt::format("{}: {}", data.file.string(), e.what()));
  } catch (const std::length_error&) {
    throw CheckpointError(
        fmt::format("{}: a size field is impossible (corrupt)", data.file.string()));
  } catch (const std::invalid_argument& e) { // the loaded particles do not fit the scene
    throw CheckpointError(fmt::format("{}: {}", data.file.string(), e.what()));
  }
}

CheckpointSet::CheckpointSet(std::filesystem::path run_folder, int keep)
    : folder_(std::move(run_folder) / "checkpoints"), keep_(std::max(keep, 1)) {}

std::filesystem::path CheckpointSet::path_for(std::int64_t step) const {
  return folder_ / fmt::format("checkpoint_{:012d}.yxc", step);
}

void CheckpointSet::write(const std::string& scene_text, Simulation& sim) {
  if (sim.comm().root()) {
    std::filesystem::create_directories(folder_);
    for (const auto& e : std::filesystem::directory_iterator(folder_)) // left by a crash
      if (e.path().extension() == ".tmp") std::filesystem::remove(e.path());
  }
  sim.comm().barrier(); // every rank opens the file in the folder rank 0 has made
  write_checkpoint(path_for(sim.step_count()), scene_text, sim);
  if (!sim.comm().root()) return;
  const auto files = list();
  for (std::size_t k = static_cast<std::size_t>(keep_); k < files.size(); ++k)
    std::filesystem::remove(files[k]);
}

std::vector<std::filesystem::path> CheckpointSet::list() const {
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(folder_)) return out;
  for (const auto& e : std::filesystem::directory_iterator(folder_))
    if (e.path().extension() == ".yxc") out.push_back(e.path());
  std::sort(out.rbegin(), out.rend()); // zero-padded steps: newest first
  return out;
}

std::optional<CheckpointData>
CheckpointSet::newest_valid(std::vector<std::string>* warnings) const {
  for (const auto& f : list()) {
    try {
      return read_checkpoint(f);
    } catch (const CheckpointError& e) {
      if (warnings) warnings->push_back(e.what());
    }
  }
  return std::nullopt;
}

} // namespace yuxi
