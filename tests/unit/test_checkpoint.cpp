// Checkpoints: a run of 2N steps and a run of N steps, saved, loaded and run N more reach the
// same state byte for byte; damaged checkpoint files are refused with messages that name the
// file and the problem, and the newest valid one is used.
#include "core/archive.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "run/scene_builder.hpp"
#include "run/simulation_checkpoint.hpp"
#include "temp_folder.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <ostream>
#include <unistd.h>
#include <zlib.h>

namespace yuxi {
namespace {

namespace fs = std::filesystem;

Scene reliability_scene() {
  return read_scene_file(YUXI_RELIABILITY_DIR "/basin.toml");
}

// Steps to `target`, saving the state after every multiple of `every` as the run driver does
// (saving must change nothing).
void run_to(Simulation& sim, std::int64_t target, std::int64_t every) {
  while (sim.step_count() < target) {
    sim.step();
    if (sim.step_count() % every == 0) {
      ArchiveWriter ar;
      sim.save_state(ar);
    }
  }
}

std::string state_bytes(Simulation& sim) {
  ArchiveWriter ar;
  sim.save_state(ar);
  return ar.data();
}

TEST(Checkpoint, ResumedRunMatchesTheUninterruptedOneByteForByte) {
  const Scene scene = reliability_scene();
  // Mid-flight (falling, landing, shaken walls), at a step that is no list build: the
  // uninterrupted run saves its state at other steps, or never.
  const std::int64_t n = 17001, every = 1000;
  auto straight = build_simulation(scene, false);
  run_to(*straight, 2 * n, every);
  auto unsaved = build_simulation(scene, false);
  unsaved->run(2 * n);

  auto first = build_simulation(scene, false);
  run_to(*first, n, every);
  ArchiveWriter saved;
  first->save_state(saved);
  auto resumed = build_simulation(scene, false);
  resumed->load({{saved.data()}, 1});
  run_to(*resumed, 2 * n, every);
  // Built straight from the state, as `yuxi run --resume` does.
  auto built = continue_simulation(scene, {{saved.data()}, 1}, std::nullopt, false);
  EXPECT_EQ(built->step_count(), n);
  run_to(*built, 2 * n, every);

  ASSERT_GT(straight->energies().dissipated, 0.0); // contacts have happened
  EXPECT_EQ(state_bytes(*straight), state_bytes(*resumed));
  EXPECT_EQ(state_bytes(*straight), state_bytes(*built));
  EXPECT_EQ(state_bytes(*straight), state_bytes(*unsaved));
  EXPECT_EQ(straight->energies().balance(), resumed->energies().balance());
}

// A run continued from a state never makes the scene's own initial particles: a branch under a
// scene whose fill could not be placed at t = 0 (the checkpoint's grains take the fills' place)
// runs, where building that scene from its start is refused.
TEST(Checkpoint, AContinuedRunNeverPlacesTheScenesOwnGrains) {
  const Scene scene = reliability_scene();
  auto first = build_simulation(scene, false);
  first->run(2000);
  ArchiveWriter saved;
  first->save_state(saved);
  std::ifstream in(YUXI_RELIABILITY_DIR "/basin.toml");
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  const Scene crowded = read_scene_text(
      text + "\n[[fill]]\nmaterial = \"grain\"\ndensity = 1.0\ncount = 100000\nseed = 1\n"
             "size = { distribution = \"uniform\", min = 0.9, max = 1.1 }\n"
             "region = { shape = \"box\", lo = [1.0, 1.0, 300.0], hi = [9.0, 9.0, 309.0] }\n",
      YUXI_RELIABILITY_DIR "/crowded.toml");
  EXPECT_THROW(build_simulation(crowded, false), SceneError);
  const auto branched = continue_simulation(
      crowded, {{saved.data()}, 1}, Simulation::BranchCheck{fish_basin_walls(*scene.basin)}, false);
  EXPECT_EQ(branched->step_count(), 2000);
  EXPECT_EQ(branched->gather_particles().n_owned(), first->gather_particles().n_owned());
  branched->run(100);
}

// A state whose cells are smaller than the scene it is resumed under would make (another
// scene's, or a crafted file's: a grid of billions of cells) is refused, naming both.
TEST(Checkpoint, AStateWithCellsSmallerThanTheScenesIsRefused) {
  const Scene scene = reliability_scene(); // cell_size = 3.6
  auto first = build_simulation(scene, false);
  first->run(1000);
  ArchiveWriter saved;
  first->save_state(saved);
  Scene wider = scene;
  wider.sim.cell_size = 5.0;
  try {
    continue_simulation(wider, {{saved.data()}, 1}, std::nullopt, false);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the checkpoint's cells (edge 3.6"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("are not this scene's (edge at least 5"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(continue_simulation(scene, {{saved.data()}, 1}, std::nullopt, false));
}

using test::temp_dir;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

struct Damage {
  const char* what;
  std::string (*apply)(std::string);
  const char* expected;
};
// ctest lists a case by its name and this, not by a dump of the parameter's bytes.
void PrintTo(const Damage& c, std::ostream* os) {
  *os << c.what;
}

class DamagedCheckpoint : public ::testing::TestWithParam<Damage> {};

TEST_P(DamagedCheckpoint, IsRefusedWithAClearMessage) {
  const Scene scene = reliability_scene();
  auto sim = build_simulation(scene, false);
  run_to(*sim, 1000, 1000);
  const auto dir = temp_dir("damage");
  write_checkpoint(dir / "c.yxc", resolved_scene_toml(scene), *sim);
  const std::string good = slurp(dir / "c.yxc");
  EXPECT_NO_THROW(parse_checkpoint(good, "c.yxc"));
  try {
    parse_checkpoint(GetParam().apply(good), "c.yxc");
    FAIL() << GetParam().what << ": accepted";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find(GetParam().expected), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("c.yxc: ", 0), 0u) << "names the file: " << e.what();
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Table, DamagedCheckpoint,
    ::testing::Values(
        Damage{"truncated", [](std::string b) { return b.substr(0, b.size() / 2); },
               "truncated: the header announces"},
        Damage{"flipped bit",
               [](std::string b) {
                 b[b.size() / 2] ^= 0x10;
                 return b;
               },
               "checksum mismatch: the file is corrupt"},
        Damage{"wrong version",
               [](std::string b) {
                 b[8] = 99;
                 return b;
               },
               "checkpoint format version 99; this yuxi reads versions 5 to"},
        Damage{"not a checkpoint", [](std::string) { return std::string("hello, world: no"); },
               "not a yuxi checkpoint"},
        Damage{"empty", [](std::string) { return std::string(); }, "not a yuxi checkpoint"},
        Damage{"trailing bytes", [](std::string b) { return b + "xx"; }, "trailing bytes"}),
    [](const ::testing::TestParamInfo<Damage>& p) {
      std::string n = p.param.what;
      for (auto& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

// An intact file that holds no rank's state (crafted: a run always writes at least one) is
// refused, not loaded as an empty system.
TEST(Checkpoint, AFileWithNoRanksStateIsRefused) {
  ArchiveWriter head;
  std::string scene;
  std::int64_t step = 10;
  double time = 1.0, largest_grain_radius = 0.5;
  std::uint64_t sections = 0;
  head.string(scene);
  head.value(step);
  head.value(time);
  head.value(largest_grain_radius);
  head.value(sections);
  const std::string payload = head.release();
  std::string bytes = "YUXICKPT";
  const auto put = [&bytes](const auto& v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  };
  put(checkpoint_format_version);
  put(std::uint32_t{0x01020304});
  put(static_cast<std::uint64_t>(payload.size()));
  bytes += payload;
  put(static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(payload.data()), static_cast<uInt>(payload.size()))));
  const CheckpointData data = parse_checkpoint(bytes, "c.yxc");
  EXPECT_EQ(data.n_sections, 0u);
  auto sim = build_simulation(reliability_scene(), false);
  try {
    apply_checkpoint(data, *sim);
    FAIL() << "accepted";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("c.yxc: no rank's state in the file"), std::string::npos)
        << e.what();
  }
}

TEST(Checkpoint, ACorruptNewestCheckpointFallsBackToThePreviousOne) {
  const Scene scene = reliability_scene();
  auto sim = build_simulation(scene, false);
  const auto dir = temp_dir("set");
  CheckpointSet set(dir, 3);
  for (int k = 1; k <= 4; ++k) {
    run_to(*sim, 1000 * k, 1000);
    write_checkpoint(set, resolved_scene_toml(scene), *sim);
  }
  ASSERT_EQ(set.list().size(), 3u); // keeps the newest three
  {
    std::fstream f(set.path_for(4000), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x5a');
  }
  std::vector<std::string> refused;
  const auto data = set.newest_valid(Comm::self(), &refused);
  ASSERT_TRUE(data.has_value());
  EXPECT_EQ(data->step, 3000);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_NE(refused[0].find("checkpoint_000000004000.yxc: checksum mismatch"), std::string::npos)
      << refused[0];
  fs::remove_all(dir);
}

} // namespace
} // namespace yuxi
