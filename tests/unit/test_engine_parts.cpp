// The engine's parts alone, without a Simulation (docs/ARCHITECTURE.md, "The engine's parts"):
// the energy ledger's sums and its judgement of a gain, the sources' id counter and its
// checkpoint section, the exchange's layout on one rank, the cells' sizing, and the plain view
// of the particles.
#include "core/archive.hpp"
#include "sim/cell_sizing.hpp"
#include "sim/energy_ledger.hpp"
#include "sim/exchange.hpp"
#include "sim/sources.hpp"
#include "sim/state_layout.hpp"

#include <gtest/gtest.h>
#include <stdexcept>

namespace yuxi {
namespace {

ParticleStore two_grains_and_a_wall() {
  ParticleStore s;
  ParticleSpec a;
  a.position = {1.0, 2.0, 3.0};
  a.velocity = {3.0, 0.0, 4.0}; // |v| = 5
  a.angular_velocity = {0.0, 2.0, 0.0};
  a.radius = 0.5;
  a.mass = 2.0;
  s.add(a, 0);
  ParticleSpec b = a;
  b.position = {4.0, 5.0, -1.0};
  b.velocity = {0.0, 1.0, 0.0};
  b.spins = false; // locked rotation: no rotational energy
  s.add(b, 1);
  ParticleSpec w;
  w.position = {0.0, 0.0, 0.0};
  w.velocity = {9.0, 9.0, 9.0};
  w.kind = Kind::wall;
  s.add(w, 2);
  return s;
}

TEST(EnergyLedger, SumsTheGrainsEnergiesAndLeavesWallsOut) {
  const ParticleStore s = two_grains_and_a_wall();
  SimulationConfig c;
  c.box = Box{{-10, -10, -10}, {10, 10, 10}};
  c.box.boundary[0] = Boundary::periodic;
  c.gravity = {0.5, 0.0, -1.0}; // along x periodic: no potential there
  EnergyLedger ledger;
  ledger.books().dissipated = 7.0;
  ContactTally tally;
  tally.elastic = 0.25;
  tally.touching = 3;
  const EnergyBooks e = ledger.parts(s, c, tally, 12, 0.5);
  EXPECT_DOUBLE_EQ(e.translational, 0.5 * 2.0 * 25.0 + 0.5 * 2.0 * 1.0);
  // J = (2/5) m r^2 = 0.2; J w^2 / 2 = 0.4 (grain b's rotation is locked)
  EXPECT_DOUBLE_EQ(e.rotational, 0.5 * 0.2 * 4.0);
  // -m g_potential . x with g_potential = (0, 0, -1): m z
  EXPECT_DOUBLE_EQ(e.gravitational, 2.0 * 3.0 + 2.0 * -1.0);
  EXPECT_EQ(e.grains, 2u);
  EXPECT_EQ(e.contacts, 3u);
  EXPECT_EQ(e.elastic, 0.25);
  EXPECT_EQ(e.dissipated, 7.0); // the cumulative books carried
  EXPECT_EQ(e.step, 12);
}

TEST(EnergyLedger, TheBooksOfAListBuildAreTakenOnce) {
  EnergyLedger ledger;
  EXPECT_FALSE(ledger.take_due().has_value());
  EnergyBooks b;
  b.dissipated = 1.0;
  ledger.leave_due(b);
  const auto due = ledger.take_due();
  ASSERT_TRUE(due.has_value());
  EXPECT_EQ(due->dissipated, 1.0);
  EXPECT_FALSE(ledger.take_due().has_value());
}

TEST(EnergyLedger, AGainOfMoreThanATenthOfTheEnergyInPlayIsUnstable) {
  EnergyLedger ledger;
  ledger.set_initial_balance(100.0);
  EnergyBooks e;
  e.translational = 105.0; // balance 105: a gain of 5 in 205 in play
  EXPECT_FALSE(ledger.unstable_gain(e).has_value());
  e.translational = 150.0; // a gain of 50 in 250
  const auto gain = ledger.unstable_gain(e);
  ASSERT_TRUE(gain.has_value());
  EXPECT_DOUBLE_EQ(gain->gained, 50.0);
  EXPECT_DOUBLE_EQ(gain->in_play, 250.0);
}

TEST(Sources, IdsNeverGoBackAndTheCounterIsSaved) {
  Sources sources;
  sources.ids_from(10);
  sources.ids_from(4); // (a lower bound never lowers it)
  EXPECT_EQ(sources.next_id(), 10);
  EXPECT_EQ(sources.take_id(), 10);
  EXPECT_EQ(sources.take_id(), 11);
  EXPECT_FALSE(sources.insertion_due(5, 1e-3)); // no insert, nothing due
  ArchiveWriter out;
  sources.save(out);
  Sources loaded;
  ArchiveReader in(out.data());
  loaded.load(in, state_layout);
  EXPECT_TRUE(in.at_end());
  EXPECT_EQ(loaded.next_id(), 12);
}

TEST(Exchange, LaysOutOneRankAndRefusesAnotherLayoutsCuts) {
  const Box box{{0, 0, 0}, {8, 6, 4}};
  Exchange exchange(box, Comm::self(), {0, 0, 0}, Vec3{}, 1.0);
  EXPECT_EQ(exchange.cell_edge(), 1.0);
  EXPECT_EQ(exchange.decomposition().dims(), (std::array<int, 3>{1, 1, 1}));
  exchange.lay_out({0, 0, 0}, Vec3{}, 2.0);
  EXPECT_EQ(exchange.cell_edge(), 2.0);
  EXPECT_GE(exchange.grid().edge().x, 2.0);
  const auto cuts = exchange.cuts();
  EXPECT_NO_THROW(exchange.set_cuts(cuts));
  auto two_along_x = cuts;
  two_along_x[0] = {0.0, 4.0, 8.0};
  EXPECT_THROW(exchange.set_cuts(two_along_x), std::invalid_argument);
}

TEST(CellSizing, TheCellsHoldTheReachAndTheSkin) {
  SimulationConfig c;
  c.skin = 0.5;
  EXPECT_DOUBLE_EQ(cell_edge_for(c, 2.0), 2.5);
  c.min_contact_reach = 3.0; // larger grains to come
  EXPECT_DOUBLE_EQ(cell_edge_for(c, 2.0), 3.5);
  c.cell_size = 3.2; // the scene's cells shorten the skin to fit
  EXPECT_DOUBLE_EQ(cell_edge_for(c, 2.0), 3.2);
  EXPECT_NEAR(c.skin, 0.2, 1e-15);
  c.cell_size = 2.5;
  EXPECT_THROW(cell_edge_for(c, 2.0), std::invalid_argument); // below the reach of 3
}

TEST(CellSizing, TheOccupiedRegionIsTheParticlesOrThePeriodicBox) {
  Box box{{0, 0, 0}, {100, 100, 100}};
  box.boundary[1] = Boundary::periodic;
  const ParticleStore s = two_grains_and_a_wall(); // x in [-1, 4.5], z in [-1.5, 3.5]
  const Vec3 l = occupied_lengths(box, s);
  EXPECT_DOUBLE_EQ(l.x, 5.5);
  EXPECT_DOUBLE_EQ(l.y, 100.0);
  EXPECT_DOUBLE_EQ(l.z, 5.0);
  const Vec3 none = occupied_lengths(box, ParticleStore{});
  EXPECT_EQ(none.x, 100.0);
  const Comm one = Comm::self();
  EXPECT_EQ(occupied_lengths(box, s, &one).x, l.x);
}

TEST(ParticleView, PointsAtEveryFieldOfTheStore) {
  ParticleStore s = two_grains_and_a_wall();
  const ParticleView v = s.view();
  EXPECT_EQ(v.n_owned(), 3u);
  EXPECT_EQ(v.size(), 3u);
  std::size_t fields = 0;
  s.for_each_field([&](auto&) { ++fields; });
  EXPECT_EQ(sizeof(ParticleView), fields * sizeof(void*) + 2 * sizeof(std::size_t));
  v.x[1].y = 42.0; // writes reach the store
  EXPECT_EQ(s.x[1].y, 42.0);
  EXPECT_EQ(v.gid[2], 2);
  EXPECT_TRUE(v.is_grain(0));
  EXPECT_FALSE(v.is_grain(2));
  const ConstParticleView c = v; // read-only, the same particles
  EXPECT_EQ(c.radius, s.radius.data());
  EXPECT_EQ(c.motion, s.motion.data());
}

} // namespace
} // namespace yuxi
