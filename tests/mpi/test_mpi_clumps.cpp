// Clumps on several ranks (docs/clumps.md, section 3; sim/exchange.hpp): a clump's owner is the
// rank of its centre of mass and holds every member, whose ghosts reach the clumps' reach
// farther; clumps cross the cut planes and the periodic faces whole, with their bodies. A pour
// of rods into a periodic bed gives the serial run's answer, and a run resumes bit for bit.
#include "mpi_support.hpp"

namespace yuxi {
namespace {

using namespace mpi_test;

// Rods (three spheres in a row) and spheres fall onto a floor in a box periodic in x and y,
// drifting along x and y so that they cross the cut planes and the periodic faces; an insert
// pours more rods from the top, an outlet in one corner of the floor drains them.
Scene rod_bed() {
  return read_scene_text(R"(materials = ["grain", "wall"]
[run]
name = "rods"
dt = 1.0e-4
t_end = 1.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [12.0, 12.0, 8.0]
gravity = [0.0, 0.0, -20.0]
boundary = ["periodic", "periodic", "wall"]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.0e4
k_t = 5.0e3
gamma_n = 30.0
gamma_t = 10.0
mu_s = 0.5
mu_d = 0.5
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 2.0e4
k_t = 5.0e3
gamma_n = 30.0
gamma_t = 10.0
mu_s = 0.5
mu_d = 0.5
[[shape]]
name = "rod"
spheres = [[-0.6, 0.0, 0.0, 0.3], [0.0, 0.0, 0.0, 0.3], [0.6, 0.0, 0.0, 0.3]]
[[fill]]
shape = "rod"
material = "grain"
density = 1.0
count = 150
size = { distribution = "uniform", min = 0.5, max = 0.6 }
velocity = [3.0, 2.0, 0.0]
velocity_spread = 1.0
seed = 3
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [12.0, 12.0, 4.0] }
[[fill]]
material = "grain"
density = 1.0
count = 60
radius = 0.35
velocity = [-2.0, 1.0, 0.0]
seed = 4
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [12.0, 12.0, 5.0] }
[[insert]]
shape = "rod"
material = "grain"
density = 1.0
radius = 0.6
rate = 400.0
total = 40
interval = 0.05
velocity = [1.0, -1.0, 0.0]
region = { shape = "box", lo = [0.0, 0.0, 5.5], hi = [12.0, 12.0, 8.0] }
[[outlet]]
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [3.0, 3.0, 0.8] }
)",
                         "rods.toml");
}

std::unique_ptr<Simulation> rods(Comm comm) {
  return build_simulation(rod_bed(), false, nullptr, comm);
}

TEST(Mpi, ClumpsMatchTheSerialRun) {
  const Comm world = Comm::world();
  const auto parallel = rods(world);
  parallel->run(3000);
  const Snapshot a = snapshot(*parallel);
  const auto poured = parallel->inflow()[0].grains;
  const auto drained = parallel->outflow()[0].grains; // (collective)
  const auto clumps_here = static_cast<double>(parallel->clumps().size());
  const double clumps = world.sum(clumps_here);
  if (world.rank() == 0) {
    const auto serial = rods(Comm::self());
    serial->run(3000);
    EXPECT_EQ(serial->inflow()[0].grains, poured);
    EXPECT_EQ(serial->outflow()[0].grains, drained);
    EXPECT_EQ(static_cast<double>(serial->clumps().size()), clumps);
    EXPECT_GT(poured, 0);
    EXPECT_GT(drained, 0);
    EXPECT_GT(serial->energies().dissipated, 10.0); // (grains that collide, not a gas)
    const Snapshot b = snapshot(*serial);
    expect_same(a, b, 1e-8, 1e-6, &serial->config().box);
  }
}

TEST(Mpi, ARunOfClumpsResumesBitForBit) {
  const Comm world = Comm::world();
  const auto first = rods(world);
  first->run(700);
  ArchiveWriter saved;
  first->save_state(saved);
  first->run(800);
  ArchiveWriter straight;
  first->save_state(straight);
  const auto resumed = rods(world);
  resumed->load({{saved.data()}, static_cast<std::uint64_t>(world.size())});
  resumed->run(800);
  ArchiveWriter after;
  resumed->save_state(after);
  EXPECT_TRUE(straight.data() == after.data()) << "rank " << world.rank();
}

// A checkpoint written on every rank, read back by one rank alone (its sections merged), goes on
// as the run on every rank does, to round-off.
TEST(Mpi, ACheckpointOfClumpsResumesOnOneRank) {
  const Comm world = Comm::world();
  const auto parallel = rods(world);
  parallel->run(700);
  const auto dir = shared_temp_dir("clump_checkpoint");
  const auto path = dir / "rods.yxc";
  write_checkpoint(path, "rods", *parallel);
  parallel->run(800);
  const Snapshot a = snapshot(*parallel);
  if (world.root()) {
    const auto serial = rods(Comm::self());
    apply_checkpoint(read_checkpoint(path, Comm::self()), *serial);
    serial->run(800);
    expect_same(a, snapshot(*serial), 1e-8, 1e-6, &serial->config().box);
    std::filesystem::remove_all(dir);
  }
}

} // namespace
} // namespace yuxi
