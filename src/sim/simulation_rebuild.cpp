// The list build of a simulation: escapes, periodic wrap, migration between ranks, balancing,
// sorting by cell, ghosts, neighbour list, contact history (simulation.hpp, phase 2).
#include "sim/contact_reach.hpp"
#include "sim/simulation.hpp"

#include <fmt/format.h>

namespace yuxi {

void Simulation::rebuild(BuildAfter after) {
  const bool after_load = after == BuildAfter::load || after == BuildAfter::load_at_last_build;
  const bool in_step = after == BuildAfter::step;
  // (the spans without exchanges go into timers_.neighbor_local)
  if (!after_load) {
    PhaseTimer timer(timers_.neighbor_local);
    history_->stash(store_, list_);
  }
  // Rebalance by measured cost at the first rebuild after the start (the start could only
  // count particles), then every rebalance_every rebuilds.
  if (in_step && comm_.size() > 1 && config_.rebalance_every > 0 &&
      (rebuilds_ == 1 || (rebuilds_ > 0 && rebuilds_ % config_.rebalance_every == 0)))
    rebalance();
  handle_escapes();
  if (after == BuildAfter::edit && edit_) {
    store_.clear_ghosts();
    edit_();
  }
  if (in_step) {
    if (!outlets_.empty()) handle_outlets();
    if (!inserts_.empty()) insert_due_batches();
  }
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
  // Sort owned particles by cell so that neighbours sit close in memory: the grains first,
  // then the wall particles (so the integration runs over the grains alone, with no test of
  // the kind, which alternates unpredictably along cells that hold both).
  {
    PhaseTimer timer(timers_.neighbor_local);
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
  // Ghosts, each with copies of the contact states it may be needed for on its receiver.
  history_->prepare_ghost_copies(store_);
  const GhostPayload copies{
      [&](std::span<const std::uint32_t> sent) { return history_->ghost_copies(sent); },
      [&](std::uint32_t first, const std::string& bytes) {
        history_->ghost_copies_arrived(store_, first, bytes);
      }};
  halo_.build(store_, decomp_, comm_, cell_edge_, &copies);
  PhaseTimer timer(timers_.neighbor_local);
  store_.trim_capacity();
  grid_.bin(store_.x);
  build_neighbor_list(store_, grid_, range_, list_);
  // Where forces on ghosts go back to another rank, the pairs with a ghost come first
  // (compute_forces()).
  list_.index_ghost_pairs(halo_.sends_to_other_ranks());
  near_.picked = false; // (they index the old list)
  near_walls_.picked = false;
  list_.planes.clear();
  for (std::uint32_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i)) continue;
    for (std::uint32_t p = 0; p < planes_.size(); ++p)
      if (planes_[p].distance_at_rest(store_.x[i]) <
          store_.radius[i] + range_ + planes_[p].max_excursion())
        list_.planes.push_back({i, p});
  }
  list_wall_candidates();
  history_->restore(store_, list_);
  if (after != BuildAfter::load_at_last_build)
    for (std::size_t i = 0; i < store_.n_owned(); ++i) store_.x_build[i] = store_.x[i];
  ++rebuilds_;
  // The energy books of this state are summed over the ranks and checked at the next step's
  // collective: a collective here would make every rank wait for the slowest list build, and
  // again at that step for the slowest pairs, where one wait covers both. (A loaded state's
  // books were checked before it was saved.)
  if (step_ > 0 && in_step) books_due_ = energy_parts();
}

void Simulation::migrate() {
  // Particles go to the rank that owns their place now, each with copies of the states of its
  // contacts (contact_history.hpp: the rank that computes a pair after the rebuild may be
  // either partner's); repeated until every rank holds only its own (one round unless the cut
  // planes have just moved).
  for (int round = 0; round < 64; ++round) {
    Halo::migrate(
        store_, decomp_, comm_,
        [&](const std::vector<std::size_t>& leaving) {
          std::vector<GlobalId> gids(leaving.size());
          for (std::size_t k = 0; k < leaving.size(); ++k) gids[k] = store_.gid[leaving[k]];
          return history_->copies_for(gids);
        },
        [&](std::size_t, const std::string& bytes) { history_->give(bytes); });
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
    books_.removed += mechanical_energy(i);
  }
  if (gone.empty()) return;
  store_.remove_owned(gone);
  books_.escaped += gone.size();
}

} // namespace yuxi
