// The list build of a simulation (phase 3 of a step, simulation.hpp): escapes, sources,
// periodic wrap, migration between ranks, balancing, sorting by cell, ghosts, neighbour list,
// the walls' candidates, contact history.
#include "sim/simulation.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace yuxi {

void Simulation::build_lists(const ListBuildPlan& plan) {
  using After = ListBuildPlan::After;
  const bool after_load = plan.after == After::load || plan.after == After::load_at_last_build;
  const bool in_step = plan.after == After::step;
  ContactStates& history = contacts_.history();
  const Comm& c = comm();
  // (the spans without exchanges go into timers_.neighbor_local)
  if (!after_load) {
    PhaseTimer timer(timers_.neighbor_local);
    history.stash(store_, search_.list());
  }
  // Balance by measured cost at the first list build after the start (the start could only
  // count particles), then every rebalance_every list builds.
  if (in_step && c.size() > 1 && config_.rebalance_every > 0 &&
      (list_builds_ == 1 || (list_builds_ > 0 && list_builds_ % config_.rebalance_every == 0)))
    exchange_.balance(store_, search_.list(), config_.balance_by, timers_.busy());
  handle_escapes();
  if (plan.after == After::edit && plan.edit && *plan.edit) {
    store_.clear_ghosts();
    (*plan.edit)();
  }
  if (in_step) {
    const Sources::Books books{ledger_.books().inserted, ledger_.books().removed};
    const Vec3 g_potential = potential_gravity(config_);
    if (sources_.has_outlets())
      sources_.drain_outlets(store_, clumps_, config_.box, g_potential, books);
    if (!sources_.inserts().empty())
      sources_.insert_due_batches(store_, clumps_, config_, exchange_.decomposition(), c,
                                  walls_.planes(), time_, step_, books);
  }
  // Wrap grains into the periodic box along axes that one rank spans; across ranks the
  // migration shifts them.
  const auto dims = exchange_.decomposition().dims();
  // (A clump's members stand whole about its centre, which wraps here, taking them along.)
  if (!clumps_.empty() && (in_step || plan.after == After::edit))
    clumps_.wrap(member_wrap_box(), store_);
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i) || store_.body[i] >= 0) continue;
    Vec3 wrapped = config_.box.wrap(store_.x[i]);
    for (int a = 0; a < 3; ++a)
      if (dims[a] > 1) wrapped[a] = store_.x[i][a];
    store_.x[i] = wrapped;
  }
  if (c.size() > 1) exchange_.migrate(store_, history, clumps_);
  // Sort owned particles by cell so that neighbours sit close in memory: the free grains
  // first, then the clumps' members, then the wall particles (so the integration runs over the
  // free grains alone, with no test of the kind, which alternates unpredictably along cells
  // that hold both).
  {
    PhaseTimer timer(timers_.neighbor_local);
    const CellGrid& grid = exchange_.grid();
    const std::size_t n = store_.n_owned(), cells = grid.n_cells();
    std::vector<std::uint32_t> key(n), count(3 * cells + 1, 0), order(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t group = !store_.is_grain(i) ? 2 : store_.body[i] >= 0 ? 1 : 0;
      key[i] = static_cast<std::uint32_t>(grid.cell_index(store_.x[i]) + group * cells);
      ++count[key[i] + 1];
    }
    for (std::size_t k = 0; k < 3 * cells; ++k) count[k + 1] += count[k];
    n_grains_ = count[cells];
    n_movers_ = count[2 * cells];
    for (std::size_t i = 0; i < n; ++i) order[count[key[i]]++] = static_cast<std::uint32_t>(i);
    store_.permute_owned(order);
    if (!clumps_.empty()) clumps_.index_members(store_);
  }
  // Ghosts, each with copies of the contact states it may be needed for on its receiver.
  exchange_.make_ghosts(store_, history);
  PhaseTimer timer(timers_.neighbor_local);
  store_.trim_capacity();
  exchange_.grid().bin(store_.x);
  // Where forces on ghosts go back to another rank, the pairs with a ghost come first
  // (compute_forces()).
  search_.build(store_, exchange_.grid(), exchange_.halo().sends_to_other_ranks(), walls_.planes());
  walls_.list_candidates(store_, n_movers_, exchange_.grid(), search_.skin(), time_,
                         search_.list());
  history.restore(store_, search_.list());
  contacts_.size_for(search_.list(), walls_.element_forces_here());
  if (plan.after != After::load_at_last_build)
    for (std::size_t i = 0; i < store_.n_owned(); ++i) store_.x_build[i] = store_.x[i];
  ++list_builds_;
  // The energy books of this state are summed over the ranks and checked at the next step's
  // collective (EnergyLedger::leave_due). A loaded state's books were checked before it was
  // saved.
  if (step_ > 0 && in_step) ledger_.leave_due(energy_parts());
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
  const Vec3 g_potential = potential_gravity(config_);
  const Box& box = config_.box;
  std::vector<std::size_t> gone, clumps_gone;
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_finite(store_.x[i]) || !is_finite(store_.v[i]) || !is_finite(store_.w[i]))
      throw SimulationError(fmt::format("step {}, t = {}: non-finite state of {}; its contacts: {}",
                                        step_, time_, describe_particle(i), describe_contacts(i)));
    if (!store_.is_grain(i) || box.contains(store_.x[i])) continue;
    if (config_.on_escape == EscapePolicy::stop)
      throw SimulationError(fmt::format("step {}, t = {}: {} left the domain [{}, {}] x [{}, {}] "
                                        "x [{}, {}] (set on_escape = \"remove\" to drop it); its "
                                        "contacts: {}",
                                        step_, time_, describe_particle(i), box.lo.x, box.hi.x,
                                        box.lo.y, box.hi.y, box.lo.z, box.hi.z,
                                        describe_contacts(i)));
    if (store_.body[i] >= 0) { // (a clump leaves whole, once, with the first member out)
      clumps_gone.push_back(clumps_.body_of(store_, i));
      continue;
    }
    gone.push_back(i);
    ledger_.books().removed += mechanical_energy(store_, i, g_potential);
  }
  const std::size_t escaped = gone.size();
  if (!clumps_gone.empty()) {
    std::sort(clumps_gone.begin(), clumps_gone.end());
    clumps_gone.erase(std::unique(clumps_gone.begin(), clumps_gone.end()), clumps_gone.end());
    for (const std::size_t b : clumps_gone)
      ledger_.books().removed += clumps_.mechanical_energy(b, g_potential);
    const std::vector<std::size_t> members = clumps_.remove(store_, clumps_gone);
    gone.insert(gone.end(), members.begin(), members.end());
    std::sort(gone.begin(), gone.end());
  }
  if (gone.empty()) return;
  store_.remove_owned(gone);
  ledger_.books().escaped += escaped + clumps_gone.size();
}

} // namespace yuxi
