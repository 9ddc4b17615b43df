#include "scene/fish_basin.hpp"

#include <cmath>
#include <stdexcept>

namespace yuxi {

double draw_grain_radius(Random& rng, double mean, double sd) {
  for (;;) {
    const double z = rng.normal();
    if (std::abs(z) <= 3.0) return mean + sd * z;
  }
}

int basin_wall_gap(const FishBasinSpec& b) {
  const double largest = b.radius_mean + 3.0 * b.radius_sd;
  return largest + b.jitter + b.wall_radius > b.spacing ? 1 : 0;
}

namespace {

Vec3 point_in_ball(Random& rng, double radius) {
  for (;;) {
    const Vec3 p{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    if (norm2(p) <= 1.0) return radius * p;
  }
}

// What lattice cell (i, j, k) of the basin holds: the bottom's or the side's wall particles, a
// grain at t = 0, or nothing. `gap`: basin_wall_gap().
enum class BasinCell { empty, bottom, side, grain };
BasinCell basin_cell(const FishBasinSpec& b, int gap, int i, int j, int k) {
  const double rho = std::hypot(i + 0.5 - 0.5 * b.cells[0], j + 0.5 - 0.5 * b.cells[1]);
  const double outer = b.radius + b.wall_thickness;
  if (k < b.bottom_layers && rho <= outer) return BasinCell::bottom;
  if (b.side_particles && k >= b.bottom_layers && k < b.bottom_layers + b.wall_height &&
      rho > b.radius && rho <= outer)
    return BasinCell::side;
  if (k >= b.bottom_layers + gap && k < b.bottom_layers + gap + b.fill_layers &&
      rho <= b.radius - gap)
    return BasinCell::grain;
  return BasinCell::empty;
}

} // namespace

std::vector<WallMotion> fish_basin_motions(const FishBasinSpec& b, const Vec3& origin) {
  RadialCosineMotion excitation = b.excitation;
  excitation.center = {origin.x + 0.5 * b.cells[0] * b.spacing,
                       origin.y + 0.5 * b.cells[1] * b.spacing, 0.0};
  return {StaticMotion{}, excitation};
}

std::size_t fish_basin_walls(const FishBasinSpec& b) {
  std::size_t walls = 0;
  const int gap = basin_wall_gap(b);
  for (int k = 0; k < b.cells[2]; ++k)
    for (int j = 0; j < b.cells[1]; ++j)
      for (int i = 0; i < b.cells[0]; ++i) {
        const BasinCell c = basin_cell(b, gap, i, j, k);
        walls += c == BasinCell::bottom || c == BasinCell::side;
      }
  return walls;
}

BuiltParticles build_fish_basin(const FishBasinSpec& b, const Vec3& origin) {
  if (b.radius + b.wall_thickness > 0.5 * std::min(b.cells[0], b.cells[1]))
    throw std::invalid_argument("basin radius plus wall thickness exceeds half the lattice");
  if (b.bottom_layers + b.wall_height > b.cells[2])
    throw std::invalid_argument("basin bottom plus wall height exceeds the lattice height");
  if (b.fill_layers + basin_wall_gap(b) > b.wall_height)
    throw std::invalid_argument("basin fill is higher than its wall");

  // Grains start clear of the walls: when the largest grain plus its jitter plus a wall particle
  // does not fit in one lattice spacing, one cell is left empty next to the walls.
  const int gap = basin_wall_gap(b);
  Random rng(b.seed);
  BuiltParticles out;
  out.motions = fish_basin_motions(b, origin);

  struct Grain {
    Vec3 position;
    double radius;
  };
  std::vector<Grain> grains;
  GlobalId next_id = 0;
  for (int k = 0; k < b.cells[2]; ++k)
    for (int j = 0; j < b.cells[1]; ++j)
      for (int i = 0; i < b.cells[0]; ++i) {
        const Vec3 centre = origin + b.spacing * Vec3{i + 0.5, j + 0.5, k + 0.5};
        const BasinCell cell = basin_cell(b, gap, i, j, k);
        if (cell == BasinCell::bottom || cell == BasinCell::side) {
          ParticleSpec w;
          w.position = centre;
          w.radius = b.wall_radius;
          w.mass = 1.0;
          w.kind = Kind::wall;
          w.material = b.wall_material;
          w.motion = cell == BasinCell::side ? 1 : 0;
          out.particles.add(w, next_id++);
          ++out.n_walls;
        } else if (cell == BasinCell::grain) {
          const double r = draw_grain_radius(rng, b.radius_mean, b.radius_sd);
          grains.push_back({centre + point_in_ball(rng, b.jitter), r});
        }
      }
  double mean_r3 = 0.0;
  for (const auto& g : grains) mean_r3 += g.radius * g.radius * g.radius;
  mean_r3 /= grains.empty() ? 1.0 : static_cast<double>(grains.size());
  for (const auto& g : grains) {
    ParticleSpec s;
    s.position = g.position;
    s.radius = g.radius;
    s.mass = g.radius * g.radius * g.radius / mean_r3;
    s.material = b.grain_material;
    out.particles.add(s, next_id++);
  }
  out.n_grains = grains.size();
  return out;
}

} // namespace yuxi
