// The device engine on a scene, timed: `device_chute SCENE STEPS [--cuda] [--replicate NX NY NZ]
// [--cpu-too]`. Prints the device, the particles, the rate in particle-steps/s, the device's bytes
// per particle, the energy books, and a digest (FNV-1a over the bits of every particle's x, v
// and w in id order) that two builds, or two machines, compare to the bit. --cpu-too runs the
// CPU engine (unreplicated) on the same steps first, for the ratio on the same machine.
#include "io/scene_reader.hpp"
#include "run/device_run.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

namespace {

std::uint64_t digest(const yuxi::device::HostParticles& p) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto add = [&](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) h = (h ^ b[k]) * 1099511628211ULL;
  };
  add(p.x.data(), p.x.size() * sizeof(yuxi::Vec3));
  add(p.v.data(), p.v.size() * sizeof(yuxi::Vec3));
  add(p.w.data(), p.w.size() * sizeof(yuxi::Vec3));
  return h;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

int main(int argc, char** argv) try {
  using namespace yuxi;
  if (argc < 3) {
    std::fprintf(stderr, "usage: device_chute SCENE STEPS [--cuda] [--replicate NX NY NZ] "
                         "[--cpu-too]\n");
    return 2;
  }
  const std::string path = argv[1];
  const std::int64_t steps = std::stoll(argv[2]);
  DeviceChoice choice = DeviceChoice::host;
  Replicas replicas;
  bool cpu_too = false;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--cuda") choice = DeviceChoice::cuda;
    if (arg == "--cpu-too") cpu_too = true;
    if (arg == "--replicate" && a + 3 < argc)
      for (int k = 0; k < 3; ++k) replicas.n[k] = std::stoi(argv[++a]);
  }
  std::ifstream in(path);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  Scene scene = read_scene_text(text, path);
  auto sim = build_simulation(scene, false);

  const auto t_setup = std::chrono::steady_clock::now();
  const auto engine = make_device_engine(*sim, choice, replicas);
  const double setup = seconds_since(t_setup);
  const std::size_t n = engine->particles().size();
  const double particles = static_cast<double>(n), step_count = static_cast<double>(steps);
  engine->run(1); // first touch of every kernel
  const auto t0 = std::chrono::steady_clock::now();
  engine->run(steps);
  const device::HostParticles p = engine->particles(); // waits for the device
  const double wall = seconds_since(t0);
  const device::DeviceEnergies e = engine->energies();
  std::printf("device: %s\n", engine->device_name().c_str());
  std::printf("particles %zu, steps %lld, list builds %lld, pairs %zu (%.2f per particle)\n", n,
              static_cast<long long>(steps), static_cast<long long>(engine->list_builds()),
              engine->listed_pairs(), static_cast<double>(engine->listed_pairs()) / particles);
  std::printf("setup %.3f s, run %.3f s: %.4g particle-steps/s\n", setup, wall,
              particles * step_count / wall);
  const device::DeviceMemory m = engine->device_memory();
  const auto per_particle = [&](std::size_t b) { return static_cast<double>(b) / particles; };
  std::printf("device memory %.0f bytes per particle: particles %.0f, cells %.0f, listed pairs "
              "%.0f, contacts %.0f, planes %.0f, clumps %.0f, sums and scratch %.0f; at most "
              "%.0f\n",
              per_particle(m.total()), per_particle(m.particles), per_particle(m.cells),
              per_particle(m.pairs), per_particle(m.contacts), per_particle(m.planes),
              per_particle(m.clumps), per_particle(m.work), per_particle(m.peak));
  std::printf("energies: translational %.17g rotational %.17g elastic %.17g dissipated %.17g "
              "gravity work %.17g\n",
              e.translational, e.rotational, e.elastic, e.dissipated, e.gravity_work);
  std::printf("digest %016llx\n", static_cast<unsigned long long>(digest(p)));
  if (cpu_too) {
    const std::size_t cpu_n = sim->particles().n_owned();
    sim->run(1);
    const auto t1 = std::chrono::steady_clock::now();
    sim->run(steps);
    const double cpu_wall = seconds_since(t1);
    std::printf("cpu engine, 1 core: %zu particles, %.3f s: %.4g particle-steps/s\n", cpu_n,
                cpu_wall, static_cast<double>(cpu_n) * step_count / cpu_wall);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "device_chute: %s\n", e.what());
  return 1;
}
