// The device engine's host build (Thrust's CPP system) against the CPU engine, on LAMMPS's chute
// (32,000 spheres, the linear law with LAMMPS's friction convention, periodic in x and y, a
// frozen rough base): the forces of the start to 1e-13 relative, the energy books after 1,000
// steps to 1e-9, and its own runs repeated to the bit. Its sums run in another order than the CPU
// engine's, so the two agree to round-off, not to the bit (docs/ARCHITECTURE.md, "The device
// engine"). Label "device".
#include "contact/hertz_mindlin.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "device/device_engine.hpp"
#include "io/scene_reader.hpp"
#include "run/device_run.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"
#include "small_basin.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>

namespace yuxi {
namespace {

std::unique_ptr<Simulation> scene_simulation(const std::string& name) {
  const std::string path = std::string(YUXI_SCENES_DIR "/") + name;
  std::ifstream in(path);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  Scene scene = read_scene_text(text, path);
  return build_simulation(scene, false);
}

// max over particles and components of |a - b|, over max |b|.
double relative_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      diff = std::max(diff, std::abs(a[i][k] - b[i][k]));
      scale = std::max(scale, std::abs(b[i][k]));
    }
  return scale > 0 ? diff / scale : diff;
}

// Every book of the device engine against the CPU engine's, within `relative` of the CPU's. The
// device engine started where the CPU's books stood at `start` (zero at the run's start): its
// cumulative books count from there.
void expect_books_agree(const device::DeviceEnergies& dev, const EnergyBooks& cpu,
                        const EnergyBooks& start, double relative) {
  const auto close = [relative](double a, double b) {
    return std::abs(a - b) <= relative * std::abs(b);
  };
  EXPECT_PRED2(close, dev.translational, cpu.translational);
  EXPECT_PRED2(close, dev.rotational, cpu.rotational);
  EXPECT_PRED2(close, dev.elastic, cpu.elastic);
  EXPECT_PRED2(close, dev.relaxation, cpu.relaxation);
  EXPECT_PRED2(close, dev.dissipated, cpu.dissipated - start.dissipated);
  EXPECT_PRED2(close, dev.gravity_work, cpu.gravity_work - start.gravity_work);
  EXPECT_PRED2(close, dev.wall_work, cpu.wall_work - start.wall_work);
  EXPECT_PRED2(close, dev.removed, cpu.removed - start.removed);
}

// The CPU engine's owned grains and walls, in global-id order (serial: all of them).
ParticleStore by_id(const Simulation& sim) {
  return sim.gather_particles();
}

TEST(DeviceEngine, ChuteStartForcesMatchTheCpuEngine) {
  const auto sim = scene_simulation("chute-lammps.toml");
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  const device::HostParticles got = engine->particles();
  const ParticleStore expected = by_id(*sim);
  ASSERT_EQ(got.size(), expected.n_owned());
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got.gid[i], expected.gid[i]);
  // The grains' (the CPU engine's wall particles collect their contacts' reactions, the device
  // engine's keep none: neither moves them).
  std::vector<Vec3> f, t, got_f, got_t;
  for (std::size_t i = 0; i < got.size(); ++i)
    if (expected.kind[i] == Kind::grain) {
      f.push_back(expected.f[i]);
      t.push_back(expected.torque[i]);
      got_f.push_back(got.f[i]);
      got_t.push_back(got.torque[i]);
    }
  ASSERT_GT(f.size(), 30000u);
  EXPECT_GT(engine->listed_pairs(), 3 * got.size()) << "the chute is dense";
  EXPECT_LE(relative_difference(got_f, f), 1e-13);
  EXPECT_LE(relative_difference(got_t, t), 1e-13);
  EXPECT_LE(relative_difference(
                got.x, std::vector<Vec3>(expected.x.begin(), expected.x.begin() + got.size())),
            0.0);
}

TEST(DeviceEngine, ChuteEnergiesAfterAThousandStepsMatchTheCpuEngine) {
  const auto sim = scene_simulation("chute-lammps.toml");
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  const std::int64_t steps = 1000;
  sim->run(steps);
  engine->run(steps);
  EXPECT_EQ(engine->step(), steps);
  EXPECT_GT(engine->list_builds(), 5) << "the flow rebuilt its list";
  const EnergyBooks cpu = sim->energies();
  const device::DeviceEnergies dev = engine->energies();
  expect_books_agree(dev, cpu, EnergyBooks{}, 1e-9);
  EXPECT_GT(cpu.dissipated, 0.0);
  // What the device holds stays near what the run needs (DeviceEngine::device_memory): 288 bytes
  // a particle and 202 a touching contact now; keeping the frictional law's whole state, every
  // energy per contact, each particle's force and torque, and its radius, mass and inertias
  // rather than its species held 517 and 308.
  const device::DeviceMemory memory = engine->device_memory();
  const double per_particle = static_cast<double>(memory.total()) / 32000.0;
  const double per_contact =
      static_cast<double>(memory.contacts) / static_cast<double>(dev.contacts);
  EXPECT_LT(per_particle, 300.0) << "bytes a particle (the goal: at most 300)";
  // ... and at most, list builds and outputs included (312 when written).
  EXPECT_GE(memory.peak, memory.total());
  EXPECT_LT(static_cast<double>(memory.peak) / 32000.0, 330.0) << "bytes a particle at most";
  EXPECT_LT(per_contact, 240.0) << "bytes per touching contact";
  const device::HostParticles got = engine->particles();
  const ParticleStore expected = by_id(*sim);
  EXPECT_LE(relative_difference(
                got.v, std::vector<Vec3>(expected.v.begin(), expected.v.begin() + got.size())),
            1e-8);
}

// Every other contact law, 300 steps of the chute under it (scenes/chute-laws/): the device
// engine's host build against the CPU engine, the energy books to 1e-9 and the velocities to
// 1e-8.
class DeviceEngineLaw : public testing::TestWithParam<const char*> {};

TEST_P(DeviceEngineLaw, AgreesWithTheCpuEngine) {
  const auto sim = scene_simulation(std::string("chute-laws/chute-") + GetParam() + ".toml");
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  const std::int64_t steps = 300;
  sim->run(steps);
  engine->run(steps);
  const EnergyBooks cpu = sim->energies();
  const device::DeviceEnergies dev = engine->energies();
  ASSERT_GT(cpu.dissipated, 0.0) << "the law dissipates in this flow";
  ASSERT_GT(sim->last_tally().touching, 5000u) << "a dense flow";
  expect_books_agree(dev, cpu, EnergyBooks{}, 1e-9);
  const device::HostParticles got = engine->particles();
  const ParticleStore expected = by_id(*sim);
  const auto owned = [&](const std::vector<Vec3>& a) {
    return std::vector<Vec3>(a.begin(), a.begin() + got.size());
  };
  EXPECT_LE(relative_difference(got.v, owned(expected.v)), 1e-8);
  EXPECT_LE(relative_difference(got.w, owned(expected.w)), 1e-8);
}

// A law with rolling resistance keeps each contact's rolling spring on the device (the others
// keep the tangential spring alone, device/kept_state.hpp): the springs come back whole.
TEST(DeviceEngine, KeepsTheRollingSpringsOfALawThatRolls) {
  const auto sim = scene_simulation("chute-laws/chute-rolling.toml");
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  engine->run(100);
  const auto* law = dynamic_cast<const device::LawEngine<HertzMindlin>*>(engine.get());
  ASSERT_NE(law, nullptr);
  std::size_t rolling = 0, open = 0;
  for (const auto& c : law->open_contacts()) {
    ++open;
    if (norm2(c.state.rolling.spring) > 0.0) ++rolling;
  }
  EXPECT_GT(open, 5000u);
  EXPECT_GT(rolling, open / 2) << "most touching contacts roll a little";
}

INSTANTIATE_TEST_SUITE_P(Laws, DeviceEngineLaw,
                         testing::Values("hooke", "hertz", "luding", "thermo", "rolling"),
                         [](const testing::TestParamInfo<const char*>& law) {
                           return std::string(law.param);
                         });

// A bed of Hertz-Mindlin grains settling on a plane in a periodic box, of the size
// distribution `size` (a scene's `size = {...}`).
std::unique_ptr<Simulation> settling_bed(const std::string& size) {
  const std::string text = R"(
materials = ["grain"]
[run]
dt = 1.0e-4
t_end = 1.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [12.0, 12.0, 30.0]
boundary = ["periodic", "periodic", "open"]
gravity = [0.0, 0.0, -9.81]
skin = 0.1
[material.grain]
youngs_modulus = 1.0e6
poisson_ratio = 0.3
density = 1000.0
[contact]
model = "hertz_mindlin"
[[contact.pair]]
materials = ["grain", "grain"]
restitution = 0.5
friction = 0.5
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "grain"
[[fill]]
material = "grain"
count = 3000
placement = "lattice"
jitter = 0.05
seed = 3
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [12.0, 12.0, 26.0] }
)" + size + "\n";
  Scene scene = read_scene_text(text, "settling-bed.toml");
  return build_simulation(scene, false);
}

// Grains of many sizes (each its own radius, mass and inertia on the device) and of two sizes
// (their index into a table of two): both against the CPU engine, and the table saving what it
// should (Particles, Species).
TEST(DeviceEngine, GrainsOfOneSizeEachOrOfTwoSizesMatchTheCpuEngine) {
  std::size_t particle_bytes[2] = {0, 0};
  int k = 0;
  for (const char* size :
       {"size = { distribution = \"uniform\", min = 0.3, max = 0.4 }",
        "size = { distribution = \"discrete\", radii = [0.3, 0.4], weights = [1.0, 1.0] }"}) {
    SCOPED_TRACE(size);
    const auto sim = settling_bed(size);
    const auto engine = make_device_engine(*sim, DeviceChoice::host);
    const std::int64_t steps = 8000;
    sim->run(steps);
    engine->run(steps);
    const EnergyBooks cpu = sim->energies();
    ASSERT_GT(sim->last_tally().touching, 1000u) << "the grains have reached the plane";
    expect_books_agree(engine->energies(), cpu, EnergyBooks{}, 1e-9);
    const device::HostParticles got = engine->particles();
    const ParticleStore expected = by_id(*sim);
    ASSERT_EQ(got.size(), expected.n_owned());
    for (std::size_t i = 0; i < got.size(); ++i) {
      ASSERT_EQ(got.radius[i], expected.radius[i]);
      ASSERT_EQ(got.mass[i], expected.mass[i]);
      ASSERT_EQ(got.inv_inertia[i], expected.inv_inertia[i]);
    }
    EXPECT_LE(relative_difference(
                  got.v, std::vector<Vec3>(expected.v.begin(), expected.v.begin() + got.size())),
              1e-8);
    ASSERT_EQ(got.size(), 3000u);
    particle_bytes[k++] = engine->device_memory().particles;
  }
  // 32 bytes of radius, mass and inertias a particle, or a 2-byte index into a table of two.
  EXPECT_EQ(particle_bytes[0] - particle_bytes[1], 3000u * 30u - 2u * 32u);
}

TEST(DeviceEngine, RepeatsItselfToTheBit) {
  const auto sim = scene_simulation("chute-lammps.toml");
  const auto a = make_device_engine(*sim, DeviceChoice::host);
  const auto b = make_device_engine(*sim, DeviceChoice::host);
  a->run(300);
  b->run(300);
  const device::HostParticles pa = a->particles(), pb = b->particles();
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_EQ(std::memcmp(pa.x.data(), pb.x.data(), pa.size() * sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(pa.v.data(), pb.v.data(), pa.size() * sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(pa.w.data(), pb.w.data(), pa.size() * sizeof(Vec3)), 0);
  const device::DeviceEnergies ea = a->energies(), eb = b->energies();
  EXPECT_EQ(ea.dissipated, eb.dissipated);
  EXPECT_EQ(ea.elastic, eb.elastic);
}

TEST(DeviceEngine, RefusesWhatItDoesNotRunByName) {
  const auto sim = scene_simulation("bulk/beverloo-small.toml");
  try {
    make_device_engine(*sim, DeviceChoice::host);
    FAIL() << "a silo's cylinders, mesh, insert and outlet are not run on the device yet";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* table : {"[[cylinder]]", "[[mesh]]", "[[insert]]", "[[outlet]]"})
      EXPECT_NE(what.find(table), std::string::npos) << table << " in: " << what;
  }
}

// A scene handed to the engine that contradicts itself is refused, naming what is wrong: forces,
// coefficients, planes and clumps.
TEST(DeviceEngine, RefusesAContradictoryScene) {
  const auto two_grains = [] {
    device::DeviceScene scene;
    scene.lo = Vec3{0.0, 0.0, 0.0};
    scene.hi = Vec3{10.0, 10.0, 10.0};
    scene.dt = 1e-4;
    scene.skin = 0.1;
    device::HostParticles& p = scene.particles;
    for (int k = 0; k < 2; ++k) {
      p.x.push_back(Vec3{2.0 + 3.0 * k, 5.0, 5.0});
      p.v.push_back(Vec3{});
      p.w.push_back(Vec3{});
      p.x_rest.push_back(p.x.back());
      p.radius.push_back(0.5);
      p.mass.push_back(1.0);
      p.inv_mass.push_back(1.0);
      p.inv_inertia.push_back(10.0);
      p.gid.push_back(k);
      p.kind.push_back(Kind::grain);
      p.material.push_back(0);
      p.motion.push_back(0);
    }
    return scene;
  };
  const std::vector<LinearSpringDashpot::Coeffs> one(1);
  const auto refused = [&](const device::DeviceScene& scene,
                           const std::vector<LinearSpringDashpot::Coeffs>& coeffs) -> std::string {
    try {
      device::make_host_engine<LinearSpringDashpot>(scene, coeffs, {});
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(taken)";
  };
  EXPECT_EQ(refused(two_grains(), one), "(taken)");
  device::DeviceScene forces = two_grains();
  forces.forces_given = true;
  forces.particles.f.assign(1, Vec3{});
  forces.particles.torque.assign(2, Vec3{});
  EXPECT_EQ(refused(forces, one), "device engine: 1 forces and 2 torques given for 2 particles");
  EXPECT_EQ(refused(two_grains(), std::vector<LinearSpringDashpot::Coeffs>(2)),
            "device engine: coefficients for 2 material pairs, expected 1");
  device::DeviceScene plane = two_grains();
  plane.planes.push_back(device::DevicePlane{Vec3{}, Vec3{0.0, 0.0, 1.0}, 3});
  EXPECT_EQ(refused(plane, one), "device engine: a plane of material 3, beyond the scene's 1");
  // The two grains as members of clump 0: named while the scene holds no clump 0, missing while
  // the clump has a third member, taken once the clump is theirs.
  device::DeviceScene clump = two_grains();
  clump.particles.body.assign(2, 0);
  EXPECT_EQ(refused(clump, one), "device engine: a particle names clump 0, which is not here");
  device::DeviceClump& c = clump.clumps.emplace_back();
  c.id = 0;
  c.mass = 2.0;
  c.inertia = Vec3{0.1, 0.2, 0.2};
  c.x = Vec3{3.5, 5.0, 5.0};
  c.members = {Vec3{-1.5, 0.0, 0.0}, Vec3{1.5, 0.0, 0.0}, Vec3{3.0, 0.0, 0.0}};
  EXPECT_EQ(refused(clump, one), "device engine: member 2 (particle 2) of clump 0 is missing");
  c.members.pop_back();
  EXPECT_EQ(refused(clump, one), "(taken)");
}

// The small basin of tests/small_basin.hpp, settled by the CPU engine to t = 3.0.
std::unique_ptr<Simulation> settled_small_basin(EscapePolicy on_escape) {
  const std::string path = std::string(YUXI_SCENES_DIR "/basin-small.toml");
  std::ifstream in(path);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  Scene scene = read_scene_text(test::small_basin(text), path);
  scene.sim.on_escape = on_escape;
  auto sim = build_simulation(scene, false);
  sim->run(30000);
  return sim;
}

// The fish basin's wall particles on the device: 0.5 tau from t = 3.0 on both engines, the side
// wall shaking from 3.2. The books to 1e-9, the work of the wall included; the positions to 1e-9
// of the box.
TEST(DeviceEngine, BasinWallParticlesMatchTheCpuEngine) {
  const auto sim = settled_small_basin(EscapePolicy::stop);
  const EnergyBooks before = sim->energies();
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  sim->run(5000);
  engine->run(5000);
  EXPECT_NEAR(engine->time(), sim->time(), 1e-12);
  const EnergyBooks cpu = sim->energies();
  const device::DeviceEnergies dev = engine->energies();
  ASSERT_GT(cpu.wall_work - before.wall_work, 0.0) << "the shaking wall works on the grains";
  expect_books_agree(dev, cpu, before, 1e-9);
  const device::HostParticles got = engine->particles();
  const ParticleStore expected = by_id(*sim);
  ASSERT_EQ(got.size(), expected.n_owned());
  double worst = 0.0;
  for (std::size_t i = 0; i < got.size(); ++i)
    worst = std::max(worst, norm(got.x[i] - expected.x[i]));
  EXPECT_LE(worst, 1e-9 * 36.0);
}

// Grains thrown out of the top of the box leave both engines at the same list build, their
// mechanical energy booked as removed (on_escape = "remove").
TEST(DeviceEngine, EscapedGrainsLeaveAsOnTheCpuEngine) {
  const auto sim = settled_small_basin(EscapePolicy::remove);
  // The three highest grains thrown up at 300 sigma/tau: out through z = 150 within 0.5 tau.
  const ParticleStore now = sim->gather_particles();
  std::vector<std::pair<double, GlobalId>> heights;
  for (std::size_t i = 0; i < now.n_owned(); ++i)
    if (now.kind[i] == Kind::grain) heights.emplace_back(now.x[i].z, now.gid[i]);
  std::sort(heights.rbegin(), heights.rend());
  const std::vector<GlobalId> thrown{heights[0].second, heights[1].second, heights[2].second};
  sim->set_velocities(thrown, std::vector<Vec3>(3, Vec3{0.0, 0.0, 300.0}));
  const EnergyBooks before = sim->energies();
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  sim->run(6000);
  engine->run(6000);
  const EnergyBooks cpu = sim->energies();
  const device::DeviceEnergies dev = engine->energies();
  ASSERT_EQ(cpu.escaped - before.escaped, 3);
  EXPECT_EQ(dev.escaped, 3);
  expect_books_agree(dev, cpu, before, 1e-9);
  EXPECT_EQ(engine->particles().size(), sim->gather_particles().n_owned());
}

// A run continued mid-way comes with its forces, computed at the last step's half-step
// velocities; it keeps them until its first step has computed its own. A grain thrown out of the
// box stops that first step at its list build: the forces handed back are the ones it came with.
TEST(DeviceEngine, ARunStoppedInItsFirstStepHandsBackTheForcesItCameWith) {
  const auto sim = settled_small_basin(EscapePolicy::stop);
  const ParticleStore now = sim->gather_particles();
  GlobalId highest = -1;
  double top = -1e300;
  for (std::size_t i = 0; i < now.n_owned(); ++i)
    if (now.kind[i] == Kind::grain && now.x[i].z > top) {
      top = now.x[i].z;
      highest = now.gid[i];
    }
  const std::vector<GlobalId> thrown{highest};
  sim->set_velocities(thrown, std::vector<Vec3>{Vec3{0.0, 0.0, 1e9}}); // out in one step
  const ParticleStore given = sim->gather_particles();
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  EXPECT_THROW(engine->run(10), std::runtime_error);
  const device::HostParticles got = engine->particles();
  ASSERT_EQ(got.size(), given.n_owned());
  for (std::size_t i = 0; i < got.size(); ++i)
    if (given.kind[i] == Kind::grain) {
      ASSERT_EQ(got.f[i], given.f[i]) << "grain " << given.gid[i];
      ASSERT_EQ(got.torque[i], given.torque[i]) << "grain " << given.gid[i];
    }
}

#if !defined(YUXI_HAVE_CUDA)
// Two grains meeting obliquely (impact parameter b/d = 0.5) under the thermodynamic law, without
// gravity: after they part, the device engine's velocities and spins are the CPU engine's, so
// the law's speed-dependent restitution, its relaxation and its tangential history run the same.
TEST(DeviceEngine, ThermodynamicObliqueCollisionMatchesTheCpuEngine) {
  const std::string text = R"(
materials = ["grain"]
[run]
dt = 1.0e-4
t_end = 1.0
[domain]
lo = [-5.0, -5.0, -5.0]
hi = [5.0, 5.0, 5.0]
gravity = [0.0, 0.0, 0.0]
[material.grain]
youngs_modulus = 5.0e6
poisson_ratio = 0.3
[contact]
model = "thermodynamic"
[[contact.pair]]
materials = ["grain", "grain"]
friction = 0.4
eta_hat = 0.9
[[particle]]
position = [-0.55, 0.25, 0.0]
velocity = [1.0, 0.0, 0.0]
radius = 0.5
density = 1.0
material = "grain"
[[particle]]
position = [0.55, -0.25, 0.0]
velocity = [-1.0, 0.0, 0.0]
radius = 0.5
density = 1.0
material = "grain"
)";
  Scene scene = read_scene_text(text, "oblique.toml");
  const auto sim = build_simulation(scene, false);
  const auto engine = make_device_engine(*sim, DeviceChoice::host);
  sim->run(2000);
  engine->run(2000);
  const device::HostParticles got = engine->particles();
  const ParticleStore expected = by_id(*sim);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(sim->last_tally().touching, 0u) << "the grains have parted";
  const double speed = norm(expected.v[0]);
  EXPECT_LT(speed, 0.99) << "the collision dissipated";
  EXPECT_GT(std::abs(expected.v[0].y), 0.01) << "an oblique collision deflects";
  EXPECT_GT(norm(expected.w[0]), 0.01) << "friction spun the grains";
  EXPECT_LE(
      relative_difference(got.v, std::vector<Vec3>(expected.v.begin(), expected.v.begin() + 2)),
      1e-12);
  EXPECT_LE(
      relative_difference(got.w, std::vector<Vec3>(expected.w.begin(), expected.w.begin() + 2)),
      1e-12);
  const device::DeviceEnergies dev = engine->energies();
  const EnergyBooks cpu = sim->energies();
  EXPECT_GT(cpu.dissipated, 0.0);
  EXPECT_NEAR(dev.dissipated, cpu.dissipated, 1e-12 * cpu.dissipated);
}

TEST(DeviceEngine, AskingForAGpuWithoutCudaSaysHowToGetOne) {
  const auto sim = scene_simulation("chute-lammps.toml");
  try {
    make_device_engine(*sim, DeviceChoice::cuda);
    FAIL() << "this build has no CUDA";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("-DYUXI_CUDA=ON"), std::string::npos) << e.what();
  }
}
#endif

} // namespace
} // namespace yuxi
