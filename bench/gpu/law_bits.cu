// Do the contact laws give the same bits on the GPU as on the CPU?
//
// Every law is a YUXI_HD function of plain data (docs/ARCHITECTURE.md, "The seam"). This program
// evaluates each law on the same contacts on both sides, carrying each contact's state over
// several steps, and counts the contacts whose force, torques, energies or state differ in any
// bit. It also counts, over random arguments, where the device's sqrt, division, exp, log, pow,
// sin, cos and cbrt differ from the host's libm, and checks that yuxi's own exp, log and pow
// (core/portable_math.hpp), which a law calls instead, agree everywhere.
//
// Build (FMA contraction off on both sides):
//   nvcc -std=c++20 --expt-relaxed-constexpr --fmad=false -Xcompiler -ffp-contract=off \
//        -arch=sm_90 -Isrc bench/gpu/law_bits.cu -o law_bits
// Run: law_bits [contacts] [steps]; prints one line per law and per function, exit 1 where a law
// or a portable function differs.
#include "contact/hertz_mindlin.hpp"
#include "contact/hooke.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/luding.hpp"
#include "contact/thermodynamic.hpp"
#include "core/portable_math.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <cuda_runtime.h>

namespace yuxi {
namespace {

#define CHECK_CUDA(call)                                                                           \
  do {                                                                                             \
    const cudaError_t e = (call);                                                                  \
    if (e != cudaSuccess) {                                                                        \
      std::fprintf(stderr, "%s:%d: %s\n", __FILE__, __LINE__, cudaGetErrorString(e));             \
      std::exit(2);                                                                                \
    }                                                                                              \
  } while (0)

// splitmix64: integer only, so both sides draw the same numbers.
YUXI_HD inline std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A uniform number in [lo, hi): 53 random bits times 2^-53 is exact, then one multiply-add
// (not fused: --fmad=false and -ffp-contract=off).
YUXI_HD inline double uniform(std::uint64_t& state, double lo, double hi) {
  state = mix(state);
  const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * u;
}

// Contact k at step `step`: two grains of radius 0.4 - 0.6 and mass 0.5 - 1.5 touching with an
// overlap up to 2 % of the radius, moving and spinning at random.
YUXI_HD inline ContactGeometry contact(std::uint64_t k, int step) {
  std::uint64_t s = mix(k * 1315423911ULL + static_cast<std::uint64_t>(step));
  Vec3 d{uniform(s, -1, 1), uniform(s, -1, 1), uniform(s, -1, 1)};
  const double a_i = uniform(s, 0.4, 0.6), a_j = uniform(s, 0.4, 0.6);
  const double overlap = uniform(s, 1e-6, 0.02);
  d = d * ((a_i + a_j - overlap) / std::sqrt(norm2(d)));
  const Vec3 v_i{uniform(s, -1, 1), uniform(s, -1, 1), uniform(s, -1, 1)};
  const Vec3 v_j{uniform(s, -1, 1), uniform(s, -1, 1), uniform(s, -1, 1)};
  const Vec3 w_i{uniform(s, -2, 2), uniform(s, -2, 2), uniform(s, -2, 2)};
  const Vec3 w_j{uniform(s, -2, 2), uniform(s, -2, 2), uniform(s, -2, 2)};
  const double inv_m_i = 1 / uniform(s, 0.5, 1.5), inv_m_j = 1 / uniform(s, 0.5, 1.5);
  return pair_geometry(d, norm2(d), a_i, a_j, v_i, v_j, w_i, w_j, inv_m_i, inv_m_j, 1e-4);
}

template <class Model>
__global__ void run_steps(typename Model::Coeffs c, typename Model::State* s, ContactResult* out,
                          int n, int steps) {
  const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (k >= n) return;
  typename Model::State state = s[k];
  ContactResult r;
  for (int step = 0; step < steps; ++step) r = Model::evaluate(contact(k, step), c, state);
  s[k] = state;
  out[k] = r;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}
bool same_bits(const ContactResult& a, const ContactResult& b) {
  return same_bits(a.force, b.force) && same_bits(a.torque_i, b.torque_i) &&
         same_bits(a.torque_j, b.torque_j) && same_bits(a.elastic, b.elastic) &&
         same_bits(a.dissipated, b.dissipated) && same_bits(a.relaxation, b.relaxation) &&
         a.touching == b.touching;
}

// Runs `Model` on n contacts for `steps` steps on both sides; returns the contacts that differ.
template <class Model>
int compare_law(const char* name, const typename Model::Coeffs& c, int n, int steps) {
  using State = typename Model::State;
  std::vector<State> host_state(n);
  std::vector<ContactResult> host_out(n);
  for (int k = 0; k < n; ++k)
    for (int step = 0; step < steps; ++step)
      host_out[k] = Model::evaluate(contact(k, step), c, host_state[k]);

  State* d_state = nullptr;
  ContactResult* d_out = nullptr;
  CHECK_CUDA(cudaMalloc(&d_state, sizeof(State) * n));
  CHECK_CUDA(cudaMalloc(&d_out, sizeof(ContactResult) * n));
  const std::vector<State> fresh(n);
  CHECK_CUDA(cudaMemcpy(d_state, fresh.data(), sizeof(State) * n, cudaMemcpyHostToDevice));
  cudaEvent_t start, stop;
  CHECK_CUDA(cudaEventCreate(&start));
  CHECK_CUDA(cudaEventCreate(&stop));
  CHECK_CUDA(cudaEventRecord(start));
  run_steps<Model><<<(n + 255) / 256, 256>>>(c, d_state, d_out, n, steps);
  CHECK_CUDA(cudaEventRecord(stop));
  CHECK_CUDA(cudaGetLastError());
  CHECK_CUDA(cudaEventSynchronize(stop));
  float ms = 0;
  CHECK_CUDA(cudaEventElapsedTime(&ms, start, stop));
  std::vector<State> dev_state(n);
  std::vector<ContactResult> dev_out(n);
  CHECK_CUDA(cudaMemcpy(dev_state.data(), d_state, sizeof(State) * n, cudaMemcpyDeviceToHost));
  CHECK_CUDA(cudaMemcpy(dev_out.data(), d_out, sizeof(ContactResult) * n, cudaMemcpyDeviceToHost));
  CHECK_CUDA(cudaFree(d_state));
  CHECK_CUDA(cudaFree(d_out));

  int differ = 0, first = -1;
  for (int k = 0; k < n; ++k)
    if (!same_bits(host_out[k], dev_out[k]) || !(host_state[k] == dev_state[k])) {
      if (first < 0) first = k;
      ++differ;
    }
  std::printf("law %-22s contacts %d steps %d differ %d", name, n, steps, differ);
  if (first >= 0)
    std::printf(" (first: contact %d, force x host %.17g device %.17g)", first,
                host_out[first].force.x, dev_out[first].force.x);
  std::printf("  device %.3g contact-evaluations/s\n",
              static_cast<double>(n) * steps / (ms * 1e-3));
  return differ;
}

enum class Fn { sqrt, div, exp, log, pow, sin, cos, cbrt, portable_exp, portable_log, portable_pow };

YUXI_HD inline double apply(Fn f, double x, double y) {
  switch (f) {
  case Fn::sqrt: return std::sqrt(x);
  case Fn::div: return x / y;
  case Fn::exp: return std::exp(x);
  case Fn::log: return std::log(x);
  case Fn::pow: return std::pow(x, y);
  case Fn::sin: return std::sin(x);
  case Fn::cos: return std::cos(x);
  case Fn::cbrt: return std::cbrt(x);
  case Fn::portable_exp: return portable::exp(x);
  case Fn::portable_log: return portable::log(x);
  case Fn::portable_pow: return portable::pow(x, y);
  }
  return 0;
}

YUXI_HD inline void arguments(Fn f, std::uint64_t k, double& x, double& y) {
  std::uint64_t s = mix(k ^ 0x5bd1e995ULL);
  switch (f) {
  case Fn::exp:
  case Fn::portable_exp: x = uniform(s, -40, 1); break; // decays: exp(-dt/tau), exp(-rate dt)
  case Fn::sin:
  case Fn::cos: x = uniform(s, -100, 100); break;  // wall motion phases
  default: x = uniform(s, 1e-6, 10); break;
  }
  y = uniform(s, 0.1, 3);
}

__global__ void apply_all(Fn f, double* out, int n) {
  const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (k >= n) return;
  double x, y;
  arguments(f, static_cast<std::uint64_t>(k), x, y);
  out[k] = apply(f, x, y);
}

// Returns the arguments where the two sides differ.
int compare_function(Fn f, const char* name, int n) {
  double* d_out = nullptr;
  CHECK_CUDA(cudaMalloc(&d_out, sizeof(double) * n));
  apply_all<<<(n + 255) / 256, 256>>>(f, d_out, n);
  CHECK_CUDA(cudaGetLastError());
  std::vector<double> dev(n);
  CHECK_CUDA(cudaMemcpy(dev.data(), d_out, sizeof(double) * n, cudaMemcpyDeviceToHost));
  CHECK_CUDA(cudaFree(d_out));
  int differ = 0;
  double worst_ulps = 0;
  for (int k = 0; k < n; ++k) {
    double x, y;
    arguments(f, static_cast<std::uint64_t>(k), x, y);
    const double h = apply(f, x, y);
    if (!same_bits(h, dev[k])) {
      ++differ;
      const double ulp = std::nextafter(std::fabs(h), INFINITY) - std::fabs(h);
      worst_ulps = std::fmax(worst_ulps, std::fabs(h - dev[k]) / ulp);
    }
  }
  std::printf("function %-13s arguments %d differ %d (%.4f %%), worst %.0f ulp\n", name, n,
              differ, 100.0 * differ / n, worst_ulps);
  return differ;
}

} // namespace
} // namespace yuxi

int main(int argc, char** argv) {
  using namespace yuxi;
  const int n = argc > 1 ? std::atoi(argv[1]) : 1 << 20;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 8;
  cudaDeviceProp prop{};
  CHECK_CUDA(cudaGetDeviceProperties(&prop, 0));
  std::printf("device %s, %d multiprocessors, %.1f GiB\n", prop.name, prop.multiProcessorCount,
              prop.totalGlobalMem / 1073741824.0);

  LinearSpringDashpot::Coeffs linear;
  linear.k_n = 2e5;
  linear.k_t = 2e5 * 2 / 7;
  linear.gamma_n = 50;
  linear.gamma_t = 25;
  linear.mu_s = linear.mu_d = 0.5;
  linear.k_r = 1e3;
  linear.mu_r = 0.1;
  HertzMindlin::Coeffs hertz;
  hertz.e_star = 1e5;
  hertz.g_star = 4e4;
  hertz.restitution = 0.8;
  hertz.friction = 0.5;
  hertz.beta = std::log(0.8) / std::sqrt(std::log(0.8) * std::log(0.8) + pi * pi);
  hertz.mu_r = 0.05;
  Luding::Coeffs luding;
  luding.k1 = 1e5;
  luding.kp = 5e5;
  luding.kc = 1e4;
  luding.gamma_n = 20;
  luding.k_t = 4e4;
  luding.gamma_t = 10;
  luding.mu_s = luding.mu_d = 0.5;
  luding.k_r = 1e3;
  luding.mu_r = 0.1;
  luding.k_o = 1e3;
  luding.mu_o = 0.1;
  Thermodynamic::Coeffs thermo;
  thermo.e_star = 1e5;
  Hooke::Coeffs hooke;
  hooke.k_n = 2e5;
  hooke.gamma_n = 50;

  int differ = 0;
  differ += compare_law<LinearSpringDashpot>("linear_spring_dashpot", linear, n, steps);
  differ += compare_law<HertzMindlin>("hertz_mindlin", hertz, n, steps);
  differ += compare_law<Luding>("luding", luding, n, steps);
  differ += compare_law<Thermodynamic>("thermodynamic", thermo, n, steps);
  differ += compare_law<Hooke>("hooke", hooke, n, steps);

  const struct {
    Fn f;
    const char* name;
  } libm[] = {{Fn::sqrt, "sqrt"}, {Fn::div, "div"}, {Fn::exp, "exp"}, {Fn::log, "log"},
              {Fn::pow, "pow"},   {Fn::sin, "sin"}, {Fn::cos, "cos"}, {Fn::cbrt, "cbrt"}};
  for (const auto& fn : libm) compare_function(fn.f, fn.name, n);
  // yuxi's own: these must agree everywhere (core/portable_math.hpp).
  int portable_differ = compare_function(Fn::portable_exp, "portable::exp", n);
  portable_differ += compare_function(Fn::portable_log, "portable::log", n);
  portable_differ += compare_function(Fn::portable_pow, "portable::pow", n);
  std::printf("contacts that differ: %d; portable results that differ: %d\n", differ,
              portable_differ);
  return differ == 0 && portable_differ == 0 ? 0 : 1;
}
