// A simulation's construction, its step phase by phase, its force evaluation and the checks
// that stop a run with a diagnosis.
#include "sim/simulation.hpp"

#include "sim/cell_sizing.hpp"
#include "sim/contact_reach.hpp"
#include "sim/particle_diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace yuxi {

Simulation::Simulation(SimulationConfig config, ParticleStore particles,
                       std::vector<PlaneWall> planes, std::vector<WallMotion> motions,
                       AnyContactLaw law, Comm comm, std::vector<ShapedWall> shaped_walls,
                       std::vector<ClumpBody> clumps)
    : config_(std::move(config)), store_(std::move(particles)),
      exchange_(config_.box, comm, config_.ranks, occupied_lengths(config_.box, store_),
                cell_edge_for(config_, contact_reach(store_))),
      search_(config_.skin, config_.box), contacts_(std::move(law), config_.backend),
      walls_(config_, std::move(planes), std::move(motions), std::move(shaped_walls)) {
  if (!(config_.dt > 0.0)) throw std::invalid_argument("time step must be positive");
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    if (store_.motion[i] >= walls_.motions().size())
      throw std::invalid_argument(fmt::format("particle {} refers to wall motion {} of {}",
                                              store_.gid[i], store_.motion[i],
                                              walls_.motions().size()));
  clumps_.set(std::move(clumps));
  clumps_.index_members(store_); // (every member there, each naming a clump that is)
  walls_.size_for(config_.skin, exchange_.cell_edge());
  for (std::size_t i = 0; i < store_.n_owned(); ++i) sources_.ids_from(store_.gid[i] + 1);
  // Every rank holds every particle here: cut by particle count (unless balancing is off),
  // keep this sub-domain's (a clump goes where its centre of mass is).
  update_clump_reach();
  if (comm.size() > 1) exchange_.take_share(store_, clumps_, config_.rebalance_every > 0);
  refresh();
  ledger_.set_initial_balance(energies().balance());
}

void Simulation::set_sources(std::vector<InsertSpec> inserts, std::vector<OutletSpec> outlets) {
  sources_.set(std::move(inserts), std::move(outlets));
  update_clump_reach();
}

bool Simulation::ghosts_reach_for_clumps() const {
  const Box& box = config_.box;
  return comm().size() > 1 || box.periodic(0) || box.periodic(1) || box.periodic(2);
}

void Simulation::check_clump_span(double span, const std::string& what) const {
  for (int a = 0; a < 3; ++a)
    if (config_.box.periodic(a) && span > config_.box.length(a))
      throw std::invalid_argument(fmt::format(
          "{} spans {:.6g} (the diameter of its bounding sphere), more than the periodic box's "
          "length along {}, {:.6g}: its members would meet their own periodic images, which the "
          "members of one clump never touch; make the box longer along {}, or the clump smaller",
          what, span, "xyz"[a], config_.box.length(a), "xyz"[a]));
}

void Simulation::update_clump_reach() {
  if (!ghosts_reach_for_clumps()) return;
  const auto [span, id] = clumps_.widest();
  const double widest = comm().max(span);
  if (widest == span && id >= 0) check_clump_span(span, fmt::format("clump {}", id));
  check_clump_span(widest, "a clump on another rank");
  for (std::size_t k = 0; k < sources_.inserts().size(); ++k)
    check_clump_span(sources_.inserts()[k].clump_span(),
                     fmt::format("a clump of [[insert]] {}", k));
  double reach = std::max(config_.clump_reach, comm().max(clumps_.reach()));
  for (const InsertSpec& insert : sources_.inserts()) reach = std::max(reach, insert.clump_reach());
  if (reach != exchange_.clump_reach()) exchange_.set_clump_reach(reach);
}

Box Simulation::member_wrap_box() const {
  Box box = config_.box;
  const auto dims = exchange_.decomposition().dims();
  for (int a = 0; a < 3; ++a)
    if (dims[a] > 1) box.boundary[a] = Boundary::open; // (the migration shifts them)
  return box;
}

void Simulation::refresh() {
  walls_.place(store_, time_, true);
  build_lists({});
  start_forces_from_gravity();
  compute_forces(false);
  stop_if_unhealthy();
}

void Simulation::step() {
  const Drift drift = kick_drift();
  exchange_or_build_lists(agree_on_list_build(drift));
  compute_forces();
  final_kick();
  book_step();
}

Simulation::Drift Simulation::kick_drift() {
  PhaseTimer timer(timers_.integrate);
  const double dt = config_.dt;
  const double limit2 = 0.25 * config_.skin * config_.skin;
  Drift drift;
  drift.list_build_due = list_build_requested_;
  list_build_requested_ = false;
  const std::size_t n = store_.n_owned();
  const Vec3 g_periodic = periodic_gravity(config_);
  double gravity_work = 0.0;
  // The forces of the last step are spent here, so the same pass starts the new ones from
  // gravity (one sweep over the particles instead of two).
  const Vec3 gravity = config_.gravity;
  {
    // The plain view (core/particle_view.hpp): a local copy of the pointers, so the compiler
    // need not reload an array's address after every store.
    const ParticleView p = store_.view();
    const double* inv_mass = p.inv_mass;
    const double* inv_inertia = p.inv_inertia;
    const double* mass = p.mass;
    const Vec3* x_build = p.x_build;
    Vec3* x = p.x;
    Vec3* v = p.v;
    Vec3* w = p.w;
    Vec3* f = p.f;
    Vec3* torque = p.torque;
    bool moved_far = false;
    // Grains, then wall particles (the order of a list build); walls keep no force.
    for (std::size_t i = n_grains_; i < n; ++i) {
      f[i] = Vec3{};
      torque[i] = Vec3{};
    }
    // Component by component (the arithmetic of the Vec3 operators, in their order): the
    // compiler keeps every value in a register, where Vec3 temporaries went through the stack.
    const double half_dt = 0.5 * dt;
    double fastest2 = 0.0; // largest |v|^2 of a grain this step
    for (std::size_t i = 0; i < n_grains_; ++i) {
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
    drift.moved2 = fastest2 * dt * dt;
    if (!clumps_.empty()) {
      clumps_.kick_drift(dt, g_periodic, gravity_work);
      // (a member's displacement, its clump's turn included)
      moved_far |= clumps_.place_members(store_, limit2, &drift.moved2);
    }
    drift.list_build_due = drift.list_build_due || moved_far;
  }
  ledger_.books().gravity_work += gravity_work;
  time_ += dt;
  ++step_;
  if (!sources_.inserts().empty() && sources_.insertion_due(step_, dt)) drift.list_build_due = true;
  if (walls_.place(store_, time_, false, &drift.moved2)) drift.list_build_due = true;
  return drift;
}

bool Simulation::agree_on_list_build(const Drift& drift) {
  PhaseTimer timer(timers_.comm);
  // One collective answers three questions: must any rank build the lists, did the last force
  // evaluation on any rank find an overlap beyond the limit (check_health), and how far did a
  // particle move (for the near pairs)? The second stops the run here, one drift after the
  // step that found it, with that step's diagnosis.
  double flags[3] = {drift.list_build_due ? 1.0 : 0.0, ledger_.health_error().empty() ? 0.0 : 1.0,
                     drift.moved2};
  comm().max(flags, 3);
  if (flags[1] > 0) stop_if_unhealthy_together();
  settle_energy_books(); // (right after the collective above: no rank waits again)
  search_.note_displacement(std::sqrt(flags[2]));
  return flags[0] > 0;
}

void Simulation::exchange_or_build_lists(bool build_now) {
  if (build_now) {
    PhaseTimer timer(timers_.neighbor);
    build_lists({});
  } else {
    PhaseTimer timer(timers_.comm);
    exchange_.forward(store_);
  }
}

void Simulation::final_kick() {
  // Second half kick of the particles owned now (a list build may have moved some away).
  PhaseTimer timer(timers_.integrate);
  // The view is taken again: a list build may have moved the arrays.
  const ParticleView p = store_.view();
  const double half_dt = 0.5 * config_.dt;
  for (std::size_t i = 0; i < n_grains_; ++i) { // (component by component, as above)
    const double kick = half_dt * p.inv_mass[i], spin = half_dt * p.inv_inertia[i];
    const Vec3 f = p.f[i], torque = p.torque[i];
    p.v[i].x += f.x * kick, p.v[i].y += f.y * kick, p.v[i].z += f.z * kick;
    p.w[i].x += torque.x * spin, p.w[i].y += torque.y * spin, p.w[i].z += torque.z * spin;
  }
  if (!clumps_.empty()) {
    clumps_.final_kick(config_.dt);
    clumps_.place_members(store_, 0.0, nullptr); // (velocities only)
  }
}

void Simulation::book_step() {
  const ContactTally& tally = contacts_.tally();
  ledger_.books().dissipated += tally.dissipated;
  ledger_.books().wall_work += tally.wall_work;
  walls_.add_work(contacts_.plane_loads());
  walls_.steer_servos(comm(), time_, config_.dt, step_);
}

void Simulation::stop_together(const std::string& local_error) const {
  const std::string error = comm().first_error(local_error);
  if (!error.empty()) throw SimulationError(error);
}

double Simulation::imbalance() const {
  return comm().max_over_mean(static_cast<double>(store_.n_owned()));
}

std::size_t Simulation::memory_bytes() const {
  return store_.memory_bytes() + exchange_.grid().memory_bytes() + search_.memory_bytes() +
         contacts_.history().memory_bytes();
}

void Simulation::start_forces_from_gravity() {
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    // (a clump's members start from none: gravity acts on the clump, gather_forces())
    store_.f[i] =
        store_.is_grain(i) && store_.body[i] < 0 ? store_.mass[i] * config_.gravity : Vec3{};
    store_.torque[i] = Vec3{};
  }
}

void Simulation::compute_forces(bool advance_history) {
  PhaseTimer timer(timers_.pair);
  // Owned particles start from gravity (kick_drift() or start_forces_from_gravity()); ghosts
  // collect contact forces only, summed back to their owners.
  for (std::size_t i = store_.n_owned(); i < store_.size(); ++i) {
    store_.f[i] = Vec3{};
    store_.torque[i] = Vec3{};
  }
  contacts_.tally() = ContactTally{};
  const double dt = advance_history ? config_.dt : 0.0;
  search_.refresh_near(store_, contacts_.history().pair_slots(), walls_.shaped(),
                       config_.near_fraction);
  const NeighborList& list = search_.list();
  const auto compute = [&](PairSet set) {
    contacts_.compute_pairs(store_.view(), list, search_.held_near_pairs(), walls_.planes(), time_,
                            dt, walls_.particles_still(), set);
  };
  if (list.ghost_pairs.empty()) {
    compute(PairSet::all);
    timer.switch_to(timers_.comm);
    exchange_.reverse(store_);
  } else {
    // The pairs with a ghost first: their forces travel back to the ghosts' owners while the
    // pairs of owned particles are computed, so neither rank waits for the message unless the
    // other is later than that whole computation.
    compute(PairSet::ghost);
    timer.switch_to(timers_.comm);
    exchange_.reverse_start(store_);
    timer.switch_to(timers_.pair);
    compute(PairSet::owned);
    timer.switch_to(timers_.comm);
    exchange_.reverse_finish(store_);
  }
  if (!walls_.shaped().empty()) {
    timer.switch_to(timers_.pair);
    contacts_.compute_shaped(store_.view(), list, search_.held_near_wall_elements(),
                             walls_.shaped(), time_, dt, walls_.shaped_loads_here(),
                             walls_.element_forces_here());
  }
  if (!clumps_.empty()) clumps_.gather_forces(store_, config_.gravity);
  check_health();
}

void Simulation::check_health() {
  const ContactTally& tally = contacts_.tally();
  std::string error;
  overlap_speed_ = -1.0;
  if (tally.max_overlap_ratio > config_.max_overlap_ratio) {
    error = fmt::format("step {}, t = {}: overlap of {:.3g} times the smaller radius (limit {}) "
                        "at {}",
                        step_, time_, tally.max_overlap_ratio, config_.max_overlap_ratio,
                        describe_particle(tally.worst_particle) +
                            "; its contacts: " + describe_contacts(tally.worst_particle));
    overlap_speed_ = norm(store_.v[tally.worst_particle]);
  }
  ledger_.set_health_error(std::move(error));
}

void Simulation::stop_if_unhealthy_together() const {
  // Where an overlap went too deep, its cause: a time step too long for the stiffest contact
  // (at the overlapping grain's speed), or, where the step resolves that contact well, contacts
  // too soft for what they carry (a collective look at the contacts, on a failure only).
  std::string error = ledger_.health_error();
  const double speed = comm().max(overlap_speed_);
  if (speed >= 0.0) {
    const double steps = stiffest_contact(speed).contact_time / config_.dt;
    if (overlap_speed_ >= 0.0)
      error += steps >= 20.0
                   ? fmt::format("; the time step resolves the stiffest contact (dt = t_c/{:.0f}): "
                                 "the contacts are too soft for the loads or the impact speeds "
                                 "they meet (stiffer contacts, or less load or speed)",
                                 steps)
                   : fmt::format("; the time step is too large for the contact stiffness or the "
                                 "impact speed (dt = t_c/{:.1f} of the stiffest contact)",
                                 steps);
  }
  stop_together(error);
}

std::string Simulation::describe_particle(std::size_t i) const {
  return yuxi::describe_particle(store_, i);
}

std::string Simulation::describe_contacts(std::size_t i) const {
  return yuxi::describe_contacts(store_, config_.box, walls_.planes(), time_, i);
}

EnergyBooks Simulation::energies() const {
  EnergyBooks e = energy_parts();
  e.sum_over(comm()); // one reduction for all
  return e;
}

EnergyBooks Simulation::energy_parts() const {
  EnergyBooks e = ledger_.parts(store_, config_, contacts_.tally(), step_, time_);
  clumps_.add_energies(e, potential_gravity(config_));
  return e;
}

void Simulation::settle_energy_books() {
  std::optional<EnergyBooks> due = ledger_.take_due();
  if (!due) return;
  due->sum_over(comm());
  check_energy_books(*due);
}

void Simulation::check_energy_books(const EnergyBooks& e) const {
  const std::optional<EnergyLedger::Gain> gain = ledger_.unstable_gain(e);
  if (!gain) return;
  const double gained = gain->gained, in_play = gain->in_play;
  // Energy that came with wall contacts born deep is no fault of the time step: say where.
  const DeepStarts& deep = contacts_.deep_starts();
  const double deep_energy = comm().sum(deep.energy), worst = comm().max(deep.worst);
  if (deep_energy >= 0.25 * gained) {
    const std::string where = comm().first_error(
        worst > 0 && deep.worst == worst ? walls_.describe_deep_start(deep) : std::string{});
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

StiffestContact Simulation::stiffest_contact(double impact_speed) const {
  // Smallest grain mass and radius per material, and which materials appear on walls.
  const std::size_t n_mat = contacts_.n_materials();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> m_min(n_mat, inf), r_min(n_mat, inf);
  std::vector<bool> on_wall(n_mat, false);
  std::vector<double> grains(n_mat, 0.0); // (two grains of a material must exist to meet)
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const auto k = store_.material[i];
    if (k >= n_mat) continue;
    if (store_.body[i] >= 0) continue; // (a clump's member: its clump, below)
    if (store_.is_grain(i)) {
      m_min[k] = std::min(m_min[k], store_.mass[i]);
      r_min[k] = std::min(r_min[k], store_.radius[i]);
      grains[k] += 1.0;
    } else {
      on_wall[k] = true;
    }
  }
  // A clump's members: the least mass a contact on the clump can meet, the smallest member.
  for (const ClumpBody& b : clumps_.bodies()) {
    const auto k = b.material;
    if (k >= n_mat) continue;
    m_min[k] = std::min(m_min[k], b.smallest_contact_mass());
    for (const double r : b.radii) r_min[k] = std::min(r_min[k], r);
    grains[k] += static_cast<double>(b.members.size());
  }
  walls_.mark_materials(on_wall);
  // The grains that inserts will pour: the smallest their size distribution gives.
  // (A clump's least contact mass grows as its size cubed: the smallest clump's is the least.)
  for (const InsertSpec& insert : sources_.inserts()) {
    const auto k = insert.grains.material;
    if (k >= n_mat) continue;
    const double r = insert.grains.size.smallest();
    const double m = insert.pours_clumps()
                         ? make_clump(insert.clump.scaled(r / insert.clump.bounding_radius),
                                      insert.grains.density, k, 0, {}, {})
                               .body.smallest_contact_mass()
                         : insert.grains.mass_of(r);
    m_min[k] = std::min(m_min[k], m);
    r_min[k] = std::min(r_min[k], insert.smallest_sphere());
    grains[k] += 2.0;
  }
  const Comm& c = comm();
  if (n_mat > 0) c.sum(grains.data(), static_cast<int>(n_mat));
  for (std::size_t k = 0; k < n_mat; ++k) { // over all ranks
    m_min[k] = -c.max(-m_min[k]);
    r_min[k] = -c.max(-r_min[k]);
    on_wall[k] = c.any(on_wall[k]);
  }
  StiffestContact best{inf, 0, 0, 0};
  contacts_.visit_law([&](const auto& law) {
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
  });
  return best;
}

} // namespace yuxi
