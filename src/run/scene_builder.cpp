#include "run/scene_builder.hpp"

#include "sim/clump_bodies.hpp"

#include <fmt/format.h>
#include <span>

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

namespace {

// The scene's particles at t = 0, as every rank builds them: the basin's, the [[particle]]s, the
// [[clump]]s, the fills in file order, each clear of every particle placed before it; and the
// clumps' bodies.
struct SceneParticles {
  ParticleStore particles;
  std::vector<ClumpBody> clumps;
};

// The grains a fill of clumps placed become clumps of its shape: each grain's ball bounds its
// clump (scaled to the ball's radius), turned at random about its centre of mass from the fill's
// own stream; the members take the ids from `next` on. A shape of one member leaves the grains
// spheres, as the fill placed them.
void add_clumps(const Scene& scene, const FillSpec& f, std::span<const ParticleSpec> grains,
                GlobalId& next, SceneParticles& out) {
  const ClumpShape& shape = scene.shapes[static_cast<std::size_t>(f.shape)];
  Random turns(f.grains.seed * 4 + 4);
  for (const ParticleSpec& p : grains) {
    if (shape.members.size() == 1) {
      out.particles.add(p, next++);
      continue;
    }
    PlacedClump c = make_clump(shape.scaled(p.radius / shape.bounding_radius), f.grains.density,
                               p.material, next, p.position, random_orientation(turns), p.velocity);
    c.body.shape = f.shape;
    for (const ParticleSpec& m : c.members) out.particles.add(m, next++);
    out.clumps.push_back(c.body);
  }
}

SceneParticles scene_particles(const Scene& scene, BuildReport& r) {
  SceneParticles out;
  ParticleStore& particles = out.particles;
  if (scene.basin) {
    BuiltParticles basin = build_fish_basin(*scene.basin, scene.sim.box.lo);
    particles = std::move(basin.particles);
    r.walls = basin.n_walls;
    r.grains = basin.n_grains;
  }
  GlobalId next = static_cast<GlobalId>(particles.n_owned());
  for (const auto& p : scene.particles) {
    particles.add(p, next++);
    (p.kind == Kind::grain ? r.grains : r.walls) += 1;
  }
  for (const ClumpSpec& c : scene.clumps) {
    const ClumpShape& shape = scene.shapes[static_cast<std::size_t>(c.shape)];
    PlacedClump placed = make_clump(shape.scaled(c.scale), c.density, c.material, next, c.position,
                                    c.orientation * shape.frame, c.velocity, c.angular_velocity);
    ++r.grains;
    if (placed.members.size() == 1) {
      particles.add(lone_member_as_sphere(placed), next++);
      continue;
    }
    placed.body.shape = c.shape;
    for (const ParticleSpec& m : placed.members) particles.add(m, next++);
    out.clumps.push_back(placed.body);
  }
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
      if (f.shape >= 0)
        add_clumps(scene, f, grains, next, out);
      else
        for (const auto& p : grains) particles.add(p, next++);
      (f.walls ? r.walls : r.grains) += grains.size();
      r.filled += grains.size();
      placed.insert(placed.end(), grains.begin(), grains.end());
    }
  }
  return out;
}

// The wall particles' motions: the basin's, or standing still.
std::vector<WallMotion> scene_motions(const Scene& scene) {
  if (scene.basin) return fish_basin_motions(*scene.basin, scene.sim.box.lo);
  return {StaticMotion{}};
}

} // namespace

SimulationFrame scene_frame(const Scene& scene) {
  std::vector<std::string> shape_names;
  for (const ClumpShape& shape : scene.shapes) shape_names.push_back(shape.name);
  return {scene.sim,   scene.planes,  scene_motions(scene), scene.law,
          scene.walls, scene.inserts, scene.outlets,        std::move(shape_names)};
}

std::size_t scene_wall_particles(const Scene& scene) {
  // A fill of wall particles by packing fraction or mass places them to count them (and with
  // them everything placed before it).
  for (const FillSpec& f : scene.fills)
    if (f.walls && f.amount != FillSpec::Amount::count) {
      BuildReport r;
      scene_particles(scene, r);
      return r.walls;
    }
  std::size_t walls = scene.basin ? fish_basin_walls(*scene.basin) : 0;
  for (const auto& p : scene.particles) walls += p.kind == Kind::grain ? 0 : 1;
  for (const FillSpec& f : scene.fills)
    if (f.walls) walls += static_cast<std::size_t>(f.value);
  return walls;
}

std::unique_ptr<Simulation> build_simulation(const Scene& scene, bool force_dt, BuildReport* report,
                                             Comm comm) {
  if (!(scene.largest_grain_radius > 0.0))
    throw SceneError(fmt::format("{}: the scene has no grains: add a [basin], [[fill]], "
                                 "[[insert]], [[particle]] or [[clump]] entries, or start it from "
                                 "another run's state (yuxi run --from, Python's "
                                 "Simulation.branch)",
                                 scene.source));
  BuildReport r;
  SceneParticles built = scene_particles(scene, r);
  ParticleStore& particles = built.particles;
  check_outlets(scene, particles, r);
  SimulationFrame frame = scene_frame(scene);
  r.impact = impact_speed(scene, particles, frame.motions);
  auto sim = std::make_unique<Simulation>(std::move(frame.config), std::move(particles),
                                          std::move(frame.planes), std::move(frame.motions),
                                          std::move(frame.law), comm, std::move(frame.shaped_walls),
                                          std::move(built.clumps));
  if (!frame.inserts.empty() || !frame.outlets.empty())
    sim->set_sources(std::move(frame.inserts), std::move(frame.outlets));
  sim->name_shapes(std::move(frame.shape_names));
  check_time_step(scene, *sim, force_dt, r);
  if (report) *report = r;
  return sim;
}

std::unique_ptr<Simulation> continue_simulation(const Scene& scene, const SavedState& saved,
                                                std::optional<Simulation::BranchCheck> branch,
                                                bool force_dt, BuildReport* report, Comm comm) {
  SimulationFrame frame = scene_frame(scene);
  auto sim = std::make_unique<Simulation>(std::move(frame), saved, comm, branch);
  // What the state holds, and the impact speed of its grains.
  BuildReport r;
  const ParticleStore& s = sim->particles();
  // (a clump is one grain, as energies.csv and a fresh start count it: its body, here, and not
  // its members)
  double counts[2] = {static_cast<double>(sim->clumps().size()), 0.0};
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (!s.is_grain(i))
      counts[1] += 1.0;
    else if (s.body[i] < 0)
      counts[0] += 1.0;
  comm.sum(counts, 2);
  r.grains = static_cast<std::size_t>(counts[0]);
  r.walls = static_cast<std::size_t>(counts[1]);
  check_running_time_step(scene, *sim, force_dt, r);
  if (report) *report = r;
  return sim;
}

void check_running_time_step(const Scene& scene, const Simulation& sim, bool force_dt,
                             BuildReport& r) {
  // (every rank's grains: the fastest, named by the first rank that has it)
  // (the motions alone: a whole frame would copy the scene's meshes)
  const ImpactSpeed mine = impact_speed(scene, sim.particles(), scene_motions(scene));
  r.impact.speed = sim.comm().max(mine.speed);
  r.impact.source = sim.comm().first_error(mine.speed == r.impact.speed ? mine.source : "");
  check_time_step(scene, sim, force_dt, r);
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
