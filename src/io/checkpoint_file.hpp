// Checkpoint files: a run's whole state, written atomically and checked when read.
//
// Layout: "YUXICKPT" | u32 format version | u32 byte-order mark 0x01020304 | u64 payload size |
// payload | u32 CRC-32 of the payload (zlib). The payload holds the resolved scene (TOML), the
// step and time, the largest grain's radius (from format 8), and one section per MPI rank with
// that rank's Simulation::save_state(). Every
// rank writes its own section, and reads only its share back: rank 0 reads the head and where
// the sections start, each rank reads its sections, and the CRC of the whole is combined from
// the ranks' CRCs of what they read. A run resumed on the same number of ranks takes each
// rank's own section and continues bit for bit; on another number the ranks share out the
// sections and the particles and contact states are redistributed (Simulation::load): correct,
// not bitwise. Files are written to a temporary name, flushed to disk (fsync) and renamed, so a
// crash at any moment leaves either the previous checkpoint or the new one, never half of one.
#pragma once

#include "domain/comm.hpp"
#include "sim/state_layout.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace yuxi {

// The format version a checkpoint is written in: the layout of Simulation::save_state. Files
// of older layouts down to oldest_state_layout are read too.
inline constexpr std::uint32_t checkpoint_format_version = state_layout;

class CheckpointError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// What the head of a checkpoint says besides the sections.
struct CheckpointHead {
  std::string scene_text; // the resolved scene
  std::int64_t step = 0;
  double time = 0;
  double largest_grain_radius = 0; // the cells of a branch whose scene builds no grain
};

// Collective: writes `file` atomically with the head (rank 0's) and every rank's `section`
// (a simulation's saved state: run/simulation_checkpoint.hpp writes a simulation's).
void write_checkpoint_file(const std::filesystem::path& file, const Comm& comm,
                           const CheckpointHead& head, const std::string& section);

// A verified checkpoint's head and this rank's share of its sections, not yet applied to a
// simulation.
struct CheckpointData {
  std::filesystem::path file;
  std::string scene_text;
  std::int64_t step = 0;
  double time = 0;
  // The largest grain's radius in the saved state (NaN in files before format 8): the cells of
  // a branch whose scene builds no grain.
  double largest_grain_radius = NAN;
  // Simulation::save_state of ranks first_section, first_section + 1, ... of the run that wrote
  // the file, which had n_sections ranks. On as many ranks, each rank's share is its own
  // section; on others, a block of consecutive sections (possibly none).
  std::vector<std::string> sections;
  std::uint64_t first_section = 0;
  std::uint64_t n_sections = 0;
  std::uint32_t format_version = checkpoint_format_version;
};

// Collective: reads and verifies a checkpoint, each rank its share of the sections; throws
// CheckpointError on every rank, naming the file and the problem.
CheckpointData read_checkpoint(const std::filesystem::path& file, const Comm& comm);
// Verifies checkpoint bytes (for the fuzzer and tests), with every section as the share;
// `name` labels the messages.
CheckpointData parse_checkpoint(std::string bytes, const std::string& name);

// The checkpoints of a run folder: `<run>/checkpoints/checkpoint_<step>.yxc`.
class CheckpointSet {
public:
  explicit CheckpointSet(std::filesystem::path run_folder, int keep = 3);
  std::filesystem::path path_for(std::int64_t step) const;
  // Collective: writes the checkpoint of `step` through `write_file(path)` (every rank calls
  // it, once the folder exists) and removes the oldest beyond `keep`; returns the file.
  std::filesystem::path
  write(const Comm& comm, std::int64_t step,
        const std::function<void(const std::filesystem::path&)>& write_file) const;
  // Files present, newest first.
  std::vector<std::filesystem::path> list() const;
  // Collective: the newest checkpoint that verifies (rank 0's listing of the folder); each
  // refused one is reported through `warnings`.
  std::optional<CheckpointData> newest_valid(const Comm& comm,
                                             std::vector<std::string>* warnings) const;

private:
  std::filesystem::path folder_;
  int keep_;
};

} // namespace yuxi
