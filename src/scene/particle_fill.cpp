#include "scene/particle_fill.hpp"

#include "core/ball_volume.hpp"
#include "core/units.hpp"
#include "scene/ball_hash.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace yuxi {

double GrainKind::mass_of(double r) const {
  return density * (volume_fraction * ball_volume(r));
}

Vec3 GrainKind::draw_velocity(Random& rng) const {
  if (velocity_spread <= 0) return velocity;
  for (;;) { // a point uniform in the unit ball
    const Vec3 u{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    if (norm2(u) <= 1.0) return velocity + velocity_spread * u;
  }
}

namespace {

// The radii of the fill, from its size stream: the count, or as many as reach the volume or
// mass asked for (the last one included where it brings the total nearer).
std::vector<double> draw_radii(const FillSpec& f, double region_volume) {
  Random rng(f.grains.seed * 4 + 1);
  std::vector<double> radii;
  if (f.amount == FillSpec::Amount::count) {
    const auto n = static_cast<std::size_t>(std::llround(f.value));
    for (std::size_t k = 0; k < n; ++k) radii.push_back(f.grains.size.draw(rng));
    return radii;
  }
  const bool by_mass = f.amount == FillSpec::Amount::mass;
  const double target = by_mass ? f.value : f.value * region_volume;
  double total = 0;
  while (total < target) {
    const double r = f.grains.size.draw(rng);
    const double add = by_mass ? f.grains.mass_of(r) : f.grains.volume_fraction * ball_volume(r);
    if (total + add - target > target - total) break; // the next one would overshoot more
    radii.push_back(r);
    total += add;
    if (radii.size() > (std::size_t{1} << 31))
      throw FillError(fmt::format("{}: more than 2^31 grains asked for", f.name));
  }
  return radii;
}

ParticleSpec grain(const FillSpec& f, const Vec3& x, double r, Random& velocities) {
  ParticleSpec p;
  p.position = x;
  p.radius = r;
  p.mass = f.grains.mass_of(r);
  p.material = f.grains.material;
  p.kind = f.walls ? Kind::wall : Kind::grain;
  if (!f.walls) p.velocity = f.grains.draw_velocity(velocities);
  return p;
}

} // namespace

std::vector<ParticleSpec> fill_particles(const FillSpec& f, const Box& domain,
                                         std::span<const ParticleSpec> others) {
  const double volume = f.region.volume_in(domain);
  if (!(volume > 0))
    throw FillError(fmt::format("{}: the region ({}) has no volume inside the domain", f.name,
                                f.region.describe()));
  const std::vector<double> radii = draw_radii(f, volume);
  double grains_volume = 0;
  for (double r : radii) grains_volume += ball_volume(r);
  const double fraction = grains_volume / volume;
  const double r_max = f.grains.size.largest();
  if (f.placement == FillSpec::Placement::random && fraction > random_fill_limit)
    throw FillError(fmt::format(
        "{}: the balls of {} grains (a clump's: its bounding ball) make a packing fraction of "
        "{:.3f} in the region ({:.4g} of volume), beyond what random placement without overlap "
        "reaches (it jams near 0.35-0.38): use "
        "placement = \"lattice\", or pour the grains with [[insert]] and let them settle",
        f.name, radii.size(), fraction, volume));

  // A grain wider than the region along an axis has no place in it at all.
  {
    Vec3 lo, hi;
    f.region.bounds_in(domain, lo, hi);
    for (int a = 0; a < 3; ++a)
      if (2 * r_max > hi[a] - lo[a])
        throw FillError(fmt::format(
            "{}: its largest grain, of radius {:.4g} (a clump's: its bounding radius), is wider "
            "than the region ({}) along {} ({:.4g} across): no place holds it",
            f.name, r_max, f.region.describe(), "xyz"[a], hi[a] - lo[a]));
  }
  // The scene's particles near the region take up room. Along a periodic axis a grain may
  // straddle the face: it is looked for at its images across it, and a region that spans the
  // axis end to end holds it there (Region::contains_sphere_in).
  Vec3 lo, hi;
  f.region.bounds_in(domain, lo, hi);
  double reach = 2 * r_max;
  for (const auto& p : others) reach = std::max(reach, p.radius + r_max);
  BallHash placed(reach);
  for (const auto& p : others) {
    const Vec3 x = domain.wrap(p.position);
    bool near = true;
    for (int a = 0; a < 3; ++a)
      near = near && (domain.periodic(a) || (x[a] >= lo[a] - reach && x[a] <= hi[a] + reach));
    if (near) placed.add(x, p.radius);
  }
  Random places(f.grains.seed * 4 + 2), velocities(f.grains.seed * 4 + 3);
  std::vector<ParticleSpec> out;
  out.reserve(radii.size());
  const auto overlaps = [&](const Vec3& x, double r) {
    for (const Vec3& image : domain.images_within(x, reach))
      if (placed.overlaps(image, r)) return true;
    return false;
  };
  const auto fits = [&](const Vec3& x, double r) {
    return domain.contains(x) && f.region.contains_sphere_in(x, r, domain) && !overlaps(x, r);
  };

  if (f.placement == FillSpec::Placement::random) {
    for (double r : radii) {
      bool done = false;
      for (int attempt = 0; attempt < f.attempts_per_grain && !done; ++attempt) {
        const auto x = f.region.sample(places, domain);
        if (!x) break;
        if (!fits(*x, r)) continue;
        placed.add(*x, r);
        out.push_back(grain(f, *x, r, velocities));
        done = true;
      }
      if (!done) {
        double placed_volume = 0;
        for (const auto& p : out) placed_volume += ball_volume(p.radius);
        throw FillError(fmt::format(
            "{}: placed {} of {} grains; no free place for the next after {} random draws (the "
            "balls placed, a clump's its bounding ball, fill {:.3f} of the region; with 1000 "
            "draws a grain, random placement "
            "of equal spheres fills about 0.29 of a periodic box, less of a region whose faces "
            "the balls must clear, and 0.38 only with endless draws): ask for fewer, raise "
            "the fill's attempts, use placement = \"lattice\", or pour the grains with [[insert]]",
            f.name, out.size(), radii.size(), f.attempts_per_grain, placed_volume / volume));
      }
    }
    return out;
  }

  // Lattice: sites a = 2 (r_max + jitter) apart (with a hair of room), bottom layer first.
  const double a = 2.0 * (r_max + f.jitter) * (1.0 + 1e-9);
  std::array<int, 3> n{};
  for (int k = 0; k < 3; ++k) n[k] = static_cast<int>(std::floor((hi[k] - lo[k]) / a));
  std::size_t sites = 0, k = 0;
  for (int iz = 0; iz < n[2] && k < radii.size(); ++iz)
    for (int iy = 0; iy < n[1] && k < radii.size(); ++iy)
      for (int ix = 0; ix < n[0] && k < radii.size(); ++ix) {
        const Vec3 site{lo.x + (ix + 0.5) * a, lo.y + (iy + 0.5) * a, lo.z + (iz + 0.5) * a};
        if (!domain.contains(site) || !f.region.contains_sphere(site, r_max + f.jitter) ||
            overlaps(site, r_max + f.jitter))
          continue;
        ++sites;
        Vec3 offset;
        if (f.jitter > 0) do {
            offset = {places.uniform(-1, 1), places.uniform(-1, 1), places.uniform(-1, 1)};
          } while (norm2(offset) > 1.0);
        const Vec3 x = site + f.jitter * offset;
        placed.add(x, radii[k]);
        out.push_back(grain(f, x, radii[k], velocities));
        ++k;
      }
  if (out.size() < radii.size())
    throw FillError(fmt::format(
        "{}: the lattice of spacing {:.4g} (the largest diameter plus twice the jitter) has {} "
        "free sites in the region; {} grains asked for: ask for fewer, enlarge the region, or "
        "pour the grains with [[insert]]",
        f.name, a, sites, radii.size()));
  return out;
}

} // namespace yuxi
