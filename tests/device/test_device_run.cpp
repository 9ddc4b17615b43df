// A whole run on the device engine (RunOptions::device, `yuxi run --device`), in its host build,
// on LAMMPS's chute cut to 300 steps: the run folder holds what the CPU engine's holds, with the
// same books to 1e-9; a checkpoint written on the device resumes on the device bit for bit, and on
// the CPU engine (and the CPU engine's on the device) as a correct continuation. And the small
// basin's [analysis] on the device against the CPU engine's. Label "device".
#include "io/scene_reader.hpp"
#include "run/run_driver.hpp"
#include "run/run_opening.hpp"
#include "small_basin.hpp"
#include "temp_folder.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace yuxi {
namespace {

namespace fs = std::filesystem;

// The chute for 300 steps, a row of energies.csv and a frame every 100, a checkpoint every 150;
// `extra` is added to its text.
Scene short_chute(const std::string& extra = "") {
  const std::string path = YUXI_SCENES_DIR "/chute-lammps.toml";
  std::ifstream in(path);
  std::string text{std::istreambuf_iterator<char>(in), {}};
  const auto replace = [&text](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("no " + from + " in the chute");
    text.replace(at, from.size(), to);
  };
  replace("t_end = 1.0 ", "t_end = 0.03 ");
  replace("snapshot_interval = 0.0 ", "snapshot_interval = 0.01 ");
  text += "\n[checkpoint]\nevery_steps = 150\nevery_minutes = 0\nkeep = 5\n" + extra;
  return read_scene_text(text, path);
}

struct Finished {
  std::unique_ptr<Simulation> sim;
  RunSummary summary;
};

// Runs `opened` to its end into `dir`, on the device engine's host build or the CPU engine.
Finished run_into(OpenedRun opened, const fs::path& dir, bool on_device) {
  RunOptions options;
  options.output_dir = dir;
  options.scene_text = opened.scene_text;
  if (on_device) options.device = DeviceChoice::host;
  fs::create_directories(dir);
  Finished f;
  f.summary = run_to_end(opened.scene, *opened.sim, options);
  f.sim = std::move(opened.sim);
  return f;
}

std::vector<std::vector<double>> csv_rows(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line); // the header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// Every value of each row of `a` within `relative` of the largest of its column in `b`, against
// the row of `b` of the same step (a run continued from a checkpoint starts its file there, at a
// step the other may have no row of).
void expect_rows_agree(const fs::path& a, const fs::path& b, double relative) {
  const auto ra = csv_rows(a), rb = csv_rows(b);
  ASSERT_FALSE(rb.empty());
  std::size_t compared = 0;
  for (const auto& row : ra)
    for (const auto& other : rb) {
      if (other[0] != row[0]) continue;
      ++compared;
      for (std::size_t c = 0; c < row.size(); ++c) {
        double scale = 0.0;
        for (const auto& r : rb) scale = std::max(scale, std::abs(r[c]));
        EXPECT_LE(std::abs(row[c] - other[c]), relative * scale)
            << "step " << row[0] << ", column " << c << " of " << a;
      }
    }
  EXPECT_GE(compared, 2u) << a << " and " << b << " share fewer than two steps";
}

// The particles' dynamic state, bit for bit.
void expect_same_bits(const Simulation& a, const Simulation& b) {
  const ParticleStore pa = a.gather_particles(), pb = b.gather_particles();
  ASSERT_EQ(pa.n_owned(), pb.n_owned());
  const auto same = [&](const std::vector<Vec3>& u, const std::vector<Vec3>& v) {
    return std::memcmp(u.data(), v.data(), pa.n_owned() * sizeof(Vec3)) == 0;
  };
  EXPECT_TRUE(same(pa.x, pb.x));
  EXPECT_TRUE(same(pa.v, pb.v));
  EXPECT_TRUE(same(pa.w, pb.w));
  EXPECT_TRUE(same(pa.f, pb.f));
  EXPECT_EQ(a.step_count(), b.step_count());
}

fs::path checkpoint_at(const fs::path& run, int step) {
  char name[64];
  std::snprintf(name, sizeof name, "checkpoint_%012d.yxc", step);
  return run / "checkpoints" / name;
}

class DeviceRun : public testing::Test {
protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::temp_dir("device_run"));
    cpu_ = new Finished(run_into(open_scene(short_chute(), false), *dir_ / "cpu", false));
    device_ = new Finished(run_into(open_scene(short_chute(), false), *dir_ / "device", true));
  }
  static void TearDownTestSuite() {
    delete cpu_;
    delete device_;
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path* dir_;
  static Finished *cpu_, *device_;
};
fs::path* DeviceRun::dir_ = nullptr;
Finished* DeviceRun::cpu_ = nullptr;
Finished* DeviceRun::device_ = nullptr;

TEST_F(DeviceRun, WritesTheCpuEnginesFilesWithTheSameBooks) {
  ASSERT_FALSE(device_->summary.failed) << device_->summary.failure;
  EXPECT_EQ(device_->summary.steps, 300);
  EXPECT_EQ(device_->summary.device, "host (Thrust CPP)");
  EXPECT_GT(device_->summary.device_bytes_per_particle, 0.0);
  for (const char* file :
       {"energies.csv", "particles.pvd", "particles_000000300.vtu", "particles.lammpstrj"})
    EXPECT_TRUE(fs::exists(*dir_ / "device" / file)) << file;
  for (int step : {150, 300}) EXPECT_TRUE(fs::exists(checkpoint_at(*dir_ / "device", step)));
  expect_rows_agree(*dir_ / "device" / "energies.csv", *dir_ / "cpu" / "energies.csv", 1e-9);
  // The contacts counted as the CPU engine counts them.
  const auto rows = csv_rows(*dir_ / "device" / "energies.csv");
  const auto cpu_rows = csv_rows(*dir_ / "cpu" / "energies.csv");
  EXPECT_EQ(rows.back()[15], cpu_rows.back()[15]);
  EXPECT_GT(rows.back()[15], 10000);
}

// A [[coarse_grain]] table of kinetic fields runs on the device engine (which records no
// contacts) and writes the CPU engine's fields; one that needs the contacts is refused there,
// with a message that names it.
TEST(DeviceRunCoarseGraining, KineticFieldsRunOnTheDeviceAndContactFieldsAreRefused) {
  const fs::path dir = test::temp_dir("device_run_cg");
  const auto with_table = [](const std::string& fields) {
    return short_chute("\n[[coarse_grain]]\nname = \"flow\"\nwidth = 1.0\naverage = \"xy\"\n"
                       "n = [1, 1, 80]\ninterval = 0.01\nfields = [" +
                       fields + "]\n");
  };
  const std::string kinetic = "\"density\", \"velocity\", \"temperature\"";
  const Finished cpu = run_into(open_scene(with_table(kinetic), false), dir / "cpu", false);
  const Finished device = run_into(open_scene(with_table(kinetic), false), dir / "device", true);
  ASSERT_FALSE(cpu.summary.failed || device.summary.failed);
  // The run times its samples (the log's "coarse-graining X%"): within its wall time.
  for (const RunSummary* s : {&cpu.summary, &device.summary}) {
    EXPECT_GT(s->coarse_grain_seconds, 0.0);
    EXPECT_LT(s->coarse_grain_seconds, s->wall_seconds);
  }
  for (const char* step : {"000000100", "000000300"}) {
    const std::string name = std::string("coarse_grain/flow/flow_") + step + ".csv";
    const auto a = csv_rows(dir / "device" / name), b = csv_rows(dir / "cpu" / name);
    ASSERT_EQ(a.size(), 80u) << name;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      for (std::size_t c = 0; c < a[k].size(); ++c)
        EXPECT_NEAR(a[k][c], b[k][c], 1e-9 * (1.0 + std::abs(b[k][c]))) << name << " row " << k;
  }
  try {
    run_into(open_scene(with_table("\"density\", \"stress\""), false), dir / "refused", true);
    ADD_FAILURE() << "a table of the stress ran on the device engine";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("[[coarse_grain]] 'flow'"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST_F(DeviceRun, ItsCheckpointResumesOnTheDeviceBitForBit) {
  Finished resumed =
      run_into(open_branch(short_chute(), checkpoint_at(*dir_ / "device", 150), false),
               *dir_ / "device-resumed", true);
  ASSERT_FALSE(resumed.summary.failed) << resumed.summary.failure;
  EXPECT_EQ(resumed.summary.steps, 150);
  expect_same_bits(*resumed.sim, *device_->sim);
  expect_rows_agree(*dir_ / "device-resumed" / "energies.csv", *dir_ / "device" / "energies.csv",
                    0.0);
}

TEST_F(DeviceRun, CheckpointsCarryOnAcrossEngines) {
  // The device's state continued on the CPU engine, and the CPU engine's on the device: each
  // agrees with the other engine's run straight through to round-off.
  Finished on_cpu =
      run_into(open_branch(short_chute(), checkpoint_at(*dir_ / "device", 150), false),
               *dir_ / "device-then-cpu", false);
  Finished on_device =
      run_into(open_branch(short_chute(), checkpoint_at(*dir_ / "cpu", 150), false),
               *dir_ / "cpu-then-device", true);
  ASSERT_FALSE(on_cpu.summary.failed || on_device.summary.failed);
  expect_rows_agree(*dir_ / "device-then-cpu" / "energies.csv", *dir_ / "device" / "energies.csv",
                    1e-9);
  expect_rows_agree(*dir_ / "cpu-then-device" / "energies.csv", *dir_ / "cpu" / "energies.csv",
                    1e-9);
}

// The tokens of a CSV file, line by line.
std::vector<std::vector<std::string>> csv_tokens(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> lines;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) cells.push_back(cell);
    lines.push_back(cells);
  }
  return lines;
}

// Every CSV file the CPU engine's analysis wrote, written by the device engine too, line for
// line: words equal, numbers within `relative` of the largest of their column.
void expect_same_analysis(const fs::path& cpu, const fs::path& device, double relative) {
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(cpu)) {
    if (entry.path().extension() != ".csv") continue;
    ++files;
    const fs::path other = device / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    const auto a = csv_tokens(entry.path()), b = csv_tokens(other);
    ASSERT_EQ(a.size(), b.size()) << other;
    std::vector<double> scale;
    for (const auto& row : a)
      for (std::size_t c = 0; c < row.size(); ++c) {
        scale.resize(std::max(scale.size(), row.size()), 0.0);
        char* end = nullptr;
        const double x = std::strtod(row[c].c_str(), &end);
        if (end != row[c].c_str()) scale[c] = std::max(scale[c], std::abs(x));
      }
    for (std::size_t r = 0; r < a.size(); ++r) {
      ASSERT_EQ(a[r].size(), b[r].size()) << other << " line " << r;
      for (std::size_t c = 0; c < a[r].size(); ++c) {
        char *end_a = nullptr, *end_b = nullptr;
        const double x = std::strtod(a[r][c].c_str(), &end_a);
        const double y = std::strtod(b[r][c].c_str(), &end_b);
        if (end_a == a[r][c].c_str() || end_b == b[r][c].c_str() || std::isnan(x) || std::isnan(y))
          EXPECT_EQ(a[r][c], b[r][c]) << other << " line " << r;
        else
          EXPECT_LE(std::abs(x - y), relative * scale[c])
              << other << " line " << r << " column " << c;
      }
    }
  }
  EXPECT_GE(files, 5u) << "the analysis wrote few files: " << cpu;
}

// The small basin of tests/small_basin.hpp with its [analysis] moved to its shaking (from
// t = 3.2): surfaces, a velocity section, elastic maps and the first period's averages, to
// t = 3.24.
Scene shaken_small_basin() {
  const std::string path = YUXI_SCENES_DIR "/basin-small.toml";
  std::ifstream in(path);
  std::string text = test::small_basin(std::string{std::istreambuf_iterator<char>(in), {}});
  const test::SceneEdit edits[] = {
      {R"(t_end = 11\.0 )", "t_end = 3.24 "},
      {R"(surface_times = \[[^\]]*\])", "surface_times = [3.21, 3.23]"},
      {R"(velocity_times = \[[^\]]*\])", "velocity_times = [3.22]"},
      {R"(elastic_map_times = \[[^\]]*\])", "elastic_map_times = [3.202, 3.21]"},
  };
  return read_scene_text(test::edited_scene(std::move(text), edits), path);
}

// The fish-basin analysis on the device engine: its samples are where the CPU engine's are, and
// the per-grain elastic energies come from the device's contacts. Both engines start from the
// same bed, settled by the CPU engine to t = 3.19; the files agree to 1e-6.
TEST(DeviceRunAnalysis, WritesTheCpuEnginesAnalysis) {
  const fs::path dir = test::temp_dir("device_analysis");
  std::vector<fs::path> analysis;
  for (const bool on_device : {false, true}) {
    OpenedRun basin = open_scene(shaken_small_basin(), false);
    basin.sim->run(31900);
    const fs::path out = dir / (on_device ? "device" : "cpu");
    const Finished f = run_into(std::move(basin), out, on_device);
    ASSERT_FALSE(f.summary.failed) << f.summary.failure;
    analysis.push_back(out / "analysis");
  }
  expect_same_analysis(analysis[0], analysis[1], 1e-6);
  fs::remove_all(dir);
}

} // namespace
} // namespace yuxi
