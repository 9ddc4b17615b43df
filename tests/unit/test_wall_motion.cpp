// Prescribed wall motion: the fish-basin excitation against its defining formula
// (docs/models/fish-basin.md section 6), r = R + dr cos(m alpha) sin(omega (t - t0)), with the
// velocity its time derivative.
#include "scene/wall_motion.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

TEST(WallMotion, RadialCosineFollowsItsFormulaForEveryMode) {
  for (int mode : {0, 1, 2, 3, 4, 7, -3}) {
    const RadialCosineMotion m{{36.0, 30.0, 5.0}, mode, 0.9, 400.0, 10.0};
    for (double alpha = -3.1; alpha < 3.2; alpha += 0.37) {
      const double rest_radius = 31.5;
      const Vec3 rest{36.0 + rest_radius * std::cos(alpha), 30.0 + rest_radius * std::sin(alpha),
                      7.5};
      for (double t : {10.0, 10.0013, 10.1, 12.345}) {
        const double shape = 0.9 * std::cos(mode * alpha);
        const double r = rest_radius + shape * std::sin(400.0 * (t - 10.0));
        const double rdot = 400.0 * shape * std::cos(400.0 * (t - 10.0));
        const PlacedState p = place(WallMotion{m}, rest, t);
        SCOPED_TRACE(testing::Message() << "mode " << mode << ", alpha " << alpha << ", t " << t);
        EXPECT_NEAR(p.position.x, 36.0 + r * std::cos(alpha), 1e-11);
        EXPECT_NEAR(p.position.y, 30.0 + r * std::sin(alpha), 1e-11);
        EXPECT_EQ(p.position.z, 7.5);
        EXPECT_NEAR(p.velocity.x, rdot * std::cos(alpha), 1e-9);
        EXPECT_NEAR(p.velocity.y, rdot * std::sin(alpha), 1e-9);
        EXPECT_EQ(p.velocity.z, 0.0);
        // the velocity is the derivative of the position (central difference, O(h^2))
        const double h = 1e-6;
        const Vec3 ahead = place(WallMotion{m}, rest, t + h).position;
        const Vec3 behind = place(WallMotion{m}, rest, t - h).position;
        if (t - h >= 10.0) {
          EXPECT_NEAR((ahead.x - behind.x) / (2 * h), p.velocity.x, 1e-3);
        }
      }
    }
  }
}

TEST(WallMotion, AtRestBeforeTheStartAndOnTheAxis) {
  const RadialCosineMotion m{{0.0, 0.0, 0.0}, 2, 0.9, 400.0, 10.0};
  const Vec3 rest{3.0, 4.0, 1.0};
  const PlacedState before = place(WallMotion{m}, rest, 9.999);
  EXPECT_EQ(before.position, rest);
  EXPECT_EQ(before.velocity, Vec3{});
  const PlacedState axis = place(WallMotion{m}, Vec3{0.0, 0.0, 2.0}, 10.5);
  EXPECT_EQ(axis.position, (Vec3{0.0, 0.0, 2.0}));
  const PlacedState still = StaticMotion{}.at_time(10.5).place(rest);
  EXPECT_EQ(still.position, rest);
  EXPECT_EQ(still.velocity, Vec3{});
  // What the engine skips when placing walls: a motion at rest leaves every particle in place.
  EXPECT_TRUE(at_rest(at_time(WallMotion{m}, 9.999)));
  EXPECT_FALSE(at_rest(at_time(WallMotion{m}, 10.0)));
  EXPECT_TRUE(at_rest(at_time(WallMotion{StaticMotion{}}, 10.5)));
}

} // namespace
} // namespace yuxi
