// yuxi's unit system.
//
// The engine is unit-agnostic: every quantity is a plain double in whatever consistent system
// the scene uses. The fish-basin scenes use the reduced units of Li & Cai (2008):
//   length sigma = mean grain radius, mass m = mean grain mass, time tau with g = 1 sigma/tau^2.
// Stiffness is then in m/tau^2, damping rates in 1/tau, energies in m sigma^2/tau^2.
// Validation cases from the literature use SI (m, kg, s) unchanged.
#pragma once

namespace yuxi {
inline constexpr double pi = 3.14159265358979323846;
} // namespace yuxi
