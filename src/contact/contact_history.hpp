// Per-contact state kept across list builds.
//
// Each listed pair that holds a contact has a slot in `states` (its number is kept aligned with
// the neighbour list, 4 bytes a pair; `none` for a pair that does not touch). The room for the
// slots is made when the list is built: a slot for every listed pair, and a free list as long
// (address space: pages are touched only as slots are used), so the pair loop never allocates.
// A contact that begins takes a free slot (or the next unused one), one that ends gives it back:
// the states stay as compact as the contacts that touch, and in a granular flow most listed
// pairs are near misses (the chute lists about six pairs per touching contact), which the pair
// loop passes with 4 bytes each, not a whole state. (A slot fixed per listed pair, or per near
// pair, or handed out once per pair and list build, spreads the touching pairs' states over more
// memory: the chute ran 6, 14 and 2 % slower, docs/performance.md, "Contact history".)
//
// Grain-plane candidates keep one state each. At a list build the states are stashed by the
// global ids of the two partners, the particles are reordered and the list rebuilt, and each new
// list entry picks its state back up. A pair listed as (i, j) before and (j, i) after gets the
// mirrored state. Only states that differ from a fresh one are stashed: a default state carries
// nothing.
//
// A grain touching a shaped wall (a mesh or a cylinder) may have several contacts with it at
// once (a groove's two faces), and each moves over the wall's triangles: a grain-wall candidate
// keeps a fixed set of max_wall_contacts states, each with the normal it had, and the wall's new
// contacts pick up the states whose normals are nearest theirs (sim/contact_forces.hpp). They
// are stashed by (grain id, wall index) with their normals.
//
// Ownership (for MPI ranks and checkpoints): a contact's state lives on the rank that computes
// the pair, which is the rank that lists it: the owner of both particles, or, for a pair across
// ranks, the owner of the particle that sees the other in its half shell of ghosts
// (domain/halo.hpp). A grain-plane contact lives with its grain. Which rank that is can change
// at a list build (particles migrate, cut planes move), so at a list build the stashed states
// travel as copies with the particles they concern: with a particle that migrates
// (copies_for), and with a particle sent as a ghost for the pairs whose other particle is not
// owned by the sender (ghost_copies). Every rank that could list the pair after the list build then
// holds its state, and only the one that lists it picks it up: copies elsewhere are dropped with
// the stash. A contact is therefore never lost, and never duplicated.
//
// The stash is a plain array, and restore() walks it: each stashed contact looks for its pair
// in the rows of its two particles (found by global id), so a list build costs no hashing per
// listed pair and no allocation per contact; violent runs build the lists every few steps.
#pragma once

#include "contact/state_columns.hpp"
#include "core/archive.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <string_view>
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

// The operations on contact states that a list build, a migration and a checkpoint make,
// whatever the model's State: one virtual call per list build (never per pair), so the simulation
// handles the history of any model through this one interface. ContactHistory below is the
// implementation; the comments there say what each does.
class ContactStates {
public:
  virtual ~ContactStates() = default;
  virtual void stash(const ParticleStore& s, const NeighborList& list) = 0;
  virtual void restore(const ParticleStore& s, const NeighborList& list) = 0;
  virtual void prepare_ghost_copies(const ParticleStore& s) = 0;
  virtual std::string ghost_copies(std::span<const std::uint32_t> sent) const = 0;
  virtual void ghost_copies_arrived(const ParticleStore& s, std::uint32_t first,
                                    const std::string& bytes) = 0;
  virtual std::vector<std::string> copies_for(const std::vector<GlobalId>& gids) const = 0;
  virtual void give(const std::string& bytes) = 0;
  virtual std::string stashed_bytes() const = 0;
  // Checkpoints: the states of the current list saved, or loaded into the stash.
  virtual void save(ArchiveWriter& ar, const ParticleStore& s, const NeighborList& list) const = 0;
  virtual void load(ArchiveReader& ar) = 0;
  // Drops every stashed state: the next list build opens every contact fresh (a run that
  // branches from another's state under another contact law).
  virtual void forget() = 0;
  virtual std::size_t memory_bytes() const = 0;
  // The slot of each listed pair (aligned with NeighborList::partners; none: no state).
  virtual const std::uint32_t* pair_slots() const = 0;
  // The model's state as named columns (contact/state_columns.hpp), for analysis: the fields,
  // and the values of listed pair p (as seen from its row particle), of grain-plane candidate
  // k, or of contact c of grain-wall candidate k, appended to `out` (a fresh state's where the
  // contact holds none).
  virtual std::vector<StateField> state_fields() const = 0;
  virtual void pair_state(std::uint32_t p, std::vector<double>& out) const = 0;
  virtual void plane_state(std::size_t k, std::vector<double>& out) const = 0;
  virtual void wall_state(std::size_t k, std::size_t c, std::vector<double>& out) const = 0;
};

inline constexpr std::size_t max_wall_contacts = 6;

// A contact of a grain with a shaped wall: its state and the normal it had when last evaluated.
template <class State> struct WallContact {
  Vec3 normal;
  State state;
};

// The contacts of one grain with one shaped wall (ContactHistory::wall_contact(k, 0) to
// (k, n - 1)), a record of fixed size with no pointer. The first is held in place: most grains
// touch a wall once, and the wall loop then reads one small record per candidate (about 120
// bytes with the linear law's state). The others, for a grain in a groove or on an edge between
// two faces, are held in a block of the history's, found by index: the room for a block per
// candidate is made at the list build, and a candidate takes its block when it first needs one,
// so the wall loop allocates nothing. (A record with room for all six, 632 bytes with the
// linear law, ran the mesh drum 5 to 10 % slower: docs/performance.md, "Contact history".)
template <class State> struct WallContactSet {
  static constexpr std::uint32_t no_block = 0xFFFFFFFFu;
  std::uint8_t n = 0;
  std::uint32_t block = no_block; // index of its block of further contacts
  WallContact<State> first{};
};

template <class State> class ContactHistory final : public ContactStates {
public:
  static constexpr std::uint32_t none = 0xFFFFFFFFu; // no slot

  // The slot in `states` of each listed pair that holds a contact, or none.
  std::vector<std::uint32_t> pair_slot;
  // The states of the contacts (and free slots); room for one per listed pair is reserved at
  // the list build.
  std::vector<State> states;
  std::vector<State> plane; // aligned with NeighborList::planes
  // 1 where the plane state may differ from a fresh one (the contact touched since it was last
  // released).
  std::vector<std::uint8_t> plane_live;
  std::vector<WallContactSet<State>> wall; // aligned with NeighborList::walls

  // Contact c of grain-wall candidate k (c < wall[k].n, or c < a count made room for).
  WallContact<State>& wall_contact(std::size_t k, std::size_t c) {
    return c == 0 ? wall[k].first : wall_blocks_[wall[k].block][c - 1];
  }
  const WallContact<State>& wall_contact(std::size_t k, std::size_t c) const {
    return c == 0 ? wall[k].first : wall_blocks_[wall[k].block][c - 1];
  }
  // Makes wall_contact(k, 0) to (k, count - 1) usable (count <= max_wall_contacts): a candidate's
  // first need of a block takes the next one, within the room made at the list build.
  void make_wall_room(std::size_t k, std::size_t count) {
    if (count > 1 && wall[k].block == WallContactSet<State>::no_block) {
      wall[k].block = static_cast<std::uint32_t>(wall_blocks_.size());
      wall_blocks_.emplace_back();
    }
  }

  // The state of listed pair p, opened fresh if it holds none: a free slot, or the next unused
  // one, within the room made at the list build.
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
  // The state of live pair p.
  State& state_of(std::uint32_t p) { return states[pair_slot[p]]; }

  struct Entry {
    ContactKey key;
    State state; // as seen from key.first
  };
  // A grain-wall contact: key (grain id, wall index).
  struct WallEntry {
    ContactKey key;
    Vec3 normal;
    State state;
  };

  // The grain-wall contacts of the current list.
  std::vector<WallEntry> wall_entries(const ParticleStore& s, const NeighborList& list) const {
    std::vector<WallEntry> out;
    for (std::size_t k = 0; k < list.walls.size() && k < wall.size(); ++k)
      for (std::size_t c = 0; c < wall[k].n; ++c)
        out.push_back({{s.gid[list.walls[k].particle], static_cast<GlobalId>(list.walls[k].wall)},
                       wall_contact(k, c).normal,
                       wall_contact(k, c).state});
    return out;
  }

  // Every non-default state, keyed by global ids, in neighbour-list order.
  std::vector<Entry> entries(const ParticleStore& s, const NeighborList& list) const {
    std::vector<Entry> out;
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
  void stash(const ParticleStore& s, const NeighborList& list) override {
    stash_ = entries(s, list);
    wall_stash_ = wall_entries(s, list);
  }

  // Saves the states of the current list, or loads them into the stash for the next restore().
  void save(ArchiveWriter& ar, const ParticleStore& s, const NeighborList& list) const override {
    std::vector<Entry> all = entries(s, list);
    ar.vector(all);
    std::vector<WallEntry> walls = wall_entries(s, list);
    ar.vector(walls);
  }
  void load(ArchiveReader& ar) override {
    std::vector<Entry> all;
    ar.vector(all);
    stash_ = std::move(all);
    std::vector<WallEntry> walls;
    ar.vector(walls);
    wall_stash_ = std::move(walls);
  }

  void forget() override {
    forget_copies();
    wall_stash_ = std::vector<WallEntry>();
  }

  // Gives each entry of the new list its stashed state (or a fresh one).
  void restore(const ParticleStore& s, const NeighborList& list) override {
    pair_slot.assign(list.n_pairs(), none);
    // Room for a slot per listed pair, and for as many free ones (made again where it would be
    // far too large: its memory would otherwise stay at its largest ever).
    if (states.capacity() > 2 * list.n_pairs() + 1024) states = std::vector<State>();
    states.clear();
    states.reserve(list.n_pairs());
    if (free_.capacity() > 2 * list.n_pairs() + 1024) free_ = std::vector<std::uint32_t>();
    free_.clear();
    free_.reserve(list.n_pairs());
    plane.assign(list.planes.size(), State{});
    plane_live.assign(list.planes.size(), 0);
    restore_walls(s, list);
    if (stash_.empty()) return forget_copies();
    const OwnedIndex owned = owned_.has_value() ? std::move(*owned_) : OwnedIndex(s);
    // The row of particle `row` (if owned here) lists the pair when its partner has global id
    // `other`; the state is stored as seen from the lower id.
    const auto place = [&](std::size_t row, GlobalId other, const State& state, bool mirror) {
      if (row == OwnedIndex::none) return;
      for (std::uint32_t p = list.offsets[row]; p < list.offsets[row + 1]; ++p)
        if (s.gid[list.partners[p]] == other) open(p) = mirror ? state.mirrored() : state;
    };
    std::unordered_map<ContactKey, const State*, ContactKeyHash> plane_states;
    for (const Entry& e : stash_) {
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
    forget_copies();
  }

  // Bytes held by the per-contact arrays (slots, states, live flags, free list and stash): of the
  // states' room, the slots used (the rest is address space no page of which has been touched).
  std::size_t memory_bytes() const override {
    return plane_live.capacity() + (pair_slot.capacity() + free_.size()) * sizeof(std::uint32_t) +
           (states.size() + plane.capacity()) * sizeof(State) + stash_.capacity() * sizeof(Entry) +
           wall.capacity() * sizeof(WallContactSet<State>) +
           wall_blocks_.size() * sizeof(WallBlock) + wall_stash_.capacity() * sizeof(WallEntry);
  }

  std::size_t stashed() const { return stash_.size(); }
  const std::uint32_t* pair_slots() const override { return pair_slot.data(); }

  std::vector<StateField> state_fields() const override { return yuxi::state_fields<State>(); }
  void pair_state(std::uint32_t p, std::vector<double>& out) const override {
    const bool held = p < pair_slot.size() && pair_slot[p] != none;
    append_state_values(held ? states[pair_slot[p]] : State{}, out);
  }
  void plane_state(std::size_t k, std::vector<double>& out) const override {
    append_state_values(k < plane.size() ? plane[k] : State{}, out);
  }
  void wall_state(std::size_t k, std::size_t c, std::vector<double>& out) const override {
    const bool held = k < wall.size() && c < wall[k].n;
    append_state_values(held ? wall_contact(k, c).state : State{}, out);
  }

  // Migration between ranks: copies of the stashed states of the contacts that the particles
  // `gids` take part in (with either partner, or as the grain of a plane or wall contact),
  // packed as bytes, one string per particle (a block: see pack()). The stash keeps them: the pair
  // may still be computed here, with the particle that left as a ghost. One pass over the stash for
  // all the particles that leave (a few hundred at a list build, against thousands of stashed
  // contacts).
  std::vector<std::string> copies_for(const std::vector<GlobalId>& gids) const override {
    std::vector<std::string> out(gids.size());
    if (gids.empty()) return out;
    std::unordered_map<GlobalId, std::size_t> leaving;
    leaving.reserve(gids.size());
    // A bit per id modulo 2^16 screens the stash before the hash lookup: the few leaving ids
    // set few bits, so most entries are passed over with one load.
    std::vector<std::uint64_t> maybe(1024, 0);
    const auto bit = [](GlobalId g) { return static_cast<std::uint64_t>(g) & 0xFFFF; };
    for (std::size_t k = 0; k < gids.size(); ++k) {
      leaving.emplace(gids[k], k);
      maybe[bit(gids[k]) >> 6] |= std::uint64_t{1} << (bit(gids[k]) & 63);
    }
    std::vector<std::string> pairs(gids.size()), walls(gids.size());
    for (const Entry& e : stash_)
      for (const GlobalId g : {e.key.first, e.key.second}) {
        if (!(maybe[bit(g) >> 6] >> (bit(g) & 63) & 1)) continue;
        const auto it = leaving.find(g);
        if (it != leaving.end())
          pairs[it->second].append(reinterpret_cast<const char*>(&e), sizeof e);
      }
    for (const WallEntry& e : wall_stash_) {
      const auto it = leaving.find(e.key.first);
      if (it != leaving.end())
        walls[it->second].append(reinterpret_cast<const char*>(&e), sizeof e);
    }
    for (std::size_t k = 0; k < gids.size(); ++k)
      if (!pairs[k].empty() || !walls[k].empty()) out[k] = pack(pairs[k], walls[k]);
    return out;
  }
  // Takes blocks of pack() (any number, one after another).
  void give(const std::string& bytes) override {
    std::size_t at = 0;
    while (at + 2 * sizeof(std::uint64_t) <= bytes.size()) {
      std::uint64_t n_pairs = 0, n_walls = 0;
      std::memcpy(&n_pairs, bytes.data() + at, sizeof n_pairs);
      std::memcpy(&n_walls, bytes.data() + at + sizeof n_pairs, sizeof n_walls);
      at += 2 * sizeof(std::uint64_t);
      for (std::uint64_t k = 0; k < n_pairs && at + sizeof(Entry) <= bytes.size(); ++k) {
        Entry e;
        std::memcpy(&e, bytes.data() + at, sizeof e);
        stash_.push_back(e);
        at += sizeof e;
      }
      for (std::uint64_t k = 0; k < n_walls && at + sizeof(WallEntry) <= bytes.size(); ++k) {
        WallEntry e;
        std::memcpy(&e, bytes.data() + at, sizeof e);
        wall_stash_.push_back(e);
        at += sizeof e;
      }
    }
  }
  // Pair contacts' states keyed by global ids (another engine's), as give() takes them.
  static std::string pack_entries(std::span<const Entry> entries) {
    return pack({reinterpret_cast<const char*>(entries.data()), entries.size() * sizeof(Entry)},
                {});
  }
  // Every stashed state as bytes (one block, for give()).
  std::string stashed_bytes() const override {
    return pack({reinterpret_cast<const char*>(stash_.data()), stash_.size() * sizeof(Entry)},
                {reinterpret_cast<const char*>(wall_stash_.data()),
                 wall_stash_.size() * sizeof(WallEntry)});
  }

  // The states that travel with ghosts at a halo build (domain/halo.hpp, GhostPayload).
  // Before the build: the stashed pair contacts with one particle owned here and the other
  // not, attached to the owned one. A pair whose particles are both owned here is computed
  // here; one with neither is not (a copy left by a particle that migrated).
  void prepare_ghost_copies(const ParticleStore& s) override {
    owned_.emplace(s);
    attached_.clear();
    has_attached_.assign(s.n_owned(), 0);
    for (std::uint32_t k = 0; k < stash_.size(); ++k) {
      const ContactKey key = stash_[k].key;
      if (key.second < 0) continue;
      const std::size_t a = owned_->find(key.first), b = owned_->find(key.second);
      if ((a == OwnedIndex::none) == (b == OwnedIndex::none)) continue;
      const auto at = static_cast<std::uint32_t>(a != OwnedIndex::none ? a : b);
      attached_.push_back({at, k});
      has_attached_[at] = 1;
    }
    std::sort(attached_.begin(), attached_.end());
  }
  // The attached states of the particles `sent` (local indices, owned or ghosts passed on), as
  // (position in `sent`, entry) records.
  std::string ghost_copies(std::span<const std::uint32_t> sent) const override {
    std::string out;
    for (std::uint32_t m = 0; m < sent.size(); ++m) {
      const std::uint32_t i = sent[m];
      if (i >= has_attached_.size() || !has_attached_[i]) continue;
      auto it = std::lower_bound(attached_.begin(), attached_.end(), Attached{i, 0});
      for (; it != attached_.end() && it->particle == i; ++it) {
        out.append(reinterpret_cast<const char*>(&m), sizeof m);
        out.append(reinterpret_cast<const char*>(&stash_[it->entry]), sizeof(Entry));
      }
    }
    return out;
  }
  // States that came with the ghosts first, first + 1, ...: stashed for restore(), and attached
  // to their ghost for passing on unless the other particle is owned here (then this rank
  // computes the pair, if any rank does).
  void ghost_copies_arrived(const ParticleStore& s, std::uint32_t first,
                            const std::string& bytes) override {
    constexpr std::size_t record = sizeof(std::uint32_t) + sizeof(Entry);
    if (!owned_) owned_.emplace(s);
    for (std::size_t at = 0; at + record <= bytes.size(); at += record) {
      std::uint32_t m;
      Entry e;
      std::memcpy(&m, bytes.data() + at, sizeof m);
      std::memcpy(&e, bytes.data() + at + sizeof m, sizeof e);
      const std::uint32_t ghost = first + m;
      const GlobalId other = s.gid[ghost] == e.key.first ? e.key.second : e.key.first;
      stash_.push_back(e);
      if (owned_->find(other) != OwnedIndex::none) continue;
      if (has_attached_.size() <= ghost) has_attached_.resize(ghost + 1, 0);
      has_attached_[ghost] = 1;
      attached_.push_back({ghost, static_cast<std::uint32_t>(stash_.size() - 1)});
    }
  }

private:
  // A block of copies: the counts of pair and wall entries (8 bytes each), then the entries.
  static std::string pack(std::string_view pairs, std::string_view walls) {
    const std::uint64_t counts[2] = {pairs.size() / sizeof(Entry),
                                     walls.size() / sizeof(WallEntry)};
    std::string out(reinterpret_cast<const char*>(counts), sizeof counts);
    out.append(pairs);
    out.append(walls);
    return out;
  }
  // Gives each grain-wall candidate of the new list its stashed contacts, in stash order.
  void restore_walls(const ParticleStore& s, const NeighborList& list) {
    wall.clear();
    wall.resize(list.walls.size());
    // Room for a block per candidate (made again where it would be far too large).
    if (wall_blocks_.capacity() > 2 * list.walls.size() + 1024)
      wall_blocks_ = std::vector<WallBlock>();
    wall_blocks_.clear();
    wall_blocks_.reserve(list.walls.size());
    if (!wall_stash_.empty() && !list.walls.empty()) {
      std::unordered_map<ContactKey, std::size_t, ContactKeyHash> candidate;
      candidate.reserve(list.walls.size());
      for (std::size_t k = 0; k < list.walls.size(); ++k)
        candidate.emplace(
            ContactKey{s.gid[list.walls[k].particle], static_cast<GlobalId>(list.walls[k].wall)},
            k);
      for (const WallEntry& e : wall_stash_) {
        const auto it = candidate.find(e.key);
        if (it == candidate.end()) continue;
        const std::size_t k = it->second;
        if (wall[k].n == max_wall_contacts) continue;
        make_wall_room(k, wall[k].n + 1u);
        wall_contact(k, wall[k].n++) = {e.normal, e.state};
      }
    }
    wall_stash_ = std::vector<WallEntry>();
  }
  static ContactKey plane_key(const ParticleStore& s, const PlaneContactRef& r) {
    return {s.gid[r.particle], -static_cast<GlobalId>(r.plane) - 1};
  }
  // The stash and the copies' bookkeeping go (their memory too): made again at the next list build.
  void forget_copies() {
    stash_ = std::vector<Entry>();
    attached_ = std::vector<Attached>();
    has_attached_ = std::vector<std::uint8_t>();
    owned_.reset();
  }
  struct Attached {
    std::uint32_t particle; // local index (owned, or a ghost that passes it on)
    std::uint32_t entry;    // index into stash_
    auto operator<=>(const Attached&) const = default;
  };
  // Blocks of the grain-wall contacts beyond each candidate's first (WallContactSet).
  using WallBlock = std::array<WallContact<State>, max_wall_contacts - 1>;
  std::vector<WallBlock> wall_blocks_;
  std::vector<std::uint32_t> free_; // slots of `states` that no contact holds
  std::vector<Entry> stash_;        // copies of one contact hold the same state
  std::vector<WallEntry> wall_stash_;
  // During a list build, between prepare_ghost_copies() and restore(): the stashed states that
  // travel with each particle sent as a ghost (sorted by particle: ghosts arrive in order),
  // a flag per particle that has any, and the owned particles by global id.
  std::vector<Attached> attached_;
  std::vector<std::uint8_t> has_attached_;
  std::optional<OwnedIndex> owned_;
};

} // namespace yuxi
