#include "run/scene_builder.hpp"

#include <fmt/format.h>

namespace yuxi {

namespace {

// An outlet that holds every grain the run starts with would empty the bed at the first list
// build: refused. One that holds some of them takes those at once: a warning that counts them.
void check_outlets(const Scene& scene, const ParticleStore& particles, BuildReport& r) {
  std::size_t grains = 0;
  for (std::size_t i = 0; i < particles.n_owned(); ++i) grains += particles.kind[i] == Kind::grain;
  for (const OutletSpec& o : scene.outlets) {
    std::size_t inside = 0;
    for (std::size_t i = 0; i < particles.n_owned(); ++i)
      inside += particles.kind[i] == Kind::grain && o.region.contains(particles.x[i]);
    if (inside == 0) continue;
    if (inside == grains)
      throw SceneError(fmt::format("{}: outlet {}: its region ({}) holds all {} grains the run "
                                   "starts with; they would all leave at the first step",
                                   scene.source, o.name, o.region.describe(), grains));
    r.warnings.push_back(fmt::format("outlet {} holds {} of the {} grains the run starts with; "
                                     "they leave at the first step",
                                     o.name, inside, grains));
  }
}

} // namespace

std::string speed_note(const BuildReport& r) {
  if (!r.stiffest.depends_on_speed) return "";
  return fmt::format(", meeting at {:.4g}: {}", r.impact.speed, r.impact.source);
}

std::unique_ptr<Simulation> build_simulation(const Scene& scene, bool force_dt, BuildReport* report,
                                             Comm comm) {
  if (!(scene.largest_grain_radius > 0.0))
    throw SceneError(fmt::format("{}: the scene has no grains: add a [basin], [[fill]], "
                                 "[[insert]] or [[particle]] entries, or start it from another "
                                 "run's state (yuxi run --from, Python's Simulation.branch)",
                                 scene.source));
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
  // The fills, in file order, each clear of every particle placed before it.
  if (!scene.fills.empty()) {
    std::vector<ParticleSpec> placed;
    placed.reserve(particles.n_owned());
    for (std::size_t i = 0; i < particles.n_owned(); ++i) {
      ParticleSpec p;
      p.position = particles.x[i];
      p.radius = particles.radius[i];
      placed.push_back(p);
    }
    for (const FillSpec& f : scene.fills) {
      std::vector<ParticleSpec> grains;
      try {
        grains = fill_particles(f, scene.sim.box, placed);
      } catch (const FillError& e) {
        throw SceneError(e.what());
      }
      for (const auto& p : grains) particles.add(p, next++);
      (f.walls ? r.walls : r.grains) += grains.size();
      r.filled += grains.size();
      placed.insert(placed.end(), grains.begin(), grains.end());
    }
  }
  check_outlets(scene, particles, r);
  r.impact = impact_speed(scene, particles, motions);
  auto sim = std::make_unique<Simulation>(scene.sim, std::move(particles), scene.planes,
                                          std::move(motions), scene.law, comm, scene.walls);
  if (!scene.inserts.empty() || !scene.outlets.empty())
    sim->set_sources(scene.inserts, scene.outlets);
  check_time_step(scene, *sim, force_dt, r);
  if (report) *report = r;
  return sim;
}

void check_time_step(const Scene& scene, const Simulation& sim, bool force_dt, BuildReport& r) {
  r.stiffest = sim.stiffest_contact(r.impact.speed);
  r.dt_over_tc = scene.sim.dt / r.stiffest.contact_time;
  if (r.dt_over_tc > 0.1 && !scene.run.allow_large_dt && !force_dt) {
    const auto& m = scene.materials;
    throw TimeStepError(fmt::format(
        "{}: run.dt: {} is {:.3g} of the contact time t_c = {:.4g} of the stiffest contact "
        "({}-{}, m_eff = {:.4g}{}); at most t_c/10 = {:.4g} is allowed. Reduce dt, or set "
        "run.allow_large_dt = true to run anyway",
        scene.dt_location, scene.sim.dt, r.dt_over_tc, r.stiffest.contact_time,
        m[r.stiffest.material_a], m[r.stiffest.material_b], r.stiffest.m_eff, speed_note(r),
        r.stiffest.contact_time / 10));
  }
}

} // namespace yuxi
