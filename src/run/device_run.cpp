#include "run/device_run.hpp"

#include "device/step_phases.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace yuxi {

std::vector<std::string> device_engine_refusals(const Simulation& sim) {
  std::vector<std::string> no;
  if (sim.comm().size() > 1)
    no.push_back(
        fmt::format("{} MPI ranks (the device engine runs in one process)", sim.comm().size()));
  for (const ShapedWall& wall : sim.shaped_walls())
    no.push_back(std::holds_alternative<CylinderWall>(wall) ? "a [[cylinder]] wall"
                                                            : "a [[mesh]] wall");
  for (const WallMotion& motion : sim.wall_motions())
    if (std::holds_alternative<RigidMotion>(motion)) {
      no.push_back("wall particles in rigid motion ([[wall_particles]] with a motion)");
      break;
    }
  if (sim.wall_motions().size() > static_cast<std::size_t>(device::max_wall_motions))
    no.push_back(fmt::format("{} wall motions (at most {})", sim.wall_motions().size(),
                             device::max_wall_motions));
  if (!sim.inserts().empty()) no.push_back("[[insert]] sources");
  if (sim.has_outlets()) no.push_back("[[outlet]] sinks");
  return no;
}

namespace {

// Tiles the particles and the box `r` times along each axis.
void replicate(device::DeviceScene& scene, const Replicas& r) {
  const device::HostParticles one = scene.particles;
  const std::vector<device::DeviceClump> clumps = std::move(scene.clumps);
  scene.clumps.clear();
  GlobalId largest = 0;
  for (const GlobalId id : one.gid) largest = std::max(largest, id);
  device::HostParticles& all = scene.particles;
  all = {};
  const Vec3 length = scene.hi - scene.lo;
  int copy = 0;
  for (int cz = 0; cz < r.n[2]; ++cz)
    for (int cy = 0; cy < r.n[1]; ++cy)
      for (int cx = 0; cx < r.n[0]; ++cx, ++copy) {
        const Vec3 shift{cx * length.x, cy * length.y, cz * length.z};
        for (std::size_t i = 0; i < one.size(); ++i) {
          all.x.push_back(one.x[i] + shift);
          all.v.push_back(one.v[i]);
          all.w.push_back(one.w[i]);
          all.radius.push_back(one.radius[i]);
          all.mass.push_back(one.mass[i]);
          all.inv_mass.push_back(one.inv_mass[i]);
          all.inv_inertia.push_back(one.inv_inertia[i]);
          all.gid.push_back(one.gid[i] + copy * (largest + 1));
          all.kind.push_back(one.kind[i]);
          all.material.push_back(one.material[i]);
          all.x_rest.push_back(one.x_rest[i] + shift);
          if (!one.f.empty()) {
            all.f.push_back(one.f[i]);
            all.torque.push_back(one.torque[i]);
          }
          if (!one.x_build.empty()) all.x_build.push_back(one.x_build[i] + shift);
          all.motion.push_back(one.motion[i]);
          if (!one.body.empty())
            all.body.push_back(one.body[i] < 0 ? one.body[i] : one.body[i] + copy * (largest + 1));
        }
        for (const device::DeviceClump& c : clumps) { // (a clump's id is its first member's)
          device::DeviceClump& placed = scene.clumps.emplace_back(c);
          placed.id = c.id + copy * (largest + 1);
          placed.x = c.x + shift;
        }
      }
  for (int a = 0; a < 3; ++a) scene.hi[a] = scene.lo[a] + r.n[a] * length[a];
}

template <class Model>
std::unique_ptr<device::DeviceEngine> engine_for(const Simulation& sim,
                                                 const ContactLaw<Model>& law, DeviceChoice choice,
                                                 const Replicas& replicas) {
  device::DeviceScene scene;
  const ParticleStore& s = sim.particles();
  const std::size_t n = s.n_owned();
  device::HostParticles& p = scene.particles;
  p.x.assign(s.x.begin(), s.x.begin() + n);
  p.v.assign(s.v.begin(), s.v.begin() + n);
  p.w.assign(s.w.begin(), s.w.begin() + n);
  p.radius.assign(s.radius.begin(), s.radius.begin() + n);
  p.mass.assign(s.mass.begin(), s.mass.begin() + n);
  p.inv_mass.assign(s.inv_mass.begin(), s.inv_mass.begin() + n);
  p.inv_inertia.assign(s.inv_inertia.begin(), s.inv_inertia.begin() + n);
  p.gid.assign(s.gid.begin(), s.gid.begin() + n);
  p.kind.assign(s.kind.begin(), s.kind.begin() + n);
  p.material.assign(s.material.begin(), s.material.begin() + n);
  p.x_rest.assign(s.x_rest.begin(), s.x_rest.begin() + n);
  // Past the start, the forces of the last step come along (computed at its half-step
  // velocities: computing them again at the full-step ones would change the trajectory).
  scene.forces_given = sim.step_count() > 0;
  if (scene.forces_given) {
    p.f.assign(s.f.begin(), s.f.begin() + n);
    p.torque.assign(s.torque.begin(), s.torque.begin() + n);
    // ... and the list of the last build is made again from where the particles stood then.
    p.x_build.assign(s.x_build.begin(), s.x_build.begin() + n);
  }
  p.motion.assign(s.motion.begin(), s.motion.begin() + n);
  if (!sim.clumps().empty()) {
    p.body.assign(s.body.begin(), s.body.begin() + n);
    for (const ClumpBody& b : sim.clumps()) {
      device::DeviceClump& c = scene.clumps.emplace_back();
      c.id = b.id;
      c.mass = b.mass;
      c.inertia = b.inertia;
      c.x = b.x;
      c.v = b.v;
      c.q = b.q;
      c.p = b.p;
      c.force = b.force;
      c.torque = b.torque;
      c.members = b.members;
    }
  }
  for (const WallMotion& motion : sim.wall_motions()) {
    device::DeviceMotion& m = scene.motions.emplace_back();
    if (const auto* wave = std::get_if<RadialCosineMotion>(&motion)) {
      m.radial_cosine = true;
      m.center = wave->center;
      m.mode = wave->mode;
      m.amplitude = wave->amplitude;
      m.omega = wave->omega;
      m.t0 = wave->t0;
    }
  }
  for (const PlaneWall& plane : sim.planes())
    scene.planes.push_back(
        {plane.point, plane.normal, plane.material, plane.amplitude, plane.omega, plane.t0});
  const SimulationConfig& c = sim.config();
  scene.lo = c.box.lo;
  scene.hi = c.box.hi;
  for (int a = 0; a < 3; ++a) scene.periodic[a] = c.box.periodic(a);
  scene.gravity = c.gravity;
  scene.dt = c.dt;
  scene.skin = c.skin;
  scene.cell_size = c.cell_size;
  scene.time = sim.time();
  scene.remove_escaped = c.on_escape == EscapePolicy::remove;
  replicate(scene, replicas);
  const std::size_t m = law.coeffs.n_materials();
  scene.n_materials = m;
  std::vector<typename Model::Coeffs> table(m * m);
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < m; ++b)
      if (law.coeffs.has(a, b)) table[a * m + b] = law.coeffs(a, b);
  // The contacts open now, with their states (a run continued on the device).
  std::vector<device::KeyedState<typename Model::State>> open;
  if (const auto* history =
          dynamic_cast<const ContactHistory<typename Model::State>*>(&sim.contact_states()))
    for (const auto& e : history->entries(s, sim.neighbor_list()))
      open.push_back({e.key.first, e.key.second, e.state});
  const int copies = replicas.n[0] * replicas.n[1] * replicas.n[2];
  if (copies > 1) { // each copy's contacts, its ids offset as replicate() offsets them
    GlobalId largest = 0;
    for (const GlobalId id : s.gid) largest = std::max(largest, id);
    const std::size_t one = open.size();
    open.reserve(one * static_cast<std::size_t>(copies));
    for (int copy = 1; copy < copies; ++copy)
      for (std::size_t k = 0; k < one; ++k)
        open.push_back({open[k].first + copy * (largest + 1), open[k].second + copy * (largest + 1),
                        open[k].state});
  }
  check_device_choice(choice);
#if defined(YUXI_HAVE_CUDA)
  if (choice == DeviceChoice::cuda) return device::make_cuda_engine<Model>(scene, table, open);
#endif
  return device::make_host_engine<Model>(scene, table, open);
}

} // namespace

bool build_has_cuda() {
#if defined(YUXI_HAVE_CUDA)
  return true;
#else
  return false;
#endif
}

void check_device_choice(DeviceChoice choice) {
#if !defined(YUXI_HAVE_CUDA)
  if (choice == DeviceChoice::cuda)
    throw std::runtime_error("this build of yuxi has no CUDA: configure it with -DYUXI_CUDA=ON "
                             "(docs/gpu.md) to run on a GPU");
#else
  (void)choice;
#endif
}

std::unique_ptr<device::DeviceEngine> make_device_engine(const Simulation& sim, DeviceChoice choice,
                                                         Replicas replicas) {
  std::vector<std::string> no = device_engine_refusals(sim);
  for (int a = 0; a < 3; ++a)
    if (replicas.n[a] < 1 || (replicas.n[a] > 1 && !sim.config().box.periodic(a)))
      no.push_back(fmt::format("{} copies along axis {}, which is not periodic", replicas.n[a], a));
  if (!no.empty()) {
    std::string what = "the device engine does not run this scene's";
    for (const std::string& line : no) what += "\n  - " + line;
    throw std::invalid_argument(what);
  }
  return std::visit([&](const auto& law) { return engine_for(sim, law, choice, replicas); },
                    sim.contact_law());
}

} // namespace yuxi
