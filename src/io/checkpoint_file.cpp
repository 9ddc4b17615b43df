#include "io/checkpoint_file.hpp"

#include "core/archive.hpp"
#include "domain/shared_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <optional>
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

// Collective: the CRC-32 of the ranks' parts one after the other, on rank 0 (0 elsewhere), from
// each rank's CRC of its part and the part's length (zlib's crc32_combine64).
std::uint32_t combined_crc(const Comm& comm, std::uint32_t part_crc, std::uint64_t part_bytes) {
  std::string crc_and_length;
  put(crc_and_length, part_crc);
  put(crc_and_length, part_bytes);
  uLong crc = 0; // of nothing
  for (const auto& c : comm.gather(crc_and_length))
    crc = crc32_combine64(crc, get<std::uint32_t>(c, 0),
                          static_cast<z_off64_t>(get<std::uint64_t>(c, 4)));
  return static_cast<std::uint32_t>(crc);
}

} // namespace

void write_checkpoint_file(const std::filesystem::path& file, const Comm& comm,
                           const CheckpointHead& h, const std::string& section_bytes) {
  // Every rank writes its own section into the one file (SharedFile), in rank order:
  //   header (magic, version, byte order, payload size) | head (scene, step, time, number of
  //   sections) | per rank: section length, section | CRC-32 of the payload
  // Rank 0's part starts with the head. The CRC is combined from the ranks' CRCs of their parts.
  std::string part; // what precedes the section in this rank's part
  if (comm.root()) {
    ArchiveWriter head;
    std::string scene = h.scene_text;
    head.string(scene);
    head.value(h.step);
    head.value(h.time);
    head.value(h.largest_grain_radius);
    auto n = static_cast<std::uint64_t>(comm.size());
    head.value(n);
    part = head.release();
  }
  put(part, static_cast<std::uint64_t>(section_bytes.size())); // as ArchiveWriter::string
  const std::uint64_t part_bytes = part.size() + section_bytes.size();
  const std::uint32_t part_crc = crc_of(section_bytes, crc_of(part));
  const std::uint64_t payload =
      static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(part_bytes)));
  const std::uint32_t crc = combined_crc(comm, part_crc, part_bytes);

  // Written under a temporary name, flushed to the disk and renamed, so that a crash mid-write
  // leaves the previous checkpoint intact.
  const std::string tmp = file.string() + ".tmp";
  std::string error;
  try {
    SharedFile out(comm, tmp, SharedFile::Mode::truncate);
    const std::uint64_t at = header_size + comm.sum_below(part_bytes);
    out.write_at(at, part);
    out.write_at(at + part.size(), section_bytes);
    if (comm.root()) {
      std::string header(magic, sizeof magic);
      put(header, checkpoint_format_version);
      put(header, byte_order_mark);
      put(header, payload);
      out.write_at(0, header);
      std::string tail;
      put(tail, crc);
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

namespace {

// The bytes of a checkpoint, read by range: from a file, where each rank reads only the part it
// loads, or from memory (the fuzzer and the tests).
class CheckpointBytes {
public:
  static CheckpointBytes in_memory(std::string bytes) {
    CheckpointBytes b;
    b.size_ = bytes.size();
    b.memory_ = std::move(bytes);
    return b;
  }
  static CheckpointBytes from_file(const std::filesystem::path& file) {
    CheckpointBytes b;
    b.file_.open(file, std::ios::binary | std::ios::ate);
    if (!b.file_) throw CheckpointError(fmt::format("{}: cannot open", file.string()));
    b.size_ = static_cast<std::uint64_t>(b.file_.tellg());
    b.name_ = file.string();
    b.on_disk_ = true;
    return b;
  }
  std::uint64_t size() const { return size_; }
  // Bytes [at, at + n), which the caller has checked lie inside the file.
  std::string read(std::uint64_t at, std::uint64_t n) {
    if (!on_disk_) return memory_.substr(at, n);
    std::string out(n, '\0');
    file_.seekg(static_cast<std::streamoff>(at));
    file_.read(out.data(), static_cast<std::streamsize>(n));
    if (!file_ || static_cast<std::uint64_t>(file_.gcount()) != n)
      throw CheckpointError(fmt::format("{}: read failed at byte {}", name_, at));
    return out;
  }

private:
  CheckpointBytes() = default;
  std::string memory_;
  std::ifstream file_;
  std::string name_;
  std::uint64_t size_ = 0;
  bool on_disk_ = false;
};

// What rank 0 reads for all: the head, where each section starts, and the stored CRC-32.
struct CheckpointIndex {
  std::string scene_text;
  std::int64_t step = 0;
  double time = 0;
  double largest_grain_radius = NAN; // (from format 8)
  // The file offset of each section's length field, then the end of the payload.
  std::vector<std::uint64_t> starts;
  std::uint32_t crc = 0;
  std::uint32_t version = checkpoint_format_version;

  template <class Archive> void serialize(Archive& ar) {
    ar.string(scene_text);
    ar.value(step);
    ar.value(time);
    ar.value(largest_grain_radius);
    ar.vector(starts);
    ar.value(crc);
    ar.value(version);
  }
};

// Checks the header, reads the head and walks the sections' length fields: a few small reads,
// not the sections themselves. A file whose structure is broken is read whole once, to report
// a damaged checksum first (a flipped bit in a length field is damage, not a format error).
CheckpointIndex read_index(CheckpointBytes& bytes, const std::string& name) {
  auto fail = [&](const std::string& what) {
    throw CheckpointError(fmt::format("{}: {}", name, what));
  };
  const std::uint64_t file_size = bytes.size();
  const std::string header = bytes.read(0, std::min<std::uint64_t>(file_size, header_size));
  if (header.size() < header_size || std::memcmp(header.data(), magic, sizeof magic) != 0)
    fail("not a yuxi checkpoint (no YUXICKPT header)");
  const auto version = get<std::uint32_t>(header, 8);
  if (version < oldest_state_layout || version > checkpoint_format_version)
    fail(fmt::format("checkpoint format version {}; this yuxi reads versions {} to {}", version,
                     oldest_state_layout, checkpoint_format_version));
  if (get<std::uint32_t>(header, 12) != byte_order_mark)
    fail("written on a machine of another byte order");
  const auto size = get<std::uint64_t>(header, 16);
  const std::uint64_t after_header = file_size - header_size;
  if (size > after_header || after_header - size < 4)
    fail(fmt::format("truncated: the header announces {} bytes of data, the file holds {}", size,
                     after_header));
  if (after_header - size != 4) fail("trailing bytes after the checksum (corrupt)");
  const std::uint64_t end = header_size + size;
  CheckpointIndex index;
  index.version = version;
  index.crc = get<std::uint32_t>(bytes.read(end, 4), 0);
  std::uint64_t at = header_size;
  // The archive's own complaint about a length beyond the data (ArchiveReader::check_room).
  const auto exceeds = [] {
    throw ArchiveError("a length field exceeds the data that follows (corrupt or truncated)");
  };
  try {
    // The head: scene (as ArchiveWriter::string), step, time, the largest grain's radius (from
    // format 8), number of sections.
    const std::uint64_t fixed = 8 + 8 + 8 + (version >= 8 ? 8 : 0) + 8;
    if (size < fixed) throw ArchiveError("the data ends early (truncated)");
    const auto scene_bytes = get<std::uint64_t>(bytes.read(at, 8), 0);
    if (scene_bytes > size - fixed) exceeds();
    const std::string head = bytes.read(at, fixed + scene_bytes);
    ArchiveReader ar(head);
    ar.string(index.scene_text);
    ar.value(index.step);
    ar.value(index.time);
    if (version >= 8) {
      ar.value(index.largest_grain_radius);
      if (!(index.largest_grain_radius >= 0.0) || !std::isfinite(index.largest_grain_radius))
        throw ArchiveError("an impossible grain radius in the head (corrupt)");
    }
    std::uint64_t n = 0;
    ar.value(n);
    at += head.size();
    if (n > (end - at) / sizeof(std::uint64_t)) exceeds();
    index.starts.reserve(n + 1);
    for (std::uint64_t k = 0; k < n; ++k) {
      index.starts.push_back(at);
      if (end - at < 8) throw ArchiveError("the data ends early (truncated)");
      const auto length = get<std::uint64_t>(bytes.read(at, 8), 0);
      at += 8;
      if (length > end - at) exceeds();
      at += length;
    }
    index.starts.push_back(at);
    if (at != end) throw ArchiveError("unread data after the last section (corrupt)");
  } catch (const ArchiveError& e) {
    if (crc_of(bytes.read(header_size, size)) != index.crc)
      fail("checksum mismatch: the file is corrupt");
    fail(e.what());
  }
  return index;
}

// Throws on every rank if any failed (the lowest failing rank's message).
void agree(const Comm& comm, const std::string& error) {
  const std::string first = comm.first_error(error);
  if (!first.empty()) throw CheckpointError(first);
}

// Collective: rank 0 reads the index, and every rank reads its share of the sections (block
// by block in rank order) and the CRC of the bytes it read; rank 0 combines the ranks' CRCs
// into the file's and checks it. No rank reads or holds more than its share.
CheckpointData read_share(CheckpointBytes& bytes, const std::string& name, const Comm& comm) {
  std::string error, encoded;
  if (comm.root()) {
    try {
      CheckpointIndex index = read_index(bytes, name);
      ArchiveWriter ar;
      index.serialize(ar);
      encoded = ar.release();
    } catch (const CheckpointError& e) {
      error = e.what();
    }
  }
  agree(comm, error);
  CheckpointIndex index;
  {
    const std::string shared = comm.broadcast(encoded);
    ArchiveReader ar(shared);
    index.serialize(ar);
  }
  // Sections first .. last - 1 are this rank's; its bytes run from the start of the first to
  // the start of the next rank's, so the ranks' ranges tile the payload (rank 0's starts with
  // the head, and the last rank's ends at the payload's end).
  const auto n = static_cast<std::uint64_t>(index.starts.size() - 1);
  const auto ranks = static_cast<std::uint64_t>(comm.size());
  const auto rank = static_cast<std::uint64_t>(comm.rank());
  const auto first_of = [&](std::uint64_t r) { return n / ranks * r + std::min(r, n % ranks); };
  const std::uint64_t first = first_of(rank), last = first_of(rank + 1);
  const std::uint64_t begin = rank == 0 ? header_size : index.starts[first];
  const std::uint64_t end = rank + 1 == ranks ? index.starts[n] : index.starts[last];
  std::string share;
  try {
    share = bytes.read(begin, end - begin);
  } catch (const CheckpointError& e) {
    error = e.what();
  }
  agree(comm, error);
  const std::uint32_t crc = combined_crc(comm, crc_of(share), end - begin);
  if (comm.root() && crc != index.crc)
    error = fmt::format("{}: checksum mismatch: the file is corrupt", name);
  agree(comm, error);
  CheckpointData d;
  d.file = name;
  d.scene_text = std::move(index.scene_text);
  d.step = index.step;
  d.time = index.time;
  d.largest_grain_radius = index.largest_grain_radius;
  d.first_section = first;
  d.n_sections = n;
  d.format_version = index.version;
  for (std::uint64_t k = first; k < last; ++k) {
    const std::uint64_t at = index.starts[k] - begin + 8; // past the length field
    const std::uint64_t length = index.starts[k + 1] - index.starts[k] - 8;
    if (last - first > 1) {
      d.sections.push_back(share.substr(at, length));
      continue;
    }
    share.erase(0, at); // one section (resuming on as many ranks): kept in place, not copied
    share.resize(length);
    d.sections.push_back(std::move(share));
  }
  return d;
}

} // namespace

CheckpointData parse_checkpoint(std::string bytes, const std::string& name) {
  CheckpointBytes source = CheckpointBytes::in_memory(std::move(bytes));
  return read_share(source, name, Comm::self());
}

CheckpointData read_checkpoint(const std::filesystem::path& file, const Comm& comm) {
  std::optional<CheckpointBytes> source;
  std::string error;
  try {
    source.emplace(CheckpointBytes::from_file(file));
  } catch (const CheckpointError& e) {
    error = e.what();
  }
  agree(comm, error);
  return read_share(*source, file.string(), comm);
}

CheckpointSet::CheckpointSet(std::filesystem::path run_folder, int keep)
    : folder_(std::move(run_folder) / "checkpoints"), keep_(std::max(keep, 1)) {}

std::filesystem::path CheckpointSet::path_for(std::int64_t step) const {
  return folder_ / fmt::format("checkpoint_{:012d}.yxc", step);
}

std::filesystem::path
CheckpointSet::write(const Comm& comm, std::int64_t step,
                     const std::function<void(const std::filesystem::path&)>& write_file) const {
  if (comm.root()) {
    std::filesystem::create_directories(folder_);
    for (const auto& e : std::filesystem::directory_iterator(folder_)) // left by a crash
      if (e.path().extension() == ".tmp") std::filesystem::remove(e.path());
  }
  comm.barrier(); // every rank opens the file in the folder rank 0 has made
  const std::filesystem::path file = path_for(step);
  write_file(file);
  if (!comm.root()) return file;
  const auto files = list();
  for (std::size_t k = static_cast<std::size_t>(keep_); k < files.size(); ++k)
    std::filesystem::remove(files[k]);
  return file;
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
CheckpointSet::newest_valid(const Comm& comm, std::vector<std::string>* warnings) const {
  // Rank 0's listing, on every rank: all ranks must try the same files in the same order.
  std::string names;
  if (comm.root())
    for (const auto& f : list()) names += f.string() + '\n';
  names = comm.broadcast(names);
  for (std::size_t at = 0, next; (next = names.find('\n', at)) != std::string::npos;
       at = next + 1) {
    const std::filesystem::path f = names.substr(at, next - at);
    try {
      return read_checkpoint(f, comm);
    } catch (const CheckpointError& e) {
      if (warnings) warnings->push_back(e.what());
    }
  }
  return std::nullopt;
}

} // namespace yuxi
