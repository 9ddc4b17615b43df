#include "run/scene_builder.hpp"

#include <fmt/format.h>

namespace yuxi {

std::unique_ptr<Simulation> build_simulation(const Scene& scene, bool force_dt, BuildReport* report,
                                             Comm comm) {
  ParticleStore particles;
  std::vector<WallMotion> motions{StaticMotion{}};
  BuildReport r;
  if (scene.basin) {
    BuiltParticles basin = build_fish_basin(*scene.basin, scene.sim.box.lo);
    particles = std::move(basin.particles);
    motions = std::move(basin.motions);
    r.walls = basin.n_walls;
    r.grains = basin.n_grains;
  }
  GlobalId next = static_cast<GlobalId>(particles.n_owned());
  for (const auto& p : scene.particles) {
    particles.add(p, next++);
    (p.kind == Kind::grain ? r.grains : r.walls) += 1;
  }
  auto sim = std::make_unique<Simulation>(scene.sim, std::move(particles), scene.planes,
                                          std::move(motions), scene.law, comm, scene.walls);
  r.stiffest = sim->stiffest_contact();
  r.dt_over_tc = scene.sim.dt / r.stiffest.contact_time;
  if (r.dt_over_tc > 0.1 && !scene.run.allow_large_dt && !force_dt) {
    const auto& m = scene.materials;
    throw SceneError(fmt::format(
        "{}: run.dt: {} is {:.3g} of the contact time t_c = {:.4g} of the stiffest contact "
        "({}-{}, m_eff = {:.4g}); at most t_c/10 = {:.4g} is allowed. Reduce dt, or set "
        "run.allow_large_dt = true (or pass --force) to run anyway",
        scene.dt_location, scene.sim.dt, r.dt_over_tc, r.stiffest.contact_time,
        m[r.stiffest.material_a], m[r.stiffest.material_b], r.stiffest.m_eff,
        r.stiffest.contact_time / 10));
  }
  if (report) *report = r;
  return sim;
}

} // namespace yuxi
