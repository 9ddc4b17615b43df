// The pair loop: evaluates one contact model on every listed pair and grain-plane candidate,
// and accumulates forces, torques and the energy tallies. Templated on the model, so the inner
// loop is monomorphic and the model's evaluate() inlines.
#pragma once

#include "contact/contact_history.hpp"
#include "contact/contact_model.hpp"
#include "contact/linear_batch.hpp"
#include "core/always_inline.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "scene/plane_wall.hpp"
#include "sim/contact_tally.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>
#include <vector>

namespace yuxi {

template <class Model> class ContactForces {
public:
  using State = typename Model::State;

  explicit ContactForces(ContactLaw<Model> law) : law_(std::move(law)), batch_(make_batch(law_)) {}

  const ContactLaw<Model>& law() const { return law_; }
  ContactHistory<State> history;

  void compute(ParticleStore& s, const NeighborList& list, const std::vector<PlaneWall>& planes,
               double t, double dt, ContactTally& tally, ContactRecord& record) {
    if (record.enabled) {
      record.pair_force.assign(list.n_pairs(), Vec3{});
      record.pair_elastic.assign(list.n_pairs(), 0.0);
      record.plane_force.assign(list.planes.size(), Vec3{});
      record.plane_elastic.assign(list.planes.size(), 0.0);
    }
    if constexpr (std::is_same_v<Model, LinearSpringDashpot>) {
      if (batch_) {
        compute_pairs_in_batches(s, list, dt, tally, record);
        compute_planes(s, list, planes, t, dt, tally, record);
        return;
      }
    }
    compute_pairs(s, list, dt, tally, record);
    compute_planes(s, list, planes, t, dt, tally, record);
  }

private:
  static void track_overlap(const ContactGeometry& g, double smaller_radius, std::size_t i,
                            ContactTally& tally) {
    if (g.overlap > tally.max_overlap_ratio * smaller_radius) { // divides only on a new maximum
      tally.max_overlap_ratio = g.overlap / smaller_radius;
      tally.worst_particle = i;
    }
  }

  static void book(const ContactResult& r, ContactTally& tally) {
    tally.elastic += r.elastic;
    tally.dissipated += r.dissipated;
    tally.relaxation += r.relaxation;
    tally.touching += r.touching ? 1 : 0;
  }

  // Calls touching(i, j, p, d, a_i, a_j) for every listed pair p = (i, j) that overlaps
  // (d = x_i - x_j), in list order, and ends the contacts that have opened: the energy their
  // springs still hold is lost.
  template <class Touching>
  YUXI_ALWAYS_INLINE void sweep(const ParticleStore& s, const NeighborList& list,
                                ContactTally& tally, Touching&& touching) {
    const Vec3* x = s.x.data();
    const double* radius = s.radius.data();
    const std::uint32_t* partners = list.partners.data();
    for (std::uint32_t i = 0; i + 1 < list.offsets.size(); ++i) {
      const Vec3 xi = x[i];
      const double ai = radius[i];
      for (std::uint32_t p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
        const std::uint32_t j = partners[p];
        const Vec3 d = xi - x[j];
        const double aj = radius[j];
        const double touch = ai + aj;
        if (norm2(d) >= touch * touch) {
          if (const auto slot = history.pair_slot[p]; slot != history.none) {
            tally.dissipated +=
                Model::release(law_.coeffs(s.material[i], s.material[j]), history.states[slot]);
            history.close(p);
          }
          continue;
        }
        touching(i, j, p, d, ai, aj);
      }
    }
  }

  void compute_pairs(ParticleStore& s, const NeighborList& list, double dt, ContactTally& tally,
                     ContactRecord& record) {
    sweep(s, list, tally,
          [&](std::uint32_t i, std::uint32_t j, std::uint32_t p, const Vec3& d, double ai,
              double aj) {
            State& state = history.open(p);
            const double dist = std::sqrt(norm2(d));
            const double touch = ai + aj;
            ContactGeometry g;
            g.n = d * (1.0 / dist);
            g.overlap = touch - dist;
            g.distance = dist;
            g.v_rel = s.v[i] - s.v[j];
            g.w_i = s.w[i];
            g.w_j = s.w[j];
            g.a_i = ai;
            g.a_j = aj;
            g.m_eff = 1.0 / (s.inv_mass[i] + s.inv_mass[j]);
            g.r_eff = ai * aj / touch;
            g.dt = dt;
            const ContactResult r =
                Model::evaluate(g, law_.coeffs(s.material[i], s.material[j]), state);
            s.f[i] += r.force;
            s.f[j] -= r.force;
            s.torque[i] += r.torque_i;
            s.torque[j] += r.torque_j;
            book(r, tally);
            record.keep_pair(p, r.force, r.elastic);
            if (s.kind[j] == Kind::wall) tally.wall_work += dot(r.force, s.v[j]) * dt;
            if (s.kind[i] == Kind::wall) tally.wall_work -= dot(r.force, s.v[i]) * dt;
            track_overlap(g, std::min(ai, aj), i, tally);
          });
  }

  // The linear law in SIMD batches (linear_batch.hpp) where every pair of materials allows it.
  struct Batch {
    LinearBatch lanes;
    std::uint32_t row[LinearBatch::capacity];
    std::uint32_t partner[LinearBatch::capacity];
    std::uint32_t pair[LinearBatch::capacity];
    CapOn cap; // the friction convention, the same for every pair of materials
    Carry carry;
  };

  // A batch where every pair of materials allows one (else null).
  static std::unique_ptr<Batch> make_batch(const ContactLaw<Model>& law) {
    if constexpr (std::is_same_v<Model, LinearSpringDashpot>) {
      const auto& table = law.coeffs;
      const typename Model::Coeffs* first = nullptr;
      for (std::size_t a = 0; a < table.n_materials(); ++a)
        for (std::size_t b = 0; b < table.n_materials(); ++b) {
          if (!table.has(a, b)) continue;
          const auto& c = table(a, b);
          if (c.rolling()) return nullptr;
          if (!first) first = &c;
          if (c.friction_cap != first->friction_cap || c.carry != first->carry) return nullptr;
        }
      if (!first) return nullptr;
      auto b = std::make_unique<Batch>();
      b->cap = first->friction_cap;
      b->carry = first->carry;
      return b;
    } else {
      return nullptr;
    }
  }

  void compute_pairs_in_batches(ParticleStore& s, const NeighborList& list, double dt,
                                ContactTally& tally, ContactRecord& record) {
    Batch& b = *batch_;
    LinearBatch& lanes = b.lanes;
    lanes.size = 0;
    sweep(s, list, tally,
          [&](std::uint32_t i, std::uint32_t j, std::uint32_t p, const Vec3& d, double ai,
              double aj) {
            const SliderState& spring = history.open(p).tangential;
            const auto& c = law_.coeffs(s.material[i], s.material[j]);
            const std::size_t k = lanes.size++;
            const Vec3 v = s.v[i] - s.v[j];
            const Vec3 wi = s.w[i], wj = s.w[j];
            lanes.dx[k] = d.x, lanes.dy[k] = d.y, lanes.dz[k] = d.z;
            lanes.a_i[k] = ai, lanes.a_j[k] = aj;
            lanes.vx[k] = v.x, lanes.vy[k] = v.y, lanes.vz[k] = v.z;
            lanes.wix[k] = wi.x, lanes.wiy[k] = wi.y, lanes.wiz[k] = wi.z;
            lanes.wjx[k] = wj.x, lanes.wjy[k] = wj.y, lanes.wjz[k] = wj.z;
            lanes.inv_mass_sum[k] = s.inv_mass[i] + s.inv_mass[j];
            lanes.k_n[k] = c.k_n, lanes.k_t[k] = c.k_t;
            lanes.gamma_n[k] = c.gamma_n, lanes.gamma_t[k] = c.gamma_t;
            lanes.mu_s[k] = c.mu_s, lanes.mu_d[k] = c.mu_d;
            lanes.sx[k] = spring.spring.x, lanes.sy[k] = spring.spring.y;
            lanes.sz[k] = spring.spring.z;
            lanes.s_k[k] = spring.k;
            lanes.sliding[k] = spring.sliding ? 1.0 : 0.0;
            b.row[k] = i, b.partner[k] = j, b.pair[k] = p;
            if (lanes.full()) flush(s, dt, tally, record);
          });
    flush(s, dt, tally, record);
  }

  // Evaluates the batch and adds its forces, torques and energies, contact by contact in list
  // order (so the sums are those of the one-by-one loop).
  void flush(ParticleStore& s, double dt, ContactTally& tally, ContactRecord& record) {
    Batch& b = *batch_;
    LinearBatch& lanes = b.lanes;
    lanes.evaluate(b.cap, b.carry, dt);
    for (std::size_t k = 0; k < lanes.size; ++k) {
      const std::uint32_t i = b.row[k], j = b.partner[k], p = b.pair[k];
      const Vec3 force{lanes.fx[k], lanes.fy[k], lanes.fz[k]};
      const Vec3 nxf{lanes.nxf_x[k], lanes.nxf_y[k], lanes.nxf_z[k]};
      s.f[i] += force;
      s.f[j] -= force;
      s.torque[i] -= lanes.a_i[k] * nxf;
      s.torque[j] -= lanes.a_j[k] * nxf;
      tally.elastic += lanes.elastic[k];
      tally.dissipated += lanes.dissipated[k];
      ++tally.touching;
      record.keep_pair(p, force, lanes.elastic[k]);
      if (s.kind[j] == Kind::wall) tally.wall_work += dot(force, s.v[j]) * dt;
      if (s.kind[i] == Kind::wall) tally.wall_work -= dot(force, s.v[i]) * dt;
      const double smaller = std::min(lanes.a_i[k], lanes.a_j[k]);
      if (lanes.overlap[k] > tally.max_overlap_ratio * smaller) {
        tally.max_overlap_ratio = lanes.overlap[k] / smaller;
        tally.worst_particle = i;
      }
      SliderState& spring = history.states[history.pair_slot[p]].tangential;
      spring.spring = {lanes.sx[k], lanes.sy[k], lanes.sz[k]};
      spring.k = lanes.s_k[k];
      spring.sliding = lanes.sliding[k] != 0.0 ? 1 : 0;
    }
    lanes.size = 0;
  }

  void compute_planes(ParticleStore& s, const NeighborList& list,
                      const std::vector<PlaneWall>& planes, double t, double dt,
                      ContactTally& tally, ContactRecord& record) {
    for (std::size_t k = 0; k < list.planes.size(); ++k) {
      const auto [i, plane_index] = list.planes[k];
      const PlaneWall& wall = planes[plane_index];
      State& state = history.plane[k];
      const double dist = wall.distance(s.x[i], t);
      const double ai = s.radius[i];
      if (dist >= ai) {
        if (history.plane_live[k]) {
          tally.dissipated += Model::release(law_.coeffs(s.material[i], wall.material), state);
          history.plane_live[k] = 0;
        }
        continue;
      }
      history.plane_live[k] = 1;
      const Vec3 v_wall = wall.velocity(t);
      ContactGeometry g;
      g.n = wall.normal;
      g.overlap = ai - dist;
      g.distance = dist;
      g.v_rel = s.v[i] - v_wall;
      g.w_i = s.w[i];
      g.w_j = Vec3{};
      g.a_i = ai;
      g.a_j = 0.0;
      g.m_eff = 1.0 / s.inv_mass[i];
      g.r_eff = ai;
      g.dt = dt;
      const ContactResult r = Model::evaluate(g, law_.coeffs(s.material[i], wall.material), state);
      s.f[i] += r.force;
      s.torque[i] += r.torque_i;
      book(r, tally);
      record.keep_plane(k, r.force, r.elastic);
      tally.wall_work += dot(r.force, v_wall) * dt;
      track_overlap(g, ai, i, tally);
    }
  }

  ContactLaw<Model> law_;
  std::unique_ptr<Batch> batch_; // null where the law needs the one-by-one loop
};

} // namespace yuxi
