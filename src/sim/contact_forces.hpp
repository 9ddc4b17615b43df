// The pair loop: evaluates one contact model on every listed pair and grain-plane candidate,
// and accumulates forces, torques and the energy tallies. Templated on the model, so the inner
// loop is monomorphic and the model's evaluate() inlines.
//
// A model that can be evaluated on many contacts at once names its SIMD lanes as
// `using Batch = ...;` (the linear law: linear_batch.hpp). Where Batch::prepare() accepts the
// law's coefficients, the pair loop fills batches; every other model, and a law the batch does
// not take, is evaluated contact by contact. The choice is made once, at construction.
#pragma once

#include "contact/contact_history.hpp"
#include "contact/contact_model.hpp"
#include "core/always_inline.hpp"
#include "core/near_pairs.hpp"
#include "core/neighbor_list.hpp"
#include "core/overlap_scan.hpp"
#include "core/particle_view.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "sim/contact_tally.hpp"
#include "sim/near_wall_elements.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace yuxi {

// Which listed pairs a call of ContactForces::compute() evaluates: all of them, or (where the
// list has its ghost pairs apart: NeighborList::ghost_pairs) those with a ghost partner first,
// then the others with the flat walls.
enum class PairSet { all, ghost, owned };

// A model with SIMD lanes for the pair loop (see above).
template <class Model>
concept BatchedModel = requires {
  typename Model::Batch;
};

// The lanes of a model's batches; a placeholder for a model without (never allocated).
template <class Model> struct BatchLanes {
  struct None {
    static constexpr std::size_t capacity = 1;
  };
  using type = None;
};
template <BatchedModel Model> struct BatchLanes<Model> { using type = typename Model::Batch; };

template <class Model> class ContactForces {
public:
  using State = typename Model::State;

  // `batches` false: every contact one by one, even where the model has SIMD lanes
  // (Backend::cpu_reference).
  explicit ContactForces(ContactLaw<Model> law, bool batches = true)
      : law_(std::move(law)), batch_(batches ? make_batch(law_) : nullptr) {}

  const ContactLaw<Model>& law() const { return law_; }
  ContactHistory<State> history;
  // What the grains did to each flat wall at the last evaluation (this rank's part).
  std::vector<WallLoad> plane_loads;
  // The contacts with shaped walls that began already deep on this rank (contact_tally.hpp).
  DeepStarts deep_starts;

  // `s`: the particles' plain view (taken by value here, by reference by the per-contact
  // helpers below, which run for every contact).
  // `walls_still`: no wall particle moves (every one has zero velocity), so they do no work.
  // `near`: the near pairs of the list, scanned instead of the whole list while they hold.
  // PairSet::ghost and then PairSet::owned do what one call with PairSet::all does, with
  // the pairs in another order.
  void compute(ParticleView s, const NeighborList& list, const NearPairs* near,
               const std::vector<PlaneWall>& planes, double t, double dt, bool walls_still,
               ContactTally& tally, ContactRecord& record, PairSet set = PairSet::all) {
    walls_still_ = walls_still;
    near_ = near && near->hold() ? near : nullptr;
    set_ = set;
    if (record.enabled && set != PairSet::owned) record.start(list.planes.size());
    bool batched = false;
    if constexpr (BatchedModel<Model>) {
      if (batch_) {
        compute_pairs_in_batches(s, list, dt, tally, record);
        batched = true;
      }
    }
    if (!batched) compute_pairs(s, list, dt, tally, record);
    if (set != PairSet::ghost) compute_planes(s, list, planes, t, dt, tally, record);
  }

  // The contacts of grains with shaped walls (meshes, cylinders), placed at time t: each
  // candidate's touches (scene/wall_touch.hpp) pick up the states of its previous contacts
  // whose normals are nearest theirs (within 60 degrees), so a contact's history carries over
  // when its point moves onto another triangle; a previous contact that nothing picks up has
  // opened. `loads` (one per wall) gets what the grains do to each wall, `elements` the force
  // of each contact on its triangle or patch; `record`, where enabled, each contact. `near`,
  // where given, stands for the list's candidate triangles (the same touches). Where the model
  // has SIMD lanes, the contacts are evaluated in batches, with the same bits.
  void compute_walls(ParticleView s, const NeighborList& list, const NearWallElements* near,
                     const std::vector<ShapedWall>& walls, double t, double dt, ContactTally& tally,
                     std::vector<WallLoad>& loads, std::vector<ElementForce>& elements,
                     ContactRecord& record) {
    loads.assign(walls.size(), WallLoad{});
    elements.clear();
    if (list.walls.empty()) return;
    std::vector<Vec3>& torque_points = torque_points_;
    std::vector<std::uint8_t>& active = wall_active_;
    torque_points.resize(walls.size());
    active.resize(walls.size());
    for (std::size_t w = 0; w < walls.size(); ++w) {
      torque_points[w] = torque_point(walls[w]);
      active[w] = wall_active(walls[w], t) ? 1 : 0;
    }
    bool batched = false;
    if constexpr (BatchedModel<Model>) batched = batch_ != nullptr;
    WallBooks books{loads, elements, record, tally, torque_points, t};
    batch_releases_.clear();
    WallTouches touches;
    for (std::size_t k = 0; k < list.walls.size(); ++k) {
      const WallContactRef ref = list.walls[k];
      const std::uint32_t i = ref.particle;
      const ShapedWall& wall = walls[ref.wall];
      touches.n = 0;
      if (active[ref.wall]) {
        if (const auto* mesh = std::get_if<MeshWall>(&wall))
          mesh->touches(s.x[i], s.radius[i],
                        near ? near->of(k)
                             : std::span<const std::uint32_t>{list.wall_elements.data() + ref.first,
                                                              ref.count},
                        scratch_, order_, touches);
        else
          std::get<CylinderWall>(wall).touches(s.x[i], s.radius[i], touches);
      }
      WallContactSet<State>& set = history.wall[k];
      const auto contact = [&](std::size_t c) -> WallContact<State>& {
        return history.wall_contact(k, c);
      };
      if (touches.n == 0 && set.n == 0) continue;
      const auto& coeffs = law_.coeffs(s.material[i], wall_material(wall));
      // Each new contact (deepest first) takes the free previous state of nearest normal.
      const std::size_t n = std::min(touches.n, max_wall_contacts);
      int match[max_wall_contacts];
      bool taken[max_wall_contacts] = {};
      for (std::size_t c = 0; c < n; ++c) {
        match[c] = -1;
        double best = 0.5; // cos 60 degrees
        for (std::size_t m = 0; m < set.n; ++m) {
          const double d = dot(contact(m).normal, touches.at[c].normal);
          if (!taken[m] && d > best) best = d, match[c] = static_cast<int>(m);
        }
        if (match[c] >= 0) taken[match[c]] = true;
      }
      for (std::size_t m = 0; m < set.n; ++m)
        if (!taken[m]) {
          const double released = Model::release(coeffs, contact(m).state);
          if constexpr (BatchedModel<Model>) {
            if (batched) { // booked in its place among the batch's contacts (flush_walls)
              batch_releases_.push_back({batch_->lanes.size, released});
              continue;
            }
          }
          tally.dissipated += released;
        }
      history.make_wall_room(k, n);
      if (n > 1 || set.n > 1) move_matched_states(contact, match, n);
      for (std::size_t c = 0; c < n; ++c) {
        const WallTouch& touch = touches.at[c];
        State& state = contact(c).state;
        double deep = 0.0, approach = 0.0; // (a new contact that began deep: DeepStarts)
        if (match[c] < 0) {
          state = State{};
          if (dt > 0.0) {
            approach = std::max(0.0, -dot(s.v[i] - touch.velocity, touch.normal)) * dt;
            deep = DeepStarts::deep_overlap(s.radius[i] - touch.distance, approach, s.radius[i]);
          }
        }
        contact(c).normal = touch.normal;
        const WallSite site{
            i,    ref.wall, static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(c), &touch,
            deep, approach};
        if constexpr (BatchedModel<Model>) {
          if (batched) {
            queue_wall_contact(s, site, coeffs, state, dt, books);
            continue;
          }
        }
        const ContactGeometry g =
            against_wall(s, i, touch.normal, touch.distance, touch.velocity, dt);
        const ContactResult r = Model::evaluate(g, coeffs, state);
        s.f[i] += r.force;
        s.torque[i] += r.torque_i;
        book(r, tally);
        book_wall_contact(s, site, r.force, r.elastic, g.overlap, dt, books, r.dissipated,
                          r.relaxation);
        if (deep > 0.0)
          deep_starts.add(r.elastic, t, s.gid[i], ref.wall, touch.element, deep, approach);
      }
      set.n = static_cast<std::uint8_t>(n);
    }
    if constexpr (BatchedModel<Model>)
      if (batched) flush_walls(s, dt, books);
  }

  // Sizes the wall loop's buffers for `list`, and `elements`, by their most: each candidate's
  // contacts and its candidate elements (a step between list builds then allocates nothing).
  void size_for(const NeighborList& list, std::vector<ElementForce>& elements) {
    const std::size_t contacts = list.walls.size() * max_wall_contacts;
    elements.reserve(contacts);
    batch_releases_.reserve(contacts);
    std::size_t most = 0;
    for (const WallContactRef& ref : list.walls) most = std::max<std::size_t>(most, ref.count);
    scratch_.reserve(most);
    order_.reserve(most);
  }

private:
  // Where compute_walls() books what a wall contact does.
  struct WallBooks {
    std::vector<WallLoad>& loads;
    std::vector<ElementForce>& elements;
    ContactRecord& record;
    ContactTally& tally;
    const std::vector<Vec3>& torque_points;
    double t;
  };
  // One wall contact: grain i, its wall, its place in the list (candidate k, contact c), where
  // it touches, and where it began deep (DeepStarts) its overlap and its grain's approach.
  struct WallSite {
    std::uint32_t i, wall, k, c;
    const WallTouch* touch;
    double deep, approach;
  };
  // A wall contact in the batch: its site, with what the booking needs of its touch copied
  // (the touches are the grain's; the normal stays in the lanes).
  struct QueuedWall {
    std::uint32_t i, wall, k, c, element;
    Vec3 point, velocity;
    State* state;
    double deep, approach;
  };

  // Moves the state that wall contact c matched (match[c], -1 for none) to slot c, by swaps
  // (no copy of the whole set).
  template <class ContactAt>
  static void move_matched_states(const ContactAt& contact, const int* match, std::size_t n) {
    int slot_of[max_wall_contacts], held_by[max_wall_contacts];
    for (int m = 0; m < static_cast<int>(max_wall_contacts); ++m) slot_of[m] = held_by[m] = m;
    for (std::size_t c = 0; c < n; ++c) {
      if (match[c] < 0) continue;
      const int from = slot_of[match[c]], here = static_cast<int>(c);
      if (from == here) continue;
      std::swap(contact(c), contact(from));
      const int displaced = held_by[here];
      held_by[here] = match[c], held_by[from] = displaced;
      slot_of[match[c]] = here, slot_of[displaced] = from;
    }
  }

  // What follows the force on the grain and the energies: the wall's work, load and element
  // force, the record and the deepest overlap.
  static void book_wall_contact(const ParticleView& s, const WallSite& site, const Vec3& force,
                                double elastic, double overlap, double dt, WallBooks& books,
                                double dissipated, double relaxation) {
    const WallTouch& touch = *site.touch;
    const double work = dot(force, touch.velocity) * dt;
    books.tally.wall_work += work;
    WallLoad& load = books.loads[site.wall];
    load.force -= force;
    load.torque -= cross(touch.point - books.torque_points[site.wall], force);
    load.work += work;
    ++load.contacts;
    books.elements.push_back({site.wall, touch.element, -force});
    books.record.keep_wall({site.k, site.c, touch.element, touch.point, touch.normal, force,
                            elastic, overlap, dissipated, relaxation, work});
    track_overlap(overlap, s.radius[site.i], site.i, books.tally);
  }

  // Puts a wall contact in the batch's lanes (flushed when full).
  void queue_wall_contact(const ParticleView& s, const WallSite& site,
                          const typename Model::Coeffs& coeffs, State& state, double dt,
                          WallBooks& books) {
    Lanes& lanes = batch_->lanes;
    const std::size_t k = lanes.size++;
    const WallTouch& touch = *site.touch;
    lanes.set_wall_contact(k, touch.normal, touch.distance, s.radius[site.i],
                           s.v[site.i] - touch.velocity, s.w[site.i], s.inv_mass[site.i], state);
    if (!lanes.uniform) lanes.set_coeffs(k, coeffs);
    queued_walls_[k] = {site.i,      site.wall,      site.k, site.c,    touch.element,
                        touch.point, touch.velocity, &state, site.deep, site.approach};
    if (lanes.full()) flush_walls(s, dt, books);
  }

  // Evaluates the batch of wall contacts and books each as the one-by-one loop does, in the
  // same order, with the states released before each (the same bits whichever path runs).
  void flush_walls(const ParticleView& s, double dt, WallBooks& books) {
    Lanes& lanes = batch_->lanes;
    if (lanes.size > 0) lanes.evaluate_walls(dt);
    std::size_t released = 0;
    for (std::size_t k = 0; k < lanes.size; ++k) {
      for (; released < batch_releases_.size() && batch_releases_[released].first == k; ++released)
        books.tally.dissipated += batch_releases_[released].second;
      const QueuedWall& q = queued_walls_[k];
      const Vec3 force{lanes.fx[k], lanes.fy[k], lanes.fz[k]};
      const Vec3 nxf{lanes.nxf_x[k], lanes.nxf_y[k], lanes.nxf_z[k]};
      s.f[q.i] += force;
      s.torque[q.i] -= lanes.a_i[k] * nxf;
      books.tally.elastic += lanes.elastic[k];
      books.tally.dissipated += lanes.dissipated[k];
      ++books.tally.touching;
      WallTouch touch;
      touch.normal = {lanes.dx[k], lanes.dy[k], lanes.dz[k]}; // (as set_wall_contact() put it)
      touch.distance = lanes.distance[k];
      touch.point = q.point;
      touch.velocity = q.velocity;
      touch.element = q.element;
      book_wall_contact(s, {q.i, q.wall, q.k, q.c, &touch, q.deep, q.approach}, force,
                        lanes.elastic[k], lanes.overlap[k], dt, books, lanes.dissipated[k], 0.0);
      if (q.deep > 0.0)
        deep_starts.add(lanes.elastic[k], books.t, s.gid[q.i], q.wall, q.element, q.deep,
                        q.approach);
      lanes.save_state(k, *q.state);
    }
    for (; released < batch_releases_.size(); ++released) // after the batch's last contact
      books.tally.dissipated += batch_releases_[released].second;
    batch_releases_.clear();
    lanes.size = 0;
  }

  // The geometry of grain i against a wall element (contact/contact_geometry.hpp).
  static ContactGeometry against_wall(const ParticleView& s, std::uint32_t i, const Vec3& n,
                                      double distance, const Vec3& v_wall, double dt) {
    return wall_geometry(n, distance, s.radius[i], s.v[i], v_wall, s.w[i], s.inv_mass[i], dt);
  }

  static void track_overlap(double overlap, double smaller_radius, std::size_t i,
                            ContactTally& tally) {
    if (overlap > tally.max_overlap_ratio * smaller_radius) { // divides only on a new maximum
      tally.max_overlap_ratio = overlap / smaller_radius;
      tally.worst_particle = i;
    }
  }

  // Work of a wall particle's prescribed motion on its partner (force on i, -force on j), booked
  // and returned; none while the walls are still (the sum would only add zeros).
  double book_wall_work(const ParticleView& s, std::uint32_t i, std::uint32_t j, const Vec3& force,
                        double dt, ContactTally& tally) const {
    if (walls_still_) return 0.0;
    double work = 0.0;
    if (s.kind[j] == Kind::wall) work += dot(force, s.v[j]) * dt;
    if (s.kind[i] == Kind::wall) work -= dot(force, s.v[i]) * dt;
    tally.wall_work += work;
    return work;
  }

  static void book(const ContactResult& r, ContactTally& tally) {
    tally.elastic += r.elastic;
    tally.dissipated += r.dissipated;
    tally.relaxation += r.relaxation;
    tally.touching += r.touching ? 1 : 0;
  }

  // Calls touching(i, j, p, d, r2, a_i, a_j) for every listed pair p = (i, j) that overlaps
  // (d = x_i - x_j, r2 = |d|^2), in list order, and ends the contacts that have come apart: the
  // energy their springs still hold is lost. Chunk by chunk: first the overlap test of every
  // pair (overlap_scan.hpp), then the contact law on the pairs that passed. The near pairs,
  // where they hold, stand for the list (the same pairs touch, in the same order).
  template <class Touching>
  YUXI_ALWAYS_INLINE void sweep(const ParticleView& s, const NeighborList& list,
                                ContactTally& tally, Touching&& touching) {
    static_assert(ContactHistory<State>::none == no_slot);
    const Vec3* x = s.x;
    const double* radius = s.radius;
    const std::uint32_t* partners = list.partners.data();
    const std::uint32_t* rows = list.rows.data();
    constexpr std::uint32_t chunk = 256;
    std::uint32_t touching_pairs[chunk], parted_pairs[chunk];
    // The pairs scanned: an index list (the near pairs, or the ghost pairs) or the whole list,
    // from `first` to `last`, passing over partners at or above `partner_limit`.
    const std::uint32_t* index = near_ ? near_->pairs.data() : nullptr;
    std::uint32_t first = 0,
                  last = static_cast<std::uint32_t>(near_ ? near_->pairs.size() : list.n_pairs());
    std::uint32_t partner_limit = every_partner;
    if (set_ == PairSet::ghost) {
      if (near_)
        last = near_->n_ghost;
      else
        index = list.ghost_pairs.data(), last = static_cast<std::uint32_t>(list.ghost_pairs.size());
    } else if (set_ == PairSet::owned) {
      if (near_)
        first = near_->n_ghost;
      else
        partner_limit = list.owned_partner_limit();
    }
    for (std::uint32_t begin = first; begin < last; begin += chunk) {
      const std::uint32_t end = std::min(begin + chunk, last);
      const std::uint32_t* slot = history.pair_slot.data();
      const OverlapScanCounts found =
          index ? scan_overlaps(x, radius, rows, partners, slot, index, begin, end, touching_pairs,
                                parted_pairs)
                : scan_overlaps(x, radius, rows, partners, slot, begin, end, partner_limit,
                                touching_pairs, parted_pairs);
      for (std::uint32_t k = 0; k < found.parted; ++k) {
        const std::uint32_t p = parted_pairs[k];
        tally.dissipated += Model::release(
            law_.coeffs(s.material[rows[p]], s.material[partners[p]]), history.state_of(p));
        history.close(p);
      }
      for (std::uint32_t k = 0; k < found.touching; ++k) {
        const std::uint32_t p = touching_pairs[k], i = rows[p], j = partners[p];
        const Vec3 d = x[i] - x[j];
        touching(i, j, p, d, norm2(d), radius[i], radius[j]);
      }
    }
  }

  void compute_pairs(const ParticleView& s, const NeighborList& list, double dt,
                     ContactTally& tally, ContactRecord& record) {
    sweep(s, list, tally,
          [&](std::uint32_t i, std::uint32_t j, std::uint32_t p, const Vec3& d, double r2,
              double ai, double aj) {
            State& state = history.open(p);
            const ContactGeometry g = pair_geometry(d, r2, ai, aj, s.v[i], s.v[j], s.w[i], s.w[j],
                                                    s.inv_mass[i], s.inv_mass[j], dt);
            const ContactResult r =
                Model::evaluate(g, law_.coeffs(s.material[i], s.material[j]), state);
            s.f[i] += r.force;
            s.f[j] -= r.force;
            s.torque[i] += r.torque_i;
            s.torque[j] += r.torque_j;
            book(r, tally);
            record.keep_pair(p, r.force, r.elastic, r.dissipated, r.relaxation,
                             book_wall_work(s, i, j, r.force, dt, tally));
            track_overlap(g.overlap, std::min(ai, aj), i, tally);
          });
  }

  // The model's SIMD lanes and, for each lane, the pair it holds.
  using Lanes = typename BatchLanes<Model>::type;
  struct Batch {
    Lanes lanes;
    std::uint32_t row[Lanes::capacity];
    std::uint32_t partner[Lanes::capacity];
    std::uint32_t pair[Lanes::capacity];
  };

  // A batch where the model has lanes and they take the law (else null).
  static std::unique_ptr<Batch> make_batch(const ContactLaw<Model>& law) {
    if constexpr (BatchedModel<Model>) {
      auto b = std::make_unique<Batch>();
      if (!b->lanes.prepare(law.coeffs)) return nullptr;
      return b;
    } else {
      return nullptr;
    }
  }

  void compute_pairs_in_batches(const ParticleView& s, const NeighborList& list, double dt,
                                ContactTally& tally, ContactRecord& record) {
    if (batch_->lanes.uniform)
      fill_batches<true>(s, list, dt, tally, record);
    else
      fill_batches<false>(s, list, dt, tally, record);
  }

  template <bool uniform>
  void fill_batches(const ParticleView& s, const NeighborList& list, double dt, ContactTally& tally,
                    ContactRecord& record) {
    Batch& b = *batch_;
    Lanes& lanes = b.lanes;
    lanes.size = 0;
    sweep(s, list, tally,
          [&](std::uint32_t i, std::uint32_t j, std::uint32_t p, const Vec3& d, double, double ai,
              double aj) {
            const std::size_t k = lanes.size++;
            lanes.set_contact(k, d, ai, aj, s.v[i] - s.v[j], s.w[i], s.w[j],
                              s.inv_mass[i] + s.inv_mass[j], history.open(p));
            if constexpr (!uniform) lanes.set_coeffs(k, law_.coeffs(s.material[i], s.material[j]));
            b.row[k] = i, b.partner[k] = j, b.pair[k] = p;
            if (lanes.full()) flush(s, dt, tally, record);
          });
    flush(s, dt, tally, record);
  }

  // Evaluates the batch and adds its forces, torques and energies, contact by contact in list
  // order (so the sums are those of the one-by-one loop).
  void flush(const ParticleView& s, double dt, ContactTally& tally, ContactRecord& record) {
    Batch& b = *batch_;
    Lanes& lanes = b.lanes;
    lanes.evaluate(dt);
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
      record.keep_pair(p, force, lanes.elastic[k], lanes.dissipated[k], 0.0,
                       book_wall_work(s, i, j, force, dt, tally));
      track_overlap(lanes.overlap[k], std::min(lanes.a_i[k], lanes.a_j[k]), i, tally);
      lanes.save_state(k, history.state_of(p));
    }
    lanes.size = 0;
  }

  void compute_planes(const ParticleView& s, const NeighborList& list,
                      const std::vector<PlaneWall>& planes, double t, double dt,
                      ContactTally& tally, ContactRecord& record) {
    plane_loads.assign(planes.size(), WallLoad{});
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
      const ContactGeometry g = against_wall(s, i, wall.normal, dist, v_wall, dt);
      const ContactResult r = Model::evaluate(g, law_.coeffs(s.material[i], wall.material), state);
      s.f[i] += r.force;
      s.torque[i] += r.torque_i;
      book(r, tally);
      const double work = dot(r.force, v_wall) * dt;
      record.keep_plane(k, r.force, r.elastic, r.dissipated, r.relaxation, work);
      tally.wall_work += work;
      WallLoad& load = plane_loads[plane_index];
      load.force -= r.force;
      load.work += work;
      ++load.contacts;
      track_overlap(g.overlap, ai, i, tally);
    }
  }

  ContactLaw<Model> law_;
  std::vector<FeatureTouch> scratch_; // a mesh's candidate touches of one grain
  std::vector<std::uint32_t> order_;
  std::vector<Vec3> torque_points_;       // each shaped wall's, for the step being computed
  std::vector<std::uint8_t> wall_active_; // 1 for each shaped wall active in that step
  // The wall contacts in the batch, and the energies of wall contacts released while it filled,
  // each with the lane it came before.
  QueuedWall queued_walls_[Lanes::capacity];
  std::vector<std::pair<std::size_t, double>> batch_releases_;
  std::unique_ptr<Batch> batch_;    // null where the law needs the one-by-one loop
  bool walls_still_ = false;        // of the step being computed
  PairSet set_ = PairSet::all;      // of the call being computed
  const NearPairs* near_ = nullptr; // the near pairs scanned this step, if they hold
};

} // namespace yuxi
