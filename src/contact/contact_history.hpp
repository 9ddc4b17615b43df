// Per-contact state kept across neighbour-list rebuilds.
//
// Between rebuilds each listed pair holds a slot number (4 bytes, aligned with the neighbour
// list) into a pool of states kept only for the contacts that touch: in a granular flow most
// listed pairs are near misses (the chute lists about six pairs per touching contact), so the
// pair loop streams 4 bytes, not a whole state, past each of them. Grain-plane candidates are
// few and keep one state each. At a rebuild the states are stashed by the global ids of
// the two partners, the particles are reordered and the list rebuilt, and each new list entry
// picks its state back up. A pair listed as (i, j) before and (j, i) after gets the mirrored
// state. Only states that differ from a fresh one are stashed: a default state carries nothing.
//
// Ownership (for MPI migration and checkpoints): a contact belongs with its particle of lower
// global id; a grain-plane contact with its grain.
//
// The stash is a plain array, and restore() walks it: each stashed contact looks for its pair
// in the rows of its two particles (found by global id), so a rebuild costs no hashing per
// listed pair and no allocation per contact; violent runs rebuild every few steps.
#pragma once

#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

namespace yuxi {

struct ContactKey {
  GlobalId first;  // lower global id (the grain, for a plane contact)
  GlobalId second; // higher global id, or -(plane index + 1) for a plane contact
  bool operator==(const ContactKey&) const = default;
};

// Local index of each owned particle by global id: a table when the ids are dense enough,
// a hash map otherwise (ids read from a LAMMPS data file may be anything).
class OwnedIndex {
public:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);
  explicit OwnedIndex(const ParticleStore& s) {
    GlobalId top = -1;
    for (std::size_t i = 0; i < s.n_owned(); ++i) top = std::max(top, s.gid[i]);
    const auto n = static_cast<std::size_t>(top + 1);
    dense_ = top >= 0 && n <= 8 * s.n_owned() + 1024;
    if (dense_) {
      table_.assign(n, none);
      for (std::size_t i = 0; i < s.n_owned(); ++i) table_[static_cast<std::size_t>(s.gid[i])] = i;
    } else {
      for (std::size_t i = 0; i < s.n_owned(); ++i) map_.emplace(s.gid[i], i);
    }
  }
  std::size_t find(GlobalId g) const {
    if (dense_)
      return g >= 0 && static_cast<std::size_t>(g) < table_.size()
                 ? table_[static_cast<std::size_t>(g)]
                 : none;
    const auto it = map_.find(g);
    return it == map_.end() ? none : it->second;
  }

private:
  bool dense_ = true;
  std::vector<std::size_t> table_;
  std::unordered_map<GlobalId, std::size_t> map_;
};

struct ContactKeyHash {
  std::size_t operator()(const ContactKey& k) const noexcept {
    const auto a = static_cast<std::uint64_t>(k.first);
    const auto b = static_cast<std::uint64_t>(k.second);
    return static_cast<std::size_t>(a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull));
  }
};

template <class State> class ContactHistory {
public:
  static constexpr std::uint32_t none = 0xFFFFFFFFu; // slot of a pair that does not touch

  // Slot in `states` of each listed pair (aligned with NeighborList::partners), or none.
  std::vector<std::uint32_t> pair_slot;
  std::vector<State> states; // the touching pairs' states (and free slots)
  std::vector<State> plane;  // aligned with NeighborList::planes
  // 1 where the plane state may differ from a fresh one (the contact touched since it was last
  // released).
  std::vector<std::uint8_t> plane_live;

  // The state of listed pair p, opened fresh if it has none.
  State& open(std::uint32_t p) {
    std::uint32_t& slot = pair_slot[p];
    if (slot != none) return states[slot];
    if (free_.empty()) {
      slot = static_cast<std::uint32_t>(states.size());
      return states.emplace_back();
    }
    slot = free_.back();
    free_.pop_back();
    return states[slot] = State{};
  }
  // Listed pair p has opened: its slot is free for another contact.
  void close(std::uint32_t p) {
    free_.push_back(pair_slot[p]);
    pair_slot[p] = none;
  }

  struct Entry {
    ContactKey key;
    State state; // as seen from key.first
  };

  // Every non-default state, keyed by global ids, in neighbour-list order.
  std::vector<Entry> entries(const ParticleStore& s, const NeighborList& list) const {
    std::vector<Entry> out;
    out.reserve(states.size() - free_.size() + plane.size());
    const State fresh{};
    for (std::size_t i = 0; i + 1 < list.offsets.size(); ++i)
      for (std::uint32_t p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
        if (pair_slot[p] == none || states[pair_slot[p]] == fresh) continue;
        const State& state = states[pair_slot[p]];
        const GlobalId a = s.gid[i], b = s.gid[list.partners[p]];
        out.push_back({{std::min(a, b), std::max(a, b)}, a < b ? state : state.mirrored()});
      }
    for (std::size_t k = 0; k < list.planes.size(); ++k)
      if (!(plane[k] == fresh)) out.push_back({plane_key(s, list.planes[k]), plane[k]});
    return out;
  }

  // Moves every non-default state into the stash, keyed by global ids.
  void stash(const ParticleStore& s, const NeighborList& list) { stash_ = entries(s, list); }

  // Saves the states of the current list, or loads them into the stash for the next restore().
  template <class Archive>
  void checkpoint(Archive& ar, const ParticleStore& s, const NeighborList& list) {
    std::vector<Entry> all;
    if constexpr (!Archive::loading) all = entries(s, list);
    ar.vector(all);
    if constexpr (Archive::loading) {
      stash_ = std::move(all);
    }
  }

  // Gives each entry of the new list its stashed state (or a fresh one).
  void restore(const ParticleStore& s, const NeighborList& list) {
    pair_slot.assign(list.n_pairs(), none);
    // The pool restarts at the size of the stash with a quarter to spare for the contacts that
    // open before the next rebuild (its memory would otherwise stay at its largest ever).
    states = std::vector<State>(); // (not "= {}": that keeps the capacity)
    states.reserve(stash_.size() + stash_.size() / 4 + 16);
    free_.clear();
    plane.assign(list.planes.size(), State{});
    plane_live.assign(list.planes.size(), 0);
    if (stash_.empty()) return;
    const OwnedIndex owned(s);
    // The row of particle `row` (if owned here) lists the pair when its partner has global id
    // `other`; the state is stored as seen from the lower id.
    const auto place = [&](std::size_t row, GlobalId other, const State& state, bool mirror) {
      if (row == OwnedIndex::none) return;
      for (std::uint32_t p = list.offsets[row]; p < list.offsets[row + 1]; ++p)
        if (s.gid[list.partners[p]] == other) open(p) = mirror ? state.mirrored() : state;
    };
    std::unordered_map<ContactKey, const State*, ContactKeyHash> plane_states;
    for (const Entry& e : stash_) {
      if (e.key.first == taken) continue;
      if (e.key.second < 0) {
        plane_states[e.key] = &e.state;
        continue;
      }
      place(owned.find(e.key.first), e.key.second, e.state, false);
      place(owned.find(e.key.second), e.key.first, e.state, true);
    }
    if (!plane_states.empty())
      for (std::size_t k = 0; k < list.planes.size(); ++k) {
        const auto it = plane_states.find(plane_key(s, list.planes[k]));
        if (it == plane_states.end()) continue;
        plane[k] = *it->second;
        plane_live[k] = 1;
      }
    stash_ = std::vector<Entry>(); // its memory too: it is rebuilt at the next rebuild
  }

  // Bytes held by the per-contact arrays (slots, states, live flags, free list and stash).
  std::size_t memory_bytes() const {
    return (pair_slot.capacity() + free_.capacity()) * sizeof(std::uint32_t) +
           (states.capacity() + plane.capacity()) * sizeof(State) + plane_live.capacity() +
           stash_.capacity() * sizeof(Entry);
  }

  std::size_t stashed() const {
    return static_cast<std::size_t>(std::count_if(
        stash_.begin(), stash_.end(), [](const Entry& e) { return e.key.first != taken; }));
  }

  // Migration between ranks: the stashed states owned by the particles `gids` (the contacts
  // whose lower global id they have), packed as bytes, one string per particle, and removed
  // from the stash; and the reverse. One pass over the stash for all the particles that leave
  // (a few hundred at a rebuild, against thousands of stashed contacts).
  std::vector<std::string> take_owned_by(const std::vector<GlobalId>& gids) {
    std::vector<std::string> out(gids.size());
    if (gids.empty()) return out;
    std::unordered_map<GlobalId, std::size_t> leaving;
    leaving.reserve(gids.size());
    for (std::size_t k = 0; k < gids.size(); ++k) leaving.emplace(gids[k], k);
    for (Entry& e : stash_) {
      if (e.key.first == taken) continue;
      const auto it = leaving.find(e.key.first);
      if (it == leaving.end()) continue;
      out[it->second].append(reinterpret_cast<const char*>(&e), sizeof e);
      e.key.first = taken;
    }
    return out;
  }
  void give(const std::string& bytes) {
    for (std::size_t at = 0; at + sizeof(Entry) <= bytes.size(); at += sizeof(Entry)) {
      Entry e;
      std::memcpy(&e, bytes.data() + at, sizeof e);
      stash_.push_back(e);
    }
  }
  // Every stashed state as bytes (for give()).
  std::string stashed_bytes() const {
    std::string out;
    for (const Entry& e : stash_)
      if (e.key.first != taken) out.append(reinterpret_cast<const char*>(&e), sizeof e);
    return out;
  }

private:
  static ContactKey plane_key(const ParticleStore& s, const PlaneContactRef& r) {
    return {s.gid[r.particle], -static_cast<GlobalId>(r.plane) - 1};
  }
  static constexpr GlobalId taken = -1; // key.first of an entry that has left (migration)
  std::vector<std::uint32_t> free_;     // slots of `states` that no contact holds
  std::vector<Entry> stash_;            // later entries win over earlier ones with their key
};

} // namespace yuxi
