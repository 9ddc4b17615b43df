// Grains placed at the start of a run ([[fill]]): in a region, a count of them, or as many as
// make a packing fraction or a total mass, either at random without overlap or on a cubic
// lattice with a random offset.
//
// Random sequential placement (each grain at a uniformly drawn place that overlaps nothing
// placed before) jams near a packing fraction of 0.35-0.38 for spheres (Widom 1966; Talbot,
// Tarjus & Schaaf 2000 give 0.38 for monodisperse spheres): a request beyond 0.38 is refused
// before any grain is placed, with the advice to use the lattice or to pour the grains with
// [[insert]]. The lattice's spacing is the largest diameter plus twice the offset, so it holds
// a packing fraction of at most pi/6 (0.52) of the largest grains.
//
// Every random number comes from the fill's own seeded streams (sizes, places, velocities),
// so the grains are the same on every rank and every run of the scene.
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"
#include "scene/region.hpp"
#include "scene/size_distribution.hpp"

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace yuxi {

// What the grains of a source are like: sizes, material and density, initial velocity.
struct GrainKind {
  SizeDistribution size;
  std::uint8_t material = 0;
  double density = 1.0;       // [mass/length^3]: m = density 4/3 pi r^3
  Vec3 velocity;              // mean initial velocity [length/time]
  double velocity_spread = 0; // plus a vector uniform in a ball of this radius [length/time]
  std::uint64_t seed = 1;
  // Clumps: a grain's volume over that of its bounding ball (1 for spheres), so that a grain of
  // bounding radius r weighs density volume_fraction 4/3 pi r^3.
  double volume_fraction = 1.0;

  double mass_of(double r) const;
  // The initial velocity of one grain, from the stream.
  Vec3 draw_velocity(Random& rng) const;
};

struct FillSpec {
  std::string name; // for messages ("fill[2]")
  Region region;
  GrainKind grains;
  enum class Amount { count, packing_fraction, mass };
  Amount amount = Amount::count;
  double value = 0; // the count, packing fraction or total mass
  enum class Placement { random, lattice };
  Placement placement = Placement::random;
  double jitter = 0.0;           // lattice: random offset of each grain, within a ball [length]
  int attempts_per_grain = 1000; // random: draws of a place before the fill gives up
  bool walls = false;            // fixed wall particles (a rough floor) instead of grains
  // Clumps of the scene's shape of this index (-1: spheres): each grain placed is the shape's
  // bounding ball, of the radius drawn, and the clump is turned at random inside it
  // (run/scene_builder.cpp), so clumps never overlap what the fill would not.
  int shape = -1;
};

// The request cannot be met: what() says how many grains fit and why.
class FillError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The fill's grains, inside `domain` and clear of `others` (the particles already in the
// scene). Throws FillError when they do not fit.
std::vector<ParticleSpec> fill_particles(const FillSpec& fill, const Box& domain,
                                         std::span<const ParticleSpec> others);

// Random sequential placement's jamming limit, above which a random fill is refused.
inline constexpr double random_fill_limit = 0.38;

} // namespace yuxi
