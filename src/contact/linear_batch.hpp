// The linear spring-dashpot law (linear_spring_dashpot.hpp) evaluated on a batch of contacts
// at once, for the pair loop's common case: no rolling resistance, and one friction convention
// (friction_cap, tangential_carry) for every pair of materials. The model names it as its
// `Batch` (sim/contact_forces.hpp takes any model's batch through the same members).
//
// Wall contacts (a triangle of a mesh, a cylinder's patch) go through the same lanes with their
// normal and distance given, since the wall's geometry finds them (set_wall_contact(),
// evaluate_walls()).
//
// The contacts are held as a structure of arrays and the evaluation is one loop without
// branches (both arms of the Coulomb test are computed and one is selected), so the compiler
// turns it into SIMD instructions: two or more contacts per instruction instead of one, which
// is most of the cost of a dense packing, where nearly every listed pair touches.
//
// Every lane computes exactly what LinearSpringDashpot::evaluate() computes, operation for
// operation in the same order, so a contact gets the same bits whichever path evaluates it
// (the answers do not depend on the number of MPI ranks, which changes how contacts fill
// batches). tests/unit/test_linear_batch.cpp holds the two paths to that.
#pragma once

#include "contact/frictional_spring.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/pair_table.hpp"
#include "core/always_inline.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace yuxi {

struct LinearBatch {
  static constexpr std::size_t capacity = 32;
  using Coeffs = LinearSpringDashpot::Coeffs;
  using State = LinearSpringDashpot::State;

  // Takes the law's table of coefficients: false where some pair of materials needs the
  // one-by-one law (rolling resistance, or friction conventions that differ between pairs).
  // Where every pair has the same coefficients, the lanes hold them from here on.
  bool prepare(const PairTable<Coeffs>& table) {
    const Coeffs* first = nullptr;
    for (std::size_t a = 0; a < table.n_materials(); ++a)
      for (std::size_t b = 0; b < table.n_materials(); ++b) {
        if (!table.has(a, b)) continue;
        const auto& c = table(a, b);
        if (c.rolling()) return false;
        if (!first) first = &c;
        if (c.friction_cap != first->friction_cap || c.carry != first->carry) return false;
      }
    if (!first) return false;
    friction_cap = first->friction_cap;
    tangential_carry = first->carry;
    uniform = true;
    for (std::size_t a = 0; a < table.n_materials(); ++a)
      for (std::size_t c = 0; c < table.n_materials(); ++c) {
        if (!table.has(a, c)) continue;
        const auto& x = table(a, c);
        uniform = uniform && x.k_n == first->k_n && x.k_t == first->k_t &&
                  x.gamma_n == first->gamma_n && x.gamma_t == first->gamma_t &&
                  x.mu_s == first->mu_s && x.mu_d == first->mu_d;
      }
    if (uniform)
      for (std::size_t k = 0; k < capacity; ++k) set_coeffs(k, *first);
    return true;
  }

  std::size_t size = 0; // lanes in use, counted by the caller
  // The law's conventions, the same for every pair of materials (set by prepare(); they fill
  // bytes that the alignment of the lanes leaves free).
  CapOn friction_cap = CapOn::spring;
  Carry tangential_carry = Carry::rotate;
  bool uniform = false; // one law for every pair of materials: the lanes hold its coefficients

  // Filled by the caller, one lane per contact.
  // x_i - x_j [length]; for a wall contact its unit normal
  alignas(64) double dx[capacity], dy[capacity], dz[capacity];
  alignas(64) double distance[capacity];           // wall contacts: centre to wall point [length]
  alignas(64) double a_i[capacity], a_j[capacity]; // radii [length]
  alignas(64) double vx[capacity], vy[capacity], vz[capacity];    // v_i - v_j [length/time]
  alignas(64) double wix[capacity], wiy[capacity], wiz[capacity]; // w_i [1/time]
  alignas(64) double wjx[capacity], wjy[capacity], wjz[capacity]; // w_j [1/time]
  alignas(64) double inv_mass_sum[capacity];                      // 1/m_i + 1/m_j [1/mass]
  alignas(64) double k_n[capacity], k_t[capacity], gamma_n[capacity], gamma_t[capacity];
  alignas(64) double mu_s[capacity], mu_d[capacity];
  // The tangential spring: read, then overwritten with its new value.
  alignas(64) double sx[capacity], sy[capacity], sz[capacity]; // s [length]
  alignas(64) double s_k[capacity];                            // its stiffness last step
  alignas(64) double sliding[capacity];                        // 1 while sliding, else 0

  // Results.
  alignas(64) double fx[capacity], fy[capacity], fz[capacity];          // force on i [force]
  alignas(64) double nxf_x[capacity], nxf_y[capacity], nxf_z[capacity]; // n x f_t [force]
  alignas(64) double overlap[capacity];                                 // [length]
  alignas(64) double elastic[capacity], dissipated[capacity];           // [energy]

  bool full() const { return size == capacity; }

  // Fills lane k with one contact: d = x_i - x_j, v = v_i - v_j, its law's coefficients and
  // its state (the tangential spring).
  void set_lane(std::size_t k, const Vec3& d, double radius_i, double radius_j, const Vec3& v,
                const Vec3& w_i, const Vec3& w_j, double inverse_mass_sum, const Coeffs& c,
                const State& state) {
    set_contact(k, d, radius_i, radius_j, v, w_i, w_j, inverse_mass_sum, state);
    set_coeffs(k, c);
  }
  // The same without the coefficients: where every pair of materials has the same law, the
  // lanes hold it from the start (prepare()) and each contact fills the rest.
  void set_contact(std::size_t k, const Vec3& d, double radius_i, double radius_j, const Vec3& v,
                   const Vec3& w_i, const Vec3& w_j, double inverse_mass_sum, const State& state) {
    const SliderState& spring = state.tangential;
    dx[k] = d.x, dy[k] = d.y, dz[k] = d.z;
    a_i[k] = radius_i, a_j[k] = radius_j;
    vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
    wix[k] = w_i.x, wiy[k] = w_i.y, wiz[k] = w_i.z;
    wjx[k] = w_j.x, wjy[k] = w_j.y, wjz[k] = w_j.z;
    inv_mass_sum[k] = inverse_mass_sum;
    sx[k] = spring.spring.x, sy[k] = spring.spring.y, sz[k] = spring.spring.z;
    s_k[k] = spring.k;
    sliding[k] = spring.sliding ? 1.0 : 0.0;
  }
  // Fills lane k with a grain's contact with a wall of zero radius, no spin and infinite mass:
  // unit normal n from the wall's point to the centre, `dist` between them, v = v_i - v_wall.
  // Lanes filled so are evaluated by evaluate_walls(), which takes n and dist as given: the
  // results are those of LinearSpringDashpot::evaluate() on the geometry the one-by-one wall
  // loop builds (against_wall in sim/contact_forces.hpp).
  void set_wall_contact(std::size_t k, const Vec3& n, double dist, double radius, const Vec3& v,
                        const Vec3& w_i, double inverse_mass, const State& state) {
    set_contact(k, n, radius, 0.0, v, w_i, Vec3{}, inverse_mass, state);
    distance[k] = dist;
  }
  void set_coeffs(std::size_t k, const Coeffs& c) {
    k_n[k] = c.k_n, k_t[k] = c.k_t;
    gamma_n[k] = c.gamma_n, gamma_t[k] = c.gamma_t;
    mu_s[k] = c.mu_s, mu_d[k] = c.mu_d;
  }

  // The tangential spring of lane k after evaluate().
  SliderState spring(std::size_t k) const {
    SliderState st;
    st.spring = {sx[k], sy[k], sz[k]};
    st.k = s_k[k];
    st.sliding = sliding[k] != 0.0 ? 1 : 0;
    return st;
  }

  // The state of the contact in lane k after evaluate() (the rolling spring is unused here).
  void save_state(std::size_t k, State& state) const { state.tangential = spring(k); }

  // Evaluates every lane with the conventions prepare() took (the state arrays are updated in
  // place).
  void evaluate(double dt) { evaluate(friction_cap, tangential_carry, dt); }
  // The same with the conventions given.
  void evaluate(CapOn cap, Carry carry, double dt) { dispatch<false>(cap, carry, dt); }
  // Lanes filled by set_wall_contact(), with the conventions prepare() took or those given.
  void evaluate_walls(double dt) { evaluate_walls(friction_cap, tangential_carry, dt); }
  void evaluate_walls(CapOn cap, Carry carry, double dt) { dispatch<true>(cap, carry, dt); }

private:
  template <bool walls> void dispatch(CapOn cap, Carry carry, double dt) {
    switch (cap) {
    case CapOn::spring:
      return carry == Carry::rotate ? run<CapOn::spring, Carry::rotate, walls>(dt)
                                    : run<CapOn::spring, Carry::project, walls>(dt);
    case CapOn::total:
      return carry == Carry::rotate ? run<CapOn::total, Carry::rotate, walls>(dt)
                                    : run<CapOn::total, Carry::project, walls>(dt);
    case CapOn::total_lammps:
      return carry == Carry::rotate ? run<CapOn::total_lammps, Carry::rotate, walls>(dt)
                                    : run<CapOn::total_lammps, Carry::project, walls>(dt);
    }
  }

  // The loop is compiled twice on x86-64: for the baseline instruction set (two lanes per SSE2
  // instruction) and for AVX2 (four), chosen at run time, so a portable build still uses the
  // wider registers where the processor has them. The arithmetic is the same in both (no
  // contraction into FMA: the build is ISO C++, -ffp-contract=off), so are the bits.
  template <CapOn cap, Carry carry, bool walls> void run(double dt) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) return run_avx2<cap, carry, walls>(dt);
#endif
    lanes<cap, carry, walls>(dt);
  }

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  template <CapOn cap, Carry carry, bool walls>
  __attribute__((target("avx2"))) void run_avx2(double dt) {
    lanes<cap, carry, walls>(dt);
  }
#endif

  template <CapOn cap, Carry carry, bool walls> YUXI_ALWAYS_INLINE void lanes(double dt) {
    for (std::size_t k = 0; k < size; ++k) {
      // Geometry: n from j to i (given for a wall), overlap, reduced mass.
      double dist, nx, ny, nz;
      if constexpr (walls) {
        dist = distance[k];
        nx = dx[k], ny = dy[k], nz = dz[k];
      } else {
        dist = std::sqrt(dx[k] * dx[k] + dy[k] * dy[k] + dz[k] * dz[k]);
        const double inv_dist = 1.0 / dist;
        nx = dx[k] * inv_dist, ny = dy[k] * inv_dist, nz = dz[k] * inv_dist;
      }
      const double delta = (a_i[k] + a_j[k]) - dist;
      const double m_eff = 1.0 / inv_mass_sum[k];
      // Contact-point velocity v_c = v_i - v_j - (a_i w_i + a_j w_j) x n, split along n.
      const double ax = a_i[k] * wix[k] + a_j[k] * wjx[k];
      const double ay = a_i[k] * wiy[k] + a_j[k] * wjy[k];
      const double az = a_i[k] * wiz[k] + a_j[k] * wjz[k];
      const double cx = vx[k] - (ay * nz - az * ny);
      const double cy = vy[k] - (az * nx - ax * nz);
      const double cz = vz[k] - (ax * ny - ay * nx);
      const double vn = cx * nx + cy * ny + cz * nz;
      const double ux = cx - vn * nx, uy = cy - vn * ny, uz = cz - vn * nz; // tangential
      // Normal force: spring and dashpot.
      const double fn = k_n[k] * delta - m_eff * gamma_n[k] * vn;
      // The old spring carried into the new tangent plane.
      const double old_x = sx[k], old_y = sy[k], old_z = sz[k];
      const double along = old_x * nx + old_y * ny + old_z * nz;
      double px = old_x - along * nx, py = old_y - along * ny, pz = old_z - along * nz;
      if constexpr (carry == Carry::rotate) {
        const double len2 = old_x * old_x + old_y * old_y + old_z * old_z;
        const double p2 = px * px + py * py + pz * pz;
        const double scale = std::sqrt(len2 / p2);
        const bool keep = len2 == 0.0;
        const bool flat = p2 == 0.0;
        px = keep ? old_x : (flat ? 0.0 : px * scale);
        py = keep ? old_y : (flat ? 0.0 : py * scale);
        pz = keep ? old_z : (flat ? 0.0 : pz * scale);
      }
      // The slider (frictional_spring.hpp, slide()).
      const double kt = k_t[k];
      const double eta = m_eff * gamma_t[k];
      const double ix = ux * dt, iy = uy * dt, iz = uz * dt; // increment
      double spx = px + ix, spy = py + iy, spz = pz + iz;
      double dmx = ux * -eta, dmy = uy * -eta, dmz = uz * -eta;
      double fsx = spx * -kt, fsy = spy * -kt, fsz = spz * -kt;
      const double lx = cap == CapOn::spring ? fsx : fsx + dmx;
      const double ly = cap == CapOn::spring ? fsy : fsy + dmy;
      const double lz = cap == CapOn::spring ? fsz : fsz + dmz;
      const double abs_fn = std::abs(fn);
      const double mu_static = mu_s[k], mu_dynamic = mu_d[k];
      const double limit = (sliding[k] != 0.0 ? mu_dynamic : mu_static) * abs_fn;
      const double l2 = lx * lx + ly * ly + lz * lz;
      const bool slip = l2 > limit * limit;
      const double cut = mu_dynamic * abs_fn / std::sqrt(l2);
      const double cx2 = lx * cut, cy2 = ly * cut, cz2 = lz * cut; // capped force
      if constexpr (cap == CapOn::spring) {
        fsx = slip ? cx2 : fsx, fsy = slip ? cy2 : fsy, fsz = slip ? cz2 : fsz;
      } else if constexpr (cap == CapOn::total) {
        fsx = slip ? cx2 : fsx, fsy = slip ? cy2 : fsy, fsz = slip ? cz2 : fsz;
        dmx = slip ? 0.0 : dmx, dmy = slip ? 0.0 : dmy, dmz = slip ? 0.0 : dmz;
      } else {
        fsx = slip ? cx2 - dmx : fsx, fsy = slip ? cy2 - dmy : fsy, fsz = slip ? cz2 - dmz : fsz;
      }
      const bool stiff = kt > 0;
      const double qx = fsx / -kt, qy = fsy / -kt, qz = fsz / -kt; // the spring that gives f_s
      spx = slip ? (stiff ? qx : 0.0) : spx;
      spy = slip ? (stiff ? qy : 0.0) : spy;
      spz = slip ? (stiff ? qz : 0.0) : spz;
      const double stored = 0.5 * kt * (spx * spx + spy * spy + spz * spz);
      const double old_k = s_k[k];
      const double old_stored = 0.5 * old_k * (old_x * old_x + old_y * old_y + old_z * old_z);
      const double wx = 0.5 * (px * old_k + spx * kt);
      const double wy = 0.5 * (py * old_k + spy * kt);
      const double wz = 0.5 * (pz * old_k + spz * kt);
      const double work_in = wx * ix + wy * iy + wz * iz;
      const double slider_heat =
          work_in - (stored - old_stored) - (dmx * ux + dmy * uy + dmz * uz) * dt;
      const double ftx = fsx + dmx, fty = fsy + dmy, ftz = fsz + dmz;
      // Results.
      fx[k] = fn * nx + ftx;
      fy[k] = fn * ny + fty;
      fz[k] = fn * nz + ftz;
      nxf_x[k] = ny * ftz - nz * fty;
      nxf_y[k] = nz * ftx - nx * ftz;
      nxf_z[k] = nx * fty - ny * ftx;
      overlap[k] = delta;
      elastic[k] = 0.5 * k_n[k] * delta * delta + stored;
      dissipated[k] = m_eff * gamma_n[k] * vn * vn * dt + slider_heat;
      sx[k] = spx, sy[k] = spy, sz[k] = spz;
      s_k[k] = kt;
      sliding[k] = slip ? 1.0 : 0.0;
    }
  }
};

} // namespace yuxi
