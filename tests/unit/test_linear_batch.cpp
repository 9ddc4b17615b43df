// The batched linear law (SIMD lanes) against the contact-by-contact law on the pair loop's own
// geometry (pair_geometry, wall_geometry): the same bits for every friction convention, sticking
// and sliding, with and without a tangential spring or damper, against grains and wall
// particles, over many steps of each contact's history.
// The engine relies on this: a contact's answer must not depend on which path evaluated it, or
// on the batch it fell in (which changes with the number of MPI ranks).
#include "contact/linear_batch.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "core/random.hpp"

#include <array>
#include <gtest/gtest.h>
#include <ostream>
#include <tuple>

namespace yuxi {
namespace {

using Law = LinearSpringDashpot;

struct Contact {
  Vec3 d; // x_i - x_j
  double a_i, a_j, inv_m_i, inv_m_j;
  Vec3 v_rel, w_i, w_j;
  Law::Coeffs c;
};

Vec3 random_vec(Random& r, double scale) {
  return {r.uniform(-scale, scale), r.uniform(-scale, scale), r.uniform(-scale, scale)};
}

Contact random_contact(Random& r, CapOn cap, Carry carry) {
  Contact k;
  k.a_i = r.uniform(0.4, 0.6);
  k.a_j = r.uniform(0.4, 0.6);
  const Vec3 dir = random_vec(r, 1.0);
  k.d = dir * ((k.a_i + k.a_j - r.uniform(1e-4, 1e-2)) / norm(dir));
  k.inv_m_i = r.uniform(1.0, 3.0);
  k.inv_m_j = r.uniform() < 0.2 ? 0.0 : r.uniform(1.0, 3.0); // some against wall particles
  k.v_rel = random_vec(r, 2.0);
  k.w_i = random_vec(r, 5.0);
  k.w_j = random_vec(r, 5.0);
  k.c.k_n = r.uniform(1e5, 3e5);
  k.c.k_t = r.uniform() < 0.1 ? 0.0 : r.uniform(0.2, 1.0) * k.c.k_n;
  k.c.gamma_n = r.uniform(0.0, 100.0);
  k.c.gamma_t = r.uniform() < 0.5 ? 0.0 : r.uniform(0.0, 50.0);
  k.c.mu_s = r.uniform(0.05, 0.9); // small ones slide often
  k.c.mu_d = k.c.mu_s * r.uniform(0.5, 1.0);
  k.c.friction_cap = cap;
  k.c.carry = carry;
  return k;
}

// The geometry as the one-by-one pair loop builds it from positions: its own function
// (contact/contact_geometry.hpp), with v_j = 0 so that v_i - v_j is the contact's v_rel.
ContactGeometry geometry_of(const Contact& k, double dt) {
  return pair_geometry(k.d, norm2(k.d), k.a_i, k.a_j, k.v_rel, Vec3{}, k.w_i, k.w_j, k.inv_m_i,
                       k.inv_m_j, dt);
}

// Lane k of an evaluated batch against the one-by-one law's result `ref` for the same contact
// (radii a_i, a_j; `spring`: the state the law left): force, both torques, energies, spring.
void expect_lane_is(const LinearBatch& batch, std::size_t k, const ContactResult& ref, double a_i,
                    double a_j, const SliderState& spring) {
  EXPECT_EQ(batch.fx[k], ref.force.x);
  EXPECT_EQ(batch.fy[k], ref.force.y);
  EXPECT_EQ(batch.fz[k], ref.force.z);
  const Vec3 nxf{batch.nxf_x[k], batch.nxf_y[k], batch.nxf_z[k]};
  EXPECT_EQ(Vec3{} - a_i * nxf, ref.torque_i);
  EXPECT_EQ(Vec3{} - a_j * nxf, ref.torque_j);
  EXPECT_EQ(batch.elastic[k], ref.elastic);
  EXPECT_EQ(batch.dissipated[k], ref.dissipated);
  EXPECT_EQ(batch.spring(k), spring);
}

class LinearBatchMatches : public testing::TestWithParam<std::tuple<CapOn, Carry>> {};

// The conventions by name in ctest's list, not as bytes.
const char* cap_name(CapOn c) {
  return c == CapOn::spring ? "spring" : c == CapOn::total ? "total" : "total_lammps";
}
const char* carry_name(Carry c) {
  return c == Carry::rotate ? "rotate" : "project";
}

} // namespace

void PrintTo(CapOn c, std::ostream* os) {
  *os << cap_name(c);
}
void PrintTo(Carry c, std::ostream* os) {
  *os << carry_name(c);
}

namespace {

TEST_P(LinearBatchMatches, TheOneByOneLawBitForBit) {
  const auto [cap, carry] = GetParam();
  const double dt = 1e-4;
  Random r(7);
  // A full batch and a partial one (the tail of the pair loop).
  for (const std::size_t n : {LinearBatch::capacity, std::size_t{13}}) {
    std::array<Contact, LinearBatch::capacity> contacts;
    std::array<Law::State, LinearBatch::capacity> states{};
    for (std::size_t k = 0; k < n; ++k) contacts[k] = random_contact(r, cap, carry);
    LinearBatch batch;
    std::size_t slid = 0, stuck = 0;
    for (int step = 0; step < 40; ++step) {
      batch.size = n;
      for (std::size_t k = 0; k < n; ++k) {
        const Contact& c = contacts[k];
        batch.set_lane(k, c.d, c.a_i, c.a_j, c.v_rel, c.w_i, c.w_j, c.inv_m_i + c.inv_m_j, c.c,
                       states[k]);
      }
      batch.evaluate(cap, carry, dt);
      for (std::size_t k = 0; k < n; ++k) {
        const ContactResult ref =
            Law::evaluate(geometry_of(contacts[k], dt), contacts[k].c, states[k]);
        SCOPED_TRACE(testing::Message() << "contact " << k << ", step " << step);
        expect_lane_is(batch, k, ref, contacts[k].a_i, contacts[k].a_j, states[k].tangential);
        const SliderState& s = states[k].tangential;
        (s.sliding ? slid : stuck) += 1;
        // The contact moves on: it turns and its velocities change, so the spring is carried.
        Contact& c = contacts[k];
        c.d += c.v_rel * dt + random_vec(r, 2e-4);
        c.v_rel += random_vec(r, 0.2);
        c.w_i += random_vec(r, 0.5);
      }
    }
    EXPECT_GT(slid, 0u); // both branches of the Coulomb test were compared
    EXPECT_GT(stuck, 0u);
  }
}

// Wall contacts (a mesh's triangle, a cylinder's patch) go through the lanes with their normal
// and distance given: the same bits as the law on the geometry the one-by-one wall loop builds
// (a wall of zero radius, no spin and infinite mass, moving with its own velocity).
TEST_P(LinearBatchMatches, WallContactsBitForBit) {
  const auto [cap, carry] = GetParam();
  const double dt = 1e-4;
  Random r(11);
  const std::size_t n = 21;
  std::array<Contact, LinearBatch::capacity> contacts;
  std::array<Law::State, LinearBatch::capacity> states{};
  std::array<Vec3, LinearBatch::capacity> normal;
  std::array<double, LinearBatch::capacity> distance;
  for (std::size_t k = 0; k < n; ++k) {
    contacts[k] = random_contact(r, cap, carry);
    const Vec3 dir = random_vec(r, 1.0);
    normal[k] = dir * (1.0 / norm(dir));
    distance[k] = contacts[k].a_i - r.uniform(1e-4, 1e-2);
  }
  LinearBatch batch;
  std::size_t slid = 0, stuck = 0;
  for (int step = 0; step < 40; ++step) {
    batch.size = n;
    for (std::size_t k = 0; k < n; ++k) {
      const Contact& c = contacts[k];
      batch.set_wall_contact(k, normal[k], distance[k], c.a_i, c.v_rel, c.w_i, c.inv_m_i,
                             states[k]);
      batch.set_coeffs(k, c.c);
    }
    batch.evaluate_walls(cap, carry, dt);
    for (std::size_t k = 0; k < n; ++k) {
      const Contact& c = contacts[k];
      // (the wall loop's own geometry, the wall at rest so that v_i - v_wall is v_rel)
      const ContactGeometry g =
          wall_geometry(normal[k], distance[k], c.a_i, c.v_rel, Vec3{}, c.w_i, c.inv_m_i, dt);
      const ContactResult ref = Law::evaluate(g, c.c, states[k]);
      SCOPED_TRACE(testing::Message() << "wall contact " << k << ", step " << step);
      expect_lane_is(batch, k, ref, c.a_i, 0.0, states[k].tangential);
      EXPECT_EQ(batch.overlap[k], g.overlap);
      (states[k].tangential.sliding ? slid : stuck) += 1;
      // The contact turns and slides on.
      const Vec3 turned = normal[k] + random_vec(r, 2e-3);
      normal[k] = turned * (1.0 / norm(turned));
      distance[k] += r.uniform(-2e-4, 2e-4);
      contacts[k].v_rel += random_vec(r, 0.2);
      contacts[k].w_i += random_vec(r, 0.5);
    }
  }
  EXPECT_GT(slid, 0u);
  EXPECT_GT(stuck, 0u);
}

INSTANTIATE_TEST_SUITE_P(EveryConvention, LinearBatchMatches,
                         testing::Combine(testing::Values(CapOn::spring, CapOn::total,
                                                          CapOn::total_lammps),
                                          testing::Values(Carry::rotate, Carry::project)),
                         [](const testing::TestParamInfo<std::tuple<CapOn, Carry>>& p) {
                           return std::string("cap_") + cap_name(std::get<0>(p.param)) + "_carry_" +
                                  carry_name(std::get<1>(p.param));
                         });

} // namespace
} // namespace yuxi
