// The pair loop: evaluates one contact model on every listed pair and grain-plane candidate,
// and accumulates forces, torques and the energy tallies. Templated on the model, so the inner
// loop is monomorphic and the model's evaluate() inlines.
#pragma once

#include "contact/contact_history.hpp"
#include "contact/contact_model.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "scene/plane_wall.hpp"
#include "sim/contact_tally.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace yuxi {

template <class Model> class ContactForces {
public:
  using State = typename Model::State;

  explicit ContactForces(ContactLaw<Model> law) : law_(std::move(law)) {}

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

  void compute_pairs(ParticleStore& s, const NeighborList& list, double dt, ContactTally& tally,
                     ContactRecord& record) {
    const Vec3* x = s.x.data();
    const double* radius = s.radius.data();
    const std::uint32_t* partners = list.partners.data();
    for (std::uint32_t i = 0; i + 1 < list.offsets.size(); ++i) {
      const Vec3 xi = x[i];
      const double ai = radius[i];
      for (std::uint32_t p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
        const std::uint32_t j = partners[p];
        const Vec3 d = xi - x[j];
        const double r2 = norm2(d);
        const double aj = radius[j];
        const double touch = ai + aj;
        if (r2 >= touch * touch) {
          if (const auto slot = history.pair_slot[p]; slot != history.none) {
            // separated: the contact's history ends
            tally.dissipated +=
                Model::release(law_.coeffs(s.material[i], s.material[j]), history.states[slot]);
            history.close(p);
          }
          continue;
        }
        State& state = history.open(p);
        const double dist = std::sqrt(r2);
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
        if (record.enabled) {
          record.pair_force[p] = r.force;
          record.pair_elastic[p] = r.elastic;
        }
        if (s.kind[j] == Kind::wall) tally.wall_work += dot(r.force, s.v[j]) * dt;
        if (s.kind[i] == Kind::wall) tally.wall_work -= dot(r.force, s.v[i]) * dt;
        track_overlap(g, std::min(ai, aj), i, tally);
      }
    }
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
      if (record.enabled) {
        record.plane_force[k] = r.force;
        record.plane_elastic[k] = r.elastic;
      }
      tally.wall_work += dot(r.force, v_wall) * dt;
      track_overlap(g, ai, i, tally);
    }
  }

  ContactLaw<Model> law_;
};

} // namespace yuxi
