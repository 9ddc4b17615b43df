// Per-contact state kept across neighbour-list rebuilds.
//
// Between rebuilds the state lives in arrays aligned with the neighbour list (one entry per
// listed pair, one per grain-plane candidate). At a rebuild it is stashed by the global ids of
// the two partners, the particles are reordered and the list rebuilt, and each new list entry
// picks its state back up. A pair listed as (i, j) before and (j, i) after gets the mirrored
// state. Only states that differ from a fresh one are stashed: a default state carries nothing.
//
// Ownership (for MPI migration and checkpoints): a contact belongs with its particle of lower
// global id; a grain-plane contact with its grain.
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

struct ContactKeyHash {
  std::size_t operator()(const ContactKey& k) const noexcept {
    const auto a = static_cast<std::uint64_t>(k.first);
    const auto b = static_cast<std::uint64_t>(k.second);
    return static_cast<std::size_t>(a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull));
  }
};

template <class State> class ContactHistory {
public:
  std::vector<State> pair;  // aligned with NeighborList::partners
  std::vector<State> plane; // aligned with NeighborList::planes
  // 1 where the state may differ from a fresh one (the contact touched since it was last
  // released): the pair loop reads these bytes, not the states, for the many listed pairs
  // that do not touch.
  std::vector<std::uint8_t> pair_live, plane_live;

  struct Entry {
    ContactKey key;
    State state; // as seen from key.first
  };

  // Every non-default state, keyed by global ids, in neighbour-list order.
  std::vector<Entry> entries(const ParticleStore& s, const NeighborList& list) const {
    std::vector<Entry> out;
    const State fresh{};
    for (std::size_t i = 0; i + 1 < list.offsets.size(); ++i)
      for (std::uint32_t p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
        if (pair[p] == fresh) continue;
        const GlobalId a = s.gid[i], b = s.gid[list.partners[p]];
        out.push_back({{std::min(a, b), std::max(a, b)}, a < b ? pair[p] : pair[p].mirrored()});
      }
    for (std::size_t k = 0; k < list.planes.size(); ++k)
      if (!(plane[k] == fresh)) out.push_back({plane_key(s, list.planes[k]), plane[k]});
    return out;
  }

  // Moves every non-default state into the stash, keyed by global ids.
  void stash(const ParticleStore& s, const NeighborList& list) {
    stash_.clear();
    by_owner_.clear();
    for (const auto& e : entries(s, list)) stash_.emplace(e.key, e.state);
  }

  // Saves the states of the current list, or loads them into the stash for the next restore().
  template <class Archive>
  void checkpoint(Archive& ar, const ParticleStore& s, const NeighborList& list) {
    std::vector<Entry> all;
    if constexpr (!Archive::loading) all = entries(s, list);
    ar.vector(all);
    if constexpr (Archive::loading) {
      stash_.clear();
      for (const auto& e : all) stash_.emplace(e.key, e.state);
    }
  }

  // Gives each entry of the new list its stashed state (or a fresh one).
  void restore(const ParticleStore& s, const NeighborList& list) {
    pair.assign(list.n_pairs(), State{});
    plane.assign(list.planes.size(), State{});
    pair_live.assign(list.n_pairs(), 0);
    plane_live.assign(list.planes.size(), 0);
    if (stash_.empty()) return;
    for (std::size_t i = 0; i + 1 < list.offsets.size(); ++i)
      for (std::uint32_t p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
        const GlobalId a = s.gid[i], b = s.gid[list.partners[p]];
        const auto it = stash_.find(ContactKey{std::min(a, b), std::max(a, b)});
        if (it == stash_.end()) continue;
        pair[p] = a < b ? it->second : it->second.mirrored();
        pair_live[p] = 1;
      }
    for (std::size_t k = 0; k < list.planes.size(); ++k) {
      const auto it = stash_.find(plane_key(s, list.planes[k]));
      if (it == stash_.end()) continue;
      plane[k] = it->second;
      plane_live[k] = 1;
    }
    stash_.clear();
  }

  std::size_t stashed() const { return stash_.size(); }

  // Migration between ranks: the stashed states owned by particle `gid` (the contacts whose
  // lower global id it has), packed as bytes and removed from the stash; and the reverse.
  std::string take_owned_by(GlobalId gid) {
    if (by_owner_.empty() && !stash_.empty())
      for (const auto& [key, state] : stash_) by_owner_[key.first].push_back(key);
    std::string out;
    const auto it = by_owner_.find(gid);
    if (it == by_owner_.end()) return out;
    for (const ContactKey& key : it->second) {
      const auto st = stash_.find(key);
      if (st == stash_.end()) continue;
      const Entry e{key, st->second};
      out.append(reinterpret_cast<const char*>(&e), sizeof e);
      stash_.erase(st);
    }
    by_owner_.erase(it);
    return out;
  }
  void give(const std::string& bytes) {
    for (std::size_t at = 0; at + sizeof(Entry) <= bytes.size(); at += sizeof(Entry)) {
      Entry e;
      std::memcpy(&e, bytes.data() + at, sizeof e);
      stash_.insert_or_assign(e.key, e.state);
      if (!by_owner_.empty()) by_owner_[e.key.first].push_back(e.key); // may move on again
    }
  }
  void forget_owner_index() { by_owner_.clear(); }
  // Every stashed state as bytes (for give()).
  std::string stashed_bytes() const {
    std::string out;
    for (const auto& [key, state] : stash_) {
      const Entry e{key, state};
      out.append(reinterpret_cast<const char*>(&e), sizeof e);
    }
    return out;
  }

private:
  static ContactKey plane_key(const ParticleStore& s, const PlaneContactRef& r) {
    return {s.gid[r.particle], -static_cast<GlobalId>(r.plane) - 1};
  }
  std::unordered_map<ContactKey, State, ContactKeyHash> stash_;
  std::unordered_map<GlobalId, std::vector<ContactKey>> by_owner_; // built on first migration
};

} // namespace yuxi
