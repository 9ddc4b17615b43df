#include "sim/exchange.hpp"

#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <stdexcept>
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
  decomp_.set_min_slab(cell_edge_ + clump_reach_);
  grid_ = local_grid();
}

void Exchange::set_clump_reach(double reach) {
  clump_reach_ = reach;
  decomp_.set_min_slab(cell_edge_ + clump_reach_);
  grid_ = local_grid();
}

CellGrid Exchange::local_grid() const {
  Box box = decomp_.local_box();
  for (int a = 0; a < 3; ++a) box.lo[a] -= clump_reach_, box.hi[a] += clump_reach_;
  return CellGrid(box, cell_edge_);
}

std::vector<std::size_t> Exchange::anchors(const ParticleStore& s,
                                           const ClumpBodies& clumps) const {
  std::vector<std::size_t> anchor(s.n_owned());
  std::vector<std::pair<GlobalId, std::size_t>> members; // (id, index), to find the anchors
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    anchor[i] = i;
    if (s.body[i] >= 0) members.emplace_back(s.gid[i], i);
  }
  if (members.empty()) return anchor;
  std::sort(members.begin(), members.end());
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    if (s.body[i] < 0) continue;
    const std::size_t b = clumps.find(s.body[i]);
    const GlobalId id =
        b < clumps.size() ? s.body[i] + static_cast<GlobalId>(clumps.bodies()[b].anchor()) : -1;
    const auto at =
        std::lower_bound(members.begin(), members.end(), std::pair<GlobalId, std::size_t>{id, 0});
    if (at == members.end() || at->first != id)
      throw std::logic_error(fmt::format("grain {}: its clump {} or the clump's anchor member is "
                                         "not on its rank",
                                         s.gid[i], s.body[i]));
    anchor[i] = at->second;
  }
  return anchor;
}

std::vector<Vec3> Exchange::owner_places(const ParticleStore& s, const ClumpBodies& clumps) const {
  if (clump_reach_ == 0.0) return {};
  const std::vector<std::size_t> anchor = anchors(s, clumps);
  std::vector<Vec3> at(s.n_owned());
  for (std::size_t i = 0; i < s.n_owned(); ++i) at[i] = s.x[anchor[i]];
  return at;
}

void Exchange::take_share(ParticleStore& s, ClumpBodies& clumps, bool balance) {
  if (balance) decomp_.balance(s.x, std::vector<double>(s.n_owned(), 1.0), comm_);
  const std::vector<std::size_t> anchor = anchors(s, clumps);
  const auto here = [&](std::size_t i) { return decomp_.owns(decomp_.box().wrap(s.x[anchor[i]])); };
  std::vector<std::size_t> elsewhere;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (!here(i)) elsewhere.push_back(i);
  // (a clump stays with its anchor member)
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.body[i] >= 0 && anchor[i] == i && !here(i)) clumps.take_out(clumps.find(s.body[i]));
  s.remove_owned(elsewhere);
  grid_ = local_grid();
}

void Exchange::cut_by_count(const ParticleStore& s) {
  cuts_moved_ = true;
  if (comm_.size() > 1)
    decomp_.balance(owned_positions(s), std::vector<double>(s.n_owned(), 1.0), comm_);
  grid_ = local_grid();
}

void Exchange::set_cuts(const std::array<std::vector<double>, 3>& cuts) {
  for (int a = 0; a < 3; ++a) decomp_.set_cuts(a, cuts[a]);
  // The cells of the saved sub-domain: the list build then sorts and bins as the saved run.
  grid_ = local_grid();
}

std::array<std::vector<double>, 3> Exchange::cuts() const {
  return {decomp_.cuts(0), decomp_.cuts(1), decomp_.cuts(2)};
}

void Exchange::migrate(ParticleStore& s, ContactStates& history, ClumpBodies& clumps) {
  // With clumps (on every rank alike), each particle's payload is its contact states, then, for
  // a clump's anchor member, its clump's body: [u64 bytes][states][u8 body?][body].
  const bool with_bodies = clump_reach_ > 0.0;
  for (int round = 0; round < 64; ++round) {
    const std::vector<Vec3> at = owner_places(s, clumps);
    Halo::migrate(
        s, decomp_, comm_,
        [&](const std::vector<std::size_t>& leaving) {
          std::vector<GlobalId> gids(leaving.size());
          for (std::size_t k = 0; k < leaving.size(); ++k) gids[k] = s.gid[leaving[k]];
          std::vector<std::string> out = history.copies_for(gids);
          if (!with_bodies) return out;
          std::vector<std::size_t> gone; // bodies, by index
          for (std::size_t k = 0; k < leaving.size(); ++k) {
            const std::size_t i = leaving[k];
            std::size_t b = s.body[i] >= 0 ? clumps.find(s.body[i]) : clumps.size();
            if (b < clumps.size() &&
                s.gid[i] != s.body[i] + static_cast<GlobalId>(clumps.bodies()[b].anchor()))
              b = clumps.size(); // (the body goes with its anchor member)
            const std::uint64_t n = out[k].size();
            std::string bytes(reinterpret_cast<const char*>(&n), sizeof n);
            bytes += out[k];
            bytes += b < clumps.size() ? '\1' : '\0';
            if (b < clumps.size()) {
              bytes += clumps.pack(b);
              gone.push_back(b);
            }
            out[k] = std::move(bytes);
          }
          std::sort(gone.begin(), gone.end());
          for (std::size_t g = gone.size(); g-- > 0;) clumps.take_out(gone[g]);
          return out;
        },
        [&](std::size_t, const std::string& bytes, const Vec3& shift) {
          if (!with_bodies) return history.give(bytes);
          std::uint64_t n = 0;
          std::memcpy(&n, bytes.data(), sizeof n);
          history.give(bytes.substr(sizeof n, n));
          if (bytes[sizeof n + n] == '\1') clumps.take_in(bytes.substr(sizeof n + n + 1), shift);
        },
        at);
    // Between list builds nothing moves more than half the skin, less than any sub-domain is
    // wide: one hop per axis takes every particle to its owner unless the cut planes moved.
    if (!cuts_moved_) break;
    const std::vector<Vec3> now = owner_places(s, clumps);
    bool stray = false;
    for (std::size_t i = 0; i < s.n_owned() && !stray; ++i)
      stray = !decomp_.owns(now.empty() ? s.x[i] : now[i]);
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
  grid_ = local_grid();
}

void Exchange::make_ghosts(ParticleStore& s, ContactStates& history) {
  history.prepare_ghost_copies(s);
  const GhostPayload copies{
      [&](std::span<const std::uint32_t> sent) { return history.ghost_copies(sent); },
      [&](std::uint32_t first, const std::string& bytes) {
        history.ghost_copies_arrived(s, first, bytes);
      }};
  halo_.build(s, decomp_, comm_, cell_edge_ + clump_reach_, &copies);
}

} // namespace yuxi
