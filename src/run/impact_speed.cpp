#include "run/impact_speed.hpp"

#include <cmath>
#include <fmt/format.h>

namespace yuxi {
namespace {

// The fastest surface speed of a rigid motion over the given points (omega |k x (p - c)| at
// most, plus the drift and the oscillation's amplitude times its frequency).
template <class Points> double rigid_speed(const RigidMotion& m, const Points& points) {
  double arm = 0.0;
  if (m.omega != 0.0)
    for (const Vec3& p : points) arm = std::max(arm, norm(cross(m.axis, p - m.center)));
  return std::abs(m.omega) * arm + norm(m.drift) + std::abs(m.amplitude * m.frequency);
}

} // namespace

ImpactSpeed impact_speed(const Scene& scene, const ParticleStore& particles,
                         const std::vector<WallMotion>& motions) {
  ImpactSpeed best{0.0, ""};
  const auto consider = [&](double v, const std::string& source) {
    if (v > best.speed) best = {v, source};
  };
  // The highest fall: from the top of the highest grain, or of an insert's region, down to the
  // bottom of the domain, along gravity's components on non-periodic axes (those on periodic
  // axes have no potential).
  const Box& box = scene.sim.box;
  Vec3 g;
  for (int a = 0; a < 3; ++a) g[a] = box.periodic(a) ? 0.0 : scene.sim.gravity[a];
  if (const double g_abs = norm(g); g_abs > 0.0) {
    const Vec3 up = g * (-1.0 / g_abs);
    double bottom = HUGE_VAL, top = -HUGE_VAL;
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner{k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y,
                        k & 4 ? box.hi.z : box.lo.z};
      bottom = std::min(bottom, dot(corner, up));
    }
    for (std::size_t i = 0; i < particles.n_owned(); ++i)
      if (particles.kind[i] == Kind::grain)
        top = std::max(top, dot(particles.x[i], up) + particles.radius[i]);
    for (const InsertSpec& s : scene.inserts) {
      Vec3 lo, hi;
      s.region.bounds_in(box, lo, hi);
      for (int k = 0; k < 8; ++k)
        top = std::max(
            top, dot(Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}, up));
    }
    const double height = top - bottom;
    if (height > 0.0 && std::isfinite(height))
      consider(std::sqrt(2.0 * g_abs * height),
               fmt::format("a fall of {:.4g} under gravity, from the highest grain or insert to "
                           "the bottom of the domain",
                           height));
  }
  // Particles as they start, and wall particles as their motions move them.
  std::vector<std::vector<Vec3>> moved(motions.size());
  for (std::size_t i = 0; i < particles.n_owned(); ++i) {
    if (particles.kind[i] == Kind::grain)
      consider(norm(particles.v[i]),
               fmt::format("the initial velocity of particle {}", particles.gid[i]));
    else if (particles.motion[i] < motions.size())
      moved[particles.motion[i]].push_back(particles.x[i]);
  }
  for (std::size_t k = 0; k < motions.size(); ++k) {
    if (moved[k].empty()) continue;
    if (const auto* radial = std::get_if<RadialCosineMotion>(&motions[k]))
      consider(std::abs(radial->amplitude * radial->omega), "the wall particles' radial mode");
    else if (const auto* rigid = std::get_if<RigidMotion>(&motions[k]))
      consider(rigid_speed(*rigid, moved[k]), "the wall particles' motion");
  }
  for (const PlaneWall& p : scene.planes)
    consider(std::abs(p.amplitude * p.omega), fmt::format("the oscillation of plane '{}'", p.name));
  for (const ShapedWall& w : scene.walls) {
    const std::string name = wall_name(w);
    if (const auto* mesh = std::get_if<MeshWall>(&w)) {
      double v = 0.0;
      if (const auto* rigid = std::get_if<RigidMotion>(&mesh->motion))
        v = rigid_speed(*rigid, mesh->whole_mesh().vertices);
      else if (const auto* radial = std::get_if<RadialCosineMotion>(&mesh->motion))
        v = std::abs(radial->amplitude * radial->omega);
      consider(v + norm(mesh->surface_velocity), fmt::format("the motion of mesh '{}'", name));
    } else {
      const auto& c = std::get<CylinderWall>(w);
      consider(std::abs(c.omega) * c.radius + rigid_speed(c.carried, std::vector<Vec3>{}),
               fmt::format("the surface of cylinder '{}'", name));
    }
  }
  for (const InsertSpec& s : scene.inserts)
    consider(norm(s.grains.velocity) + s.grains.velocity_spread,
             fmt::format("the velocity insert {} gives its grains", s.name));
  if (!(best.speed > 0.0) || !std::isfinite(best.speed))
    best = {1.0, "nothing in the scene sets a speed: 1 length/time"};
  return best;
}

} // namespace yuxi
