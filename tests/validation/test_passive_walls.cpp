// Walls at rest never add energy: grazing, frictional, spinning impacts of a grain on a fixed
// flat wall and on a fixed wall particle, over a sweep of angles, leave the grain with no more
// kinetic energy (translational + rotational) than it brought, for every contact model.
#include "core/units.hpp"
#include "validation/impact_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

using validation::Body;
using validation::Impact;

double kinetic(const Vec3& v, const Vec3& w, double m, double r) {
  return 0.5 * m * norm2(v) + 0.5 * 0.4 * m * r * r * norm2(w);
}

std::vector<AnyContactLaw> laws() {
  LinearSpringDashpot::Coeffs lin{1e5, 2.0 / 7.0 * 1e5, 20.0, 10.0, 0.6, 0.4};
  lin.k_r = 1e4;
  lin.mu_r = 0.05;
  ContactLaw<HertzMindlin> hm{PairTable<HertzMindlin::Coeffs>(1)};
  hm.coeffs.set(0, 0, HertzMindlin::mix(1e7, 0.3, 1e7, 0.3, 0.8, 0.5));
  Luding::Coeffs lc;
  lc.k1 = 5e4;
  lc.kp = 2e5;
  lc.phi_f = 0.05;
  lc.gamma_n = 10;
  lc.k_t = 2e4;
  lc.mu_s = 0.6;
  lc.mu_d = 0.4;
  lc.k_r = 1e4;
  lc.mu_r = 0.05;
  ContactLaw<Luding> lud{PairTable<Luding::Coeffs>(1)};
  lud.coeffs.set(0, 0, lc);
  return {validation::linear_law(lin, 1), hm, lud};
}

TEST(PassiveWalls, NeverAddEnergy) {
  int impacts = 0;
  for (const auto& law : laws())
    for (bool particle_wall : {false, true})
      for (double theta : {0.0, 20.0, 45.0, 70.0, 85.0, 89.0})
        for (double spin : {-20.0, 0.0, 20.0}) {
          const double th = theta * pi / 180, r = 0.5, m = 0.5;
          Impact s;
          s.law = law;
          s.dt = 2e-5;
          const Vec3 v{std::sin(th), 0.3 * std::sin(th), -std::cos(th) - 0.05};
          const Vec3 w{spin * 0.3, spin, 0};
          s.bodies.push_back({{0, 0, r + 1e-9}, v, w, r, m});
          if (particle_wall)
            s.bodies.push_back({{0.1, 0, -r - 1e-9}, {}, {}, r, 1.0, 0, Kind::wall});
          else
            s.planes.push_back(validation::flat_wall({0, 0, 0}, {0, 0, 1}, 0));
          const auto out = validation::run_impact(s);
          ASSERT_TRUE(out.separated);
          const double before = kinetic(v, w, m, r), after = kinetic(out.v[0], out.w[0], m, r);
          EXPECT_LE(after, before * (1 + 1e-9))
              << "theta " << theta << " spin " << spin
              << (particle_wall ? " wall particle" : " plane") << " model " << law.index();
          ++impacts;
        }
  EXPECT_EQ(impacts, 108);
}

} // namespace
} // namespace yuxi
