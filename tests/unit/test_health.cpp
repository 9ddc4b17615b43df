// A contact that overlaps beyond max_overlap_ratio times the smaller radius stops the run with
// a diagnosis: the time step is too large for the stiffness, or the impact too fast.
#include "io/checkpoint_file.hpp"
#include "temp_folder.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <string>

namespace yuxi {
namespace {

TEST(Health, AnOverlapBeyondTheLimitStopsTheRunWithADiagnosis) {
  Simulation sim = test::head_on(1.1);
  const std::string diagnosis = test::failure_of(sim, 1000);
  EXPECT_NE(diagnosis.find("overlap of"), std::string::npos) << diagnosis;
  EXPECT_NE(diagnosis.find("time step is too large"), std::string::npos) << diagnosis;
  EXPECT_NE(diagnosis.find("its contacts: grain"), std::string::npos) << diagnosis;
  // It stops at the first step past the limit (overlap 0.5), the collective one drift later:
  // the grains close at 20 per unit time, 0.02 per step.
  const auto& s = sim.particles();
  const double overlap = 1.0 - norm(s.x[0] - s.x[1]);
  EXPECT_GT(overlap, 0.5);
  EXPECT_LT(overlap, 0.5 + 2 * 0.02);
}

TEST(Health, NoCheckpointKeepsAnOverlapBeyondTheLimit) {
  Simulation sim = test::head_on(1.1);
  const auto& s = sim.particles();
  // Up to the step whose forces found the overlap; it stops the run at the next collective.
  while (1.0 - norm(s.x[0] - s.x[1]) <= 0.5) sim.step();
  const auto file = test::temp_dir("health") / "c.yxc";
  EXPECT_THROW(write_checkpoint(file, "", sim), SimulationError);
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(Health, AnInitialOverlapBeyondTheLimitIsRefused) {
  EXPECT_THROW(test::head_on(0.4), SimulationError);
}

} // namespace
} // namespace yuxi
