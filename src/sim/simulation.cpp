#include "sim/simulation.hpp"

#include "sim/contact_reach.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

namespace yuxi {
namespace {

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
    lo.name = fmt::format("box {} lo", "xyz"[a]);
    hi.name = fmt::format("box {} hi", "xyz"[a]);
    planes.push_back(lo);
    planes.push_back(hi);
  }
}

// Lengths of the region the particles occupy (the whole box along periodic axes), for the
// choice of the rank layout: a tall box over a shallow bed is cut across the bed, not through
// it (every rank holds every particle when the simulation is built).
Vec3 occupied_lengths(const Box& box, const ParticleStore& s) {
  if (s.n_owned() == 0) return {box.length(0), box.length(1), box.length(2)};
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
  const double reach = std::max(contact_reach(s), c.min_contact_reach);
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
                       AnyContactLaw law, Comm comm, std::vector<ShapedWall> walls)
    : config_(std::move(config)), comm_(comm),
      decomp_(config_.box, comm_, config_.ranks, occupied_lengths(config_.box, particles)),
      store_(std::move(particles)), planes_(std::move(planes)), motions_(std::move(motions)),
      walls_(std::move(walls)), wall_work_(walls_.size(), 0.0), mesh_bins_(walls_.size()),
      mesh_x_build_(walls_.size()), law_(std::move(law)),
      forces_(std::visit([](const auto& l) -> Forces { return ContactForces(l); }, law_)),
      history_(std::visit([](auto& f) -> ContactStates* { return &f.history; }, forces_)),
      n_materials_(std::visit([](const auto& l) { return l.coeffs.n_materials(); }, law_)),
      cell_edge_(cell_edge_for(config_, store_)), grid_(config_.box, cell_edge_) {
  if (!(config_.dt > 0.0)) throw std::invalid_argument("time step must be positive");
  if (motions_.empty()) motions_.push_back(StaticMotion{});
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    if (store_.motion[i] >= motions_.size())
      throw std::invalid_argument(fmt::format("particle {} refers to wall motion {} of {}",
                                              store_.gid[i], store_.motion[i], motions_.size()));
  add_box_walls(config_, planes_);
  plane_work_.assign(planes_.size(), 0.0);
  range_ = config_.skin;
  // Positions are rounded at every step: a bound of a few units in the last place of the
  // largest coordinate a particle in the box can have, for each step's displacement.
  for (int a = 0; a < 3; ++a)
    position_round_off_ =
        std::max({position_round_off_, std::abs(config_.box.lo[a]), std::abs(config_.box.hi[a])});
  position_round_off_ *= 8.0 * std::numeric_limits<double>::epsilon();
  decomp_.set_min_slab(cell_edge_);
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    next_gid_ = std::max(next_gid_, store_.gid[i] + 1);
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

bool Simulation::place_walls(double t, bool every_one, double* moved2) {
  const double limit2 = 0.25 * config_.skin * config_.skin;
  bool moved_far = place_shaped_walls(t, every_one);
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
  if (walls_still_ && !every_one) return moved_far; // (frozen bases, a basin before its start)
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
  const bool rebuild_here = kick_drift();
  exchange_or_rebuild(agree_on_rebuild(rebuild_here));
  compute_forces();
  final_kick();
  books_.dissipated += tally_.dissipated;
  books_.wall_work += tally_.wall_work;
  for (std::size_t w = 0; w < wall_loads_.size(); ++w) wall_work_[w] += wall_loads_[w].work;
  if (!planes_.empty()) {
    const auto& loads = std::visit(
        [](const auto& f) -> const std::vector<WallLoad>& { return f.plane_loads; }, forces_);
    for (std::size_t p = 0; p < loads.size() && p < plane_work_.size(); ++p)
      plane_work_[p] += loads[p].work;
  }
  steer_servo_walls();
}

bool Simulation::kick_drift() {
  PhaseTimer timer(timers_.integrate);
  const double dt = config_.dt;
  const double limit2 = 0.25 * config_.skin * config_.skin;
  bool must_rebuild = rebuild_requested_;
  rebuild_requested_ = false;
  const std::size_t n = store_.n_owned();
  const Vec3 g_periodic = periodic_gravity();
  double gravity_work = 0.0;
  // The forces of the last step are spent here, so the same pass starts the new ones from
  // gravity (one sweep over the particles instead of two).
  const Vec3 gravity = config_.gravity;
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
    moved2_ = fastest2 * dt * dt;
  }
  books_.gravity_work += gravity_work;
  time_ += dt;
  ++step_;
  if (!inserts_.empty() && insertion_due(step_)) must_rebuild = true;
  if (place_walls(time_, false, &moved2_)) must_rebuild = true;
  return must_rebuild;
}

bool Simulation::agree_on_rebuild(bool rebuild_here) {
  PhaseTimer timer(timers_.comm);
  // One collective answers three questions: must any rank rebuild, did the last force
  // evaluation on any rank find an overlap beyond the limit (check_health), and how far did a
  // particle move (for the near pairs)? The second stops the run here, one drift after the
  // step that found it, with that step's diagnosis.
  double flags[3] = {rebuild_here ? 1.0 : 0.0, health_error_.empty() ? 0.0 : 1.0, moved2_};
  comm_.max(flags, 3);
  if (flags[1] > 0) stop_together(health_error_);
  settle_energy_books(); // (right after the collective above: no rank waits again)
  // The bound on every particle's displacement since the near pairs were picked, with room for
  // the round-off of positions.
  last_displacement_ = std::sqrt(flags[2]);
  near_.moved += last_displacement_ + position_round_off_;
  return flags[0] > 0;
}

void Simulation::exchange_or_rebuild(bool rebuild_now) {
  if (rebuild_now) {
    PhaseTimer timer(timers_.neighbor);
    rebuild();
  } else {
    PhaseTimer timer(timers_.comm);
    halo_.forward(store_, comm_);
  }
}

void Simulation::final_kick() {
  // Second half kick of the particles owned now (a rebuild may have moved some away).
  PhaseTimer timer(timers_.integrate);
  // The pointers are taken again: a rebuild may have moved the arrays.
  const double* inv_mass = store_.inv_mass.data();
  const double* inv_inertia = store_.inv_inertia.data();
  const Vec3* f = store_.f.data();
  const Vec3* torque = store_.torque.data();
  Vec3* v = store_.v.data();
  Vec3* w = store_.w.data();
  const double half_dt = 0.5 * config_.dt;
  for (std::size_t i = 0; i < owned_grains_; ++i) { // (component by component, as above)
    const double kick = half_dt * inv_mass[i], spin = half_dt * inv_inertia[i];
    v[i].x += f[i].x * kick, v[i].y += f[i].y * kick, v[i].z += f[i].z * kick;
    w[i].x += torque[i].x * spin, w[i].y += torque[i].y * spin, w[i].z += torque[i].z * spin;
  }
}

void Simulation::stop_together(const std::string& local_error) const {
  const std::string error = comm_.first_error(local_error);
  if (!error.empty()) throw SimulationError(error);
}

double Simulation::imbalance() const {
  return comm_.max_over_mean(static_cast<double>(store_.n_owned()));
}

std::size_t Simulation::memory_bytes() const {
  return store_.memory_bytes() + grid_.memory_bytes() + list_.memory_bytes() +
         near_.memory_bytes() + near_walls_.memory_bytes() + history_->memory_bytes();
}

void Simulation::settle_energy_books() {
  if (!books_due_) return;
  EnergyBooks books = *books_due_;
  books_due_.reset();
  books.sum_over(comm_);
  check_energy_books(books);
}

void Simulation::check_energy_books(const EnergyBooks& e) const {
  // The books (mechanical + dissipated + removed - wall work) stay constant up to the
  // integrator's error, about 1 % in violent runs at t_c/dt = 20. A gain of 10 % of the energy
  // in play means the integration is unstable.
  const double in_play = std::abs(initial_balance_) + e.dissipated + std::abs(e.wall_work) +
                         e.removed + std::abs(e.mechanical());
  const double gained = e.balance() - initial_balance_;
  if (!(gained <= 0.1 * in_play) && in_play > 0) {
    // Energy that came with wall contacts born deep is no fault of the time step: say where.
    const DeepStarts& deep =
        std::visit([](const auto& f) -> const DeepStarts& { return f.deep_starts; }, forces_);
    const double deep_energy = comm_.sum(deep.energy), worst = comm_.max(deep.worst);
    if (deep_energy >= 0.25 * gained) {
      const std::string where = comm_.first_error(
          worst > 0 && deep.worst == worst ? describe_deep_start(deep) : std::string{});
      throw SimulationError(fmt::format(
          "step {}, t = {}: the energy books gained {:.4g} since the start ({:.0f} % of the "
          "energy in play), and {:.4g} of it came with contacts with walls that began already "
          "deep, which no time step explains: {}. A contact that begins deep makes its spring's "
          "energy from nothing: a wall that appears over grains (its active window), grains "
          "placed inside a wall, or the wall's contact rules (docs/walls.md section 2)",
          step_, time_, gained, 100 * gained / in_play, deep_energy, where));
    }
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

void Simulation::start_forces_from_gravity() {
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    store_.f[i] = store_.is_grain(i) ? store_.mass[i] * config_.gravity : Vec3{};
    store_.torque[i] = Vec3{};
  }
}

void Simulation::compute_forces(bool advance_history) {
  PhaseTimer timer(timers_.pair);
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
    timer.switch_to(timers_.comm);
    halo_.reverse(store_, comm_);
  } else {
    // The pairs with a ghost first: their forces travel back to the ghosts' owners while the
    // pairs of owned particles are computed, so neither rank waits for the message unless the
    // other is later than that whole computation.
    compute(PairSet::ghost);
    timer.switch_to(timers_.comm);
    halo_.reverse_start(store_, comm_);
    timer.switch_to(timers_.pair);
    compute(PairSet::owned);
    timer.switch_to(timers_.comm);
    halo_.reverse_finish(store_, comm_);
  }
  if (!walls_.empty()) {
    timer.switch_to(timers_.pair);
    std::visit(
        [&](auto& f) {
          f.compute_walls(store_, list_,
                          near_.hold() && near_walls_.picked ? &near_walls_ : nullptr, walls_,
                          time_, dt, tally_, wall_loads_, element_forces_, record_);
        },
        forces_);
  }
  check_health();
}

void Simulation::refresh_near_pairs() {
  if (near_.hold()) return;
  near_.picked = false;
  near_walls_.picked = false;
  // The margin leaves room for about `lasting` steps at the last step's pace (a pick costs
  // about one scan of the whole list; a dense packing has many pairs just short of touching,
  // so a wider margin keeps many more), and at most a fraction of the skin. Near pairs that
  // would last fewer than `min_steps` steps are not worth picking: the whole list is scanned.
  constexpr double lasting = 16.0, min_steps = 4.0;
  const double pace = last_displacement_ + position_round_off_;
  const double margin = std::min(config_.near_fraction * config_.skin, 2.0 * lasting * pace);
  if (!(margin > 0.0) || 2.0 * min_steps * pace >= margin) return;
  pick_near_pairs(store_.x.data(), store_.radius.data(), list_, history_->pair_slots(), margin,
                  near_);
  if (!list_.walls.empty()) pick_near_wall_elements(store_, list_, walls_, margin, near_walls_);
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

std::string Simulation::describe_deep_start(const DeepStarts& deep) const {
  const ShapedWall& wall = walls_[deep.wall];
  const std::string element =
      std::holds_alternative<MeshWall>(wall)
          ? fmt::format("triangle {}", deep.element)
          : fmt::format("patch {} (0 the side, 1 and 2 the caps)", deep.element);
  return fmt::format("the one that began with the most energy ({:.4g}) began at t = {:.6g} on wall "
                     "'{}', {}, against grain {}, overlapping it by {:.4g} where the grain had "
                     "come {:.4g} nearer the wall in the step",
                     deep.worst, deep.time, wall_name(wall), element, deep.grain, deep.overlap,
                     deep.approach);
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

EnergyBooks Simulation::energies() const {
  EnergyBooks e = energy_parts();
  e.sum_over(comm_); // one reduction for all
  return e;
}

EnergyBooks Simulation::energy_parts() const {
  const Vec3 g_potential = potential_gravity();
  EnergyBooks e = books_;
  e.step = step_;
  e.time = time_;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i)) continue;
    e.translational += 0.5 * store_.mass[i] * norm2(store_.v[i]);
    e.rotational += rotational_energy(i);
    e.gravitational -= store_.mass[i] * dot(g_potential, store_.x[i]);
    ++e.grains;
  }
  e.elastic = tally_.elastic;
  e.relaxation = tally_.relaxation;
  e.contacts = tally_.touching;
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

StiffestContact Simulation::stiffest_contact(double impact_speed) const {
  // Smallest grain mass and radius per material, and which materials appear on walls.
  const std::size_t n_mat = n_materials_;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> m_min(n_mat, inf), r_min(n_mat, inf);
  std::vector<bool> on_wall(n_mat, false);
  std::vector<double> grains(n_mat, 0.0); // (two grains of a material must exist to meet)
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const auto k = store_.material[i];
    if (k >= n_mat) continue;
    if (store_.is_grain(i)) {
      m_min[k] = std::min(m_min[k], store_.mass[i]);
      r_min[k] = std::min(r_min[k], store_.radius[i]);
      grains[k] += 1.0;
    } else {
      on_wall[k] = true;
    }
  }
  for (const auto& p : planes_)
    if (p.material < n_mat) on_wall[p.material] = true;
  for (const ShapedWall& w : walls_)
    if (wall_material(w) < n_mat) on_wall[wall_material(w)] = true;
  // The grains that inserts will pour: the smallest their size distribution gives.
  for (const InsertSpec& insert : inserts_) {
    const auto k = insert.grains.material;
    if (k >= n_mat) continue;
    const double r = insert.grains.size.smallest();
    m_min[k] = std::min(m_min[k], insert.grains.mass_of(r));
    r_min[k] = std::min(r_min[k], r);
    grains[k] += 2.0;
  }
  if (n_mat > 0) comm_.sum(grains.data(), static_cast<int>(n_mat));
  for (std::size_t k = 0; k < n_mat; ++k) { // over all ranks
    m_min[k] = -comm_.max(-m_min[k]);
    r_min[k] = -comm_.max(-r_min[k]);
    on_wall[k] = comm_.any(on_wall[k]);
  }
  StiffestContact best{inf, 0, 0, 0};
  std::visit(
      [&](const auto& law) {
        using M = typename std::decay_t<decltype(law)>::model_type;
        const auto& table = law.coeffs;
        for (std::size_t a = 0; a < n_mat; ++a)
          for (std::size_t b = 0; b < n_mat; ++b) {
            if (!table.has(a, b) || m_min[a] == inf) continue;
            auto consider = [&](double m_eff, double r_eff) {
              const double tc = M::contact_time(table(a, b), m_eff, r_eff, impact_speed);
              if (tc < best.contact_time)
                best = {tc, static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(b), m_eff,
                        M::contact_time(table(a, b), m_eff, r_eff, 2.0 * impact_speed) != tc};
            };
            if (m_min[b] < inf && (a != b || grains[a] >= 2.0))
              consider(m_min[a] * m_min[b] / (m_min[a] + m_min[b]),
                       r_min[a] * r_min[b] / (r_min[a] + r_min[b]));
            if (on_wall[b]) consider(m_min[a], r_min[a]);
          }
      },
      law_);
  return best;
}

} // namespace yuxi
