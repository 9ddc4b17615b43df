// The "fish basin" of Li & Cai (2008) (docs/models/fish-basin.md section 6): a flat-bottomed
// vertical cylinder built of wall particles on a cubic lattice, filled with polydisperse grains,
// one particle per lattice cell. The side wall vibrates radially in a cos(m alpha) mode from t0 on;
// the bottom stays at rest.
//
// Geometry, in lattice cells of edge `spacing` (the lattice fills [0, cells] of the box):
//  - bottom: `bottom_layers` layers, every cell with centre radius <= radius + wall_thickness;
//  - side wall: the next `wall_height` layers, cells with radius < rho <= radius + thickness;
//  - grains: `fill_layers` layers above the bottom, cells with rho <= radius,
// where rho is the horizontal distance of a cell centre from the axis, in cells. When a grain
// next to a wall could overlap it (largest grain + jitter + wall radius > spacing), one layer
// of cells is left empty along the walls (basin_wall_gap).
#pragma once

#include "core/particle_store.hpp"
#include "core/random.hpp"
#include "scene/wall_motion.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace yuxi {

struct FishBasinSpec {
  std::array<int, 3> cells{24, 24, 16}; // lattice size (the paper: 160 x 160 x 50)
  double spacing = 3.0;                 // lattice cell edge [sigma]
  double radius = 10.0;                 // inner radius of the container [cells]
  double wall_thickness = 1.6;          // [cells]
  int wall_height = 15;                 // side-wall layers above the bottom
  int bottom_layers = 1;
  int fill_layers = 8;      // grain layers at t = 0
  double wall_radius = 1.5; // touching neighbours at spacing 3: leak-proof
  double radius_mean = 1.0; // grain radius ~ Normal(mean, sd), truncated at 3 sd
  double radius_sd = 0.1;
  double jitter = 0.2; // random start offset, uniform in a ball [sigma]
  std::uint64_t seed = 2008;
  RadialCosineMotion excitation{{}, 2, 0.9, 400.0, 10.0}; // centre is set by the builder
  std::uint8_t grain_material = 0;
  std::uint8_t wall_material = 1;
  // false: no side wall of particles (a [[mesh]] or [[cylinder]] stands in for it)
  bool side_particles = true;
};

struct BuiltParticles {
  ParticleStore particles;
  std::vector<WallMotion> motions; // index 0 static, 1 the side-wall excitation
  std::size_t n_walls = 0, n_grains = 0;
};

// Builds the basin with the lattice origin at `origin`. Grain masses are r^3 / <r^3>, so the
// mean grain mass is 1 (docs/models/fish-basin.md section 6).
BuiltParticles build_fish_basin(const FishBasinSpec& spec, const Vec3& origin = {});

// The basin's wall motions (as BuiltParticles::motions) and how many wall particles it builds,
// without building it (a state continued from a checkpoint brings its particles).
std::vector<WallMotion> fish_basin_motions(const FishBasinSpec& spec, const Vec3& origin = {});
std::size_t fish_basin_walls(const FishBasinSpec& spec);

// Empty cells left between the walls and the grains at t = 0 (0 or 1).
int basin_wall_gap(const FishBasinSpec& spec);

// Grain radius drawn from Normal(mean, sd) truncated at +-3 sd.
double draw_grain_radius(Random& rng, double mean, double sd);

} // namespace yuxi
