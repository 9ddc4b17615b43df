// Google Benchmark of the contact kernel: one linear spring-dashpot evaluation, and whole
// steps of a dense polydisperse packing (the pair loop with neighbour lists).
#include "contact/linear_spring_dashpot.hpp"
#include "core/random.hpp"
#include "sim/simulation.hpp"

#include <benchmark/benchmark.h>

namespace yuxi {
namespace {

void BM_LinearEvaluate(benchmark::State& st) {
  const LinearSpringDashpot::Coeffs c{2.5e5, 0.57e5, 100.0, 32.0, 0.84, 0.4};
  ContactGeometry g;
  g.n = {0, 0, 1};
  g.overlap = 1e-3;
  g.distance = 2 - 1e-3;
  g.v_rel = {0.1, 0.2, -0.3};
  g.w_i = {1, 0, 0};
  g.a_i = g.a_j = 1;
  g.m_eff = 0.5;
  g.r_eff = 0.5;
  g.dt = 1e-4;
  LinearSpringDashpot::State s;
  for (auto _ : st) {
    auto r = LinearSpringDashpot::evaluate(g, c, s);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_LinearEvaluate);

// N grains on a jittered simple-cubic lattice, slightly compressed, periodic, no gravity.
void BM_DenseStep(benchmark::State& st) {
  const int side = static_cast<int>(st.range(0));
  Random rng(1);
  SimulationConfig cfg;
  const double a = 1.9;
  cfg.box = {{0, 0, 0},
             {side * a, side * a, side * a},
             {Boundary::periodic, Boundary::periodic, Boundary::periodic}};
  cfg.dt = 1e-4;
  cfg.skin = 0.2;
  ParticleStore p;
  GlobalId id = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) {
        ParticleSpec s;
        s.position = {(i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a};
        s.velocity = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        s.radius = rng.uniform(0.9, 1.1);
        s.mass = s.radius * s.radius * s.radius;
        p.add(s, id++);
      }
  ContactLaw<LinearSpringDashpot> law{PairTable<LinearSpringDashpot::Coeffs>(1)};
  law.coeffs.set(0, 0, {2.5e5, 0.57e5, 100.0, 32.0, 0.84, 0.4});
  Simulation sim(cfg, std::move(p), {}, {}, law);
  for (auto _ : st) sim.step();
  st.counters["particle_steps_per_s"] = benchmark::Counter(
      static_cast<double>(side * side * side), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_DenseStep)->Arg(16)->Arg(24)->Unit(benchmark::kMillisecond);

} // namespace
} // namespace yuxi
