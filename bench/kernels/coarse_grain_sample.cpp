// Google Benchmark of one coarse-graining sample against the steps it rides on: on the state of
// LAMMPS's chute (scenes/chute-lammps.toml, 32,000 grains; its data file holds a flow), a step
// with and without the contact record, the gathering of grains and contacts
// (CoarseGrainInput), and the sums of a profile along z (80 points, Gaussian, w = 1, as
// bench/coarse_grain_cost.sh) for every field and for a flow's fields (density, velocity,
// stress, temperature). A sample every 100 steps costs (record + gather + sums) / (100 steps)
// of the run; BM_EveryHundredSteps times the whole of it, 100 steps with and without a sample,
// alternating.
// usage: coarse_grain_sample [--scene PATH] [--settle STEPS] [benchmark options]
#include "analysis/coarse_grain.hpp"
#include "io/scene_reader.hpp"
#include "run/coarse_grain_contacts.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <benchmark/benchmark.h>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace yuxi {
namespace {

std::string scene_path = YUXI_SOURCE_DIR "/scenes/chute-lammps.toml";
long settle_steps = 0; // (the data file holds a flow already)

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

// What a table written every 100 steps adds to a run: 100 steps alone, then 100 steps whose
// last is recorded and followed by a sample of (sample 1) a flow's fields or (sample 2) every
// field, again and again, timed apart: the record, the gathering, the sums and the fields, and
// the steps' own slowing where a sample has pushed their data out of the caches. (The files'
// writing, 80 rows, is left out.) The counters give the median over the pairs of the ratio of
// the two blocks' times, less one, in percent: two neighbouring blocks see the same machine.
void BM_EveryHundredSteps(benchmark::State& st) {
  Simulation& sim = chute();
  const bool flow = st.range(0) == 1;
  CoarseGrainInput input;
  const analysis::CgSettings settings = profile(flow);
  const auto hundred_steps = [&](bool sample) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 99; ++k) sim.step();
    sim.record_contacts(sample);
    sim.step();
    sim.record_contacts(false);
    if (sample) {
      input.gather(sim);
      const auto fields = analysis::coarse_grain_fields(
          analysis::coarse_grain_sums(input.grains(), input.contacts, settings), settings.grid);
      benchmark::DoNotOptimize(fields.density.data());
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<double> ratios;
  bool sample_first = false; // (in turn: a drift of the flow favours neither block)
  for (auto _ : st) {
    double alone = 0.0, sampled = 0.0;
    if (sample_first)
      sampled = hundred_steps(true), alone = hundred_steps(false);
    else
      alone = hundred_steps(false), sampled = hundred_steps(true);
    sample_first = !sample_first;
    ratios.push_back(sampled / alone);
  }
  std::sort(ratios.begin(), ratios.end());
  st.counters["overhead_%"] = 100.0 * (ratios[ratios.size() / 2] - 1.0);
  st.counters["pairs"] = static_cast<double>(ratios.size());
  sim.record_contacts(true);
  sim.step();
}
BENCHMARK(BM_EveryHundredSteps)
    ->ArgName("flow")
    ->Arg(0)
    ->Arg(1)
    ->Iterations(100)
    ->Unit(benchmark::kMillisecond);

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
