#include "sim/exchange.hpp"

#include <string>

namespace yuxi {
namespace {

std::vector<Vec3> owned_positions(const ParticleStore& s) {
  return std::vector<Vec3>(s.x.begin(), s.x.begin() + static_cast<std::ptrdiff_t>(s.n_owned()));
}

} // namespace

Exchange::Exchange(const Box& box, Comm comm, std::array<int, 3> layout, Vec3 occupied,
                   double cell_edge)
    : comm_(comm), decomp_(box, comm_, layout, occupied), cell_edge_(cell_edge),
      grid_(box, cell_edge_) {
  decomp_.set_min_slab(cell_edge_);
}

void Exchange::lay_out(std::array<int, 3> layout, Vec3 occupied, double cell_edge) {
  decomp_ = Decomposition(decomp_.box(), comm_, layout, occupied);
  cell_edge_ = cell_edge;
  decomp_.set_min_slab(cell_edge_);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
}

void Exchange::take_share(ParticleStore& s, bool balance) {
  if (balance) decomp_.balance(s.x, std::vector<double>(s.n_owned(), 1.0), comm_);
  std::vector<std::size_t> elsewhere;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (!decomp_.owns(decomp_.box().wrap(s.x[i]))) elsewhere.push_back(i);
  s.remove_owned(elsewhere);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
}

void Exchange::cut_by_count(const ParticleStore& s) {
  cuts_moved_ = true;
  if (comm_.size() > 1)
    decomp_.balance(owned_positions(s), std::vector<double>(s.n_owned(), 1.0), comm_);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
}

void Exchange::set_cuts(const std::array<std::vector<double>, 3>& cuts) {
  for (int a = 0; a < 3; ++a) decomp_.set_cuts(a, cuts[a]);
  // The cells of the saved sub-domain: the list build then sorts and bins as the saved run.
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
}

std::array<std::vector<double>, 3> Exchange::cuts() const {
  return {decomp_.cuts(0), decomp_.cuts(1), decomp_.cuts(2)};
}

void Exchange::migrate(ParticleStore& s, ContactStates& history) {
  for (int round = 0; round < 64; ++round) {
    Halo::migrate(
        s, decomp_, comm_,
        [&](const std::vector<std::size_t>& leaving) {
          std::vector<GlobalId> gids(leaving.size());
          for (std::size_t k = 0; k < leaving.size(); ++k) gids[k] = s.gid[leaving[k]];
          return history.copies_for(gids);
        },
        [&](std::size_t, const std::string& bytes) { history.give(bytes); });
    // Between list builds nothing moves more than half the skin, less than any sub-domain is
    // wide: one hop per axis takes every particle to its owner unless the cut planes moved.
    if (!cuts_moved_) break;
    bool stray = false;
    for (std::size_t i = 0; i < s.n_owned() && !stray; ++i) stray = !decomp_.owns(s.x[i]);
    if (!comm_.any(stray)) break;
  }
  cuts_moved_ = false;
}

void Exchange::balance(const ParticleStore& s, const NeighborList& list, BalanceBy by,
                       double busy) {
  // Cost of a particle: itself plus the pairs in its neighbour-list row.
  std::vector<double> cost(s.n_owned(), 1.0);
  for (std::size_t i = 0; i + 1 < list.offsets.size() && i < cost.size(); ++i)
    cost[i] += list.offsets[i + 1] - list.offsets[i];
  // By time: this rank's costs scaled to sum to the seconds it computed (pairs, its own part
  // of the list builds, integration: PhaseTimes::busy) since the last balancing. The cuts then
  // give each rank the share it computes in equal time, as measured on its own particles: the
  // next balancing corrects what that leaves wrong for the particles that move.
  if (by == BalanceBy::time) {
    double counted = 0.0;
    for (double c : cost) counted += c;
    const double seconds = busy - busy_at_balance_;
    if (!comm_.any(!(seconds > 0.0)) && counted > 0.0) // (every rank has timed some work)
      for (double& c : cost) c *= seconds / counted;
  }
  busy_at_balance_ = busy;
  cuts_moved_ = true;
  decomp_.balance(owned_positions(s), cost, comm_);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
}

void Exchange::make_ghosts(ParticleStore& s, ContactStates& history) {
  history.prepare_ghost_copies(s);
  const GhostPayload copies{
      [&](std::span<const std::uint32_t> sent) { return history.ghost_copies(sent); },
      [&](std::uint32_t first, const std::string& bytes) {
        history.ghost_copies_arrived(s, first, bytes);
      }};
  halo_.build(s, decomp_, comm_, cell_edge_, &copies);
}

} // namespace yuxi
