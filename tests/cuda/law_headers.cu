// Every contact law's header compiles for the device (compile only: no GPU is needed): the
// laws are written once, as YUXI_HD functions of plain data, and a kernel instantiates each
// model's evaluate() and release(). A pair kernel takes the particles' plain view and the pair
// loop's own geometry, as a device backend will. CTest compiles this with nvcc where one is installed
// (tests/CMakeLists.txt); scripts/check-layers.sh keeps host-only includes out of the headers.
#include "contact/hertz_mindlin.hpp"
#include "contact/hooke.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/luding.hpp"
#include "contact/rolling_resistance.hpp"
#include "contact/thermodynamic.hpp"
#include "core/free_rotation.hpp"
#include "core/particle_view.hpp"

#include <cstdint>

namespace yuxi {

template <class Model>
__global__ void evaluate_contacts(const ContactGeometry* g, const typename Model::Coeffs* c,
                                  typename Model::State* s, ContactResult* out, double* released,
                                  int n) {
  const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (k >= n) return;
  out[k] = Model::evaluate(g[k], c[0], s[k]);
  const typename Model::State mirrored = s[k].mirrored();
  released[k] = Model::release(c[0], s[k]) + (mirrored == s[k] ? 0.0 : 1.0);
}

template __global__ void evaluate_contacts<LinearSpringDashpot>(const ContactGeometry*,
                                                                const LinearSpringDashpot::Coeffs*,
                                                                LinearSpringDashpot::State*,
                                                                ContactResult*, double*, int);
template __global__ void evaluate_contacts<HertzMindlin>(const ContactGeometry*,
                                                         const HertzMindlin::Coeffs*,
                                                         HertzMindlin::State*, ContactResult*,
                                                         double*, int);
template __global__ void evaluate_contacts<Luding>(const ContactGeometry*, const Luding::Coeffs*,
                                                   Luding::State*, ContactResult*, double*, int);
template __global__ void evaluate_contacts<Thermodynamic>(const ContactGeometry*,
                                                          const Thermodynamic::Coeffs*,
                                                          Thermodynamic::State*, ContactResult*,
                                                          double*, int);
template __global__ void evaluate_contacts<Hooke>(const ContactGeometry*, const Hooke::Coeffs*,
                                                  Hooke::State*, ContactResult*, double*, int);

template <class Model>
__global__ void pair_contacts(ConstParticleView p, const std::uint32_t* rows,
                              const std::uint32_t* partners, const typename Model::Coeffs* c,
                              typename Model::State* s, ContactResult* out, double dt, int n) {
  const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (k >= n) return;
  const std::uint32_t i = rows[k], j = partners[k];
  const Vec3 d = p.x[i] - p.x[j];
  const ContactGeometry g = pair_geometry(d, norm2(d), p.radius[i], p.radius[j], p.v[i], p.v[j],
                                          p.w[i], p.w[j], p.inv_mass[i], p.inv_mass[j], dt);
  const ContactGeometry wall =
      wall_geometry(g.n, g.distance, p.radius[i], p.v[i], Vec3{}, p.w[i], p.inv_mass[i], dt);
  out[k] = Model::evaluate(p.is_grain(j) ? g : wall, c[0], s[k]);
}

template __global__ void pair_contacts<LinearSpringDashpot>(
    ConstParticleView, const std::uint32_t*, const std::uint32_t*,
    const LinearSpringDashpot::Coeffs*, LinearSpringDashpot::State*, ContactResult*, double, int);
template __global__ void pair_contacts<HertzMindlin>(ConstParticleView, const std::uint32_t*,
                                                     const std::uint32_t*,
                                                     const HertzMindlin::Coeffs*,
                                                     HertzMindlin::State*, ContactResult*,
                                                     double, int);


// A clump's rotation (core/free_rotation.hpp): a half kick of the torque, the free rotation, a
// half kick, as the step will do it on the device.
__global__ void rotate_bodies(Quaternion* q, Quaternion* p, const Vec3* inertia,
                              const Vec3* torque, double dt, int n) {
  const int k = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (k >= n) return;
  kick_rotor(q[k], p[k], torque[k], 0.5 * dt);
  free_rotation(q[k], p[k], inertia[k], dt);
  kick_rotor(q[k], p[k], torque[k], 0.5 * dt);
}

} // namespace yuxi
