// Rigid clumps of spheres on the device engine's host build, against the CPU engine
// (docs/clumps.md; docs/ARCHITECTURE.md, "The device engine"): rods settling in a box periodic
// along x and y, whose members stand across the periodic faces with their clumps; clumps thrown
// out of an open box, which leave whole; and a run handed to the host and started again, which
// goes on to the bit. (A scene whose members and clumps contradict each other:
// test_device_engine.cpp, RefusesAContradictoryScene.) Label "device".
#include "device/device_engine.hpp"
#include "io/scene_reader.hpp"
#include "run/device_run.hpp"
#include "run/device_stepper.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>

namespace yuxi {
namespace {

// scenes/clumps/rod-bed.toml: rods of three spheres and plain spheres dropped onto a plane in a
// box periodic along x and y; with `throw_out`, a taller box whose top lets grains out (as
// `on_escape` says), without the spheres, and gravity `gravity`.
std::unique_ptr<Simulation> rod_bed(bool throw_out = false, const std::string& on_escape = "remove",
                                    const std::string& gravity = "[0.0, 0.0, -9.81]") {
  const std::string path = YUXI_SCENES_DIR "/clumps/rod-bed.toml";
  std::ifstream in(path);
  std::string text{std::istreambuf_iterator<char>(in), {}};
  if (throw_out) {
    const auto replace = [&](const std::string& from, const std::string& to) {
      const std::size_t at = text.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    };
    replace("hi = [8.0, 8.0, 14.0]", "hi = [8.0, 8.0, 20.0]");
    replace("on_escape = \"stop\"", "on_escape = \"" + on_escape + "\"");
    replace("gravity = [0.0, 0.0, -9.81]", "gravity = " + gravity);
    text.resize(text.rfind("[[fill]]")); // (the spheres' fill, last)
  }
  Scene scene = read_scene_text(text, path);
  return build_simulation(scene, false);
}

// The clumps' ids, highest first, and every clump thrown up at `speed`, spinning.
std::vector<GlobalId> highest_first(const Simulation& sim) {
  std::vector<std::pair<double, GlobalId>> heights;
  for (const ClumpBody& c : sim.clumps()) heights.emplace_back(c.x.z, c.id);
  std::sort(heights.rbegin(), heights.rend());
  std::vector<GlobalId> ids;
  for (const auto& h : heights) ids.push_back(h.second);
  return ids;
}
void throw_up(Simulation& sim, const std::vector<GlobalId>& ids, double speed) {
  sim.set_clump_velocities(ids, std::vector<Vec3>(ids.size(), Vec3{0.0, 0.0, speed}));
  sim.set_clump_angular_velocities(ids, std::vector<Vec3>(ids.size(), Vec3{3.0, -2.0, 1.0}));
}

// `sim` and a device engine started from it, both `steps` steps on: the engine, and both books.
struct SideBySide {
  std::unique_ptr<device::DeviceEngine> engine;
  EnergyBooks cpu;
  device::DeviceEnergies dev;
};
SideBySide run_side_by_side(Simulation& sim, std::int64_t steps) {
  SideBySide both{make_device_engine(sim, DeviceChoice::host), {}, {}};
  sim.run(steps);
  both.engine->run(steps);
  both.cpu = sim.energies();
  both.dev = both.engine->energies();
  return both;
}

bool close(double a, double b, double relative) {
  return std::abs(a - b) <= relative * std::abs(b);
}

// Every clump's centre and velocity on the device against the CPU engine's (ids in the same
// order), to `relative` of the largest.
void expect_clumps_agree(const std::vector<device::DeviceClump>& dev,
                         const std::vector<ClumpBody>& cpu, double relative) {
  ASSERT_EQ(dev.size(), cpu.size());
  double dx = 0, dv = 0, vmax = 0;
  for (std::size_t c = 0; c < dev.size(); ++c) {
    ASSERT_EQ(dev[c].id, cpu[c].id);
    dx = std::max(dx, norm(dev[c].x - cpu[c].x));
    dv = std::max(dv, norm(dev[c].v - cpu[c].v));
    vmax = std::max(vmax, norm(cpu[c].v));
  }
  EXPECT_LE(dx, relative * 8.0);
  EXPECT_LE(dv, relative * vmax);
}

TEST(DeviceClumps, RodsSettlingAcrossPeriodicFacesMatchTheCpuEngine) {
  const auto sim = rod_bed();
  const auto [engine, cpu, dev] = run_side_by_side(*sim, 6000);
  ASSERT_GT(sim->last_tally().touching, 200u) << "the rods have reached the plane and each other";
  EXPECT_EQ(dev.grains, static_cast<std::int64_t>(cpu.grains));
  EXPECT_EQ(dev.grains, 300);
  EXPECT_EQ(dev.contacts, static_cast<std::int64_t>(cpu.contacts));
  for (const auto& [d, c] : {std::pair{dev.translational, cpu.translational},
                             {dev.rotational, cpu.rotational},
                             {dev.gravitational, cpu.gravitational},
                             {dev.elastic, cpu.elastic},
                             {dev.dissipated, cpu.dissipated}})
    EXPECT_PRED3(close, d, c, 1e-9);
  expect_clumps_agree(engine->clumps(), sim->clumps(), 1e-8);
  // The members stand with their clumps, some outside the periodic box (never wrapped alone).
  const device::HostParticles got = engine->particles();
  const ParticleStore cpu_particles = sim->gather_particles();
  ASSERT_EQ(got.size(), cpu_particles.n_owned());
  int outside = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got.body[i], cpu_particles.body[i]);
    if (got.body[i] >= 0 &&
        (got.x[i].x < 0.0 || got.x[i].x >= 8.0 || got.x[i].y < 0.0 || got.x[i].y >= 8.0))
      ++outside;
    EXPECT_LE(norm(got.x[i] - cpu_particles.x[i]), 1e-8 * 8.0) << "particle " << got.gid[i];
  }
  EXPECT_GT(outside, 0) << "no member stood across a periodic face: the test misses its case";
}

// Clumps thrown out through the open top leave whole, on both engines at the same list build,
// their mechanical energy (the body's, rotation included) booked as removed.
TEST(DeviceClumps, ClumpsThrownOutOfTheBoxLeaveWhole) {
  const auto sim = rod_bed(true);
  const std::vector<GlobalId> highest = highest_first(*sim);
  const std::vector<GlobalId> thrown{highest[0], highest[1]}; // (nothing above them)
  throw_up(*sim, thrown, 60.0);
  const auto [engine, cpu, dev] = run_side_by_side(*sim, 2500);
  ASSERT_EQ(cpu.escaped, 2u);
  EXPECT_EQ(dev.escaped, 2);
  EXPECT_EQ(dev.grains, 198);
  EXPECT_PRED3(close, dev.removed, cpu.removed, 1e-12);
  EXPECT_PRED3(close, dev.translational, cpu.translational, 1e-9);
  EXPECT_PRED3(close, dev.rotational, cpu.rotational, 1e-9);
  EXPECT_EQ(engine->particles().size(), sim->gather_particles().n_owned());
  const std::vector<device::DeviceClump> left = engine->clumps();
  for (const GlobalId id : thrown)
    EXPECT_TRUE(std::none_of(left.begin(), left.end(),
                             [id](const device::DeviceClump& c) { return c.id == id; }));
  expect_clumps_agree(left, sim->clumps(), 1e-8);
}

// Every clump thrown out, under gravity with a part along the periodic x: the step whose list
// build takes the last clumps away books their gravity's work as gravity's, and the books go on
// as the CPU engine's.
TEST(DeviceClumps, TheLastClumpsToLeaveKeepTheBooksInOrder) {
  const auto sim = rod_bed(true, "remove", "[2.0, 0.0, -9.81]");
  throw_up(*sim, highest_first(*sim), 60.0);
  const auto [engine, cpu, dev] = run_side_by_side(*sim, 2500);
  ASSERT_EQ(cpu.escaped, 200u);
  EXPECT_EQ(dev.escaped, 200);
  EXPECT_EQ(dev.grains, 0);
  EXPECT_TRUE(engine->clumps().empty());
  ASSERT_GT(cpu.gravity_work, 0.0);
  EXPECT_PRED3(close, dev.gravity_work, cpu.gravity_work, 1e-9);
  EXPECT_PRED3(close, dev.removed, cpu.removed, 1e-9);
  EXPECT_EQ(dev.dissipated, 0.0);
}

// A clump out through an open face stops a run that says so, counted as one clump.
TEST(DeviceClumps, AClumpOutOfTheBoxStopsTheRunCountedOnce) {
  const auto sim = rod_bed(true, "stop");
  throw_up(*sim, {highest_first(*sim)[0]}, 60.0);
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  try {
    engine->run(2500);
    ADD_FAILURE() << "the run went on";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("0 grains and 1 clump left the box"), std::string::npos)
        << e.what();
  }
}

// The state handed to the simulation mid-way and a new engine started from it: the run goes on
// as if never stopped, to the bit (the members' places, the clumps' bodies and their loads of
// the last step come back whole).
TEST(DeviceClumps, ARunHandedOverAndStartedAgainGoesOnToTheBit) {
  const auto straight = rod_bed();
  DeviceStepper through(*straight, DeviceChoice::host);
  through.advance(6000);
  through.hand_over();
  const auto stopped = rod_bed();
  {
    DeviceStepper first(*stopped, DeviceChoice::host);
    first.advance(4500);
    first.hand_over();
    ASSERT_GT(stopped->last_tally().touching, 100u) << "handed over with the rods in contact";
  }
  {
    DeviceStepper second(*stopped, DeviceChoice::host);
    second.advance(1500);
    second.hand_over();
  }
  const ParticleStore a = straight->gather_particles(), b = stopped->gather_particles();
  ASSERT_EQ(a.n_owned(), b.n_owned());
  const std::size_t n = a.n_owned();
  EXPECT_EQ(std::memcmp(a.x.data(), b.x.data(), n * sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(a.v.data(), b.v.data(), n * sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(a.w.data(), b.w.data(), n * sizeof(Vec3)), 0);
  const std::vector<ClumpBody>& ca = straight->clumps();
  const std::vector<ClumpBody>& cb = stopped->clumps();
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t c = 0; c < ca.size(); ++c) {
    ASSERT_EQ(ca[c].x, cb[c].x) << "clump " << ca[c].id;
    ASSERT_EQ(ca[c].v, cb[c].v) << "clump " << ca[c].id;
    ASSERT_EQ(ca[c].q.w, cb[c].q.w) << "clump " << ca[c].id;
    ASSERT_EQ(ca[c].p.vector(), cb[c].p.vector()) << "clump " << ca[c].id;
  }
  // (the cumulative books are added from the handover on: to round-off)
  EXPECT_PRED3(close, stopped->energies().dissipated, straight->energies().dissipated, 1e-13);
}

// The bed tiled 2 x 2 along its periodic axes (Replicas, as device_chute tiles a scene): four
// copies of it side by side, each clump with its copy's ids and place, whose books are four
// times the bed's and whose first copy moves as the bed does, to round-off (the sums run in
// another order).
TEST(DeviceClumps, ATiledBedIsFourCopiesOfItSideBySide) {
  const auto sim = rod_bed();
  const auto one = make_device_engine(*sim, DeviceChoice::host);
  const auto four = make_device_engine(*sim, DeviceChoice::host, Replicas{{2, 2, 1}});
  one->run(5000);
  four->run(5000);
  const device::DeviceEnergies e1 = one->energies(), e4 = four->energies();
  ASSERT_GT(e1.contacts, 100);
  EXPECT_EQ(e4.grains, 4 * e1.grains);
  EXPECT_EQ(e4.contacts, 4 * e1.contacts);
  for (const auto& [d4, d1] : {std::pair{e4.translational, e1.translational},
                               {e4.rotational, e1.rotational},
                               {e4.gravitational, e1.gravitational},
                               {e4.elastic, e1.elastic},
                               {e4.dissipated, e1.dissipated}})
    EXPECT_PRED3(close, d4, 4.0 * d1, 1e-9);
  const std::vector<device::DeviceClump> c1 = one->clumps(), c4 = four->clumps();
  ASSERT_EQ(c4.size(), 4 * c1.size());
  // (copy 0 keeps the ids; copy k's ids are offset by k (largest id + 1))
  for (std::size_t c = 0; c < c1.size(); ++c) {
    ASSERT_EQ(c4[c].id, c1[c].id);
    // (a clump wraps into the bed at x or y = 8, into the tiling at 16: whole bed lengths apart)
    Vec3 d = c4[c].x - c1[c].x;
    for (int a = 0; a < 2; ++a) d[a] -= 8.0 * std::round(d[a] / 8.0);
    EXPECT_LE(norm(d), 1e-9 * 8.0) << "clump " << c1[c].id;
  }
  GlobalId largest = 0;
  for (const GlobalId id : one->particles().gid) largest = std::max(largest, id);
  for (std::size_t k = 0; k < 4 * c1.size(); ++k)
    ASSERT_EQ(c4[k].id,
              c1[k % c1.size()].id + static_cast<GlobalId>(k / c1.size()) * (largest + 1));
}

} // namespace
} // namespace yuxi
