// Google Benchmark of one coarse-graining sample against the steps it rides on: LAMMPS's chute
// (scenes/chute-lammps.toml, 32,000 grains) run for a while, then, on its state, a step with and
// without the contact record, the gathering of grains and contacts (CoarseGrainInput), and the
// sums of a profile along z (80 points, Gaussian, w = 1, as bench/coarse_grain_cost.sh) for
// every field and for a flow's fields (density, velocity, stress, temperature). A sample every
// 100 steps costs (gather + sums) / (100 step) of the run.
// usage: coarse_grain_sample [--scene PATH] [--settle STEPS] [benchmark options]
#include "analysis/coarse_grain.hpp"
#include "io/scene_reader.hpp"
#include "run/coarse_grain_contacts.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"

#include <benchmark/benchmark.h>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace yuxi {
namespace {

std::string scene_path = YUXI_SOURCE_DIR "/scenes/chute-lammps.toml";
long settle_steps = 2000;

// The chute after its settling steps, built once, its contacts recorded at its last step.
Simulation& chute() {
  static const std::unique_ptr<Simulation> sim = [] {
    auto s = build_simulation(read_scene_file(scene_path), false);
    for (long k = 0; k < settle_steps; ++k) s->step();
    s->record_contacts(true);
    s->step();
    return s;
  }();
  return *sim;
}

analysis::CgSettings profile(bool flow) {
  const Box& box = chute().config().box;
  analysis::CgSettings s;
  s.kind = analysis::CgKind::gaussian;
  s.width = 1.0;
  s.cutoff = 3.0;
  s.grid.lo = box.lo;
  s.grid.hi = box.hi;
  s.grid.n = {1, 1, 80};
  s.grid.averaged = {true, true, false};
  for (int a = 0; a < 3; ++a) s.grid.periodic[static_cast<std::size_t>(a)] = box.periodic(a);
  const std::vector<std::string> flow_fields{"density", "velocity", "stress", "temperature"};
  s.parts = flow ? analysis::parts_for(flow_fields) : analysis::CgParts{};
  return s;
}

void BM_Step(benchmark::State& st) {
  Simulation& sim = chute();
  sim.record_contacts(st.range(0) != 0);
  for (auto _ : st) sim.step();
  sim.record_contacts(true);
  sim.step();
  st.counters["grains"] = static_cast<double>(sim.particles().n_owned());
}
BENCHMARK(BM_Step)->ArgName("recorded")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_Gather(benchmark::State& st) {
  Simulation& sim = chute();
  CoarseGrainInput input;
  for (auto _ : st) {
    input.gather(sim);
    benchmark::DoNotOptimize(input.contacts.data());
  }
  st.counters["contacts"] = static_cast<double>(input.contacts.size());
}
BENCHMARK(BM_Gather)->Unit(benchmark::kMillisecond);

void BM_Sums(benchmark::State& st) {
  CoarseGrainInput input;
  input.gather(chute());
  const analysis::CgSettings settings = profile(st.range(0) != 0);
  for (auto _ : st) {
    auto sums = analysis::coarse_grain_sums(input.grains(), input.contacts, settings);
    benchmark::DoNotOptimize(sums.data());
  }
}
BENCHMARK(BM_Sums)->ArgName("flow")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

} // namespace
} // namespace yuxi

int main(int argc, char** argv) {
  std::vector<char*> rest{argv[0]};
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--scene" && a + 1 < argc)
      yuxi::scene_path = argv[++a];
    else if (arg == "--settle" && a + 1 < argc)
      yuxi::settle_steps = std::atol(argv[++a]);
    else
      rest.push_back(argv[a]);
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
