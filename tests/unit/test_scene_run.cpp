// A validation case's run folder: a long case continues from its checkpoint across sittings,
// also where its scene now ends later, and gives the bytes of one run straight to the end; a
// scene that differs otherwise starts afresh.
#include "io/scene_reader.hpp"
#include "validation/scene_run.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

namespace yuxi::validation {
namespace {

namespace fs = std::filesystem;

// Four grains dropped on a floor; `gravity` and `t_end` vary.
Scene dropping(double t_end, double gravity = -1.0) {
  std::string text = fmt::format(R"(materials = ["grain", "wall"]
[run]
name = "drop"
dt = 1.0e-3
t_end = {}
[output]
energy_interval = 0.05
snapshot_interval = 10.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [6.0, 6.0, 6.0]
gravity = [0.0, 0.0, {}]
boundary = ["wall", "wall", "wall"]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 1.0e4
gamma_n = 20.0
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 1.0e4
gamma_n = 20.0
)",
                                 t_end, gravity);
  for (int k = 0; k < 4; ++k)
    text += fmt::format("[[particle]]\nposition = [{}, 3.0, {}]\nradius = 0.5\nmass = 1.0\n"
                        "material = \"grain\"\n",
                        1.0 + 1.2 * k, 1.0 + 0.3 * k);
  return read_scene_text(text, "drop.toml");
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// As a case does: into a folder made for it (run_folder()).
void run(const Scene& scene, const fs::path& folder) {
  fs::create_directories(folder);
  run_scene(scene, folder, false);
}

class SceneRun : public ::testing::Test {
protected:
  fs::path dir = fs::temp_directory_path() / fmt::format("yuxi-scene-run-{}", ::getpid());
  void SetUp() override { fs::remove_all(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(SceneRun, ALaterEndContinuesTheSavedRunToTheBytesOfOneRun) {
  run(dropping(0.5), dir / "pieces");
  const std::string first = bytes(dir / "pieces" / "energies.csv");
  std::ofstream(dir / "pieces" / "mark") << "a fresh start empties the folder";
  run(dropping(1.0), dir / "pieces");
  EXPECT_TRUE(fs::exists(dir / "pieces" / "mark")); // continued, not run again
  run(dropping(1.0), dir / "whole");
  const std::string continued = bytes(dir / "pieces" / "energies.csv");
  EXPECT_EQ(continued.substr(0, first.size()), first); // the first sitting's rows are kept
  EXPECT_GT(continued.size(), first.size());
  EXPECT_EQ(continued, bytes(dir / "whole" / "energies.csv"));
}

TEST_F(SceneRun, AnotherSceneStartsAfresh) {
  run(dropping(0.5), dir / "run");
  std::ofstream(dir / "run" / "mark") << "a fresh start empties the folder";
  run(dropping(0.5, -2.0), dir / "run");
  EXPECT_FALSE(fs::exists(dir / "run" / "mark"));
  run(dropping(0.5, -2.0), dir / "fresh");
  EXPECT_EQ(bytes(dir / "run" / "energies.csv"), bytes(dir / "fresh" / "energies.csv"));
}

TEST_F(SceneRun, AnEarlierEndStartsAfresh) {
  run(dropping(1.0), dir / "run");
  std::ofstream(dir / "run" / "mark") << "a fresh start empties the folder";
  run(dropping(0.5), dir / "run");
  EXPECT_FALSE(fs::exists(dir / "run" / "mark"));
  run(dropping(0.5), dir / "fresh");
  EXPECT_EQ(bytes(dir / "run" / "energies.csv"), bytes(dir / "fresh" / "energies.csv"));
}

} // namespace
} // namespace yuxi::validation
