#include "sim/simulation.hpp"

#include "analysis/grain_energy.hpp"
#include "core/archive.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

namespace yuxi {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Largest centre distance at which two listed particles can touch: grain-grain or grain-wall
// (wall-wall pairs are never listed).
double contact_reach(const ParticleStore& s) {
  double grain = 0.0, wall = 0.0;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    double& largest = s.is_grain(i) ? grain : wall;
    largest = std::max(largest, s.radius[i]);
  }
  return std::max(2.0 * grain, grain + wall);
}

// Flat walls standing on the faces of Boundary::wall axes, normals pointing inwards.
void add_box_walls(const SimulationConfig& c, std::vector<PlaneWall>& planes) {
  for (int a = 0; a < 3; ++a) {
    if (c.box.boundary[a] != Boundary::wall) continue;
    PlaneWall lo, hi;
    lo.point = c.box.lo;
    hi.point = c.box.hi;
    lo.normal = Vec3{};
    hi.normal = Vec3{};
    lo.normal[a] = 1.0;
    hi.normal[a] = -1.0;
    lo.material = hi.material = c.box_wall_material;
    planes.push_back(lo);
    planes.push_back(hi);
  }
}

// Lengths of the region the particles occupy (the whole box along periodic axes), for the
// choice of the rank layout: a tall box over a shallow bed is cut across the bed, not through
// it (every rank holds every particle when the simulation is built).
Vec3 occupied_lengths(const Box& box, const ParticleStore& s) {
  if (s.n_owned() == 0) return {};
  Vec3 lo = s.x[0], hi = s.x[0];
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], s.x[i][a] - s.radius[i]);
      hi[a] = std::max(hi[a], s.x[i][a] + s.radius[i]);
    }
  Vec3 lengths;
  for (int a = 0; a < 3; ++a)
    lengths[a] = box.periodic(a) ? box.length(a) : std::min(box.length(a), hi[a] - lo[a]);
  return lengths;
}

double cell_edge_for(SimulationConfig& c, const ParticleStore& s) {
  const double reach = contact_reach(s);
  if (c.cell_size > 0.0) {
    if (c.cell_size < reach)
      throw std::invalid_argument(fmt::format(
          "cell size {} is smaller than the largest contact distance {} (largest pair of radii)",
          c.cell_size, reach));
    c.skin = std::min(c.skin, c.cell_size - reach);
  }
  if (c.skin < 0.0) throw std::invalid_argument("skin must not be negative");
  const double edge = std::max(c.cell_size, reach + c.skin);
  return edge > 0.0 ? edge : 1.0;
}

} // namespace

Simulation::Simulation(SimulationConfig config, ParticleStore particles,
                       std::vector<PlaneWall> planes, std::vector<WallMotion> motions,
                       AnyContactLaw law, Comm comm)
    : config_(std::move(config)), comm_(comm),
      decomp_(config_.box, comm_, config_.ranks, occupied_lengths(config_.box, particles)),
      store_(std::move(particles)), planes_(std::move(planes)), motions_(std::move(motions)),
      law_(std::move(law)),
      forces_(std::visit([](const auto& l) -> Forces { return ContactForces(l); }, law_)),
      cell_edge_(cell_edge_for(config_, store_)), grid_(config_.box, cell_edge_) {
  if (!(config_.dt > 0.0)) throw std::invalid_argument("time step must be positive");
  if (motions_.empty()) motions_.push_back(StaticMotion{});
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    if (store_.motion[i] >= motions_.size())
      throw std::invalid_argument(fmt::format("particle {} refers to wall motion {} of {}",
                                              store_.gid[i], store_.motion[i], motions_.size()));
  add_box_walls(config_, planes_);
  range_ = config_.skin;
  // Positions are rounded at every step: a bound of a few units in the last place of the
  // largest coordinate a particle in the box can have, for each step's displacement.
  for (int a = 0; a < 3; ++a)
    position_round_off_ =
        std::max({position_round_off_, std::abs(config_.box.lo[a]), std::abs(config_.box.hi[a])});
  position_round_off_ *= 8.0 * std::numeric_limits<double>::epsilon();
  decomp_.set_min_slab(cell_edge_);
  if (comm_.size() > 1) {
    // Every rank holds every particle here: cut by particle count (unless balancing is off),
    // keep this sub-domain's.
    if (config_.rebalance_every > 0)
      decomp_.balance(store_.x, std::vector<double>(store_.n_owned(), 1.0), comm_);
    std::vector<std::size_t> elsewhere;
    for (std::size_t i = 0; i < store_.n_owned(); ++i)
      if (!decomp_.owns(config_.box.wrap(store_.x[i]))) elsewhere.push_back(i);
    store_.remove_owned(elsewhere);
    grid_ = CellGrid(decomp_.local_box(), cell_edge_);
  }
  refresh();
  initial_balance_ = energies().balance();
}

void Simulation::refresh() {
  place_walls(time_, true);
  rebuild();
  start_forces_from_gravity();
  compute_forces(false);
  stop_if_unhealthy();
}

std::size_t Simulation::n_grains() const {
  std::int64_t n = 0;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) n += store_.is_grain(i) ? 1 : 0;
  return static_cast<std::size_t>(comm_.sum(n));
}

bool Simulation::place_walls(double t, bool every_one, double* moved2) {
  const double limit2 = 0.25 * config_.skin * config_.skin;
  bool moved_far = false;
  std::vector<WallMotionAtTime> now;
  std::vector<std::uint8_t> skip; // particles of a motion at rest are already in place
  now.reserve(motions_.size());
  walls_still_ = true;
  for (const WallMotion& m : motions_) {
    now.push_back(at_time(m, t));
    walls_still_ = walls_still_ && at_rest(now.back());
    skip.push_back(!every_one && at_rest(now.back()) ? 1 : 0);
  }
  // Motions only start (never stop), and refresh() places every wall particle: while all are
  // at rest, every wall particle stands with zero velocity, and none needs placing again.
  if (walls_still_ && !every_one) return false; // (frozen bases, a basin before its start)
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    if (store_.is_grain(i) || skip[store_.motion[i]]) continue;
    const PlacedState p = place(now[store_.motion[i]], store_.x_rest[i]);
    if (moved2) *moved2 = std::max(*moved2, norm2(p.position - store_.x[i]));
    store_.x[i] = p.position;
    store_.v[i] = p.velocity;
    if (!(norm2(p.position - store_.x_build[i]) <= limit2)) moved_far = true;
  }
  return moved_far;
}

void Simulation::step() {
  const double dt = config_.dt;
  auto t0 = Clock::now();
  // 1. Half kick and drift of the grains; walls to their prescribed place at t + dt.
  const double limit2 = 0.25 * config_.skin * config_.skin;
  bool must_rebuild = rebuild_requested_;
  rebuild_requested_ = false;
  const std::size_t n = store_.n_owned();
  const Vec3 g_periodic = periodic_gravity();
  double gravity_work = 0.0;
  // The forces of the last step are spent here, so the same pass starts the new ones from
  // gravity (one sweep over the particles instead of two).
  const Vec3 gravity = config_.gravity;
  double moved2 = 0.0; // largest squared displacement of a particle in this step
  {
    // Raw pointers: the compiler need not reload each array's address after every store.
    const double* inv_mass = store_.inv_mass.data();
    const double* inv_inertia = store_.inv_inertia.data();
    const double* mass = store_.mass.data();
    const Vec3* x_build = store_.x_build.data();
    Vec3* x = store_.x.data();
    Vec3* v = store_.v.data();
    Vec3* w = store_.w.data();
    Vec3* f = store_.f.data();
    Vec3* torque = store_.torque.data();
    bool moved_far = false;
    // Grains, then wall particles (the order of rebuild()); walls keep no force.
    for (std::size_t i = owned_grains_; i < n; ++i) {
      f[i] = Vec3{};
      torque[i] = Vec3{};
    }
    // Component by component (the arithmetic of the Vec3 operators, in their order): the
    // compiler keeps every value in a register, where Vec3 temporaries went through the stack.
    const double half_dt = 0.5 * dt;
    double fastest2 = 0.0; // largest |v|^2 of a grain this step
    for (std::size_t i = 0; i < owned_grains_; ++i) {
      const double kick = half_dt * inv_mass[i], spin = half_dt * inv_inertia[i], m = mass[i];
      const double vx = v[i].x + f[i].x * kick, vy = v[i].y + f[i].y * kick,
                   vz = v[i].z + f[i].z * kick;
      const double xx = x[i].x + vx * dt, xy = x[i].y + vy * dt, xz = x[i].z + vz * dt;
      fastest2 = std::max(fastest2, vx * vx + vy * vy + vz * vz);
      v[i].x = vx, v[i].y = vy, v[i].z = vz;
      w[i].x += torque[i].x * spin, w[i].y += torque[i].y * spin, w[i].z += torque[i].z * spin;
      x[i].x = xx, x[i].y = xy, x[i].z = xz;
      // m g_p . dx
      gravity_work += m * (g_periodic.x * vx + g_periodic.y * vy + g_periodic.z * vz) * dt;
      const double dx = xx - x_build[i].x, dy = xy - x_build[i].y, dz = xz - x_build[i].z;
      moved_far |= !(dx * dx + dy * dy + dz * dz <= limit2); // NaN too
      f[i].x = gravity.x * m, f[i].y = gravity.y * m, f[i].z = gravity.z * m;
      torque[i].x = 0.0, torque[i].y = 0.0, torque[i].z = 0.0;
    }
    must_rebuild = must_rebuild || moved_far;
    moved2 = fastest2 * dt * dt;
  }
  gravity_work_ += gravity_work;
  time_ += dt;
  ++step_;
  if (place_walls(time_, false, &moved2)) must_rebuild = true;
  timers_.integrate += seconds_since(t0);
  t0 = Clock::now();
  // One collective answers three questions: must any rank rebuild, did the last force
  // evaluation on any rank find an overlap beyond the limit (check_health), and how far did a
  // particle move (for the near pairs)? The second stops the run here, one drift after the
  // step that found it, with that step's diagnosis.
  double flags[3] = {must_rebuild ? 1.0 : 0.0, health_error_.empty() ? 0.0 : 1.0, moved2};
  comm_.max(flags, 3);
  if (flags[1] > 0) stop_together(health_error_);
  settle_energy_books(); // (right after the collective above: no rank waits again)
  timers_.comm += seconds_since(t0);
  must_rebuild = flags[0] > 0;
  // The bound on every particle's displacement since the near pairs were picked, with room for
  // the round-off of positions.
  last_displacement_ = std::sqrt(flags[2]);
  near_.moved += last_displacement_ + position_round_off_;

  // 2. Neighbour list or ghost refresh.
  t0 = Clock::now();
  if (must_rebuild) {
    rebuild();
    timers_.neighbor += seconds_since(t0);
  } else {
    halo_.forward(store_, comm_);
    timers_.comm += seconds_since(t0);
  }

  // 3. Forces.
  compute_forces();

  // 4. Second half kick (of the particles owned now: a rebuild may have moved some away).
  t0 = Clock::now();
  {
    // The pointers are taken again: a rebuild may have moved the arrays.
    const double* inv_mass = store_.inv_mass.data();
    const double* inv_inertia = store_.inv_inertia.data();
    const Vec3* f = store_.f.data();
    const Vec3* torque = store_.torque.data();
    Vec3* v = store_.v.data();
    Vec3* w = store_.w.data();
    const double half_dt = 0.5 * dt;
    for (std::size_t i = 0; i < owned_grains_; ++i) { // (component by component, as above)
      const double kick = half_dt * inv_mass[i], spin = half_dt * inv_inertia[i];
      v[i].x += f[i].x * kick, v[i].y += f[i].y * kick, v[i].z += f[i].z * kick;
      w[i].x += torque[i].x * spin, w[i].y += torque[i].y * spin, w[i].z += torque[i].z * spin;
    }
  }
  timers_.integrate += seconds_since(t0);
  dissipated_ += tally_.dissipated;
  wall_work_ += tally_.wall_work;
}

void Simulation::validate_loaded_particles() const {
  // The checksum guards against damage; this guards the engine against a checkpoint that is
  // intact but does not belong to this scene (or was crafted): nothing loaded may index out of
  // range or start the run with impossible values.
  const std::size_t n_materials =
      std::visit([](const auto& f) { return f.law().coeffs.n_materials(); }, forces_);
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const bool ok = (store_.kind[i] == Kind::grain || store_.kind[i] == Kind::wall) &&
                    store_.material[i] < n_materials && store_.motion[i] < motions_.size() &&
                    store_.radius[i] > 0 && store_.mass[i] > 0 && std::isfinite(store_.radius[i]) &&
                    std::isfinite(store_.mass[i]) && is_finite(store_.x[i]) &&
                    is_finite(store_.v[i]) && is_finite(store_.w[i]) &&
                    std::isfinite(store_.inv_mass[i]) && std::isfinite(store_.inv_inertia[i]);
    if (!ok)
      throw std::invalid_argument(fmt::format(
          "particle {} of the checkpoint is invalid for this scene (kind, material, motion, "
          "radius, mass or a non-finite value)",
          i));
  }
  // The scalar state: finite energies and times, counts a run can have.
  const double scalars[] = {time_,         dissipated_,      wall_work_,     removed_energy_,
                            gravity_work_, initial_balance_, tally_.elastic, tally_.relaxation};
  for (double x : scalars)
    if (!std::isfinite(x)) throw std::invalid_argument("the checkpoint holds a non-finite energy");
  constexpr std::size_t limit = std::size_t{1} << 48;
  if (step_ < 0 || rebuilds_ < 0 || escaped_ > limit || tally_.touching > limit)
    throw std::invalid_argument("the checkpoint holds an impossible step or count");
  if (store_.radius.empty() ? false : contact_reach(store_) > grid_.edge().x + 1e-12)
    throw std::invalid_argument("the checkpoint's particles are larger than this scene's cells");
}

void Simulation::load(const std::vector<std::string>& share, std::uint64_t written_on) {
  const bool own = written_on == static_cast<std::uint64_t>(comm_.size());
  // Every rank learns whether every other loaded its share before any takes a collective step.
  std::string error;
  try {
    if (written_on == 0) throw ArchiveError("no rank's state in the file");
    if (own && share.size() != 1) throw ArchiveError("no state for this rank in the file");
    if (own)
      load_own_section(share.front());
    else
      merge_sections(share);
    validate_loaded_particles();
  } catch (const ArchiveError& e) {
    error = e.what();
  } catch (const std::length_error&) {
    error = "a size field is impossible (corrupt)";
  } catch (const std::invalid_argument& e) { // the loaded particles do not fit the scene
    error = e.what();
  }
  loading_ = Loading::whole;
  error = comm_.first_error(error);
  if (!error.empty()) throw std::invalid_argument(error);
  if (own) {
    rebuild_after_load();
    return;
  }
  // The run's scalars, the same in every section, from the ranks that loaded one (a rank's
  // share may be empty), and the books summed over the sections, onto rank 0.
  const bool loaded = !share.empty();
  double scalars[] = {loaded ? time_ : -HUGE_VAL, loaded ? static_cast<double>(step_) : -HUGE_VAL,
                      loaded ? static_cast<double>(rebuilds_) : -HUGE_VAL,
                      loaded ? initial_balance_ : -HUGE_VAL};
  comm_.max(scalars, 4);
  time_ = scalars[0];
  step_ = static_cast<std::int64_t>(scalars[1]);
  rebuilds_ = static_cast<std::int64_t>(scalars[2]);
  initial_balance_ = scalars[3];
  double books[] = {dissipated_,
                    wall_work_,
                    removed_energy_,
                    gravity_work_,
                    static_cast<double>(escaped_),
                    tally_.elastic,
                    tally_.relaxation,
                    static_cast<double>(tally_.touching)};
  comm_.sum(books, 8);
  const bool root = comm_.root();
  dissipated_ = root ? books[0] : 0;
  wall_work_ = root ? books[1] : 0;
  removed_energy_ = root ? books[2] : 0;
  gravity_work_ = root ? books[3] : 0;
  escaped_ = root ? static_cast<std::size_t>(books[4]) : 0;
  tally_ = ContactTally{};
  if (root) {
    tally_.elastic = books[5];
    tally_.relaxation = books[6];
    tally_.touching = static_cast<std::size_t>(books[7]);
  }
  // This run's own decomposition, cut by particle count; the rebuild's migration then takes
  // every particle to its owner.
  cuts_moved_ = true;
  if (comm_.size() > 1)
    decomp_.balance(
        std::vector<Vec3>(store_.x.begin(),
                          store_.x.begin() + static_cast<std::ptrdiff_t>(store_.n_owned())),
        std::vector<double>(store_.n_owned(), 1.0), comm_);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
  rebuild_after_load();
}

void Simulation::load_own_section(const std::string& section) {
  loading_ = Loading::deferred;
  ArchiveReader ar(section);
  checkpoint(ar);
  if (!ar.at_end()) throw ArchiveError("unread data after the state");
}

void Simulation::merge_sections(const std::vector<std::string>& share) {
  ParticleStore pool;
  std::string states;
  double books[5] = {0, 0, 0, 0, 0}; // dissipated, wall work, removed, gravity work, escaped
  ContactTally tally;
  double time = 0, initial_balance = 0;
  std::int64_t step = 0, rebuilds = 0;
  loading_ = Loading::merged;
  for (std::size_t k = 0; k < share.size(); ++k) {
    ArchiveReader ar(share[k]);
    checkpoint(ar);
    if (!ar.at_end()) throw ArchiveError("unread data after a section");
    if (k == 0)
      time = time_, step = step_, rebuilds = rebuilds_, initial_balance = initial_balance_;
    for (std::size_t i = 0; i < store_.n_owned(); ++i) pool.append_copy(store_, i);
    std::visit([&](auto& f) { states += f.history.stashed_bytes(); }, forces_);
    books[0] += dissipated_, books[1] += wall_work_, books[2] += removed_energy_;
    books[3] += gravity_work_, books[4] += static_cast<double>(escaped_);
    tally.elastic += tally_.elastic;
    tally.relaxation += tally_.relaxation;
    tally.touching += tally_.touching;
  }
  store_ = std::move(pool);
  std::visit([&](auto& f) { f.history.give(states); }, forces_);
  time_ = time, step_ = step, rebuilds_ = rebuilds, initial_balance_ = initial_balance;
  dissipated_ = books[0], wall_work_ = books[1], removed_energy_ = books[2];
  gravity_work_ = books[3], escaped_ = static_cast<std::size_t>(books[4]);
  tally_ = tally;
}

void Simulation::rebuild_after_load() {
  // The stored particles are sorted and wrapped as at the rebuild before the checkpoint, so
  // this rebuild reproduces that list; the history comes from the checkpoint's stash.
  const auto counted = rebuilds_;
  rebuild(true);
  rebuilds_ = counted;
}

void Simulation::rebuild(bool after_load) {
  auto t0 = Clock::now(); // (the spans without exchanges go into timers_.neighbor_local)
  if (!after_load) std::visit([&](auto& f) { f.history.stash(store_, list_); }, forces_);
  timers_.neighbor_local += seconds_since(t0);
  // Rebalance by measured cost at the first rebuild after the start (the start could only
  // count particles), then every rebalance_every rebuilds.
  if (!after_load && comm_.size() > 1 && config_.rebalance_every > 0 &&
      (rebuilds_ == 1 || (rebuilds_ > 0 && rebuilds_ % config_.rebalance_every == 0)))
    rebalance();
  handle_escapes();
  // Wrap grains into the periodic box along axes that one rank spans; across ranks the
  // migration shifts them.
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i)) continue;
    Vec3 wrapped = config_.box.wrap(store_.x[i]);
    for (int a = 0; a < 3; ++a)
      if (decomp_.dims()[a] > 1) wrapped[a] = store_.x[i][a];
    store_.x[i] = wrapped;
  }
  if (comm_.size() > 1) migrate();
  t0 = Clock::now();
  // Sort owned particles by cell so that neighbours sit close in memory: the grains first,
  // then the wall particles (so the integration runs over the grains alone, with no test of
  // the kind, which alternates unpredictably along cells that hold both).
  {
    const std::size_t n = store_.n_owned(), cells = grid_.n_cells();
    std::vector<std::uint32_t> key(n), count(2 * cells + 1, 0), order(n);
    for (std::size_t i = 0; i < n; ++i) {
      key[i] = static_cast<std::uint32_t>(grid_.cell_index(store_.x[i]) +
                                          (store_.is_grain(i) ? 0 : cells));
      ++count[key[i] + 1];
    }
    for (std::size_t c = 0; c < 2 * cells; ++c) count[c + 1] += count[c];
    owned_grains_ = count[cells];
    for (std::size_t i = 0; i < n; ++i) order[count[key[i]]++] = static_cast<std::uint32_t>(i);
    store_.permute_owned(order);
  }
  timers_.neighbor_local += seconds_since(t0);
  // Ghosts, each with copies of the contact states it may be needed for on its receiver.
  std::visit(
      [&](auto& f) {
        f.history.prepare_ghost_copies(store_);
        const GhostPayload copies{
            [&](std::span<const std::uint32_t> sent) { return f.history.ghost_copies(sent); },
            [&](std::uint32_t first, const std::string& bytes) {
              f.history.ghost_copies_arrived(store_, first, bytes);
            }};
        halo_.build(store_, decomp_, comm_, cell_edge_, &copies);
      },
      forces_);
  t0 = Clock::now();
  store_.trim_capacity();
  grid_.bin(store_.x);
  build_neighbor_list(store_, grid_, range_, list_);
  // Where forces on ghosts go back to another rank, the pairs with a ghost come first
  // (compute_forces()).
  list_.index_ghost_pairs(halo_.sends_to_other_ranks());
  near_.picked = false; // (they index the old list)
  list_.planes.clear();
  for (std::uint32_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i)) continue;
    for (std::uint32_t p = 0; p < planes_.size(); ++p)
      if (planes_[p].distance_at_rest(store_.x[i]) <
          store_.radius[i] + range_ + planes_[p].max_excursion())
        list_.planes.push_back({i, p});
  }
  std::visit([&](auto& f) { f.history.restore(store_, list_); }, forces_);
  for (std::size_t i = 0; i < store_.n_owned(); ++i) store_.x_build[i] = store_.x[i];
  timers_.neighbor_local += seconds_since(t0);
  ++rebuilds_;
  // The energy books of this state are summed over the ranks and checked at the next step's
  // collective: a collective here would make every rank wait for the slowest list build, and
  // again at that step for the slowest pairs, where one wait covers both.
  if (step_ > 0) books_due_ = energy_parts();
}

void Simulation::migrate() {
  // Particles go to the rank that owns their place now, each with copies of the states of its
  // contacts (contact_history.hpp: the rank that computes a pair after the rebuild may be
  // either partner's); repeated until every rank holds only its own (one round unless the cut
  // planes have just moved).
  for (int round = 0; round < 64; ++round) {
    std::visit(
        [&](auto& f) {
          Halo::migrate(
              store_, decomp_, comm_,
              [&](const std::vector<std::size_t>& leaving) {
                std::vector<GlobalId> gids(leaving.size());
                for (std::size_t k = 0; k < leaving.size(); ++k) gids[k] = store_.gid[leaving[k]];
                return f.history.copies_for(gids);
              },
              [&](std::size_t, const std::string& bytes) { f.history.give(bytes); });
        },
        forces_);
    // Between list builds nothing moves more than half the skin, less than any sub-domain is
    // wide: one hop per axis takes every particle to its owner unless the cut planes moved.
    if (!cuts_moved_) break;
    bool stray = false;
    for (std::size_t i = 0; i < store_.n_owned() && !stray; ++i) stray = !decomp_.owns(store_.x[i]);
    if (!comm_.any(stray)) break;
  }
  cuts_moved_ = false;
}

void Simulation::rebalance() {
  // Cost of a particle: itself plus the pairs in its neighbour-list row.
  std::vector<double> cost(store_.n_owned(), 1.0);
  for (std::size_t i = 0; i + 1 < list_.offsets.size() && i < cost.size(); ++i)
    cost[i] += list_.offsets[i + 1] - list_.offsets[i];
  // By time: this rank's costs scaled to sum to the seconds it computed (pairs, its own part
  // of the list builds, integration: PhaseTimes::busy) since the last balancing. The cuts then
  // give each rank the share it computes in equal time, as measured on its own particles: the
  // next balancing corrects what that leaves wrong for the particles that move.
  const double busy = timers_.busy();
  if (config_.balance_by == BalanceBy::time) {
    double counted = 0.0;
    for (double c : cost) counted += c;
    const double seconds = busy - busy_at_balance_;
    if (!comm_.any(!(seconds > 0.0)) && counted > 0.0) // (every rank has timed some work)
      for (double& c : cost) c *= seconds / counted;
  }
  busy_at_balance_ = busy;
  cuts_moved_ = true;
  decomp_.balance(
      std::vector<Vec3>(store_.x.begin(),
                        store_.x.begin() + static_cast<std::ptrdiff_t>(store_.n_owned())),
      cost, comm_);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
}

void Simulation::stop_together(const std::string& local_error) const {
  const std::string error = comm_.first_error(local_error);
  if (!error.empty()) throw SimulationError(error);
}

double Simulation::imbalance() const {
  return comm_.max_over_mean(static_cast<double>(store_.n_owned()));
}

std::size_t Simulation::memory_bytes() const {
  const std::size_t history =
      std::visit([](const auto& f) { return f.history.memory_bytes(); }, forces_);
  return store_.memory_bytes() + grid_.memory_bytes() + list_.memory_bytes() +
         near_.memory_bytes() + history;
}

std::vector<double> Simulation::particle_elastic_energy() const {
  if (!record_.enabled) throw std::logic_error("particle_elastic_energy needs contact recording");
  std::vector<analysis::ContactEnergy> contacts;
  contacts.reserve(list_.n_pairs() + list_.planes.size());
  for (std::uint32_t i = 0; i + 1 < list_.offsets.size(); ++i)
    for (std::uint32_t p = list_.offsets[i]; p < list_.offsets[i + 1]; ++p)
      if (record_.pair_elastic[p] != 0.0)
        contacts.push_back({i, list_.partners[p], record_.pair_elastic[p]});
  for (std::size_t k = 0; k < list_.planes.size(); ++k)
    if (record_.plane_elastic[k] != 0.0)
      contacts.push_back(
          {list_.planes[k].particle, analysis::wall_partner, record_.plane_elastic[k]});
  // Pairs with a ghost were computed here once; the ghost's half goes back to its owner.
  std::vector<double> e = analysis::grain_elastic_energy(store_.size(), contacts);
  halo_.reverse_sum(e, comm_);
  e.resize(store_.n_owned());
  return e;
}

ParticleStore Simulation::gather_particles() const {
  ArchiveWriter out;
  ParticleStore mine = store_; // owned only, for the archive
  mine.clear_ghosts();
  mine.checkpoint(out);
  const auto parts = comm_.gather(out.data());
  ParticleStore all;
  if (!comm_.root()) return all;
  std::vector<ParticleStore> stores(parts.size());
  std::vector<std::pair<GlobalId, std::pair<std::size_t, std::size_t>>> order;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    ArchiveReader in(parts[r]);
    stores[r].checkpoint(in);
    for (std::size_t i = 0; i < stores[r].n_owned(); ++i)
      order.push_back({stores[r].gid[i], {r, i}});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [gid, where] : order) all.append_copy(stores[where.first], where.second);
  return all;
}

void Simulation::settle_energy_books() {
  if (!books_due_) return;
  std::array<double, energy_sums> sums = *books_due_;
  books_due_.reset();
  comm_.sum(sums.data(), energy_sums);
  check_energy_books(report_of(sums));
}

void Simulation::check_energy_books(const EnergyReport& e) const {
  // The books (mechanical + dissipated + removed - wall work) stay constant up to the
  // integrator's error, about 1 % in violent runs at t_c/dt = 20. A gain of 10 % of the energy
  // in play means the integration is unstable.
  const double in_play = std::abs(initial_balance_) + e.dissipated + std::abs(e.wall_work) +
                         e.removed + std::abs(e.mechanical());
  const double gained = e.balance() - initial_balance_;
  if (!(gained <= 0.1 * in_play) && in_play > 0) {
    std::size_t fastest = 0;
    double fastest_ke = -1;
    for (std::size_t i = 0; i < store_.n_owned(); ++i)
      if (store_.is_grain(i) && store_.mass[i] * norm2(store_.v[i]) > fastest_ke) {
        fastest_ke = store_.mass[i] * norm2(store_.v[i]);
        fastest = i;
      }
    throw SimulationError(fmt::format(
        "step {}, t = {}: the energy books gained {:.4g} since the start ({:.0f} % of the energy "
        "in play): the integration is unstable, the time step is too large for the contact "
        "stiffness or the impact speed. Fastest {}; its contacts: {}",
        step_, time_, gained, 100 * gained / in_play, describe_particle(fastest),
        describe_contacts(fastest)));
  }
}

void Simulation::handle_escapes() {
  std::string error;
  try {
    handle_escapes_here();
  } catch (const SimulationError& e) {
    error = e.what();
  }
  stop_together(error);
}

void Simulation::handle_escapes_here() {
  const std::size_t n = store_.n_owned();
  std::vector<std::size_t> gone;
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_finite(store_.x[i]) || !is_finite(store_.v[i]) || !is_finite(store_.w[i]))
      throw SimulationError(fmt::format("step {}, t = {}: non-finite state of {}; its contacts: {}",
                                        step_, time_, describe_particle(i), describe_contacts(i)));
    if (!store_.is_grain(i) || config_.box.contains(store_.x[i])) continue;
    if (config_.on_escape == EscapePolicy::stop)
      throw SimulationError(fmt::format("step {}, t = {}: {} left the domain [{}, {}] x [{}, {}] "
                                        "x [{}, {}] (set on_escape = \"remove\" to drop it); its "
                                        "contacts: {}",
                                        step_, time_, describe_particle(i), config_.box.lo.x,
                                        config_.box.hi.x, config_.box.lo.y, config_.box.hi.y,
                                        config_.box.lo.z, config_.box.hi.z, describe_contacts(i)));
    gone.push_back(i);
    removed_energy_ += mechanical_energy(i);
  }
  if (gone.empty()) return;
  store_.remove_owned(gone);
  escaped_ += gone.size();
}

void Simulation::start_forces_from_gravity() {
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    store_.f[i] = store_.is_grain(i) ? store_.mass[i] * config_.gravity : Vec3{};
    store_.torque[i] = Vec3{};
  }
}

void Simulation::compute_forces(bool advance_history) {
  auto t0 = Clock::now();
  // Owned particles start from gravity (step() or start_forces_from_gravity()); ghosts
  // collect contact forces only, summed back to their owners.
  for (std::size_t i = store_.n_owned(); i < store_.size(); ++i) {
    store_.f[i] = Vec3{};
    store_.torque[i] = Vec3{};
  }
  tally_ = ContactTally{};
  const double dt = advance_history ? config_.dt : 0.0;
  refresh_near_pairs();
  const auto compute = [&](PairSet set) {
    std::visit(
        [&](auto& f) {
          f.compute(store_, list_, &near_, planes_, time_, dt, walls_still_, tally_, record_, set);
        },
        forces_);
  };
  if (list_.ghost_pairs.empty()) {
    compute(PairSet::all);
    timers_.pair += seconds_since(t0);
    t0 = Clock::now();
    halo_.reverse(store_, comm_);
  } else {
    // The pairs with a ghost first: their forces travel back to the ghosts' owners while the
    // pairs of owned particles are computed, so neither rank waits for the message unless the
    // other is later than that whole computation.
    compute(PairSet::ghost);
    timers_.pair += seconds_since(t0);
    t0 = Clock::now();
    halo_.reverse_start(store_, comm_);
    timers_.comm += seconds_since(t0);
    t0 = Clock::now();
    compute(PairSet::owned);
    timers_.pair += seconds_since(t0);
    t0 = Clock::now();
    halo_.reverse_finish(store_, comm_);
  }
  timers_.comm += seconds_since(t0);
  check_health();
}

void Simulation::refresh_near_pairs() {
  if (near_.hold()) return;
  near_.picked = false;
  // The margin leaves room for about `lasting` steps at the last step's pace (a pick costs
  // about one scan of the whole list; a dense packing has many pairs just short of touching,
  // so a wider margin keeps many more), and at most a fraction of the skin. Near pairs that
  // would last fewer than `min_steps` steps are not worth picking: the whole list is scanned.
  constexpr double lasting = 16.0, min_steps = 4.0;
  const double pace = last_displacement_ + position_round_off_;
  const double margin = std::min(config_.near_fraction * config_.skin, 2.0 * lasting * pace);
  if (!(margin > 0.0) || 2.0 * min_steps * pace >= margin) return;
  std::visit(
      [&](auto& f) {
        pick_near_pairs(store_.x.data(), store_.radius.data(), list_, f.history.pair_slot.data(),
                        margin, near_);
      },
      forces_);
}

void Simulation::check_health() {
  health_error_.clear();
  if (tally_.max_overlap_ratio > config_.max_overlap_ratio)
    health_error_ = (fmt::format(
        "step {}, t = {}: overlap of {:.3g} times the smaller radius (limit {}) at {}; the time "
        "step is too large for the contact stiffness or the impact speed",
        step_, time_, tally_.max_overlap_ratio, config_.max_overlap_ratio,
        describe_particle(tally_.worst_particle) +
            "; its contacts: " + describe_contacts(tally_.worst_particle)));
}

std::string Simulation::describe_particle(std::size_t i) const {
  const auto& s = store_;
  return fmt::format("{} {} (radius {:.4g}) at ({:.6g}, {:.6g}, {:.6g}) with velocity ({:.6g}, "
                     "{:.6g}, {:.6g}), angular velocity ({:.6g}, {:.6g}, {:.6g})",
                     s.is_grain(i) ? "grain" : "wall particle", s.gid[i], s.radius[i], s.x[i].x,
                     s.x[i].y, s.x[i].z, s.v[i].x, s.v[i].y, s.v[i].z, s.w[i].x, s.w[i].y,
                     s.w[i].z);
}

std::string Simulation::describe_contacts(std::size_t i) const {
  // A diagnosis, not a hot path: every particle that overlaps i, owned (through the nearest
  // periodic image) or a ghost from another rank, each once. The halo holds the ghosts of a
  // half shell only, so partners owned by the ranks below are not seen here.
  const auto& s = store_;
  std::map<GlobalId, std::pair<bool, double>> touching; // gid -> grain?, overlap
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (s.gid[j] == s.gid[i]) continue;
    const Vec3 d = j < s.n_owned() ? config_.box.minimum_image(s.x[i], s.x[j]) : s.x[i] - s.x[j];
    const double overlap = s.radius[i] + s.radius[j] - norm(d);
    if (overlap > 0) touching.emplace(s.gid[j], std::pair{s.is_grain(j), overlap});
  }
  std::string out;
  for (const auto& [gid, contact] : touching)
    out += fmt::format("{}{} {} (overlap {:.4g})", out.empty() ? "" : ", ",
                       contact.first ? "grain" : "wall particle", gid, contact.second);
  for (const auto& p : planes_) {
    const double overlap = s.radius[i] - p.distance(s.x[i], time_);
    if (overlap > 0)
      out += fmt::format("{}flat wall (overlap {:.4g})", out.empty() ? "" : ", ", overlap);
  }
  return out.empty() ? "none" : out;
}

EnergyReport Simulation::energies() const {
  std::array<double, energy_sums> sums = energy_parts();
  comm_.sum(sums.data(), energy_sums); // one reduction for all
  return report_of(sums);
}

std::array<double, Simulation::energy_sums> Simulation::energy_parts() const {
  const Vec3 g_potential = potential_gravity();
  double translational = 0, rotational = 0, gravitational = 0, grains = 0;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i)) continue;
    translational += 0.5 * store_.mass[i] * norm2(store_.v[i]);
    rotational += rotational_energy(i);
    gravitational -= store_.mass[i] * dot(g_potential, store_.x[i]);
    ++grains;
  }
  // The counts ride along as doubles, exact below 2^53.
  return {translational,
          rotational,
          gravitational,
          tally_.elastic,
          dissipated_,
          wall_work_,
          removed_energy_,
          grains,
          static_cast<double>(tally_.touching),
          static_cast<double>(escaped_),
          gravity_work_,
          tally_.relaxation};
}

EnergyReport Simulation::report_of(const std::array<double, energy_sums>& sums) const {
  EnergyReport e;
  e.step = step_;
  e.time = time_;
  e.gravity_work = sums[10];
  e.relaxation = sums[11];
  e.translational = sums[0], e.rotational = sums[1], e.gravitational = sums[2];
  e.elastic = sums[3], e.dissipated = sums[4], e.wall_work = sums[5], e.removed = sums[6];
  e.grains = static_cast<std::size_t>(std::llround(sums[7]));
  e.contacts = static_cast<std::size_t>(std::llround(sums[8]));
  e.escaped = static_cast<std::size_t>(std::llround(sums[9]));
  return e;
}

double Simulation::mechanical_energy(std::size_t i) const {
  return 0.5 * store_.mass[i] * norm2(store_.v[i]) + rotational_energy(i) -
         store_.mass[i] * dot(potential_gravity(), store_.x[i]);
}

double Simulation::rotational_energy(std::size_t i) const {
  // A grain whose rotation is locked (infinite inertia) keeps its spin and its energy.
  const double inv = store_.inv_inertia[i];
  return inv > 0 ? 0.5 * norm2(store_.w[i]) / inv : 0.0;
}

Vec3 Simulation::periodic_gravity() const {
  Vec3 g;
  for (int a = 0; a < 3; ++a)
    if (config_.box.periodic(a)) g[a] = config_.gravity[a];
  return g;
}

StiffestContact Simulation::stiffest_contact() const {
  // Smallest grain mass and radius per material, and which materials appear on walls.
  const std::size_t n_mat =
      std::visit([](const auto& f) { return f.law().coeffs.n_materials(); }, forces_);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> m_min(n_mat, inf), r_min(n_mat, inf);
  std::vector<bool> on_wall(n_mat, false);
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const auto k = store_.material[i];
    if (k >= n_mat) continue;
    if (store_.is_grain(i)) {
      m_min[k] = std::min(m_min[k], store_.mass[i]);
      r_min[k] = std::min(r_min[k], store_.radius[i]);
    } else {
      on_wall[k] = true;
    }
  }
  for (const auto& p : planes_)
    if (p.material < n_mat) on_wall[p.material] = true;
  for (std::size_t k = 0; k < n_mat; ++k) { // over all ranks
    m_min[k] = -comm_.max(-m_min[k]);
    r_min[k] = -comm_.max(-r_min[k]);
    on_wall[k] = comm_.any(on_wall[k]);
  }
  StiffestContact best{inf, 0, 0, 0};
  std::visit(
      [&](const auto& f) {
        using M = typename std::decay_t<decltype(f.law())>::model_type;
        const auto& table = f.law().coeffs;
        for (std::size_t a = 0; a < n_mat; ++a)
          for (std::size_t b = 0; b < n_mat; ++b) {
            if (!table.has(a, b) || m_min[a] == inf) continue;
            auto consider = [&](double m_eff, double r_eff) {
              const double tc = M::contact_time(table(a, b), m_eff, r_eff, 1.0);
              if (tc < best.contact_time)
                best = {tc, static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(b), m_eff};
            };
            if (m_min[b] < inf)
              consider(m_min[a] * m_min[b] / (m_min[a] + m_min[b]),
                       r_min[a] * r_min[b] / (r_min[a] + r_min[b]));
            if (on_wall[b]) consider(m_min[a], r_min[a]);
          }
      },
      forces_);
  return best;
}

} // namespace yuxi
