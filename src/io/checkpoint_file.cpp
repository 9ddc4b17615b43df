#include "io/checkpoint_file.hpp"

#include "core/archive.hpp"

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

// A file written through a temporary file, fsync and rename, so that a crash mid-write leaves
// the previous checkpoint intact; keeps the CRC-32 of what has been written since the header.
class AtomicFile {
public:
  explicit AtomicFile(std::filesystem::path file)
      : file_(std::move(file)), tmp_(file_.string() + ".tmp") {
    fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd_ < 0)
      throw CheckpointError(fmt::format("{}: cannot create: {}", tmp_, std::strerror(errno)));
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (fd_ >= 0) { // not committed: an error left it half written
      ::close(fd_);
      ::unlink(tmp_.c_str());
    }
  }

  void write(std::string_view bytes, bool checksummed = true) {
    if (checksummed) crc_ = crc_of(bytes, crc_);
    while (!bytes.empty()) {
      const ssize_t w = ::write(fd_, bytes.data(), bytes.size());
      if (w < 0)
        throw CheckpointError(fmt::format("{}: write failed: {}", tmp_, std::strerror(errno)));
      bytes.remove_prefix(static_cast<std::size_t>(w));
    }
  }
  std::uint32_t crc() const { return crc_; }

  void commit() {
    const int fd = std::exchange(fd_, -1);
    if (::fsync(fd) != 0 || ::close(fd) != 0)
      throw CheckpointError(fmt::format("{}: cannot flush to disk", tmp_));
    std::filesystem::rename(tmp_, file_);
    const int dir = ::open(file_.parent_path().c_str(), O_RDONLY);
    if (dir >= 0) {
      ::fsync(dir); // makes the rename itself durable
      ::close(dir);
    }
  }

private:
  std::filesystem::path file_;
  std::string tmp_;
  int fd_ = -1;
  std::uint32_t crc_ = 0; // of nothing yet
};

} // namespace

void write_checkpoint(const std::filesystem::path& file, const std::string& scene_text,
                      Simulation& sim) {
  sim.stop_if_unhealthy(); // only good states are kept
  // Streamed to the file piece by piece: a checkpoint of a large run is not copied in memory.
  ArchiveWriter mine;
  sim.checkpoint(mine);
  std::vector<std::string> sections = sim.comm().gather(mine.release());
  if (!sim.comm().root()) return;
  ArchiveWriter head;
  std::string scene = scene_text;
  head.string(scene);
  std::int64_t step = sim.step_count();
  double time = sim.time();
  head.value(step);
  head.value(time);
  std::uint64_t n = sections.size();
  head.value(n);
  std::uint64_t payload = head.data().size();
  for (const auto& sec : sections) payload += sizeof(std::uint64_t) + sec.size();
  std::string header(magic, sizeof magic);
  put(header, checkpoint_format_version);
  put(header, byte_order_mark);
  put(header, payload);
  AtomicFile out(file);
  out.write(header, false);
  out.write(head.data());
  for (const auto& sec : sections) { // as ArchiveWriter::string writes them: length, bytes
    std::string length;
    put(length, static_cast<std::uint64_t>(sec.size()));
    out.write(length);
    out.write(sec);
  }
  std::string crc;
  put(crc, out.crc());
  out.write(crc, false);
  out.commit();
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
