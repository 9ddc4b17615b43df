// The energies of one particle, written once for the CPU engine's books (sim/energy_ledger.hpp)
// and the device engine's (device/step_phases.hpp), so that both add the same terms.
#pragma once

#include "core/host_device.hpp"
#include "core/vec3.hpp"

namespace yuxi {

// m v^2 / 2 [energy].
YUXI_HD inline double translational_energy(double mass, const Vec3& v) {
  return 0.5 * mass * norm2(v);
}

// J w^2 / 2 with inv_inertia = 1/J (0 when the rotation is locked: infinite inertia, which keeps
// its spin and its energy) [energy].
YUXI_HD inline double rotational_energy(const Vec3& w, double inv_inertia) {
  return inv_inertia > 0 ? 0.5 * norm2(w) / inv_inertia : 0.0;
}

// Kinetic plus gravitational energy at x under gravity's potential part g_potential (the
// periodic axes' gravity works instead: docs/ARCHITECTURE.md, "Energy books") [energy].
YUXI_HD inline double mechanical_energy(double mass, const Vec3& x, const Vec3& v, const Vec3& w,
                                        double inv_inertia, const Vec3& g_potential) {
  return translational_energy(mass, v) + rotational_energy(w, inv_inertia) -
         mass * dot(g_potential, x);
}

} // namespace yuxi
