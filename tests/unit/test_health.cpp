// A contact that overlaps beyond max_overlap_ratio times the smaller radius stops the run with
// a diagnosis: the time step is too large for the stiffness, or the impact too fast.
#include "run/simulation_checkpoint.hpp"
#include "scene/clump_shape.hpp"
#include "sim/particle_diagnosis.hpp"
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
  // (k_n = 10: dt = t_c/700 resolves the contact; the grains meet at 20, too fast for it)
  EXPECT_NE(diagnosis.find("the contacts are too soft"), std::string::npos) << diagnosis;
  EXPECT_NE(diagnosis.find("its contacts: grain"), std::string::npos) << diagnosis;
  // It stops at the first step past the limit (overlap 0.5), the collective one drift later:
  // the grains close at 20 per unit time, 0.02 per step.
  const auto& s = sim.particles();
  const double overlap = 1.0 - norm(s.x[0] - s.x[1]);
  EXPECT_GT(overlap, 0.5);
  EXPECT_LT(overlap, 0.5 + 2 * 0.02);
}

// Where the time step does not resolve the contact, the diagnosis blames the time step.
TEST(Health, AnOverlapOfAStepTooLongBlamesTheTimeStep) {
  auto cfg = test::open_box(4.0, {0, 0, 0}, 1e-3);
  const std::vector<ParticleSpec> specs{test::sphere({0.95, 0, 0}, 0.5, 1.0, {300, 0, 0}),
                                        test::sphere({2.05, 0, 0}, 0.5, 1.0, {-300, 0, 0})};
  // k_n = 1e7: t_c = pi sqrt(0.5 / 1e7) = 7e-4, shorter than the step
  Simulation sim(cfg, test::store_of(specs), {}, {}, test::linear_law({1e7, 0, 0, 0, 0, 0}),
                 Comm::self());
  const std::string diagnosis = test::failure_of(sim, 10);
  EXPECT_NE(diagnosis.find("the time step is too large for the contact stiffness"),
            std::string::npos)
      << diagnosis;
  EXPECT_NE(diagnosis.find("dt = t_c/0.7"), std::string::npos) << diagnosis;
}

// A diagnosis names a member as its clump's, and lists no member of the same clump among its
// contacts (they overlap by construction, and never touch).
TEST(Health, ADiagnosisNamesAMembersClumpAndNotItsSiblings) {
  const ClumpShape rod = make_clump_shape(
      "rod", std::vector<SphereMember>{{{-0.5, 0, 0}, 0.5}, {{0, 0, 0}, 0.5}, {{0.5, 0, 0}, 0.5}});
  ParticleStore s;
  const PlacedClump c = make_clump(rod, 1.0, 0, 10, {0, 0, 0}, Quaternion{});
  for (std::size_t k = 0; k < c.members.size(); ++k)
    s.add(c.members[k], 10 + static_cast<GlobalId>(k));
  s.add(test::sphere({-0.5, 0.9, 0}, 0.5, 1.0), 20); // touches member 0
  const Box box{{-5, -5, -5}, {5, 5, 5}};
  const std::size_t first = 0; // (store order: the members, then the sphere)
  EXPECT_NE(describe_particle(s, first).find("grain 10 (member 0 of clump 10, radius"),
            std::string::npos)
      << describe_particle(s, first);
  const std::string contacts = describe_contacts(s, box, {}, 0.0, first);
  EXPECT_NE(contacts.find("grain 20"), std::string::npos) << contacts;
  EXPECT_EQ(contacts.find("grain 11"), std::string::npos) << contacts;
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

// A square lid that comes into existence at t = 0.05 over a grain at rest, overlapping it by
// 20 % of its radius: its spring's energy comes from nothing. The diagnosis names the wall, the
// triangle and the grain, and does not blame the time step.
TEST(Health, EnergyFromAWallsContactsNamesTheWallNotTheTimeStep) {
  auto cfg = test::open_box(4.0, {0, 0, 0}, 1e-3);
  const double z = 0.4; // the lid's height: the grain (radius 0.5 at the origin) overlaps it by 0.1
  MeshWall lid;
  lid.name = "lid";
  lid.mesh = TriangleMesh::weld({{{Vec3{-2, -2, z}, Vec3{2, -2, z}, Vec3{2, 2, z}}},
                                 {{Vec3{-2, -2, z}, Vec3{2, 2, z}, Vec3{-2, 2, z}}}});
  lid.active.from = 0.05;
  Simulation sim(cfg, test::store_of({test::sphere({0, 0, 0}, 0.5, 1.0)}), {}, {},
                 test::linear_law({1e4, 0, 0, 0, 0, 0}), Comm::self(), {lid});
  const std::string diagnosis = test::failure_of(sim, 2000);
  EXPECT_NE(diagnosis.find("began already deep"), std::string::npos) << diagnosis;
  EXPECT_NE(diagnosis.find("on wall 'lid', triangle "), std::string::npos) << diagnosis;
  EXPECT_NE(diagnosis.find("against grain 0, overlapping it by 0.1 "), std::string::npos)
      << diagnosis;
  EXPECT_NE(diagnosis.find("began at t = 0.05"), std::string::npos) << diagnosis;
  EXPECT_EQ(diagnosis.find("time step is too large"), std::string::npos) << diagnosis;
}

TEST(Health, AnInitialOverlapBeyondTheLimitIsRefused) {
  EXPECT_THROW(test::head_on(0.4), SimulationError);
}

} // namespace
} // namespace yuxi
