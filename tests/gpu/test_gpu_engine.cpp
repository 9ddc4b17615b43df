// The device engine on a GPU against its host build, bit for bit (label "gpu"; built with
// -DYUXI_CUDA=ON). Each test skips, saying why, where no CUDA GPU is found. The chute under every
// contact law, rods of three spheres (clumps), the small basin's shaking wall particles and
// escapes, and a whole run through the RunDriver: the same particles, clumps, books and
// energies.csv bytes on both sides.
#include "io/scene_reader.hpp"
#include "run/device_run.hpp"
#include "run/run_driver.hpp"
#include "run/run_opening.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"
#include "small_basin.hpp"
#include "temp_folder.hpp"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace yuxi {
namespace {

namespace fs = std::filesystem;

// The shipped scenes: where the environment's YUXI_SCENES_DIR says (a build taken to a GPU
// machine), else in the source tree it was built from.
std::string scene_path(const std::string& name) {
  const char* dir = std::getenv("YUXI_SCENES_DIR");
  return std::string(dir ? dir : YUXI_SCENES_DIR) + "/" + name;
}

std::string scene_text(const std::string& name) {
  std::ifstream in(scene_path(name));
  if (!in) throw std::runtime_error("no scene " + scene_path(name));
  return {std::istreambuf_iterator<char>(in), {}};
}

std::unique_ptr<Simulation> simulation_of(const std::string& text, const std::string& name) {
  Scene scene = read_scene_text(text, scene_path(name));
  return build_simulation(scene, false);
}

// The GPU's engine, or nothing where this machine has no CUDA GPU.
std::unique_ptr<device::DeviceEngine> gpu_engine(const Simulation& sim) {
  try {
    return make_device_engine(sim, DeviceChoice::cuda);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find("no CUDA GPU") == std::string::npos) throw;
    return nullptr;
  }
}

template <class T> bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// `steps` steps of `sim`'s state on the GPU and in the host build: every particle's position,
// velocity, angular velocity and force, and every book, to the bit.
void expect_gpu_equals_host(const Simulation& sim, std::int64_t steps) {
  const auto gpu = gpu_engine(sim);
  if (!gpu) GTEST_SKIP() << "no CUDA GPU on this machine";
  const auto host = make_device_engine(sim, DeviceChoice::host);
  gpu->run(steps);
  host->run(steps);
  const device::HostParticles g = gpu->particles(), h = host->particles();
  ASSERT_EQ(g.size(), h.size());
  EXPECT_TRUE(same_bytes(g.gid, h.gid));
  EXPECT_TRUE(same_bytes(g.x, h.x));
  EXPECT_TRUE(same_bytes(g.v, h.v));
  EXPECT_TRUE(same_bytes(g.w, h.w));
  EXPECT_TRUE(same_bytes(g.f, h.f));
  const device::DeviceEnergies eg = gpu->energies(), eh = host->energies();
  EXPECT_EQ(std::memcmp(&eg, &eh, sizeof eg), 0) << "the books differ";
  EXPECT_EQ(gpu->list_builds(), host->list_builds());
  const std::vector<device::DeviceClump> cg = gpu->clumps(), ch = host->clumps();
  ASSERT_EQ(cg.size(), ch.size());
  for (std::size_t c = 0; c < cg.size(); ++c) {
    const device::DeviceClump &a = cg[c], &b = ch[c];
    const bool same = a.id == b.id && a.x == b.x && a.v == b.v && a.q == b.q && a.p == b.p &&
                      a.force == b.force && a.torque == b.torque;
    ASSERT_TRUE(same) << "clump " << b.id << " differs";
  }
}

TEST(GpuEngine, ChuteIsTheHostBuildsToTheBit) {
  const auto sim = simulation_of(scene_text("chute-lammps.toml"), "chute-lammps.toml");
  expect_gpu_equals_host(*sim, 1000);
}

class GpuEngineLaw : public testing::TestWithParam<const char*> {};

TEST_P(GpuEngineLaw, ChuteIsTheHostBuildsToTheBit) {
  const std::string name = std::string("chute-laws/chute-") + GetParam() + ".toml";
  const auto sim = simulation_of(scene_text(name), name);
  expect_gpu_equals_host(*sim, 300);
}

INSTANTIATE_TEST_SUITE_P(Laws, GpuEngineLaw, testing::Values("hooke", "hertz", "luding", "thermo"),
                         [](const testing::TestParamInfo<const char*>& law) {
                           return std::string(law.param);
                         });

// Rods of three spheres settling in a periodic box, their members across its faces (clumps'
// phases: their loads, NO_SQUISH's turns, the members' images), on both sides.
TEST(GpuEngine, RodBedIsTheHostBuildsToTheBit) {
  const auto sim = simulation_of(scene_text("clumps/rod-bed.toml"), "clumps/rod-bed.toml");
  expect_gpu_equals_host(*sim, 6000);
}

// The small basin settled by the CPU engine, then its wall shaking and throwing grains out
// (removed), on both sides.
TEST(GpuEngine, ShakenBasinIsTheHostBuildsToTheBit) {
  Scene scene = read_scene_text(test::small_basin(scene_text("basin-small.toml")),
                                scene_path("basin-small.toml"));
  scene.sim.on_escape = EscapePolicy::remove;
  const auto sim = build_simulation(scene, false);
  sim->run(31000);
  expect_gpu_equals_host(*sim, 5000);
}

// A whole run through the RunDriver on each side: energies.csv byte for byte.
TEST(GpuRun, RunFolderIsTheHostBuildsByteForByte) {
  const fs::path dir = test::temp_dir("gpu_run");
  std::string text = scene_text("chute-lammps.toml");
  text.replace(text.find("t_end = 1.0 "), 12, "t_end = 0.1 ");
  std::string csv[2];
  for (const bool on_gpu : {true, false}) {
    OpenedRun run = open_scene(read_scene_text(text, scene_path("chute-lammps.toml")), false);
    RunOptions options;
    options.output_dir = dir / (on_gpu ? "gpu" : "host");
    options.scene_text = run.scene_text;
    options.device = on_gpu ? DeviceChoice::cuda : DeviceChoice::host;
    fs::create_directories(options.output_dir);
    try {
      const RunSummary s = run_to_end(run.scene, *run.sim, options);
      ASSERT_FALSE(s.failed) << s.failure;
    } catch (const std::runtime_error& e) {
      if (on_gpu && std::string(e.what()).find("no CUDA GPU") != std::string::npos)
        GTEST_SKIP() << "no CUDA GPU on this machine";
      throw;
    }
    std::ifstream in(options.output_dir / "energies.csv");
    std::stringstream all;
    all << in.rdbuf();
    csv[on_gpu ? 0 : 1] = all.str();
  }
  EXPECT_GT(csv[0].size(), 1000u);
  EXPECT_EQ(csv[0], csv[1]);
  fs::remove_all(dir);
}

} // namespace
} // namespace yuxi
