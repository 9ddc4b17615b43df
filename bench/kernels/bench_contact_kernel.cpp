// Google Benchmark of the contact kernel: one linear spring-dashpot evaluation, whole steps of a
// dense polydisperse packing (the pair loop with neighbour lists), and the cost of a wall
// contact: a layer of 4,096 grains resting each on one fixed sphere, on a triangle of a flat
// mesh, or on nothing (the steps' other costs), and on the mesh with a mesh of a million
// triangles far above them (which should cost nothing).
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

// N grains on a jittered simple-cubic lattice, slightly compressed, periodic, no gravity, under
// `law` (the linear law's by default).
void dense_steps(benchmark::State& st, const AnyContactLaw& law) {
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
  Simulation sim(cfg, std::move(p), {}, {}, law);
  for (auto _ : st) sim.step();
  st.counters["particle_steps_per_s"] = benchmark::Counter(
      static_cast<double>(side * side * side), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_DenseStep(benchmark::State& st) {
  ContactLaw<LinearSpringDashpot> law{PairTable<LinearSpringDashpot::Coeffs>(1)};
  law.coeffs.set(0, 0, {2.5e5, 0.57e5, 100.0, 32.0, 0.84, 0.4});
  dense_steps(st, law);
}
BENCHMARK(BM_DenseStep)->Arg(16)->Arg(24)->Unit(benchmark::kMillisecond);

// The same packing under Hertz-Mindlin (e = 0.7, mu = 0.5) and the thermodynamic law (REF): the
// laws evaluated one contact at a time.
void BM_DenseStepHertz(benchmark::State& st) {
  ContactLaw<HertzMindlin> law{PairTable<HertzMindlin::Coeffs>(1)};
  law.coeffs.set(0, 0, HertzMindlin::mix(2e7, 0.3, 2e7, 0.3, 0.7, 0.5));
  dense_steps(st, law);
}
BENCHMARK(BM_DenseStepHertz)->Arg(24)->Unit(benchmark::kMillisecond);

void BM_DenseStepThermodynamic(benchmark::State& st) {
  ContactLaw<Thermodynamic> law{PairTable<Thermodynamic::Coeffs>(1)};
  Thermodynamic::Coeffs c;
  c.e_star = 2e7 / (2 * (1 - 0.09));
  law.coeffs.set(0, 0, c);
  dense_steps(st, law);
}
BENCHMARK(BM_DenseStepThermodynamic)->Arg(24)->Unit(benchmark::kMillisecond);

// A 64 x 64 layer of grains (radius 0.5, spacing 1.2) under gravity, at their resting overlap
// on what `support` puts beneath them: 0 nothing (gravity off), 1 a fixed sphere each, 2 a flat
// mesh of 2 triangles per grain, 3 that mesh and a million-triangle mesh 30 above, 4 that mesh
// and a million-triangle square 30 above, turning slowly about the vertical through its centre.
void BM_GrainsOn(benchmark::State& st) {
  const int support = static_cast<int>(st.range(0));
  constexpr int side = 64;
  constexpr double spacing = 1.2, r = 0.5, k_n = 1e5;
  SimulationConfig cfg;
  cfg.box = {{0, 0, -2}, {side * spacing, side * spacing, 40}};
  cfg.gravity = {0, 0, support == 0 ? 0.0 : -1.0};
  cfg.dt = 1e-4;
  cfg.skin = 0.1;
  ParticleStore p;
  GlobalId id = 0;
  const double rest = r - 1.0 / k_n; // the overlap that carries m g = 1
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      ParticleSpec s;
      s.position = {(i + 0.35) * spacing, (j + 0.6) * spacing,
                    support == 1 ? 1.0 - 1.0 / k_n : rest};
      s.radius = r;
      s.mass = 1.0;
      p.add(s, id++);
    }
  if (support == 1)
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        ParticleSpec s;
        s.position = {(i + 0.35) * spacing, (j + 0.6) * spacing, 0.0};
        s.radius = r;
        s.mass = 1.0;
        s.kind = Kind::wall;
        p.add(s, id++);
      }
  const auto plane = [](int n, double edge, double z, double from = 0.0) {
    std::vector<std::array<Vec3, 3>> soup;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x0 = from + i * edge, x1 = from + (i + 1) * edge;
        const double y0 = from + j * edge, y1 = from + (j + 1) * edge;
        const Vec3 a{x0, y0, z}, b{x1, y0, z}, c{x1, y1, z}, d{x0, y1, z};
        soup.push_back({a, b, c});
        soup.push_back({a, c, d});
      }
    MeshWall w;
    w.mesh = TriangleMesh::weld(soup);
    return w;
  };
  std::vector<ShapedWall> walls;
  if (support >= 2) walls.push_back(plane(side, spacing, 0.0));
  if (support == 3) walls.push_back(plane(707, side * spacing / 707, 30.0));
  if (support == 4) { // (a 50 x 50 square about the layer's centre: its corners stay inside)
    const double middle = 0.5 * side * spacing;
    MeshWall turning = plane(707, 50.0 / 707, 30.0, middle - 25.0);
    RigidMotion turn;
    turn.axis = {0, 0, 1};
    turn.center = {middle, middle, 0};
    turn.omega = 0.01;
    turning.motion = turn;
    walls.push_back(std::move(turning));
  }
  ContactLaw<LinearSpringDashpot> law{PairTable<LinearSpringDashpot::Coeffs>(1)};
  law.coeffs.set(0, 0, {k_n, 2.0 / 7.0 * k_n, 20.0, 10.0, 0.5, 0.5});
  Simulation sim(cfg, std::move(p), {}, {}, law, Comm::self(), walls);
  for (auto _ : st) sim.step();
  st.counters["contacts"] = static_cast<double>(sim.last_tally().touching);
}
BENCHMARK(BM_GrainsOn)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Unit(benchmark::kMicrosecond);

} // namespace
} // namespace yuxi
