#include "io/checkpoint_file.hpp"

#include "core/archive.hpp"

#include <algorithm>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <zlib.h>

namespace yuxi {
namespace {

constexpr char magic[8] = {'Y', 'U', 'X', 'I', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t byte_order_mark = 0x01020304;
constexpr std::size_t header_size = 8 + 4 + 4 + 8;

std::uint32_t crc_of(const std::string& s, std::size_t from, std::size_t n) {
  uLong crc = crc32(0L, Z_NULL, 0);
  const auto* p = reinterpret_cast<const Bytef*>(s.data() + from);
  while (n > 0) { // zlib takes uInt lengths
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    crc = crc32(crc, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(crc);
}

template <class T> void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T> T get(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  return v;
}

// Writes `bytes` to `file` through a temporary file, fsync and rename.
void write_atomically(const std::filesystem::path& file, const std::string& bytes) {
  const auto tmp = file.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0)
    throw CheckpointError(fmt::format("{}: cannot create: {}", tmp, std::strerror(errno)));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0) {
      ::close(fd);
      throw CheckpointError(fmt::format("{}: write failed: {}", tmp, std::strerror(errno)));
    }
    done += static_cast<std::size_t>(w);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0)
    throw CheckpointError(fmt::format("{}: cannot flush to disk", tmp));
  std::filesystem::rename(tmp, file);
  const int dir = ::open(file.parent_path().c_str(), O_RDONLY);
  if (dir >= 0) {
    ::fsync(dir); // makes the rename itself durable
    ::close(dir);
  }
}

} // namespace

void write_checkpoint(const std::filesystem::path& file, const std::string& scene_text,
                      Simulation& sim) {
  ArchiveWriter mine;
  sim.checkpoint(mine);
  std::vector<std::string> sections = sim.comm().gather(mine.data());
  if (!sim.comm().root()) return;
  ArchiveWriter ar;
  std::string scene = scene_text;
  ar.string(scene);
  std::int64_t step = sim.step_count();
  double time = sim.time();
  ar.value(step);
  ar.value(time);
  std::uint64_t n = sections.size();
  ar.value(n);
  for (auto& sec : sections) ar.string(sec);
  const std::string& payload = ar.data();
  std::string bytes(magic, sizeof magic);
  put(bytes, checkpoint_format_version);
  put(bytes, byte_order_mark);
  put(bytes, static_cast<std::uint64_t>(payload.size()));
  bytes += payload;
  put(bytes, crc_of(payload, 0, payload.size()));
  write_atomically(file, bytes);
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
  if (crc_of(bytes, header_size, size) != stored) fail("checksum mismatch: the file is corrupt");
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
