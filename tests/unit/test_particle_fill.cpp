// [[fill]]: the grains asked for, all inside the region, overlapping neither each other nor the
// particles already there, the same on every call with the same seed; a packing fraction or a
// mass turns into the right number of grains; and a request that cannot fit is refused before
// any grain is placed, with how many fit and why.
#include "io/scene_reader.hpp"
#include "run/scene_builder.hpp"
#include "scene/particle_fill.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace yuxi {
namespace {

constexpr double pi = std::numbers::pi;
const Box domain{{0, 0, 0}, {20, 20, 40}};

FillSpec box_fill(double count) {
  FillSpec f;
  f.name = "fill[1]";
  f.region = Region(BoxRegion{{2, 2, 2}, {18, 18, 30}});
  f.grains.size.kind = SizeDistribution::Kind::uniform;
  f.grains.size.min = 0.4;
  f.grains.size.max = 0.6;
  f.grains.density = 2.0;
  f.grains.seed = 42;
  f.value = count;
  return f;
}

// No two of `a` and `b` overlap (a brute-force check).
void expect_no_overlaps(const std::vector<ParticleSpec>& a, const std::vector<ParticleSpec>& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (&a == &b && j <= i) continue;
      ASSERT_GE(norm(a[i].position - b[j].position), a[i].radius + b[j].radius - 1e-12)
          << i << " " << j;
    }
  }
}

TEST(ParticleFill, RandomFillPlacesEveryGrainInsideAndApart) {
  // a wall of large balls already in the region
  std::vector<ParticleSpec> others;
  for (int i = 0; i < 5; ++i) {
    ParticleSpec p;
    p.position = {4.0 + 3 * i, 10, 10};
    p.radius = 1.5;
    others.push_back(p);
  }
  const FillSpec f = box_fill(2000);
  const auto grains = fill_particles(f, domain, others);
  ASSERT_EQ(grains.size(), 2000u);
  for (const auto& g : grains) {
    ASSERT_TRUE(f.region.contains_sphere(g.position, g.radius));
    ASSERT_GE(g.radius, 0.4);
    ASSERT_LE(g.radius, 0.6);
    ASSERT_NEAR(g.mass, 2.0 * 4.0 / 3.0 * pi * std::pow(g.radius, 3), 1e-12 * g.mass);
  }
  expect_no_overlaps(grains, grains);
  expect_no_overlaps(grains, others);
  // the same seed, the same grains; another seed, others
  const auto again = fill_particles(f, domain, others);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    ASSERT_EQ(grains[i].position.x, again[i].position.x);
    ASSERT_EQ(grains[i].radius, again[i].radius);
  }
  FillSpec other_seed = f;
  other_seed.grains.seed = 43;
  EXPECT_NE(fill_particles(other_seed, domain, others)[0].position.x, grains[0].position.x);
}

TEST(ParticleFill, PackingFractionAndMassBecomeCounts) {
  // phi = N <V> / V_region: 0.2 of 16 x 16 x 28 with <r^3> = (0.6^4 - 0.4^4) / (4 x 0.2)
  FillSpec f = box_fill(0.2);
  f.amount = FillSpec::Amount::packing_fraction;
  const auto grains = fill_particles(f, domain, {});
  double volume = 0;
  for (const auto& g : grains) volume += 4.0 / 3.0 * pi * std::pow(g.radius, 3);
  EXPECT_NEAR(volume / (16.0 * 16 * 28), 0.2, 0.6 * 4.0 / 3.0 * pi * 0.216 / (16.0 * 16 * 28));

  FillSpec m = box_fill(500.0);
  m.amount = FillSpec::Amount::mass;
  double mass = 0;
  const auto heavy = fill_particles(m, domain, {});
  for (const auto& g : heavy) mass += g.mass;
  EXPECT_NEAR(mass, 500.0, 2.0 * 4.0 / 3.0 * pi * 0.216); // within one largest grain
}

TEST(ParticleFill, TheLatticeGoesBeyondRandomPlacement) {
  // 0.45 of a box of equal grains: refused at random, placed on the lattice
  FillSpec f;
  f.name = "fill[2]";
  f.region = Region(BoxRegion{{0, 0, 0}, {10.3, 10.3, 10.3}});
  f.grains.size.radius = 0.5;
  f.amount = FillSpec::Amount::packing_fraction;
  f.value = 0.45;
  const Box box{{0, 0, 0}, {10.3, 10.3, 10.3}};
  try {
    fill_particles(f, box, {});
    FAIL() << "a random fill of 0.45 was accepted";
  } catch (const FillError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fill[2]"), std::string::npos) << what;
    EXPECT_NE(what.find("lattice"), std::string::npos) << what;
  }
  f.placement = FillSpec::Placement::lattice;
  f.jitter = 0.01;
  const auto grains = fill_particles(f, box, {});
  EXPECT_NEAR(double(grains.size()), 0.45 * std::pow(10.3, 3) / (pi / 6), 1.0);
  expect_no_overlaps(grains, grains);
  // beyond the lattice's capacity (10^3 sites at spacing 1.02): refused, naming the sites
  f.value = 0.55;
  try {
    fill_particles(f, box, {});
    FAIL() << "a lattice beyond its sites was accepted";
  } catch (const FillError& e) {
    EXPECT_NE(std::string(e.what()).find("1000 free sites"), std::string::npos) << e.what();
  }
}

TEST(ParticleFill, AWallFillMakesFixedParticles) {
  // a rough floor: one lattice layer of wall particles, which carry no velocity
  FillSpec f;
  f.name = "floor";
  f.walls = true;
  f.region = Region(BoxRegion{{0, 0, 1.0}, {10, 10, 2.22}});
  f.grains.size.radius = 0.5;
  f.grains.velocity = {1, 0, 0};
  f.placement = FillSpec::Placement::lattice;
  f.jitter = 0.1;
  f.value = 64;
  const auto floor = fill_particles(f, domain, {});
  ASSERT_EQ(floor.size(), 64u);
  for (const auto& p : floor) {
    EXPECT_EQ(p.kind, Kind::wall);
    EXPECT_EQ(norm(p.velocity), 0.0);
    EXPECT_LE(std::abs(p.position.z - 1.61), 0.1 + 1e-9);
  }
}

// A grain wider than the region has no place in it: said so, rather than "the region is full".
TEST(ParticleFill, AGrainWiderThanTheRegionIsRefusedAsSuch) {
  FillSpec f = box_fill(1);
  f.region = Region(BoxRegion{{2, 2, 2}, {18, 3, 30}}); // 1 across along y
  f.grains.size.kind = SizeDistribution::Kind::constant;
  f.grains.size.radius = 0.6;
  try {
    fill_particles(f, domain, {});
    FAIL() << "a grain wider than its region was placed";
  } catch (const FillError& e) {
    EXPECT_NE(std::string(e.what()).find("wider than the region"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("along y (1 across)"), std::string::npos) << e.what();
  }
}

TEST(ParticleFill, ARandomFillThatJamsSaysHowManyFit) {
  // 0.36 asked, with a crowd already there: the fill gives up and says how far it got
  FillSpec f = box_fill(0.36);
  f.amount = FillSpec::Amount::packing_fraction;
  f.grains.size.kind = SizeDistribution::Kind::constant;
  f.grains.size.radius = 0.5;
  f.attempts_per_grain = 50;
  std::vector<ParticleSpec> crowd;
  for (double x = 3; x < 18; x += 1.1)
    for (double y = 3; y < 18; y += 1.1)
      for (double z = 3; z < 16; z += 1.1) {
        ParticleSpec p;
        p.position = {x, y, z};
        p.radius = 0.5;
        crowd.push_back(p);
      }
  try {
    fill_particles(f, domain, crowd);
    FAIL() << "a fill into a crowded region was accepted";
  } catch (const FillError& e) {
    EXPECT_NE(std::string(e.what()).find("placed "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("after 50 random draws"), std::string::npos) << e.what();
  }
}

// The small basin with its grains from a [[fill]] (scenes/basin-small-fill.toml): the same count,
// radii and masses as the basin's own lattice, within the sampling error of 2,048 grains.
TEST(ParticleFill, TheBasinFromAFillHasTheLatticeBasinsStatistics) {
  struct Stats {
    double n = 0, mass = 0, r = 0, r2 = 0, walls = 0;
  };
  const auto stats = [](const char* name) {
    const Scene scene = read_scene_file(std::string(YUXI_SCENES_DIR) + "/" + name);
    const auto sim = build_simulation(scene, false);
    const ParticleStore& p = sim->particles();
    Stats s;
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      if (!p.is_grain(i)) {
        s.walls += 1;
        continue;
      }
      s.n += 1, s.mass += p.mass[i], s.r += p.radius[i], s.r2 += p.radius[i] * p.radius[i];
    }
    s.mass /= s.n, s.r /= s.n, s.r2 = std::sqrt(s.r2 / s.n - s.r * s.r);
    return s;
  };
  const Stats lattice = stats("basin-small.toml"), fill = stats("basin-small-fill.toml");
  EXPECT_EQ(fill.n, lattice.n);
  EXPECT_EQ(fill.walls, lattice.walls);
  const double error = 0.1 / std::sqrt(lattice.n); // of a mean radius; masses vary as 3 x that
  EXPECT_NEAR(fill.r, lattice.r, 4 * std::sqrt(2.0) * error);
  EXPECT_NEAR(fill.mass, lattice.mass, 4 * std::sqrt(2.0) * 3 * error);
  EXPECT_NEAR(fill.r2, lattice.r2, 0.01); // the sd, 0.1
}

} // namespace
} // namespace yuxi
