// The rotation integrator (core/free_rotation.hpp) on a free asymmetric body: its lab angular
// momentum kept to round-off over 10^6 steps, its energy error bounded and shrinking as dt^2,
// and the intermediate-axis flip (Dzhanibekov) returning with the period of the Euler
// equations' exact solution, 4 K(k) / nu in Jacobi's elliptic functions (Landau & Lifshitz,
// Mechanics, section 37).
#include "core/free_rotation.hpp"
#include "core/quaternion.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace yuxi {
namespace {

const Vec3 inertia{1.0, 2.0, 3.0};

struct Rotor {
  Quaternion q, p;
};

Rotor start(const Vec3& omega_body) {
  const Quaternion q = normalized(Quaternion{0.9, 0.1, -0.3, 0.2});
  return {q, rotor_momentum(q, {inertia.x * omega_body.x, inertia.y * omega_body.y,
                                inertia.z * omega_body.z})};
}

TEST(FreeRotation, AMillionStepsKeepTheAngularMomentumAndBoundTheEnergy) {
  Rotor r = start({0.4, 1.0, -0.7});
  const Vec3 l0 = to_lab(r.q, body_angular_momentum(r.q, r.p));
  const double e0 = rotor_energy(r.q, r.p, inertia);
  double worst_energy = 0;
  for (int step = 0; step < 1000000; ++step) {
    free_rotation(r.q, r.p, inertia, 0.01);
    if (step % 1000 == 0)
      worst_energy = std::max(worst_energy, std::abs(rotor_energy(r.q, r.p, inertia) / e0 - 1));
  }
  const Vec3 l = to_lab(r.q, body_angular_momentum(r.q, r.p));
  EXPECT_LT(norm(l - l0) / norm(l0), 1e-11);
  EXPECT_NEAR(dot(r.q, r.q), 1.0, 1e-12);
  EXPECT_LT(worst_energy, 1e-4); // bounded: no drift over 10^4 time units
}

// The largest energy error over a time T with step dt.
double energy_error(double dt, double t_end) {
  Rotor r = start({0.4, 1.0, -0.7});
  const double e0 = rotor_energy(r.q, r.p, inertia);
  double worst = 0;
  for (int step = 0; step * dt < t_end; ++step) {
    free_rotation(r.q, r.p, inertia, dt);
    worst = std::max(worst, std::abs(rotor_energy(r.q, r.p, inertia) / e0 - 1));
  }
  return worst;
}

TEST(FreeRotation, TheEnergyErrorShrinksAsTheSquareOfTheStep) {
  const double coarse = energy_error(0.04, 200), fine = energy_error(0.02, 200),
               finer = energy_error(0.01, 200);
  EXPECT_NEAR(coarse / fine, 4.0, 0.4);
  EXPECT_NEAR(fine / finer, 4.0, 0.4);
}

TEST(FreeRotation, TheIntermediateAxisFlipsWithTheEulerEquationsPeriod) {
  // Spun about the intermediate axis with a small push off it, the body flips over and back.
  const Vec3 omega{0.05, 1.0, 0.02};
  Rotor r = start(omega);
  const Vec3 l{inertia.x * omega.x, inertia.y * omega.y, inertia.z * omega.z};
  const double m2 = norm2(l);
  const double e2 = inertia.x * omega.x * omega.x + inertia.y * omega.y * omega.y +
                    inertia.z * omega.z * omega.z; // 2 E
  const double i1 = inertia.x, i2 = inertia.y, i3 = inertia.z;
  double nu = 0, k2 = 0;
  if (m2 > e2 * i2) {
    nu = std::sqrt((i3 - i2) * (m2 - e2 * i1) / (i1 * i2 * i3));
    k2 = (i2 - i1) * (e2 * i3 - m2) / ((i3 - i2) * (m2 - e2 * i1));
  } else {
    nu = std::sqrt((i2 - i1) * (e2 * i3 - m2) / (i1 * i2 * i3));
    k2 = (i3 - i2) * (m2 - e2 * i1) / ((i2 - i1) * (e2 * i3 - m2));
  }
  const double period = 4 * std::comp_ellint_1(std::sqrt(k2)) / nu;
  // The times omega_2 (body frame) turns from negative to positive, found by linear
  // interpolation between steps.
  const double dt = 1e-3;
  std::vector<double> up;
  double before = omega.y;
  for (int step = 1; up.size() < 4; ++step) {
    free_rotation(r.q, r.p, inertia, dt);
    const double now = body_angular_momentum(r.q, r.p).y / i2;
    if (before < 0 && now >= 0) up.push_back(dt * (step - 1 + before / (before - now)));
    before = now;
    ASSERT_LT(step * dt, 10 * period) << "no flip";
  }
  for (std::size_t k = 1; k < up.size(); ++k)
    EXPECT_NEAR((up[k] - up[k - 1]) / period, 1.0, 1e-5) << k;
}

TEST(FreeRotation, StepsRetraceThemselvesWhenTheMomentumIsReversed) {
  // Time reversal: n steps, p -> -p, n steps: the start again, to round-off.
  Rotor r = start({0.4, 1.0, -0.7});
  const Rotor r0 = r;
  for (int step = 0; step < 1000; ++step) free_rotation(r.q, r.p, inertia, 0.01);
  r.p = -1.0 * r.p;
  for (int step = 0; step < 1000; ++step) free_rotation(r.q, r.p, inertia, 0.01);
  EXPECT_NEAR(std::abs(dot(r.q, r0.q)), 1.0, 1e-13);
  const Vec3 l = body_angular_momentum(r.q, r.p), l0 = body_angular_momentum(r0.q, r0.p);
  EXPECT_LT(norm(l + l0) / norm(l0), 1e-12);
}

TEST(FreeRotation, UnderAConstantTorqueTheMomentumGrowsAsItsImpulse) {
  // Half kick, free rotation, half kick, repeated: L_lab(t) = L_0 + tau t for a torque fixed in
  // the lab, whatever the body does in between.
  Rotor r = start({0.4, 1.0, -0.7});
  const Vec3 l0 = to_lab(r.q, body_angular_momentum(r.q, r.p));
  const Vec3 torque{0.3, -0.2, 0.5};
  const double dt = 0.01;
  for (int step = 0; step < 2000; ++step) {
    kick_rotor(r.q, r.p, torque, 0.5 * dt);
    free_rotation(r.q, r.p, inertia, dt);
    kick_rotor(r.q, r.p, torque, 0.5 * dt);
  }
  const Vec3 l = to_lab(r.q, body_angular_momentum(r.q, r.p));
  EXPECT_LT(norm(l - l0 - 20.0 * torque) / norm(l), 1e-12);
}

TEST(FreeRotation, ATorqueChangesTheAngularMomentumAsItsImpulse) {
  // A constant lab torque over a kick: L_lab grows by tau dt, whatever the orientation.
  Rotor r = start({0.4, 1.0, -0.7});
  const Vec3 l0 = to_lab(r.q, body_angular_momentum(r.q, r.p));
  const Vec3 torque{0.3, -0.2, 0.5};
  kick_rotor(r.q, r.p, torque, 0.1);
  const Vec3 l = to_lab(r.q, body_angular_momentum(r.q, r.p));
  EXPECT_LT(norm(l - l0 - 0.1 * torque), 1e-15);
}

TEST(FreeRotation, AboutAPrincipalAxisTheBodyTurnsAtItsAngularVelocity) {
  // Spun about axis 3 alone, the body turns by omega t exactly (to round-off).
  const Quaternion q0{};
  Rotor r{q0, rotor_momentum(q0, {0, 0, inertia.z * 0.8})};
  for (int step = 0; step < 1000; ++step) free_rotation(r.q, r.p, inertia, 0.005);
  const Quaternion expected = about_axis({0, 0, 1}, 0.8 * 5.0);
  EXPECT_NEAR(std::abs(dot(r.q, expected)), 1.0, 1e-13);
  EXPECT_LT(norm(lab_angular_velocity(r.q, r.p, inertia) - Vec3{0, 0, 0.8}), 1e-12);
}

} // namespace
} // namespace yuxi
